#!/usr/bin/env bash
# Example 3 of the seed (§3.5): the surface coloured by its Gaussian curvature.
#   % Piper < octa.m | Tess -s 8 -kg | KColor | Sgp | Render > octa.wff
# Shirman–Séquin (the testbed's modified fitter) with Piper's tangent rule stands in for
# Piper's scheme (see example1.sh).
. "$(dirname "$0")/common.sh"
tb fit --scheme shirman-sequin-testbed --curves piper < "$DATA" | tb tess -s 8 --kg | tb kcolor | tb render > "$OUT/example3.png"
