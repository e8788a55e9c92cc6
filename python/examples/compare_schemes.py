"""Three schemes on one mesh, compared on curvature error and G1, with matplotlib.

The mesh is the workbench's ring (a torus, R = 1, r = 0.4, whose Gaussian curvature is known
exactly), given as bare arrays like any mesh of yours: positions and triangles, nothing else.
Each scheme is fitted through it, tessellated, and its Gaussian curvature compared with the
torus's at the closest point; the G1 defect is the report's, as the command line prints it.

    python python/examples/compare_schemes.py [--resolution 24] [--out compare.png]

Run it cell by cell in a notebook if you like: each block below is one cell.
"""

import argparse

import numpy as np

import triwb

R, r = 1.0, 0.4
SCHEMES = ["shirman-sequin", "pn-triangles", "clough-tocher"]


def torus_gaussian(points):
    """The torus's Gaussian curvature at the closest point of each of `points`:
    K = cos v / (r (R + r cos v)), v the angle around the tube."""
    rho = np.hypot(points[:, 0], points[:, 1])
    v = np.arctan2(points[:, 2], rho - R)
    return np.cos(v) / (r * (R + r * np.cos(v))), v


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--resolution", type=int, default=24, help="ring steps around the axis")
    ap.add_argument("--segments", type=int, default=6, help="tessellation per patch edge")
    ap.add_argument("--out", default="compare_schemes.png")
    args = ap.parse_args()

    # --- the mesh, as arrays
    V, F = triwb.ring(args.resolution)
    print(f"mesh: {len(V)} vertices, {len(F)} triangles")

    # --- fit and measure each scheme
    rows = []
    for scheme in SCHEMES:
        fit = triwb.fit(V, F, scheme=scheme, curves="optimized")
        t = fit.tessellate(args.segments)
        exact, v = torus_gaussian(t["V"])
        k_rms = float(np.sqrt(np.mean((t["K"] - exact) ** 2)))
        g1 = fit.report["g1"]
        rows.append(
            dict(scheme=scheme, k_rms=k_rms, g1=max(g1["interior_max"], g1["exterior_max"]),
                 continuity=fit.report["continuity"], v=v, K=t["K"], exact=exact)
        )
        print(f"{scheme:>15}: K RMS error {k_rms:.4f}, G1 defect {rows[-1]['g1']:.2e} rad "
              f"({rows[-1]['continuity']})")

    # --- plot
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(13, 4), constrained_layout=True)
    names = [row["scheme"] for row in rows]
    axes[0].bar(names, [row["k_rms"] for row in rows], color="tab:blue")
    axes[0].set_title("Gaussian curvature, RMS error")
    axes[1].bar(names, [max(row["g1"], 1e-16) for row in rows], color="tab:orange")
    axes[1].set_yscale("log")
    axes[1].set_title("G1 defect (radians, largest normal jump)")
    order = np.argsort(rows[0]["v"])
    axes[2].plot(rows[0]["v"][order], rows[0]["exact"][order], "k-", lw=2, label="torus")
    for row in rows:
        axes[2].plot(row["v"], row["K"], ".", ms=1.5, label=row["scheme"])
    axes[2].set_xlabel("angle around the tube v")
    axes[2].set_ylabel("K")
    axes[2].set_title("K of the tessellation against the torus")
    axes[2].legend(markerscale=6, fontsize=8)
    for ax in axes[:2]:
        ax.tick_params(axis="x", labelrotation=15)
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")
    return rows


if __name__ == "__main__":
    main()
