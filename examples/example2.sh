#!/usr/bin/env bash
# Example 2 of the seed (§3.5): the mesh itself in wire-frame.
#   % Fitter0 < octa.m | Tess | Sgp | XRender
# Fitter0 (one degree-one patch per face) is the `flat` scheme; XRender's window is a PNG
# written by `wire`. `tess -s 1` gives one triangle per face: the mesh as it is.
. "$(dirname "$0")/common.sh"
tb fit --scheme flat < "$DATA" | tb tess -s 1 | tb wire > "$OUT/example2.png"
