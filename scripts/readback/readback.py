#!/usr/bin/env python3
"""Reads the workbench's mesh files back with the readers other tools' users use, and checks
that each reads what we wrote.

Usage (from the repository root; .ci/run makes the venv, the Rust suite runs this through
tests/tests/suite/readback.rs with the files and expectations it writes):

    python3 -m venv .venv-readback && .venv-readback/bin/pip install -r scripts/readback/requirements.txt
    (cd scripts/readback && npm install)        # optional: the Khronos glTF validator
    .venv-readback/bin/python scripts/readback/readback.py DIR

DIR holds the mesh files and `expect.json`, written by the Rust test:

    {"sample": N, "files": [{"file": "sphere.ply", "vertices": V, "faces": F,
      "positions": [[x, y, z], ...],            # the first N vertices, as a reader sees them
      "colour_bytes": [[r, g, b], ...] | null,  # the first N colours as bytes a viewer shows
      "gaussian": [...] | null, "mean": [...] | null,  # the first N curvatures (exported sign)
      "mean_positive": true | null}]}           # every mean curvature > 0 (a sphere)

Readers: trimesh, Python's meshio, libigl (`igl`, each file in its own process, since libigl
2.6.3 aborts the process on some PLY layouts), pymeshlab; and the Khronos glTF validator on
every .glb when `scripts/readback/node_modules` has it. For each reader and file it prints
what the reader read (counts, colours, quality/curvature, the sign of H) or why not, and
checks every value the reader returns against the expectations. A reader that refuses a file
for a limitation of its own that is known (listed in KNOWN below) is reported, not failed; any
other refusal, abort or wrong value fails. A reader that is not installed is reported as
skipped. Exit status: 0 when nothing failed, 1 otherwise.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

# Positions and curvatures pass through 32-bit floats: relative rounding 2^-24, and a reader
# that prints and parses text may add as much again.
F32_RELATIVE = 2.0 ** -22
# A colour byte a reader rounds from a float may differ by one step from ours.
COLOUR_STEP = 1

# Limitations of the readers themselves, known and stated (reader, extension) -> reason. A
# refusal or a missing quantity listed here is reported, never failed.
KNOWN_MISSING = {
    ("igl", "colours"): "igl.read_triangle_mesh returns positions and faces only",
    ("pymeshlab", ".ply"): "MeshLab reads PLY colours only as uchar; it reads quality (K) and colours by it",
    ("trimesh", ".off"): "trimesh 5.2 does not read OFF vertex colours",
    ("meshio", ".obj"): "Python meshio does not read OBJ vertex colours",
}

KNOWN = {
    ("meshio", ".off"): "Python meshio 5.3 reads only a plain OFF header (not COFF/NOFF)",
    ("meshio", ".glb"): "Python meshio has no glTF reader",
    ("igl", ".glb"): "libigl has no glTF reader",
}


def close(a, b, rel=F32_RELATIVE):
    return abs(a - b) <= rel * max(1.0, abs(a), abs(b))


# ---------------------------------------------------------------------------------------------
# Readers: each returns a dict with "vertices", "faces" and whichever of "positions",
# "colour_bytes", "quality", "gaussian", "mean" it can get; raises on refusal.


def read_trimesh(path, n):
    import numpy as np
    import trimesh

    m = trimesh.load(path, process=False, force="mesh")
    out = {"vertices": len(m.vertices), "faces": len(m.faces), "positions": m.vertices[:n].tolist()}
    if m.visual.kind == "vertex":
        out["colour_bytes"] = np.asarray(m.visual.vertex_colors)[:n, :3].astype(int).tolist()
    raw = m.metadata.get("_ply_raw") if isinstance(m.metadata, dict) else None
    if raw is not None:
        # A structured array (binary PLY) or a dict of arrays (text PLY).
        data = raw["vertex"]["data"]
        names = data.keys() if isinstance(data, dict) else (data.dtype.names or ())
        for ours, theirs in [("quality", "quality"), ("gaussian", "gaussian_curvature"), ("mean", "mean_curvature")]:
            if theirs in names:
                arr = np.asarray(data[theirs], dtype=float).reshape(-1)
                out[ours] = arr[:n].tolist()
                if ours == "mean":
                    out["all_mean"] = arr
    attrs = getattr(m, "vertex_attributes", {}) or {}
    for ours, theirs in [("gaussian", "_GAUSSIAN_CURVATURE"), ("mean", "_MEAN_CURVATURE")]:
        if theirs in attrs:
            arr = np.asarray(attrs[theirs], dtype=float).reshape(-1)
            out[ours] = arr[:n].tolist()
            if ours == "mean":
                out["all_mean"] = arr
    return out


def read_meshio(path, n):
    import numpy as np
    import meshio

    m = meshio.read(path)
    out = {
        "vertices": len(m.points),
        "faces": sum(len(c.data) for c in m.cells),
        "positions": np.asarray(m.points)[:n].tolist(),
    }
    pd = m.point_data
    if all(k in pd for k in ("red", "green", "blue")):
        rgb = np.stack([np.asarray(pd[k], dtype=float) for k in ("red", "green", "blue")], axis=1)
        if np.issubdtype(np.asarray(pd["red"]).dtype, np.floating):
            rgb = np.round(rgb * 255.0)
        out["colour_bytes"] = rgb[:n].astype(int).tolist()
    for ours, theirs in [("quality", "quality"), ("gaussian", "gaussian_curvature"), ("mean", "mean_curvature")]:
        if theirs in pd:
            arr = np.asarray(pd[theirs], dtype=float)
            out[ours] = arr[:n].tolist()
            if ours == "mean":
                out["all_mean"] = arr
    return out


def read_igl(path, n):
    import igl

    v, f = igl.read_triangle_mesh(str(path))
    return {"vertices": int(v.shape[0]), "faces": int(f.shape[0]), "positions": v[:n].tolist()}


def read_pymeshlab(path, n):
    import pymeshlab

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(path))
    m = ms.current_mesh()
    out = {"vertices": m.vertex_number(), "faces": m.face_number(), "positions": m.vertex_matrix()[:n].tolist()}
    if m.has_vertex_color():
        out["colour_bytes"] = (m.vertex_color_matrix()[:n, :3] * 255.0).round().astype(int).tolist()
    if m.has_vertex_scalar():
        out["quality"] = m.vertex_scalar_array()[:n].astype(float).tolist()
    return out


READERS = {
    "trimesh": (read_trimesh, {".ply", ".obj", ".off", ".glb"}),
    "meshio": (read_meshio, {".ply", ".obj", ".off", ".glb"}),
    "igl": (read_igl, {".ply", ".obj", ".off", ".glb"}),
    "pymeshlab": (read_pymeshlab, {".ply", ".obj", ".off", ".glb"}),
}

MODULES = {"trimesh": "trimesh", "meshio": "meshio", "igl": "igl", "pymeshlab": "pymeshlab"}


def installed(reader):
    try:
        __import__(MODULES[reader])
        return True
    except Exception:  # noqa: BLE001 - any import failure means "not usable here"
        return False


def read_isolated(reader, path, n):
    """Runs one reader on one file in its own process (libigl can abort the process)."""
    proc = subprocess.run(
        [sys.executable, __file__, "--one", reader, str(path), str(n)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    if proc.returncode != 0:
        tail = (proc.stderr.strip().splitlines() or ["(no message)"])[-1]
        if proc.returncode < 0:
            raise RuntimeError(f"the process died (signal {-proc.returncode}): {tail}")
        raise RuntimeError(tail)
    return json.loads(proc.stdout)


# ---------------------------------------------------------------------------------------------
# Checks


def check(reader, ext, want, got):
    """What differs between what the reader read and what we wrote (a list of problems), and
    what it read (a list of words for the table)."""
    problems, read = [], [f"{got['vertices']} v, {got['faces']} f"]
    if got["vertices"] != want["vertices"]:
        problems.append(f"{got['vertices']} vertices, wrote {want['vertices']}")
    if got["faces"] != want["faces"]:
        problems.append(f"{got['faces']} faces, wrote {want['faces']}")
    same_vertices = got["vertices"] == want["vertices"]
    if same_vertices and "positions" in got:
        for i, (p, q) in enumerate(zip(got["positions"], want["positions"])):
            if not all(close(a, b) for a, b in zip(p, q)):
                problems.append(f"vertex {i} at {p}, wrote {q}")
                break
    if "colour_bytes" in got:
        read.append("colours")
        if want.get("colour_bytes") is None:
            problems.append("colours where we wrote none")
        elif same_vertices:
            for i, (c, d) in enumerate(zip(got["colour_bytes"], want["colour_bytes"])):
                if any(abs(a - b) > COLOUR_STEP for a, b in zip(c, d)):
                    problems.append(f"colour of vertex {i} is {c}, wrote {d}")
                    break
    elif want.get("colour_bytes") is not None:
        why = KNOWN_MISSING.get((reader, "colours")) or KNOWN_MISSING.get((reader, ext))
        read.append(f"no colours (known: {why})" if why else "no colours")
    for key, expected in [("quality", "gaussian"), ("gaussian", "gaussian"), ("mean", "mean")]:
        if key not in got:
            continue
        read.append(key if key != "quality" else "quality (K)")
        values = want.get(expected)
        if values is None:
            problems.append(f"{key} where we wrote no curvature")
            continue
        if same_vertices:
            for i, (a, b) in enumerate(zip(got[key], values)):
                if not close(a, b):
                    problems.append(f"{key} of vertex {i} is {a}, wrote {b}")
                    break
    if "all_mean" in got and want.get("mean_positive"):
        negative = int((got["all_mean"] <= 0).sum())
        if negative:
            problems.append(f"H <= 0 at {negative} vertices of a sphere")
        else:
            read.append("H > 0")
    return problems, read


def validate_gltf(files):
    """The Khronos validator's verdict on each .glb: {file: (ok, text)}, or None when it is not
    installed."""
    here = Path(__file__).resolve().parent
    if not (here / "node_modules" / "gltf-validator").is_dir():
        return None
    proc = subprocess.run(
        ["node", str(here / "validate_gltf.js"), *map(str, files)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    out = {}
    for line in proc.stdout.splitlines():
        r = json.loads(line)
        text = f"{r['errors']} errors, {r['warnings']} warnings, {r['infos']} infos (generator {r['generator']})"
        if r["messages"]:
            text += ": " + "; ".join(r["messages"][:3])
        out[r["file"]] = (r["errors"] == 0, text)
    if proc.returncode not in (0, 1):
        raise RuntimeError(proc.stderr.strip())
    return out


def main(argv):
    if len(argv) >= 2 and argv[1] == "--one":
        reader, path, n = argv[2], Path(argv[3]), int(argv[4])
        got = READERS[reader][0](path, n)
        got.pop("all_mean", None)
        print(json.dumps(got))
        return 0
    if len(argv) != 2:
        print(__doc__)
        return 2
    folder = Path(argv[1])
    spec = json.loads((folder / "expect.json").read_text())
    n = spec["sample"]
    failures = 0
    available = {r: installed(r) for r in READERS}
    for reader, ok in available.items():
        if not ok:
            print(f"{reader}: skipped: not installed in {sys.executable}")
    for want in spec["files"]:
        path = folder / want["file"]
        ext = path.suffix.lower()
        for reader, (fn, exts) in READERS.items():
            if not available[reader] or ext not in exts:
                continue
            label = f"{reader:9} {want['file']:22}"
            try:
                if reader == "igl":
                    got = read_isolated(reader, path, n)
                else:
                    got = fn(path, n)
            except (Exception, SystemExit) as e:  # noqa: BLE001 - a refusal, whatever its type
                message = str(e).strip().splitlines()[-1] if str(e).strip() else type(e).__name__
                if (reader, ext) in KNOWN:
                    print(f"{label} refused (known: {KNOWN[(reader, ext)]})")
                else:
                    print(f"{label} FAIL: refused or died: {message}")
                    failures += 1
                continue
            if reader == "igl" and "all_mean" in got:
                got.pop("all_mean")
            problems, read = check(reader, ext, want, got)
            if problems:
                failures += 1
                print(f"{label} FAIL: {'; '.join(problems)} (read {', '.join(read)})")
            else:
                print(f"{label} ok: {', '.join(read)}")
    glbs = [folder / w["file"] for w in spec["files"] if w["file"].endswith(".glb")]
    if glbs:
        verdict = validate_gltf(glbs)
        if verdict is None:
            print("gltf-validator: skipped: not installed (cd scripts/readback && npm install)")
        else:
            for f in glbs:
                ok, text = verdict.get(f.name, (False, "no verdict"))
                print(f"{'validator':9} {f.name:22} {'ok' if ok else 'FAIL'}: {text}")
                failures += 0 if ok else 1
    print(f"readback: {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
