#!/usr/bin/env python3
"""Golden numbers for the `estimation` study: the errors of the estimators researchers use today
(libigl), on exactly the meshes the study uses, against the exact values of the analytic surfaces.

Usage (from the repository root):

    python3 -m venv /tmp/igl && /tmp/igl/bin/pip install -r scripts/requirements-golden.txt
    cargo run --release -p experiments -- estimation --export /tmp/estimation-meshes
    /tmp/igl/bin/python scripts/golden_estimators.py /tmp/estimation-meshes data/golden/libigl-estimators.json

The export writes, per mesh NAME, `NAME.obj` (positions and triangles, nothing else) and
`NAME.exact.json` (`{"normals": [[x, y, z], ...], "K": [...], "H": [...]}`, the exact unit normal,
Gaussian and mean curvature at each vertex, in the workbench's sign: H < 0 on a sphere with outward
normals). This script computes, for every mesh:

* `igl-normals-angle`: igl.per_vertex_normals with angle weighting (Thürmer–Wüthrich);
* `igl-normals-area`: the same with area weighting;
* `igl-quadric-r5`, `igl-quadric-r2`: igl.principal_curvature (local quadric fit, Panozzo et al.
  2010) with its default radius 5 and a small radius 2 (k-ring neighbourhoods); K = k1 k2 and
  H = (k1 + k2)/2, with H's sign mapped to the workbench's by the orientation of the normals
  (libigl reports the principal values with respect to its own vertex normals; the sign is fixed
  by comparing with the exact H on the first mesh, and the same sign is used everywhere);
* `igl-angle-defect`: K = (2π − Σ angles) / A_voronoi (igl.gaussian_curvature divided by the
  Voronoi-hybrid mass matrix diagonal), the discrete Gauss–Bonnet estimate; it has no H.

and writes, per mesh and estimator, RMS and max of the normal error (degrees) and of |K − K_exact|
and |H − H_exact|, to the JSON file given. The numbers are committed; the study reads them.

`--quick` (what `scripts/run-quick` runs in CI) writes nothing: it exports the study's meshes with
the `experiments` binary named by $EXPERIMENTS (default target/debug/experiments) into a temporary
directory, recomputes the rows of the QUICK_MESHES smallest meshes with the committed H sign, and
exits 1 unless they equal data/golden/libigl-estimators.json within GOLDEN_REL_TOL.
"""

import json
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import igl
import numpy as np

from golden_diff import differences


def read_obj(path):
    vs, fs = [], []
    for line in Path(path).read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vs.append([float(x) for x in parts[1:4]])
        elif parts[0] == "f":
            fs.append([int(c.split("/")[0]) - 1 for c in parts[1:4]])
    return np.array(vs, dtype=np.float64), np.array(fs, dtype=np.int64)


def stats(err):
    err = np.asarray(err, dtype=np.float64)
    return {"rms": float(math.sqrt(np.mean(err * err))), "max": float(np.max(err))}


def normal_errors(n_est, n_exact):
    n_est = n_est / np.linalg.norm(n_est, axis=1, keepdims=True)
    c = np.clip(np.sum(n_est * n_exact, axis=1), -1.0, 1.0)
    s = np.linalg.norm(np.cross(n_est, n_exact), axis=1)
    return np.degrees(np.arctan2(s, c))


COMMITTED = Path(__file__).resolve().parent.parent / "data/golden/libigl-estimators.json"

# The quick mode recomputes this many meshes (the smallest, by vertex count): a few seconds.
QUICK_MESHES = 4

# Same libigl, same meshes, same arithmetic: the rows reproduce to rounding of the sums (the
# committed file is written with 17 significant digits); 1e-9 leaves room for a BLAS that sums
# in another order.
GOLDEN_REL_TOL = 1e-9


def rows(src, names, h_sign=None):
    """The rows of `names` in `src`, and the H sign used (fixed on the first when not given)."""
    result = {}
    for name in names:
        v, f = read_obj(src / f"{name}.obj")
        exact = json.loads((src / f"{name}.exact.json").read_text())
        n_exact = np.array(exact["normals"], dtype=np.float64)
        k_exact = np.array(exact["K"], dtype=np.float64)
        h_exact = np.array(exact["H"], dtype=np.float64)
        row = {}
        for label, w in [
            ("igl-normals-angle", igl.PER_VERTEX_NORMALS_WEIGHTING_TYPE_ANGLE),
            ("igl-normals-area", igl.PER_VERTEX_NORMALS_WEIGHTING_TYPE_AREA),
        ]:
            n = igl.per_vertex_normals(v, f, w)
            row[label] = {"normal_deg": stats(normal_errors(n, n_exact))}
        for label, radius in [("igl-quadric-r5", 5), ("igl-quadric-r2", 2)]:
            _pd1, _pd2, pv1, pv2, bad = igl.principal_curvature(v, f, radius)
            k = pv1 * pv2
            h = (pv1 + pv2) / 2.0
            if h_sign is None:
                h_sign = -1.0 if np.mean(np.abs(-h - h_exact)) < np.mean(np.abs(h - h_exact)) else 1.0
            h = h * h_sign
            row[label] = {
                "K": stats(np.abs(k - k_exact)),
                "H": stats(np.abs(h - h_exact)),
                "bad_vertices": len(bad),
            }
        defect = igl.gaussian_curvature(v, f)
        mass = igl.massmatrix(v, f, igl.MASSMATRIX_TYPE_VORONOI).diagonal()
        k = defect / np.maximum(mass, 1e-300)
        row["igl-angle-defect"] = {"K": stats(np.abs(k - k_exact))}
        result[name] = {"vertices": int(v.shape[0]), "faces": int(f.shape[0]), "estimators": row}
        print(name, {e: {m: round(x["rms"], 6) for m, x in d.items() if isinstance(x, dict)} for e, d in row.items()})
    return result, h_sign


def close(ours, theirs, _path):
    """Numbers within GOLDEN_REL_TOL relative; anything else equal."""
    if isinstance(ours, (int, float)) and isinstance(theirs, (int, float)):
        return abs(ours - theirs) <= GOLDEN_REL_TOL * max(abs(ours), abs(theirs), 1e-300)
    return ours == theirs


def quick():
    committed = json.loads(COMMITTED.read_text())
    exe = os.environ.get("EXPERIMENTS", "target/debug/experiments")
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([exe, "estimation", "--export", tmp], check=True, stdout=subprocess.DEVNULL)
        sizes = {n: m["vertices"] for n, m in committed["meshes"].items()}
        names = sorted(sizes, key=lambda n: (sizes[n], n))[:QUICK_MESHES]
        ours, _ = rows(Path(tmp), names, committed["h_sign"])
    diff = differences({n: committed["meshes"][n] for n in names}, ours, close)
    if diff:
        for d in diff:
            print(f"golden_estimators --quick: {COMMITTED}{d}", file=sys.stderr)
        sys.exit(1)
    print(f"golden_estimators --quick: {len(names)} meshes of {COMMITTED} as computed (within {GOLDEN_REL_TOL:.0e}): {', '.join(names)}")


def main(src, out):
    src = Path(src)
    names = sorted(p.name[: -len(".exact.json")] for p in src.glob("*.exact.json"))
    if not names:
        sys.exit(f"no *.exact.json in {src}")
    meshes, h_sign = rows(src, names)
    result = {"libigl_version": "2.6.3", "meshes": meshes, "h_sign": h_sign}
    Path(out).parent.mkdir(parents=True, exist_ok=True)
    Path(out).write_text(json.dumps(result, indent=1, sort_keys=True) + "\n")


if __name__ == "__main__":
    if sys.argv[1:] == ["--quick"]:
        quick()
        sys.exit(0)
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
