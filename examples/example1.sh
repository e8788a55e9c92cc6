#!/usr/bin/env bash
# Example 1 of the seed (§3): a shaded picture of the octahedron's surface.
#   % Piper < octa.m | Tess -s 8 | Mat0 | Sgp | Render > octa.wff
# Piper's scheme itself could not be recovered: the closest construction the original testbed's
# sources hold stands in, Shirman–Séquin (the testbed's modified fitter) with Piper's tangent
# rule (examples/README.md). Sgp is not needed: render reads the triangle records.
. "$(dirname "$0")/common.sh"
tb fit --scheme shirman-sequin-testbed --curves piper < "$DATA" | tb tess -s 8 | tb mat0 | tb render > "$OUT/example1.png"
