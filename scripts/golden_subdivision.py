#!/usr/bin/env python3
"""Golden data for the `subdiv` crate: one and two steps of Loop and Catmull–Clark subdivision by
widely used C++ implementations, on small meshes with irregular valences 3–8, closed and open.

Usage (from the repository root):

    python3 -m venv /tmp/subdiv-venv
    /tmp/subdiv-venv/bin/pip install -r scripts/requirements-subdivision.txt
    /tmp/subdiv-venv/bin/python scripts/golden_subdivision.py data/golden

writes

* `subdivision-loop-warren-libigl.json`: libigl's `igl.loop` (libigl 2.6.3). Its smooth rule uses
  Warren's β = 3/(8n) for n > 3 and 3/16 for n = 3; boundary vertices (1/8, 3/4, 1/8), boundary
  edge points the midpoint (checked by hand on a single triangle and an octahedron).
* `subdivision-loop-cgal.json`: CGAL's `Subdivision_method_3::Loop_subdivision` through
  compas_cgal 0.10.0 (`compas_cgal._subdivision.subd_loop`). Loop's original
  β = (5/8 − (3/8 + ¼ cos 2π/n)²)/n; same boundary rules.
* `subdivision-catmull-clark-cgal.json`: CGAL's `Subdivision_method_3::CatmullClark_subdivision`
  through compas_cgal 0.10.0 (`subd_catmullclark`, which takes polygons of any size). Centroid face
  points, (a + b + f0 + f1)/4 edge points, ((n−2)p + (Σq + Σf)/n)/n vertex points; boundary edge
  points the midpoint and boundary vertices (1/8, 6/8, 1/8) (checked by hand on a cube and a
  2×1 quad strip).

Each file holds, per case (`closed`, `open`), the input mesh and the output after one and after two
steps (the second step is a separate call on the first step's output), positions as shortest
round-trip decimal strings of the float64 values. Vertex order is the implementation's own; the
Rust test matches vertices by nearest neighbour (unique within 1e-9, then compared at 1e-12) and
compares the faces as cyclic vertex sequences under that matching.

Timing (`--bench DIR`): reads the benchmark meshes the Rust example `export_bench_meshes` writes
(OBJ) and times three levels of each scheme, the C++ call only (the Python-side conversion of the
input arrays is outside the timer; the binding's own copy into its mesh type is inside).

`--quick` (what `scripts/run-quick` runs in CI; about a second) writes nothing under data/: it
makes the golden files in a temporary directory and fails unless they hold the committed
files' meshes (faces equal, positions within GOLDEN_TOL), then times one run of each scheme on
the closed and open meshes written as OBJ (the `--bench` path), failing unless each row has
the mesh's counts and a positive time for every scheme that applies.
"""

import json
import math
import sys
import tempfile
import time
from pathlib import Path

import igl
import numpy as np
from compas_cgal import _subdivision as cgal_subdivision
from compas_cgal import _types_std  # noqa: F401  (registers the list-of-lists face type)
from golden_diff import differences

# The same pinned libigl and compas_cgal reproduce the committed files byte for byte (measured);
# 1e-12 (the Rust test's own comparison tolerance; the meshes are of unit size) leaves room
# for another CPU's libm in the jitter and the normalization, and is far below what a changed
# rule moves (its weights are multiples of 1/64).
GOLDEN_TOL = 1e-12

VERSIONS = {"libigl": "2.6.3", "compas_cgal": "0.10.0", "numpy": np.__version__}


def icosahedron():
    t = (1.0 + math.sqrt(5.0)) / 2.0
    v = np.array(
        [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
         [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]],
        dtype=np.float64,
    )
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
         [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
         [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    return [list(p) for p in v], f


def irregular_triangles():
    """Icosahedron; edge (3, 9) split (a valence-4 vertex); the three faces at vertex 0 that
    start 0→11, 0→5, 0→1 split at their centroids (valence-3 vertices; vertex 0 gets 8,
    vertices 1 and 5 get 7); jittered by a fixed generator. Valences 3, 4, 5, 6, 7, 8."""
    v, f = icosahedron()
    m = len(v)
    v.append(list((np.array(v[3]) + np.array(v[9])) / np.linalg.norm(np.array(v[3]) + np.array(v[9]))))
    out = []
    for t in f:
        if t == [3, 9, 4]:
            out += [[3, m, 4], [m, 9, 4]]
        elif t == [3, 8, 9]:
            out += [[3, 8, m], [m, 8, 9]]
        else:
            out.append(t)
    tris = []
    for t in out:
        if t[0] == 0 and t[1] in (11, 5, 1):
            c = len(v)
            s = np.array(v[t[0]]) + np.array(v[t[1]]) + np.array(v[t[2]])
            v.append(list(s / np.linalg.norm(s)))
            tris += [[t[0], t[1], c], [t[1], t[2], c], [t[2], t[0], c]]
        else:
            tris.append(t)
    rng = np.random.default_rng(20240607)
    v = np.array(v) + rng.uniform(-0.05, 0.05, size=(len(v), 3))
    return v, tris


def open_triangles():
    """The irregular mesh with faces [3, 2, 6], [3, 6, 8] and [8, 6, 7] removed (one hole of three
    faces, each sharing an edge with the next): a boundary loop of five vertices."""
    v, f = irregular_triangles()
    drop = ([3, 2, 6], [3, 6, 8], [8, 6, 7])
    return v, [t for t in f if t not in drop]


def merge_to_polygons(v, tris):
    """Mixed polygons for Catmull–Clark: pairs of triangles sharing an edge merged into quads,
    greedily in face order, and one quad merged with a further triangle into a pentagon."""
    used = [False] * len(tris)
    polys = []
    edge_face = {}
    for i, t in enumerate(tris):
        for k in range(3):
            edge_face[(t[k], t[(k + 1) % 3])] = i
    for i, t in enumerate(tris):
        if used[i]:
            continue
        merged = None
        if i % 3 != 2:  # leave a third of the triangles alone
            for k in range(3):
                a, b, c = t[k], t[(k + 1) % 3], t[(k + 2) % 3]
                j = edge_face.get((b, a))
                if j is not None and not used[j] and j != i:
                    u = tris[j]
                    d = [x for x in u if x not in (a, b)][0]
                    merged = [a, d, b, c]
                    used[j] = True
                    break
        used[i] = True
        polys.append(merged if merged else list(t))
    # one pentagon: a quad and a triangle still alone that share an edge
    for qi, q in enumerate(polys):
        if len(q) != 4:
            continue
        for ti, t in enumerate(polys):
            if len(t) != 3:
                continue
            for k in range(4):
                a, b = q[k], q[(k + 1) % 4]
                for r in range(3):
                    if t[r] == b and t[(r + 1) % 3] == a:
                        c = t[(r + 2) % 3]
                        pent = q[: k + 1] + [c] + q[k + 1:]
                        polys[qi] = pent
                        del polys[ti]
                        return v, polys
    return v, polys


def as_json_mesh(v, f):
    return {
        "positions": [[repr(float(x)) for x in p] for p in np.asarray(v)],
        "faces": [[int(i) for i in face] for face in f],
    }


def igl_loop(v, f):
    v2, f2 = igl.loop(np.asarray(v, dtype=np.float64), np.asarray(f, dtype=np.int64), 1)
    return v2, f2.tolist()


def cgal_loop(v, f):
    v2, f2 = cgal_subdivision.subd_loop(
        np.asarray(v, dtype=np.float64), np.asarray(f, dtype=np.int32), 1
    )
    return v2, f2.tolist()


def cgal_cc(v, f):
    v2, f2 = cgal_subdivision.subd_catmullclark(
        np.asarray(v, dtype=np.float64), [list(map(int, x)) for x in f], 1
    )
    return v2, f2.tolist()


def case(name, v, f, step):
    levels = []
    cv, cf = v, f
    for _ in range(2):
        cv, cf = step(cv, cf)
        levels.append(as_json_mesh(cv, cf))
    return {"name": name, "input": as_json_mesh(v, f), "levels": levels}


def write(path, implementation, rules, cases):
    doc = {
        "generator": "scripts/golden_subdivision.py",
        "versions": VERSIONS,
        "implementation": implementation,
        "rules": rules,
        "vertex_matching": "nearest neighbour, unique within 1e-9; compared at 1e-12",
        "cases": cases,
    }
    Path(path).write_text(json.dumps(doc, separators=(",", ":")) + "\n")


def golden(out_dir):
    out = Path(out_dir)
    closed = irregular_triangles()
    opened = open_triangles()
    write(
        out / "subdivision-loop-warren-libigl.json",
        "libigl 2.6.3 igl.loop",
        "Loop, Warren's beta 3/(8n) (n>3), 3/16 (n=3); boundary (1/8,3/4,1/8), edge midpoints",
        [case("closed", *closed, igl_loop), case("open", *opened, igl_loop)],
    )
    write(
        out / "subdivision-loop-cgal.json",
        "CGAL Subdivision_method_3::Loop_subdivision via compas_cgal 0.10.0",
        "Loop, Loop's beta (5/8-(3/8+cos(2pi/n)/4)^2)/n; boundary (1/8,3/4,1/8), edge midpoints",
        [case("closed", *closed, cgal_loop), case("open", *opened, cgal_loop)],
    )
    write(
        out / "subdivision-catmull-clark-cgal.json",
        "CGAL Subdivision_method_3::CatmullClark_subdivision via compas_cgal 0.10.0",
        "Catmull-Clark; centroid face points; boundary edge midpoints, boundary vertex (1,6,1)/8",
        [
            case("closed", *merge_to_polygons(*closed), cgal_cc),
            case("open", *merge_to_polygons(*opened), cgal_cc),
        ],
    )


def read_obj(path):
    vs, fs = [], []
    for line in Path(path).read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vs.append([float(x) for x in parts[1:4]])
        elif parts[0] == "f":
            fs.append([int(c.split("/")[0]) - 1 for c in parts[1:]])
    return np.array(vs, dtype=np.float64), fs


def best_of(runs, fn):
    best = math.inf
    for _ in range(runs):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def golden_close(committed, now, path):
    """Positions (decimal strings) within GOLDEN_TOL; anything else equal."""
    if isinstance(committed, str) and isinstance(now, str) and ".positions" in path:
        return abs(float(committed) - float(now)) <= GOLDEN_TOL
    return committed == now


def write_obj(path, v, f):
    lines = [f"v {float(x)!r} {float(y)!r} {float(z)!r}" for x, y, z in np.asarray(v)]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in f]
    Path(path).write_text("\n".join(lines) + "\n")


def quick():
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        golden(tmp)
        for name in sorted(p.name for p in Path(tmp).glob("*.json")):
            committed = json.loads((Path("data/golden") / name).read_text())
            now = json.loads((Path(tmp) / name).read_text())
            # The versions record numpy's too, which the pins fix; compared like the rest.
            failures += [f"data/golden/{name}{d}" for d in differences(committed, now, golden_close)]
        meshes = {"closed": irregular_triangles(), "open": open_triangles()}
        bench_dir = Path(tmp) / "bench"
        bench_dir.mkdir()
        for name, (v, f) in meshes.items():
            write_obj(bench_dir / f"{name}.obj", v, f)
        result = bench(bench_dir, runs=1)
        for name, (v, f) in meshes.items():
            row = result.get(name, {})
            if row.get("faces") != len(f) or row.get("vertices") != len(v):
                failures.append(f"bench {name}: read {row.get('faces')} faces, "
                                f"{row.get('vertices')} vertices of {len(f)}, {len(v)}")
            for key in ("libigl_loop_warren", "cgal_loop", "cgal_catmull_clark"):
                if not row.get(key, 0) > 0:
                    failures.append(f"bench {name}: no time for {key}")
    for f in failures:
        print(f"golden_subdivision --quick: {f}", file=sys.stderr)
    if failures:
        return 1
    print(f"golden_subdivision --quick: data/golden's three files as made (within {GOLDEN_TOL:.0e}); "
          "the bench path timed both meshes")
    return 0


def bench(mesh_dir, runs=3):
    d = Path(mesh_dir)
    result = {"versions": VERSIONS, "levels": 3, "runs": runs, "statistic": "best of runs, seconds"}
    for name in sorted(p.stem for p in d.glob("*.obj")):
        v, f = read_obj(d / f"{name}.obj")
        row = {"faces": len(f), "vertices": len(v)}
        tri = all(len(x) == 3 for x in f)
        if tri:
            fi64 = np.asarray(f, dtype=np.int64)
            fi32 = np.asarray(f, dtype=np.int32)
            row["libigl_loop_warren"] = best_of(runs, lambda: igl.loop(v, fi64, 3))
            row["cgal_loop"] = best_of(runs, lambda: cgal_subdivision.subd_loop(v, fi32, 3))
        lists = [list(map(int, x)) for x in f]
        row["cgal_catmull_clark"] = best_of(
            runs, lambda: cgal_subdivision.subd_catmullclark(v, lists, 3)
        )
        result[name] = row
        print(name, row, flush=True)
    print(json.dumps(result, indent=1))
    return result


if __name__ == "__main__":
    if sys.argv[1:] == ["--quick"]:
        sys.exit(quick())
    elif len(sys.argv) == 3 and sys.argv[1] == "--bench":
        bench(sys.argv[2])
    elif len(sys.argv) == 2:
        golden(sys.argv[1])
    else:
        sys.exit(__doc__)
