#!/usr/bin/env python3
"""Smooth output triangles per second: our fit + tessellation against libigl's Loop subdivision
and a plain numpy implementation of PN triangles, on the same mesh at the same output count
(docs/performance.md, "Against libigl's Loop and numpy's PN triangles").

Usage (from the repository root, after `cargo build --release -p experiments`):

    python3 -m venv /tmp/tess-venv
    /tmp/tess-venv/bin/pip install -r scripts/requirements-subdivision.txt
    /tmp/tess-venv/bin/python scripts/compare_tessellation.py [NU NV] [--experiments BINARY]

`--quick` (what `scripts/run-quick` runs in CI, with the debug binary): a 24 × 12 torus, one run
per timing, and checks instead of a table worth reading: every method's output triangle count is
the one its lattice or subdivision gives, and our `pn-triangles` tessellation is the numpy PN
triangles' surface (every sample of one within PN_AGREEMENT of a vertex of the other, both ways).
Exit status 1 when a check fails.

The mesh is a regular 16:8-proportioned torus grid (R = 1, r = 0.4; NU × NV quads split along
one diagonal, default 320 × 160 = 102 400 triangles) with area-weighted vertex normals, written
as OBJ with its normals. Output counts match: Loop with L levels gives F·4^L triangles, a
tessellation at s segments per edge F·s², so s = 2^L (s = 4 ↔ L = 2, s = 8 ↔ L = 3).

* ours: `experiments fit --data mesh.obj --estimate none --curves chord --scheme S --segments s
  --mesh-output out.ply --report report.json`; the time is the report's `time.fit` (the fit is
  streamed: the curves) plus `time.sample` (the patches built again where they are sampled, and
  sampled into the welded mesh); reading, G1 measurement, conversion and writing are outside, as
  they are for the others. Our
  tessellation also computes normals, Gaussian and mean curvature and shape tensors per vertex,
  and welds the output into one mesh.
* libigl: `igl.loop(V, F, L)` (positions and faces only).
* numpy PN triangles (Vlachos et al. 2001): the ten control points and six normal coefficients
  per face, vectorized over faces, evaluated on the shared sample lattice by a precomputed
  Bernstein matrix; positions and normals per sample, unwelded (each face its own samples).

Each timing is the median of five runs. The numbers in docs/performance.md were made with this
script.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

RUNS = 5

# Quick mode's torus (576 triangles) and its single run per timing: seconds in a debug build.
QUICK_TORUS = (24, 12)

# Our `pn-triangles` samples and numpy's are the same cubic Bézier points evaluated in another
# order of floating-point operations: measured 6.8e-16 apart on the quick torus (radius 1.4);
# 1e-12 is far above rounding and far below any real difference of construction.
PN_AGREEMENT = 1e-12


def torus(nu, nv, major=1.0, minor=0.4):
    u = np.arange(nu) * 2 * np.pi / nu
    v = np.arange(nv) * 2 * np.pi / nv
    uu, vv = np.meshgrid(u, v, indexing="ij")
    x = (major + minor * np.cos(vv)) * np.cos(uu)
    y = (major + minor * np.cos(vv)) * np.sin(uu)
    z = minor * np.sin(vv)
    verts = np.stack([x, y, z], -1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a = i * nv + j
    b = ((i + 1) % nu) * nv + j
    c = ((i + 1) % nu) * nv + (j + 1) % nv
    d = i * nv + (j + 1) % nv
    faces = np.concatenate(
        [np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)]
    )
    return verts, faces.astype(np.int64)


def vertex_normals(verts, faces):
    p = verts[faces]
    fn = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    n = np.zeros_like(verts)
    for k in range(3):
        np.add.at(n, faces[:, k], fn)
    return n / np.linalg.norm(n, axis=1, keepdims=True)


def write_obj(path, verts, faces, normals):
    with open(path, "w") as f:
        f.write("".join(f"v {float(x)!r} {float(y)!r} {float(z)!r}\n" for x, y, z in verts))
        f.write("".join(f"vn {float(x)!r} {float(y)!r} {float(z)!r}\n" for x, y, z in normals))
        f.write("".join(f"f {a}//{a} {b}//{b} {c}//{c}\n" for a, b, c in faces + 1))


def lattice(s):
    pts = [(i / s, j / s) for j in range(s + 1) for i in range(s + 1 - j)]
    index = {}
    for k, (i, j) in enumerate((i, j) for j in range(s + 1) for i in range(s + 1 - j)):
        index[(i, j)] = k
    tris = []
    for j in range(s):
        for i in range(s - j):
            tris.append((index[(i + 1, j)], index[(i, j + 1)], index[(i, j)]))
            if i + j + 2 <= s:
                tris.append((index[(i + 1, j)], index[(i + 1, j + 1)], index[(i, j + 1)]))
    return np.array(pts), np.array(tris)


def pn_triangles(verts, faces, normals, s):
    """Positions and normals of PN triangles on the lattice of s segments, per face."""
    p = verts[faces]  # F×3×3
    n = normals[faces]
    p1, p2, p3 = p[:, 0], p[:, 1], p[:, 2]
    n1, n2, n3 = n[:, 0], n[:, 1], n[:, 2]

    def w(a, b, na):
        return np.sum((b - a) * na, axis=1, keepdims=True)

    b300, b030, b003 = p1, p2, p3
    b210 = (2 * p1 + p2 - w(p1, p2, n1) * n1) / 3
    b120 = (2 * p2 + p1 - w(p2, p1, n2) * n2) / 3
    b021 = (2 * p2 + p3 - w(p2, p3, n2) * n2) / 3
    b012 = (2 * p3 + p2 - w(p3, p2, n3) * n3) / 3
    b102 = (2 * p3 + p1 - w(p3, p1, n3) * n3) / 3
    b201 = (2 * p1 + p3 - w(p1, p3, n1) * n1) / 3
    e = (b210 + b120 + b021 + b012 + b102 + b201) / 6
    vv = (p1 + p2 + p3) / 3
    b111 = e + (e - vv) / 2

    def nv(a, b, na, nb):
        d = b - a
        v = 2 * np.sum(d * (na + nb), axis=1, keepdims=True) / np.sum(d * d, axis=1, keepdims=True)
        h = na + nb - v * d
        return h / np.linalg.norm(h, axis=1, keepdims=True)

    n110, n011, n101 = nv(p1, p2, n1, n2), nv(p2, p3, n2, n3), nv(p3, p1, n3, n1)
    uv, tris = lattice(s)
    u, v = uv[:, 0], uv[:, 1]
    wgt = 1 - u - v
    # Cubic Bernstein basis (order: b300 b030 b003 b210 b120 b021 b012 b102 b201 b111).
    basis = np.stack(
        [u**3, v**3, wgt**3, 3 * u * u * v, 3 * u * v * v, 3 * v * v * wgt,
         3 * v * wgt * wgt, 3 * u * wgt * wgt, 3 * u * u * wgt, 6 * u * v * wgt], 1
    )
    ctrl = np.stack([b300, b030, b003, b210, b120, b021, b012, b102, b201, b111], 1)
    pos = np.einsum("sk,fkd->fsd", basis, ctrl)
    nbasis = np.stack([u * u, v * v, wgt * wgt, u * v, v * wgt, wgt * u], 1)
    nctrl = np.stack([n1, n2, n3, n110, n011, n101], 1)
    nor = np.einsum("sk,fkd->fsd", nbasis, nctrl)
    nor /= np.linalg.norm(nor, axis=2, keepdims=True)
    faces_out = (np.arange(len(faces))[:, None, None] * len(uv) + tris[None]).reshape(-1, 3)
    return pos.reshape(-1, 3), nor.reshape(-1, 3), faces_out


def median_time(f, runs):
    times = []
    out = None
    for _ in range(runs):
        t = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def ours(exe, obj, scheme, s, tmp, runs, ext):
    """Median of `runs` fit + sample times of our scheme, the output triangle count and the path
    of the tessellation written (`ext` "obj" in quick mode: text, read back by its checks)."""
    times = []
    tris = None
    out = Path(tmp) / f"out-{scheme}-{s}.{ext}"
    report = Path(tmp) / "report.json"
    for _ in range(runs):
        subprocess.run(
            [exe, "fit", "--data", str(obj), "--estimate", "none", "--curves", "chord",
             "--scheme", scheme, "--segments", str(s), "--mesh-output", str(out),
             "--report", str(report)],
            capture_output=True, text=True, check=True,
        )
        r = json.loads(report.read_text())
        tris = r["tessellation"]["triangles"]
        times.append(r["time"]["fit"] + r["time"]["sample"])
    return statistics.median(times), tris, out


def read_obj_positions(path):
    return np.array(
        [[float(x) for x in line.split()[1:4]]
         for line in Path(path).read_text().splitlines() if line.startswith("v ")]
    )


def two_way_distance(a, b):
    """The largest distance from a point of either set to the nearest point of the other."""
    from scipy.spatial import cKDTree

    return max(cKDTree(b).query(a)[0].max(), cKDTree(a).query(b)[0].max())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("size", nargs="*", type=int, help="NU NV (default 320 160)")
    parser.add_argument("--quick", action="store_true", help="small torus, one run, checks")
    parser.add_argument("--experiments", default=os.environ.get("EXPERIMENTS",
                        "target/release/experiments"), help="the experiments binary")
    args = parser.parse_args()
    if args.size and len(args.size) != 2:
        parser.error("give both NU and NV")
    nu, nv = args.size or (QUICK_TORUS if args.quick else (320, 160))
    runs = 1 if args.quick else RUNS
    import igl

    verts, faces = torus(nu, nv)
    normals = vertex_normals(verts, faces)
    nf = len(faces)
    failures = []

    def expect(what, got, want):
        if got != want:
            failures.append(f"{what}: {got} output triangles, expected {want}")

    print(f"torus {nu}×{nv}: {nf} triangles")
    with tempfile.TemporaryDirectory() as tmp:
        obj = Path(tmp) / "mesh.obj"
        write_obj(obj, verts, faces, normals)
        print("| method | output triangles | time (s) | M triangles/s |")
        print("|---|---:|---:|---:|")
        for level, s in [(2, 4), (3, 8)]:
            t, (_, f_out) = median_time(lambda: igl.loop(verts, faces, level), runs)
            expect(f"libigl loop {level}", len(f_out), nf * 4**level)
            print(f"| libigl `loop`, {level} levels | {len(f_out)} | {t:.3f} | {len(f_out) / t / 1e6:.1f} |")
            t, (pn_pos, _, f_out) = median_time(lambda: pn_triangles(verts, faces, normals, s), runs)
            expect(f"numpy PN s = {s}", len(f_out), nf * s * s)
            print(f"| numpy PN triangles, s = {s} | {len(f_out)} | {t:.3f} | {len(f_out) / t / 1e6:.1f} |")
            for scheme in ["pn-triangles", "shirman-sequin", "nielson"]:
                # Shirman–Séquin has three patches per face: s/2 per patch edge is the closest
                # output count (3·(s/2)² = 0.75 s² per face); reported as measured.
                ss = s // 2 if scheme == "shirman-sequin" else s
                t, n, out = ours(args.experiments, obj, scheme, ss, tmp, runs, "obj" if args.quick else "ply")
                patches = 3 if scheme == "shirman-sequin" else 1
                expect(f"ours {scheme} s = {ss}", n, nf * patches * ss * ss)
                print(f"| ours `{scheme}`, fit + tessellate s = {ss} | {n} | {t:.3f} | {n / t / 1e6:.1f} |")
                if args.quick and scheme == "pn-triangles":
                    d = two_way_distance(read_obj_positions(out), pn_pos)
                    print(f"  ours `pn-triangles` against numpy's PN triangles, s = {s}: {d:.1e} apart")
                    if not d <= PN_AGREEMENT:
                        failures.append(f"pn-triangles s = {s}: ours and numpy's {d:.1e} apart "
                                        f"(more than {PN_AGREEMENT:.0e})")
    for f in failures:
        print(f"compare_tessellation: {f}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
