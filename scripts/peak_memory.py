#!/usr/bin/env python3
"""Peak memory of reading a bare OBJ and estimating its curvature: `experiments convert` against
libigl, and `fit --mesh-output` against the `.bzp` path, in the same run (issue 28's "Copies";
docs/performance.md, "Copies: peak memory against the `.bzp` path and libigl").

Usage (from the repository root, after `cargo build --release -p experiments`, in a venv with
scripts/requirements-golden.txt, e.g. the `.venv-scripts` that scripts/run-quick makes):

    .venv-scripts/bin/python scripts/peak_memory.py [--resolution R] [--runs N]
        [--experiments BINARY]

The mesh is the `ring` data set at resolution R (default 1000: 500 000 vertices, 10⁶ faces),
written as a bare OBJ (positions and faces) by `experiments convert`. Each program then runs N
times (default 3) as a child process, and its peak resident set is the child's `ru_maxrss`
(`os.wait4`), in MiB; the table prints the medians and the ratios:

* `convert → PLY`: `experiments convert --data ring.obj --output y.ply` (read, repair,
  estimation by the default estimator, the PLY with normals and curvature streamed out);
* `convert → .m`: the same with `--output y.m`;
* libigl: a Python child that imports numpy and igl first (the interpreter and the modules are
  its baseline, measured alone and printed), then `igl.read_triangle_mesh`,
  `igl.per_vertex_normals` and `igl.principal_curvature` (its default radius 5), and keeps the
  arrays until it exits: the same read and estimation;
* `fit → .bzp` and `fit → .glb`: `experiments fit --data ring.obj --curves optimized --output
  x.bzp`, and the same with `--segments 1 --mesh-output x.glb` instead of `--output` (the
  issue's target: the mesh output at most 1.3× the `.bzp` path).

`--quick` (what scripts/run-quick runs in CI, with the debug binary): resolution 40, one run
each, and checks instead of a table worth reading: every child exits 0, every peak is a positive
number, `convert` reports the ring's face count. The debug build's ratios say nothing about
memory at scale. Exit status 1 when a check fails.
"""

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

RUNS = 3
RESOLUTION = 1000
QUICK_RESOLUTION = 40

# The libigl child: imports first (its baseline), then the read and the estimation, the arrays
# kept alive to the end (as `convert` keeps its mesh until it is written).
LIBIGL_BASELINE = "import numpy, igl, scipy.sparse"
LIBIGL_CHILD = LIBIGL_BASELINE + """
import sys
v, f = igl.read_triangle_mesh(sys.argv[1])
n = igl.per_vertex_normals(v, f)
pd1, pd2, pv1, pv2 = igl.principal_curvature(v, f)[:4]
print(len(v), len(f), float(abs(pv1 * pv2).sum()))
"""


def peak_mib(cmd, cwd):
    """Runs `cmd` in `cwd`; returns (exit status, peak resident set in MiB, stdout + stderr)."""
    with tempfile.TemporaryFile() as out:
        child = subprocess.Popen(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(child.pid, 0)
        child.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        text = out.read().decode(errors="replace")
    # Linux reports ru_maxrss in KiB.
    return child.returncode, usage.ru_maxrss / 1024.0, text


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--resolution", type=int, default=RESOLUTION)
    ap.add_argument("--runs", type=int, default=RUNS)
    ap.add_argument("--experiments", default="target/release/experiments")
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    if args.quick:
        args.resolution, args.runs = QUICK_RESOLUTION, 1
    exe = str(Path(args.experiments).resolve())
    failures = []
    with tempfile.TemporaryDirectory() as d:
        code, _, text = peak_mib(
            [exe, "convert", "--data", "ring", "--resolution", str(args.resolution),
             "--output", "ring.obj"], d)
        if code != 0:
            sys.exit(f"peak_memory: writing the ring failed:\n{text}")
        runs = {
            "convert → PLY": [exe, "convert", "--data", "ring.obj", "--output", "y.ply"],
            "convert → .m": [exe, "convert", "--data", "ring.obj", "--output", "y.m"],
            "libigl": [sys.executable, "-c", LIBIGL_CHILD, "ring.obj"],
            "libigl's baseline (imports)": [sys.executable, "-c", LIBIGL_BASELINE],
            "fit → .bzp": [exe, "fit", "--data", "ring.obj", "--curves", "optimized",
                           "--output", "x.bzp"],
            "fit → .glb": [exe, "fit", "--data", "ring.obj", "--curves", "optimized",
                           "--segments", "1", "--mesh-output", "x.glb"],
        }
        peaks = {name: [] for name in runs}
        faces = None
        for _ in range(args.runs):
            for name, cmd in runs.items():
                for out in ("y.ply", "y.m", "x.bzp", "x.glb"):
                    Path(d, out).unlink(missing_ok=True)
                code, mib, text = peak_mib(cmd, d)
                if code != 0:
                    failures.append(f"{name} exited {code}:\n{text}")
                    continue
                if not mib > 0:
                    failures.append(f"{name}: no peak measured")
                peaks[name].append(mib)
                m = re.search(r"vertices, (\d+) faces\)", text)
                if name == "convert → PLY" and m:
                    faces = int(m.group(1))
    expected_faces = 2 * args.resolution * (args.resolution // 2)
    if faces != expected_faces:
        failures.append(f"convert reported {faces} faces, the ring has {expected_faces}")
    med = {k: statistics.median(v) for k, v in peaks.items() if v}
    print(f"ring of resolution {args.resolution}: {faces} faces; peak resident set, median of "
          f"{args.runs} run(s), MiB")
    for name, mib in med.items():
        print(f"  {name:<30} {mib:8.1f}")
    ratios = [("convert → PLY", "libigl"), ("convert → .m", "libigl"),
              ("fit → .glb", "fit → .bzp")]
    for a, b in ratios:
        if a in med and b in med:
            print(f"  {a} / {b}: {med[a] / med[b]:.2f}")
    for f in failures:
        print(f"peak_memory: {f}", file=sys.stderr)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
