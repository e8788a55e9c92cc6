"""The package runs the command line's fit job: the same nets, the same report numbers and the
same mesh file bytes, bit for bit, on the data sets, a scan, a CAD part, and on arrays."""

import json

import numpy as np
import pytest

import triwb
from conftest import REPO, read_patches, report_differences

CASES = [
    ("ring", ["--curves", "chord"]),
    ("sphere", ["--curves", "optimized", "--solver", "lm"]),
    ("capsule", ["--curves", "dbhs"]),
    ("octa", ["--curves", "optimized"]),
    ("ring", ["--scheme", "phong", "--phong-alpha", "0.5"]),
    (str(REPO / "data/meshes/bunny.ply"), ["--curves", "optimized"]),
    (str(REPO / "data/cad/gear.ply"), ["--curves", "chord"]),
    (str(REPO / "data/meshes/teapot.ply"), ["--curves", "optimized"]),
    (str(REPO / "data/cad/pipe_joint.ply"), ["--curves", "optimized", "--tangents", "per-edge"]),
]


def keywords(args):
    """`--curves optimized --phong-alpha 0.5` as fit's keyword arguments."""
    return {args[i].lstrip("-").replace("-", "_"): args[i + 1] for i in range(0, len(args), 2)}


def typed(kw):
    out = {}
    for k, v in kw.items():
        try:
            out[k] = float(v) if k in ("beta", "c", "phong_alpha") else v
        except ValueError:
            out[k] = v
    return out


def cli_fit(experiments, tmp_path, data, args):
    experiments(
        "fit", "--data", data, *args,
        "--output", tmp_path / "p.jsonl", "--report", tmp_path / "r.json",
        "--mesh-output", tmp_path / "cli.ply",
    )
    nets = np.array(read_patches(tmp_path / "p.jsonl"))
    report = json.loads((tmp_path / "r.json").read_text())
    return nets, report


@pytest.mark.parametrize("data,args", CASES, ids=[f"{d.split('/')[-1]} {' '.join(a)}" for d, a in CASES])
def test_fit_equals_the_command_line_bit_for_bit(experiments, tmp_path, data, args):
    nets, report = cli_fit(experiments, tmp_path, data, args)
    fit = triwb.fit(data, **typed(keywords(args)))
    assert fit.nets.shape == nets.shape
    assert np.array_equal(fit.nets, nets), f"largest difference {np.abs(fit.nets - nets).max()}"
    assert report_differences(report, fit.report) == []
    fit.to_mesh(tmp_path / "py.ply")
    assert (tmp_path / "py.ply").read_bytes() == (tmp_path / "cli.ply").read_bytes()


def test_arrays_fit_as_their_file_does(experiments, tmp_path):
    # A scan read into arrays (positions, triangles, no normals) and fitted from them gives what
    # the command line gives on the file.
    path = REPO / "data/meshes/bunny.ply"
    nets, report = cli_fit(experiments, tmp_path, str(path), ["--curves", "optimized"])
    V, F = triwb.read_mesh(path)
    fit = triwb.fit(V, F, curves="optimized", label=str(path))
    assert np.array_equal(fit.nets, nets)
    assert report_differences(report, fit.report) == []


def test_a_data_set_written_out_fits_as_its_arrays(experiments, tmp_path):
    # The `.m` format keeps every digit of positions, normals and shape tensors: the file and
    # the arrays are the same input.
    ring = triwb.ring(6)
    path = tmp_path / "ring.m"
    triwb.write_mesh(path, ring.V, ring.F, normals=ring.normals, shape=ring.shape)
    nets, report = cli_fit(experiments, tmp_path, str(path), ["--curves", "dbhs"])
    fit = triwb.fit(
        ring.V, ring.F, normals=ring.normals, shape=ring.shape, curves="dbhs", label=str(path)
    )
    assert np.array_equal(fit.nets, nets)
    assert report_differences(report, fit.report) == []


def test_report_keeps_the_g1_split_fallbacks_and_curve_statistics():
    fit = triwb.fit(str(REPO / "data/cad/gear.ply"))
    r = fit.report
    for key in ("interior_max", "exterior_max", "fallback_edges", "crease_edges"):
        assert key in r["g1"]
    assert r["g1"]["crease_edges"] > 0, "the gear's creases are found"
    assert isinstance(r["fallback_faces"], list)
    assert all("reason" in f for f in r["fallback_faces"])
    assert "curve_counts" in r and "time" in r
    assert fit.g1()["crease_edges"] == r["g1"]["crease_edges"]


def test_tangents_choose_the_rule_and_the_report_counts_the_corners():
    # pipe_joint has corners the per-edge tangents leave non-convex: the fans turn them (the
    # default), per-edge keeps them and only counts.
    path = str(REPO / "data/cad/pipe_joint.ply")
    star = triwb.fit(path, curves="optimized")
    own = triwb.fit(path, curves="optimized", tangents="per-edge")
    fans, kept = star.report["curve_counts"]["fan"], own.report["curve_counts"]["fan"]
    assert fans["corners_failing_before"] == kept["corners_failing_before"] > 0
    assert fans["corners_failing_after"] < fans["corners_failing_before"]
    assert kept["corners_failing_after"] == kept["corners_failing_before"]
    assert kept["sectors_fanned"] == 0 < fans["sectors_fanned"]
    assert not np.array_equal(star.nets, own.nets)
    with pytest.raises(triwb.UsageError, match="tangents"):
        triwb.fit(path, tangents="both")
