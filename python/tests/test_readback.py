"""Round trips through the tools a notebook has beside the package: what we write, trimesh and
libigl read as written; what they give (their arrays, their dtypes), we fit."""

import numpy as np
import pytest

import triwb
from conftest import REPO

trimesh = pytest.importorskip("trimesh")
igl = pytest.importorskip("igl")

# PLY stores positions as 32-bit floats by default: a unit-sized mesh comes back within half a
# unit in the last place of a float32 (6e-8 relative) of what was written.
FLOAT32_RELATIVE = 1.2e-7


def test_write_mesh_reads_back_in_trimesh_and_libigl(tmp_path):
    m = triwb.sphere(2)
    path = tmp_path / "sphere.ply"
    e = triwb.estimate(m.V, m.F)
    triwb.write_mesh(path, m.V, m.F, normals=m.normals, K=e["K"], H=e["H"])
    t = trimesh.load(path, process=False)
    assert np.array_equal(t.faces, m.F)
    assert np.abs(t.vertices - m.V).max() <= FLOAT32_RELATIVE * np.abs(m.V).max()
    V, F = igl.read_triangle_mesh(str(path))
    assert np.array_equal(F, m.F)
    assert np.abs(V - m.V).max() <= FLOAT32_RELATIVE * np.abs(m.V).max()
    # Double precision on request: every digit back.
    triwb.write_mesh(path, m.V, m.F, double=True)
    assert np.array_equal(trimesh.load(path, process=False).vertices, m.V)


def test_a_fit_written_as_glb_and_ply_loads_watertight(tmp_path):
    fit = triwb.fit("sphere")
    for ext in ("glb", "ply", "obj", "off", "stl"):
        path = fit.to_mesh(tmp_path / f"sphere.{ext}", segments=3)
        loaded = trimesh.load(path, force="mesh")
        loaded.merge_vertices()
        assert loaded.is_watertight, ext
        t = fit.tessellate(3)
        assert len(loaded.faces) == len(t["F"]), ext


def test_the_package_fits_what_libigl_and_trimesh_read():
    path = REPO / "data/meshes/bunny.ply"
    V, F = igl.read_triangle_mesh(str(path))  # float64, int64 (libigl's types)
    a = triwb.fit(V, F)
    t = trimesh.load(path, process=False)
    b = triwb.fit(t.vertices, t.faces)  # trimesh's TrackedArray subclasses
    ours = triwb.read_mesh(path)
    c = triwb.fit(ours.V, ours.F)
    assert np.array_equal(a.nets, c.nets) and np.array_equal(b.nets, c.nets)


def test_curvature_sign_agrees_with_libigl():
    # Both give H > 0 and the principal curvatures near 1 on the unit sphere with outward
    # normals (libigl's principal_curvature returns max then min).
    V, F = triwb.sphere(3)
    e = triwb.estimate(V, F)
    _, _, pv1, pv2, _ = igl.principal_curvature(V, F)
    assert np.median(pv1) > 0.9 and np.median(e["k1"]) > 0.9
    assert np.sign(np.median(pv1 + pv2)) == np.sign(np.median(e["H"])) == 1
