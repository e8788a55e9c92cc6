#!/usr/bin/env bash
# Example 5 of the seed (§3.5): a fitter that samples its own surface, no Tess.
#   % Nielson -s 8 < octa.m | Mat0 | Sgp | Render > octa.wff
# Nielson's transfinite interpolant is not implemented; PN triangles stand in, sampled inside
# fit (`--sample 8`), which then writes triangles directly, as the seed's non-Bézier fitters do.
. "$(dirname "$0")/common.sh"
tb fit --scheme pn-triangles --sample 8 < "$DATA" | tb mat0 | tb render > "$OUT/example5.png"
