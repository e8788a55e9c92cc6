#!/usr/bin/env bash
# Example 5 of the seed (§3.5): a fitter that samples its own surface, no Tess.
#   % Nielson -s 8 < octa.m | Mat0 | Sgp | Render > octa.wff
# Nielson's transfinite side-vertex interpolant (`nielson`) is evaluated, not a Bézier patch,
# so `fit` samples it itself (`-s 8`) and writes triangles directly, as the seed's
# non-Bézier fitters do.
. "$(dirname "$0")/common.sh"
tb fit --scheme nielson -s 8 < "$DATA" | tb mat0 | tb render > "$OUT/example5.png"
