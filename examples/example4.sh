#!/usr/bin/env bash
# Example 4 of the seed (§3.5): the triangles written once, read twice.
#   % Piper < octa.m | Tess -s 8 -kg > octa.out
#   % KColor < octa.out | Sgp | Render > octa.kg.wff
#   % Mat0 < octa.out | Sgp | Render > octa.simple.wff
# Shirman–Séquin with Piper's tangent rule stands in for Piper's scheme; the triangle file is kept in the seed's dstruct format
# (octa.out) as Triangle records (--triangles), which every filter detects. Mat0 ignores the kg
# it does not use.
. "$(dirname "$0")/common.sh"
tb fit --scheme shirman-sequin-testbed --curves piper < "$DATA" | tb tess -s 8 --kg --triangles --format dstruct > "$OUT/octa.out"
tb kcolor < "$OUT/octa.out" | tb render > "$OUT/example4-kg.png"
tb mat0 < "$OUT/octa.out" | tb render > "$OUT/example4-simple.png"
rm -f "$OUT/octa.out"
