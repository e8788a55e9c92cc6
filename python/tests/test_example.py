"""The notebook-style example runs and says what the schemes are: Shirman–Séquin G1 to
rounding, the two C0 schemes visibly not, every curvature error a finite number."""

import subprocess
import sys

from conftest import REPO

EXAMPLE = REPO / "python/examples/compare_schemes.py"
# G1 to rounding (the data set's measured 2.5e-14) against a visible normal jump (measured
# 2.0e-2 and 3.8e-2 rad for the C0 schemes).
G1_ROUNDING = 1e-9
C0_VISIBLE = 1e-3


def test_compare_schemes_runs_and_plots(tmp_path):
    out = tmp_path / "compare.png"
    run = subprocess.run(
        [sys.executable, str(EXAMPLE), "--resolution", "16", "--out", str(out)],
        capture_output=True, text=True, check=True, env={"MPLBACKEND": "Agg", "PATH": ""},
    )
    assert out.stat().st_size > 10_000
    lines = {l.split(":")[0].strip(): l for l in run.stdout.splitlines() if "G1 defect" in l}
    assert set(lines) == {"shirman-sequin", "pn-triangles", "clough-tocher"}
    g1 = {k: float(l.split("G1 defect")[1].split()[0]) for k, l in lines.items()}
    assert g1["shirman-sequin"] < G1_ROUNDING
    assert g1["pn-triangles"] > C0_VISIBLE and g1["clough-tocher"] > C0_VISIBLE
