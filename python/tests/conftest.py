"""Shared fixtures: the repository, the command line's binary the package is compared with, and
a JSON walk that compares two reports number for number."""

import json
import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]

# Keys whose values are measured, not computed (wall time, memory), or name where a front end
# wrote its outputs: they differ between any two runs, whatever the front end.
VOLATILE_KEYS = ("time", "seconds", "peak_memory", "streamed", "patches_out", "tessellation")


def experiments_binary():
    """The `experiments` binary: $TRIWB_EXPERIMENTS, else the workspace's debug or release build."""
    given = os.environ.get("TRIWB_EXPERIMENTS")
    if given:
        return Path(given)
    for profile in ("debug", "release"):
        p = REPO / "target" / profile / "experiments"
        if p.is_file():
            return p
    return None


@pytest.fixture(scope="session")
def experiments():
    """Runs the command line; skips (or, with TRIWB_REQUIRE_CLI=1 as in CI, fails) without it."""
    exe = experiments_binary()
    if exe is None:
        message = "no experiments binary: run `cargo build -p experiments` or set TRIWB_EXPERIMENTS"
        if os.environ.get("TRIWB_REQUIRE_CLI") == "1":
            pytest.fail(message)
        pytest.skip(message)

    def run(*args, cwd=None):
        return subprocess.run(
            [str(exe), *map(str, args)], check=True, capture_output=True, text=True, cwd=cwd
        )

    return run


def report_differences(a, b, path=""):
    """Every place two reports differ, skipping the volatile keys and the time note."""
    out = []
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if any(v in k for v in VOLATILE_KEYS):
                continue
            out += report_differences(a.get(k), b.get(k), f"{path}/{k}")
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{path}: {len(a)} items against {len(b)}"]
        for i, (x, y) in enumerate(zip(a, b)):
            if isinstance(x, str) and x.startswith("time: "):
                continue
            out += report_differences(x, y, f"{path}[{i}]")
    elif a != b or type(a) is not type(b):
        out.append(f"{path}: {a!r} against {b!r}")
    return out


def read_patches(path):
    """The control nets of a JSON Lines patch file, one list of points per patch."""
    with open(path) as f:
        return [json.loads(line)["points"] for line in f if line.strip()]
