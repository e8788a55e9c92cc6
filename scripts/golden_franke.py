#!/usr/bin/env python3
"""Golden numbers for the `franke` study: scipy's Clough–Tocher interpolant
(`scipy.interpolate.CloughTocher2DInterpolator`, which estimates the gradients itself by a
global curvature-minimizing rule and triangulates by Qhull) on exactly the point sets of the
workbench's Franke data sets, with its error over the same evaluation grid.

Usage (from the repository root):

    python3 -m venv /tmp/venv-franke && /tmp/venv-franke/bin/pip install -r scripts/requirements-franke.txt
    /tmp/venv-franke/bin/python scripts/golden_franke.py data/golden/franke-scipy.json

`--quick` (what `scripts/run-quick` runs in CI; about 2 s) writes nothing: it computes every row
and fails unless the committed data/golden/franke-scipy.json holds the same numbers (floats
within GOLDEN_REL_TOL relative, the rest equal), so the study's golden numbers are still what
the pinned scipy computes on the point sets this script makes.

The point sets are regenerated here as `mesh::datasets` makes them: the 33 x 33 grid of [0, 1]^2,
and the 100 scattered points from the workbench's SplitMix64 (rng/src/lib.rs) seeded with
FRANKE_SEED: the four corners, s = floor(sqrt(n - 4)) // 2 uniform points on each side (bottom,
right, top, left), then uniform points inside. The sums of the scattered coordinates are written
too, so that the study checks it read the golden numbers of its own points. The Franke functions
are the formulas of mesh/src/analytic_franke.rs. Qhull's Delaunay triangulation of the grid may
choose other diagonals than the workbench's rising ones (four points on a circle), so the grid
figures compare interpolants on possibly different triangulations; the scattered ones do not.
"""

import json
import math
import sys

import numpy as np
import scipy
from scipy.interpolate import CloughTocher2DInterpolator

from golden_diff import differences

MASK = (1 << 64) - 1
FRANKE_SEED = 0x4652_414E_4B45
GRID = 33
SCATTERED = 100
EVAL = 101

COMMITTED = "data/golden/franke-scipy.json"

# The same pinned scipy and numpy on the same points repeat their numbers bit for bit (measured:
# the file is reproduced byte for byte); 1e-12 relative leaves room for another CPU's BLAS and
# libm in Qhull and the gradient solve, and is far below what a changed point set or formula
# moves (the errors are 1e-4 and up).
GOLDEN_REL_TOL = 1e-12


class SplitMix64:
    def __init__(self, seed):
        self.state = seed & MASK

    def next_u64(self):
        self.state = (self.state + 0x9E3779B97F4A7C15) & MASK
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
        return z ^ (z >> 31)

    def next_f64(self):
        return (self.next_u64() >> 11) * (1.0 / (1 << 53))


def scattered(n):
    rng = SplitMix64(FRANKE_SEED)
    pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
    s = min(int(math.sqrt(n - 4)) // 2, (n - 4) // 4)
    for side in range(4):
        for _ in range(s):
            t = rng.next_f64()
            pts.append([(t, 0.0), (1.0, t), (t, 1.0), (0.0, t)][side])
    while len(pts) < n:
        x = rng.next_f64()
        y = rng.next_f64()
        pts.append((x, y))
    return np.array(pts)


def grid(n):
    h = np.arange(n) / (n - 1)
    x, y = np.meshgrid(h, h)
    return np.column_stack([x.ravel(), y.ravel()])


def franke(k, x, y):
    if k == 1:
        return (0.75 * np.exp(-((9 * x - 2) ** 2 + (9 * y - 2) ** 2) / 4)
                + 0.75 * np.exp(-((9 * x + 1) ** 2) / 49 - (9 * y + 1) / 10)
                + 0.5 * np.exp(-((9 * x - 7) ** 2 + (9 * y - 3) ** 2) / 4)
                - 0.2 * np.exp(-(9 * x - 4) ** 2 - (9 * y - 7) ** 2))
    if k == 2:
        return (np.tanh(9 * y - 9 * x) + 1) / 9
    if k == 3:
        return (1.25 + np.cos(5.4 * y)) / (6 * (1 + (3 * x - 1) ** 2))
    r2 = (x - 0.5) ** 2 + (y - 0.5) ** 2
    if k == 4:
        return np.exp(-81 / 16 * r2) / 3
    if k == 5:
        return np.exp(-81 / 4 * r2) / 3
    return np.sqrt(64 - 81 * r2) / 9 - 0.5


def report():
    e = grid(EVAL)
    rows = []
    sc = scattered(SCATTERED)
    for k in range(1, 7):
        for sampling, pts in [("grid 33 × 33", grid(GRID)), ("scattered 100", sc)]:
            ct = CloughTocher2DInterpolator(pts, franke(k, pts[:, 0], pts[:, 1]))
            s = ct(e)
            inside = ~np.isnan(s)
            err = np.abs(s[inside] - franke(k, e[inside, 0], e[inside, 1]))
            rows.append({
                "function": k,
                "sampling": sampling,
                "max_error": float(err.max()),
                "rms_error": float(np.sqrt(np.mean(err ** 2))),
                "points_outside": int((~inside).sum()),
            })
    return {
        "generator": "scripts/golden_franke.py",
        "scipy": scipy.__version__,
        "numpy": np.__version__,
        "interpolant": "scipy.interpolate.CloughTocher2DInterpolator (its own gradients and Qhull Delaunay)",
        "evaluation_grid": EVAL,
        "scattered_seed": FRANKE_SEED,
        "scattered_sum": [float(sc[:, 0].sum()), float(sc[:, 1].sum())],
        "rows": rows,
    }


def close(committed, now, _path):
    """Floats within GOLDEN_REL_TOL relative; anything else equal."""
    if isinstance(committed, float) and isinstance(now, float):
        return abs(committed - now) <= GOLDEN_REL_TOL * abs(committed)
    return committed == now


def main(argv):
    if argv == ["--quick"]:
        with open(COMMITTED) as f:
            diffs = differences(json.load(f), report(), close)
        for d in diffs:
            print(f"golden_franke --quick: {COMMITTED}{d}", file=sys.stderr)
        if diffs:
            return 1
        print(f"golden_franke --quick: {COMMITTED} as computed (within {GOLDEN_REL_TOL:.0e})")
        return 0
    if len(argv) != 1:
        sys.exit(__doc__)
    with open(argv[0], "w") as f:
        json.dump(report(), f, indent=2)
        f.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
