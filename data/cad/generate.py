#!/usr/bin/env python3
"""Generates the CAD-like crease corpus in data/cad/: parts made by CSG (manifold3d), remeshed
badly on purpose, written as binary little-endian PLY with float64 positions.

Run from the repository root, in the venv of data/cad/requirements.txt:

    python data/cad/generate.py            # writes data/cad/*.ply and the README's table
    python data/cad/generate.py --png DIR  # also renders each mesh to DIR/NAME.png (matplotlib)
    python data/cad/generate.py --check    # writes nothing; fails if a file or the table differs

Everything is deterministic: no random numbers are drawn at all (every "bad" refinement is
placed by a formula, so there is no seed to fix), and each mesh is put into a canonical order
(vertices sorted by position, faces sorted) before it is written, so that the bytes depend on
the geometry only, not on the order in which manifold3d (which may run in parallel) emits it.
`--check` rebuilds everything and compares it byte for byte with the committed files.
Trigonometry is Python's `math` (the C library's), never numpy's vectorised kernels, whose last
bit can differ between CPUs.

# The bad remeshing, and how each operation keeps the surface

Every operation below replaces triangles by triangles covering exactly the same point set,
with the same orientation, and inserts new vertices only on existing edges or inside existing
faces; so a closed oriented 2-manifold stays one, no face gets zero area (each new vertex is
strictly inside an edge or face, and `check_mesh` verifies it), and the geometry is the CSG
result's, faceted as it was.

* `slice_planes(axis, values)`: cuts every triangle by each plane `x_axis = c` (the new vertex
  on an edge a-b is `a + t (b - a)`, `t = (c - a_axis) / (b_axis - a_axis)`, computed once per
  edge and with its `axis` coordinate set to `c` exactly). Parallel planes a small step apart
  give long thin strips (anisotropic triangles); graded steps give non-uniform density; a plane
  passing close to an existing vertex gives a needle.
* `split_edge(a, b, ts)`: puts vertices at parameters `ts` along edge a-b and re-triangulates
  both faces of the edge as fans from their opposite corners: many `ts` make two T-like fans
  (a vertex of high valence with a fan of slivers); a `t` near 0 or 1 makes needles.
* `split_face(f, weights)`: puts a vertex at barycentric `weights` inside face `f` (1 → 3
  triangles); a vertex close to an edge makes a cap (an angle near 180°).

A point on an edge whose two ends share a coordinate keeps it exactly (`a + t·0 = a`), so an
edge lying in an axis-aligned plane stays in it; a point inside a face is snapped onto the face's
plane when that plane is one of the part's exact planes (`snap_planes`).

# Exact planes

Each part names its axis-aligned planar faces (`Part.planes`: `(axis, value)`, values that
are exact in binary64). After all operations every vertex within `SNAP_TOLERANCE` of such a
plane is set onto it exactly, and `planar_report` verifies that every face whose three vertices
share a coordinate is one of the named planes and that no face of a named plane is off it.
"""

import argparse
import hashlib
import math
import os
import sys
from dataclasses import dataclass, field

import numpy as np

import manifold3d as mf

HERE = os.path.dirname(os.path.abspath(__file__))

# A vertex this close (absolute, in the part's units, parts being 10-100 units across) to a
# named plane is snapped onto it: manifold3d computes in binary64, so a vertex meant to be on
# a plane is off it by rounding (a few ulps, ~1e-14) if at all; 1e-9 is far above that and far
# below every feature size used here (0.05 and up).
SNAP_TOLERANCE = 1e-9

# A slicing plane closer than this (relative to the edge's extent along the axis) to an edge's
# end does not split that edge: the new vertex would be that end again, up to rounding, and the
# triangles beside it would have zero area. 1e-6 keeps the sliver triangles (min angle down
# to ~1e-4°) but no zero-area ones (the workbench calls a face degenerate below a sine of 1e-12).
SLICE_END_GUARD = 1e-6

# Dihedral thresholds (degrees) the README counts edges over.
DIHEDRAL_SHARP = 40.0
DIHEDRAL_MILD = 10.0
# A needle has an angle below this (degrees), a cap an angle above CAP_DEG.
NEEDLE_DEG = 1.0
CAP_DEG = 170.0


# --------------------------------------------------------------------------------------------
# Mesh operations
# --------------------------------------------------------------------------------------------


class TriMesh:
    """A triangle mesh under construction: positions (list of [x, y, z] floats) and faces
    (list of [a, b, c] indices, counter-clockwise seen from outside)."""

    def __init__(self, positions, faces):
        self.p = [list(map(float, q)) for q in positions]
        self.f = [list(map(int, t)) for t in faces]

    @staticmethod
    def of_manifold(m):
        """The triangles of a manifold3d solid, its positions as binary64."""
        mesh = m.to_mesh64()
        vp = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
        tv = np.asarray(mesh.tri_verts, dtype=np.int64)
        return TriMesh(vp.tolist(), tv.tolist())

    def add_vertex(self, q):
        self.p.append([float(q[0]), float(q[1]), float(q[2])])
        return len(self.p) - 1

    def lerp(self, a, b, t):
        """`a + t (b - a)`, coordinate by coordinate (exact where a and b agree)."""
        pa, pb = self.p[a], self.p[b]
        return [pa[k] + t * (pb[k] - pa[k]) for k in range(3)]

    # -- slicing by axis-aligned planes --------------------------------------------------

    def slice_plane(self, axis, c):
        """Cuts every triangle by the plane `x_axis = c` (module docs)."""
        cut = {}  # undirected edge -> new vertex

        def side(v):
            s = self.p[v][axis] - c
            return 0 if s == 0 else (1 if s > 0 else -1)

        def crossing(a, b):
            key = (a, b) if a < b else (b, a)
            if key in cut:
                return cut[key]
            lo, hi = key
            da = self.p[lo][axis] - c
            db = self.p[hi][axis] - c
            t = da / (da - db)
            if t <= SLICE_END_GUARD or t >= 1 - SLICE_END_GUARD:
                cut[key] = None
                return None
            q = self.lerp(lo, hi, t)
            q[axis] = c
            cut[key] = self.add_vertex(q)
            return cut[key]

        out = []
        for tri in self.f:
            s = [side(v) for v in tri]
            # Rotate so that the lone vertex (on its own side) comes first, when there is one.
            pieces = None
            for r in range(3):
                a, b, d = tri[r], tri[(r + 1) % 3], tri[(r + 2) % 3]
                sa, sb, sd = s[r], s[(r + 1) % 3], s[(r + 2) % 3]
                if sa != 0 and sb == -sa and sd == -sa:
                    pab, pad = crossing(a, b), crossing(a, d)
                    if pab is None or pad is None:
                        pieces = None
                        # A guarded crossing: split what can be split, on the other edge only.
                        if pab is None and pad is not None:
                            pieces = [[a, b, pad], [pad, b, d]]
                        elif pad is None and pab is not None:
                            pieces = [[a, pab, d], [pab, b, d]]
                        else:
                            pieces = [tri]
                    else:
                        # The quadrilateral pab-b-d-pad is split along its shorter diagonal.
                        if dist2(self.p[pab], self.p[d]) <= dist2(self.p[b], self.p[pad]):
                            pieces = [[a, pab, pad], [pab, b, d], [pab, d, pad]]
                        else:
                            pieces = [[a, pab, pad], [pab, b, pad], [b, d, pad]]
                    break
                if sa == 0 and sb != 0 and sd == -sb:
                    pbd = crossing(b, d)
                    pieces = [tri] if pbd is None else [[a, b, pbd], [a, pbd, d]]
                    break
            out.extend(pieces if pieces is not None else [tri])
        self.f = out

    def slice_planes(self, axis, values):
        for c in values:
            self.slice_plane(axis, float(c))

    # -- fans and caps -----------------------------------------------------------------------

    def faces_of_edge(self, a, b):
        """The face running a→b and the one running b→a (indices), or an error."""
        fwd = bwd = None
        for i, t in enumerate(self.f):
            for r in range(3):
                if t[r] == a and t[(r + 1) % 3] == b:
                    fwd = i
                if t[r] == b and t[(r + 1) % 3] == a:
                    bwd = i
        if fwd is None:
            raise ValueError(f"no face runs along edge {a}-{b}")
        return fwd, bwd

    def split_edge(self, a, b, ts):
        """Inserts vertices at increasing parameters `ts` in (0, 1) along edge a→b and fans
        both faces of the edge from their opposite corners (module docs)."""
        ts = sorted(ts)
        assert all(0 < t < 1 for t in ts)
        fwd, bwd = self.faces_of_edge(a, b)
        new = [self.add_vertex(self.lerp(a, b, t)) for t in ts]
        chain = [a] + new + [b]
        replaced = {}
        for fi, run in ((fwd, chain), (bwd, chain[::-1])):
            if fi is None:
                continue
            t = self.f[fi]
            r = t.index(run[0])
            opp = t[(r + 2) % 3]
            replaced[fi] = [[run[i], run[i + 1], opp] for i in range(len(run) - 1)]
        out = []
        for i, t in enumerate(self.f):
            out.extend(replaced.get(i, [t]))
        self.f = out
        return new

    def split_face(self, fi, w):
        """Inserts a vertex at barycentric weights `w` (positive, summing to 1) in face `fi`."""
        assert all(x > 0 for x in w)
        a, b, c = self.f[fi]
        q = [w[0] * self.p[a][k] + w[1] * self.p[b][k] + w[2] * self.p[c][k] for k in range(3)]
        v = self.add_vertex(q)
        self.f[fi] = [a, b, v]
        self.f.append([b, c, v])
        self.f.append([c, a, v])
        return v

    # -- queries -------------------------------------------------------------------------

    def edge_near(self, q, predicate=None):
        """The edge (a, b), running a→b in some face, whose midpoint is nearest to q."""
        best, best_d = None, math.inf
        for t in self.f:
            for r in range(3):
                a, b = t[r], t[(r + 1) % 3]
                if predicate is not None and not predicate(self.p[a], self.p[b]):
                    continue
                m = [(self.p[a][k] + self.p[b][k]) / 2 for k in range(3)]
                d = dist2(m, q)
                if d < best_d:
                    best, best_d = (a, b), d
        return best

    def face_near(self, q, predicate=None):
        """The face whose centroid is nearest to q (among those satisfying `predicate`)."""
        best, best_d = None, math.inf
        for i, t in enumerate(self.f):
            pts = [self.p[v] for v in t]
            if predicate is not None and not predicate(pts):
                continue
            m = [sum(x[k] for x in pts) / 3 for k in range(3)]
            d = dist2(m, q)
            if d < best_d:
                best, best_d = i, d
        return best

    def remove_faces(self, predicate):
        """Drops every face whose three corner positions satisfy `predicate`; returns the count."""
        keep = [t for t in self.f if not predicate([self.p[v] for v in t])]
        n = len(self.f) - len(keep)
        self.f = keep
        return n

    # -- finishing -----------------------------------------------------------------------

    def snap_planes(self, planes):
        """Sets every coordinate within SNAP_TOLERANCE of a named plane onto it exactly."""
        for axis, c in planes:
            for q in self.p:
                if q[axis] != c and abs(q[axis] - c) <= SNAP_TOLERANCE:
                    q[axis] = c

    def canonical(self):
        """Drops unused vertices, sorts vertices by position and faces by index triple (each
        face rotated to start at its smallest index, keeping its orientation)."""
        used = sorted({v for t in self.f for v in t})
        order = sorted(used, key=lambda v: (self.p[v][0], self.p[v][1], self.p[v][2]))
        remap = {v: i for i, v in enumerate(order)}
        p = [self.p[v] for v in order]
        faces = []
        for t in self.f:
            t = [remap[v] for v in t]
            r = t.index(min(t))
            faces.append(t[r:] + t[:r])
        faces.sort()
        self.p, self.f = p, faces


def dist2(a, b):
    return sum((a[k] - b[k]) ** 2 for k in range(3))


def graded(lo, hi, n, ratio):
    """n values strictly between lo and hi, steps growing geometrically by `ratio` (dense at lo)."""
    steps = [ratio**i for i in range(n + 1)]
    total = sum(steps)
    out, acc = [], 0.0
    for s in steps[:-1]:
        acc += s
        out.append(lo + (hi - lo) * acc / total)
    return out


def uniform(lo, hi, n):
    """n values strictly between lo and hi, evenly spaced."""
    return [lo + (hi - lo) * (i + 1) / (n + 1) for i in range(n)]


# --------------------------------------------------------------------------------------------
# Measurements (the README's table)
# --------------------------------------------------------------------------------------------


def angle_between(u, v):
    """∠(u, v) = atan2(|u × v|, u · v), accurate near 0 and π."""
    c = np.cross(u, v)
    return np.arctan2(np.linalg.norm(c, axis=-1), np.sum(u * v, axis=-1))


def stats(p, f):
    """What the README reports about a mesh (positions p: V×3, faces f: F×3, both arrays).

    * angles of a face: at each corner, ∠ between its two edges (`angle_between`), degrees;
      a needle has its smallest angle under NEEDLE_DEG, a cap its largest over CAP_DEG;
    * aspect ratio: the longest edge over the shortest altitude, L² / (2 A) (an equilateral
      triangle has 2/√3 ≈ 1.155, a needle or a cap a large one);
    * dihedral angle of an edge with two faces: ∠ between the unit face normals (0 flat), the
      same rule as the workbench's `mesh::features::Features::detect`;
    * boundary edges have one face, non-manifold edges three or more, misoriented edges two
      faces running the same way; components join faces across edges.
    """
    a, b, c = p[f[:, 0]], p[f[:, 1]], p[f[:, 2]]
    ang = np.degrees(
        np.stack(
            [angle_between(b - a, c - a), angle_between(c - b, a - b), angle_between(a - c, b - c)],
            axis=1,
        )
    )
    n = np.cross(b - a, c - a)
    area2 = np.linalg.norm(n, axis=1)
    lmax = np.max(
        np.stack(
            [
                np.linalg.norm(b - a, axis=1),
                np.linalg.norm(c - b, axis=1),
                np.linalg.norm(a - c, axis=1),
            ],
            axis=1,
        ),
        axis=1,
    )
    aspect = lmax**2 / area2
    unit = n / area2[:, None]

    # Edges: directed half-edges grouped by undirected key.
    half = {}
    for i, t in enumerate(f.tolist()):
        for r in range(3):
            u, v = t[r], t[(r + 1) % 3]
            half.setdefault((min(u, v), max(u, v)), []).append((i, u < v))
    boundary = nonmanifold = misoriented = 0
    dihedral = []
    parent = list(range(len(f)))

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for key, hs in half.items():
        if len(hs) == 1:
            boundary += 1
            continue
        if len(hs) > 2:
            nonmanifold += 1
            continue
        (f1, d1), (f2, d2) = hs
        if d1 == d2:
            misoriented += 1
        dihedral.append((f1, f2))
        r1, r2 = find(f1), find(f2)
        if r1 != r2:
            parent[r1] = r2
    pairs = np.asarray(dihedral, dtype=np.int64).reshape(-1, 2)
    dih = np.degrees(angle_between(unit[pairs[:, 0]], unit[pairs[:, 1]]))
    components = len({find(i) for i in range(len(f))})
    return {
        "vertices": len(p),
        "faces": len(f),
        "edges": len(half),
        "sharp": int(np.sum(dih > DIHEDRAL_SHARP)),
        "mild": int(np.sum(dih > DIHEDRAL_MILD)),
        "min_angle": float(np.min(ang)),
        "max_angle": float(np.max(ang)),
        "max_aspect": float(np.max(aspect)),
        "needles": int(np.sum(np.min(ang, axis=1) < NEEDLE_DEG)),
        "caps": int(np.sum(np.max(ang, axis=1) > CAP_DEG)),
        "boundary": boundary,
        "nonmanifold": nonmanifold,
        "misoriented": misoriented,
        "components": components,
        "min_area2": float(np.min(area2 / (lmax * lmax))),
        "max_valence": int(np.max(np.bincount(f.ravel()))),
    }


def signed_volume(p, f):
    a, b, c = p[f[:, 0]], p[f[:, 1]], p[f[:, 2]]
    return float(np.sum(np.einsum("ij,ij->i", a, np.cross(b, c)))) / 6.0


def planar_report(p, f, planes):
    """Checks the exact-plane claim: every face within SNAP_TOLERANCE of a named plane lies on
    it exactly, and every named plane has faces. Returns the number of faces on named planes
    and, for axis-aligned planes that are not named but that faces lie on exactly all the same
    (a gear's tooth tip on the x axis, symmetric in y, for one), their face counts."""
    named = set(planes)
    on = 0
    extra = {}
    for t in f.tolist():
        q = p[t]
        for axis in range(3):
            vals = q[:, axis]
            if vals[0] == vals[1] == vals[2]:
                key = (axis, float(vals[0]))
                if key in named:
                    on += 1
                else:
                    extra[key] = extra.get(key, 0) + 1
            else:
                for ax, c in planes:
                    if ax == axis and np.all(np.abs(vals - c) <= SNAP_TOLERANCE):
                        raise AssertionError(f"face {t} is near plane {(ax, c)} but not on it")
    counts = {}
    for t in f.tolist():
        for axis, c in planes:
            if all(p[v][axis] == c for v in t):
                counts[(axis, c)] = counts.get((axis, c), 0) + 1
    for key in planes:
        if key not in counts:
            raise AssertionError(f"no face lies on the named plane {key}")
    return on, extra


def check_mesh(name, p, f, st, part):
    """The corpus's promises: no zero-area face, no non-manifold or misoriented edge, closed
    unless the part is open, outward (positive volume) when closed."""
    problems = []
    if st["nonmanifold"] or st["misoriented"]:
        problems.append(f"{st['nonmanifold']} non-manifold, {st['misoriented']} misoriented edges")
    # The workbench's zero-area rule is a sine of 1e-12; stay a thousand times above it.
    if st["min_area2"] <= 1e-9:
        problems.append(f"a face of (almost) zero area: sine {st['min_area2']:.3g}")
    if part.open != (st["boundary"] > 0):
        problems.append(f"boundary edges {st['boundary']}, open = {part.open}")
    if not part.open and signed_volume(p, f) <= 0:
        problems.append("negative volume (inward winding)")
    if problems:
        raise AssertionError(f"{name}: " + "; ".join(problems))


# --------------------------------------------------------------------------------------------
# PLY
# --------------------------------------------------------------------------------------------


def ply_bytes(p, f, name):
    header = (
        "ply\n"
        "format binary_little_endian 1.0\n"
        f"comment {name}: generated by data/cad/generate.py, CC0 1.0\n"
        f"element vertex {len(p)}\n"
        "property double x\nproperty double y\nproperty double z\n"
        f"element face {len(f)}\n"
        "property list uchar int vertex_indices\n"
        "end_header\n"
    ).encode("ascii")
    verts = np.asarray(p, dtype="<f8").tobytes()
    rec = np.zeros(len(f), dtype=[("n", "u1"), ("i", "<i4", (3,))])
    rec["n"] = 3
    rec["i"] = np.asarray(f, dtype=np.int64)
    return header + verts + rec.tobytes()


# --------------------------------------------------------------------------------------------
# The parts
# --------------------------------------------------------------------------------------------


@dataclass
class Part:
    """A corpus mesh: its builder, the exact planes it has, and what was done to it."""

    name: str
    what: str
    bad: str
    planes: list = field(default_factory=list)
    open: bool = False


PARTS = []


def part(name, what, bad, planes=(), open=False):
    def register(build):
        PARTS.append((Part(name, what, bad, list(planes), open), build))
        return build

    return register


def box_planes(x0, x1, y0, y1, z0, z1):
    return [(0, x0), (0, x1), (1, y0), (1, y1), (2, z0), (2, z1)]


def cube(x0, y0, z0, x1, y1, z1):
    """The axis-aligned box [x0, x1] × [y0, y1] × [z0, z1] (exact corners)."""
    return mf.Manifold.cube((x1 - x0, y1 - y0, z1 - z0)).translate((x0, y0, z0))


def zcyl(cx, cy, z0, z1, r, n, r_top=None):
    """A cylinder (or frustum, radius r at z0 and r_top at z1) of axis x = cx, y = cy."""
    top = r if r_top is None else r_top
    return mf.Manifold.cylinder(z1 - z0, r, top, n).translate((cx, cy, z0))


@part(
    "box",
    "a plain box 40 × 30 × 20, meshed by hand, not by CSG",
    "anisotropic grids on the sides and bottom (columns in x graded by 1.12, 0.147 wide at "
    "x = 0 to 4.42 at x = 40, against rows 4 high in z and 12 and 18 wide in y, each quad cut "
    "along one diagonal); non-uniform density (dense near x = 0); the top face is one fan of 66 "
    "slivers from an interior vertex 0.05 from the edge y = 0 (needles toward the far sides, "
    "caps beside the near one)",
    planes=box_planes(0.0, 40.0, 0.0, 30.0, 0.0, 20.0),
)
def build_box():
    xs = [0.0] + graded(0.0, 40.0, 30, 1.12) + [40.0]
    ys = [0.0, 12.0, 30.0]
    zs = [0.0] + uniform(0.0, 20.0, 4) + [20.0]
    index, pos, faces = {}, [], []

    def vid(q):
        q = tuple(float(x) for x in q)
        if q not in index:
            index[q] = len(pos)
            pos.append(list(q))
        return index[q]

    def grid(point, us, vs):
        """Quads over us × vs, point(u, v) → position; (u, v) counter-clockwise seen from
        outside; each quad split along its p00-p11 diagonal."""
        for i in range(len(us) - 1):
            for j in range(len(vs) - 1):
                p00, p10 = vid(point(us[i], vs[j])), vid(point(us[i + 1], vs[j]))
                p11, p01 = vid(point(us[i + 1], vs[j + 1])), vid(point(us[i], vs[j + 1]))
                faces.append([p00, p10, p11])
                faces.append([p00, p11, p01])

    x0, x1, y0, y1, z0, z1 = 0.0, 40.0, 0.0, 30.0, 0.0, 20.0
    # Outward normal = u × v for each face's parametrisation.
    grid(lambda u, v: (x1, u, v), ys, zs)  # +x: y × z
    grid(lambda u, v: (x0, v, u), zs, ys)  # -x: z × y
    grid(lambda u, v: (v, y1, u), zs, xs)  # +y: z × x
    grid(lambda u, v: (u, y0, v), xs, zs)  # -y: x × z
    grid(lambda u, v: (v, u, z0), ys, xs)  # -z: y × x
    # Top: the boundary ring of z = z1, counter-clockwise seen from above, fanned from c.
    ring = (
        [(x, y0) for x in xs[:-1]]
        + [(x1, y) for y in ys[:-1]]
        + [(x, y1) for x in xs[::-1][:-1]]
        + [(x0, y) for y in ys[::-1][:-1]]
    )
    c = vid((1.5, 0.05, z1))
    ids = [vid((x, y, z1)) for x, y in ring]
    for i in range(len(ids)):
        faces.append([ids[i], ids[(i + 1) % len(ids)], c])
    return TriMesh(pos, faces)


@part(
    "box_fillet",
    "a box 40 × 30 × 16 whose top edges and vertical edges are filleted (radius 5: the hull of "
    "four spheres at the top corners and four cylinders below them); the fillets meet the flat "
    "faces tangentially (G1, not C2); the bottom rim is a sharp 90° edge",
    "the hull's own long slivers across the flat faces and along the fillets; 13 slicing "
    "planes x = const (2.86 apart) cutting them into needles; a T-like fan (24 vertices "
    "on one edge of the top face, 25 slivers on each side)",
    planes=box_planes(0.0, 40.0, 0.0, 30.0, 0.0, 16.0),
)
def build_box_fillet():
    r, n = 5.0, 32
    pieces = []
    for cx in (r, 40.0 - r):
        for cy in (r, 30.0 - r):
            pieces.append(mf.Manifold.sphere(r, n).translate((cx, cy, 16.0 - r)))
            pieces.append(zcyl(cx, cy, 0.0, 16.0 - r, r, n))
    m = TriMesh.of_manifold(mf.Manifold.batch_hull(pieces))
    m.snap_planes(box_planes(0.0, 40.0, 0.0, 30.0, 0.0, 16.0))
    m.slice_planes(0, uniform(0.0, 40.0, 13))
    a, b = m.edge_near((20.0, 15.0, 16.0), lambda p, q: p[2] == q[2] == 16.0)
    m.split_edge(a, b, uniform(0.0, 1.0, 24))
    return m


@part(
    "cylinder_chamfer",
    "a cylinder of radius 12 and height 30 (48 facets) with 2 × 2 chamfers (45°) on both rims, "
    "revolved from its profile",
    "9 slicing planes z = const graded by 1.6 (rings 0.143 high above the bottom chamfer to "
    "9.84 below the top one; the facets are 1.57 wide): non-uniform density; 3 planes x = const "
    "cutting facets and end discs obliquely (needles); the end discs are fans of 48 around "
    "their centres (as revolved); caps inserted beside 6 edges of the top disc",
    planes=[(2, 0.0), (2, 30.0)],
)
def build_cylinder_chamfer():
    R, H, c = 12.0, 30.0, 2.0
    profile = [(0.0, 0.0), (R - c, 0.0), (R, c), (R, H - c), (R - c, H), (0.0, H)]
    m = TriMesh.of_manifold(mf.CrossSection([profile]).revolve(48))
    m.snap_planes([(2, 0.0), (2, 30.0)])
    m.slice_planes(2, graded(c, H - c, 9, 1.6))
    m.slice_planes(0, [-7.3, 0.55, 9.7])
    add_caps(m, [(R * 0.5 * math.cos(k), R * 0.5 * math.sin(k), H) for k in range(6)], 2, H)
    return m


def add_caps(m, near, axis, value, height=0.02):
    """For each point, the face of the plane x_axis = value nearest to it gets a vertex at
    `height` (barycentric weight of its third corner) above its longest edge's midpoint: the
    angle there is close to 180° (a cap)."""
    for q in near:
        fi = m.face_near(q, lambda pts: all(x[axis] == value for x in pts))
        t = m.f[fi]
        lengths = [dist2(m.p[t[r]], m.p[t[(r + 1) % 3]]) for r in range(3)]
        r = lengths.index(max(lengths))
        w = [0.0, 0.0, 0.0]
        w[r] = w[(r + 1) % 3] = (1.0 - height) / 2
        w[(r + 2) % 3] = height
        v = m.split_face(fi, w)
        m.p[v][axis] = value


@part(
    "plate_holes",
    "a plate 60 × 40 × 6 with six through holes of radius 2 to 5 (24 to 40 facets), one of "
    "them 0.6 from the plate's edge",
    "the booleans' fans of slivers from the plate's corners to the holes; 12 slicing planes "
    "y = const graded by 1.35 (0.289 apart at y = 0 to 10.6 at y = 40) and 3 planes x = const "
    "(needles, non-uniform density); caps inserted beside 8 edges of the top face",
    planes=box_planes(0.0, 60.0, 0.0, 40.0, 0.0, 6.0),
)
def build_plate_holes():
    plate = cube(0.0, 0.0, 0.0, 60.0, 40.0, 6.0)
    holes = [
        (10.0, 10.0, 3.0, 28),
        (30.0, 12.0, 5.0, 40),
        (50.0, 9.0, 2.5, 24),
        (12.0, 30.0, 4.0, 32),
        (31.0, 28.0, 2.0, 24),
        (55.4, 30.0, 4.0, 32),  # 0.6 from x = 60
    ]
    for cx, cy, r, n in holes:
        plate = plate - zcyl(cx, cy, -1.0, 7.0, r, n)
    m = TriMesh.of_manifold(plate)
    m.snap_planes(box_planes(0.0, 60.0, 0.0, 40.0, 0.0, 6.0))
    m.slice_planes(1, graded(0.0, 40.0, 12, 1.35))
    m.slice_planes(0, [15.2, 37.1, 58.8])
    add_caps(m, [(6.0 + 7.0 * k, 20.0 + 3.0 * (k % 3), 6.0) for k in range(8)], 2, 6.0)
    return m


@part(
    "boss",
    "a plate 50 × 50 × 8 with a cylindrical boss (radius 10, 48 facets, 12 high) on top and a "
    "hole of radius 5 (32 facets) through boss and plate",
    "8 slicing planes z = const graded by 1.5 on the boss wall and in the hole (0.16 apart "
    "at the boss's foot to 4.11 at its top, facets 1.3 wide): anisotropic rings; 4 planes "
    "x = const; a T-like fan (30 vertices on one edge of the boss's top annulus)",
    planes=box_planes(0.0, 50.0, 0.0, 50.0, 0.0, 8.0) + [(2, 20.0)],
)
def build_boss():
    solid = cube(0.0, 0.0, 0.0, 50.0, 50.0, 8.0) + zcyl(25.0, 25.0, 8.0, 20.0, 10.0, 48)
    solid = solid - zcyl(25.0, 25.0, -1.0, 21.0, 5.0, 32)
    m = TriMesh.of_manifold(solid)
    planes = box_planes(0.0, 50.0, 0.0, 50.0, 0.0, 8.0) + [(2, 20.0)]
    m.snap_planes(planes)
    m.slice_planes(2, graded(8.0, 20.0, 8, 1.5))
    m.slice_planes(0, uniform(0.0, 50.0, 4))
    a, b = m.edge_near((25.0, 25.0 + 7.5, 20.0), lambda p, q: p[2] == q[2] == 20.0)
    m.split_edge(a, b, uniform(0.0, 1.0, 30))
    return m


def gear_profile(teeth, module, pressure_deg, flank_points):
    """The outline of a spur gear, counter-clockwise: involute flanks from the base (or root)
    circle to the tip circle, tip and root arcs as straight chords.

    The involute of the base circle r_b, unrolled by angle s: (r_b (cos s + s sin s),
    r_b (sin s − s cos s)), at radius r_b √(1 + s²); a tooth is centred on its axis with half
    thickness π m / 4 on the pitch circle r_p = m z / 2, where the involute's polar angle is
    inv(α) = tan α − α (α the pressure angle)."""
    rp = module * teeth / 2.0
    rb = rp * math.cos(math.radians(pressure_deg))
    ra = rp + module
    rf = rp - 1.25 * module
    alpha = math.radians(pressure_deg)
    inv_alpha = math.tan(alpha) - alpha
    half = math.pi / (2 * teeth) + inv_alpha  # half the tooth's angular width at the base
    s_max = math.sqrt((ra / rb) ** 2 - 1.0)
    pts = []
    for k in range(teeth):
        axis = 2 * math.pi * k / teeth
        flank = []
        for i in range(flank_points):
            s = s_max * i / (flank_points - 1)
            x = rb * (math.cos(s) + s * math.sin(s))
            y = rb * (math.sin(s) - s * math.cos(s))
            flank.append((math.hypot(x, y), math.atan2(y, x)))
        # Right flank (clockwise side of the tooth axis), root to tip, then left flank back.
        right = [(r, axis - half + t) for r, t in flank]
        left = [(r, axis + half - t) for r, t in reversed(flank)]
        root_a = axis - math.pi / teeth
        pts.append((rf, root_a))
        pts.append((rf, axis - half))
        pts.extend(right)
        pts.extend(left)
        pts.append((rf, axis + half))
    return [(r * math.cos(t), r * math.sin(t)) for r, t in pts]


@part(
    "gear",
    "a spur gear: 17 teeth, module 2, 20° pressure angle, involute flanks of 7 points, "
    "extruded 10 high, with a bore of radius 5 (32 facets) and a keyway 3 wide and 1 deep "
    "beyond the bore (its floor the plane x = 6)",
    "the triangulator's fans of needles on both end faces; 3 slicing planes z = const graded "
    "by 2 (0.667 below the top face to 5.33 above the bottom): thin strips along the flanks",
    planes=[(2, 0.0), (2, 10.0), (0, 6.0), (1, -1.5), (1, 1.5)],
)
def build_gear():
    outline = gear_profile(17, 2.0, 20.0, 7)
    bore = mf.CrossSection.circle(5.0, 32)
    key = mf.CrossSection.square((1.5, 3.0)).translate((4.5, -1.5))
    section = mf.CrossSection([outline]) - bore - key
    m = TriMesh.of_manifold(section.extrude(10.0))
    m.slice_planes(2, graded(10.0, 0.0, 3, 2.0))
    return m


@part(
    "swiss_cheese",
    "a box 40 × 30 × 20 with eleven spherical holes of radius 3 to 8 (geodesic spheres, 24 "
    "segments) cut, each breaking the surface (through faces, edges and a corner; some "
    "overlap)",
    "the booleans' slivers: the flat faces are fans from their corners to the sphere cuts; "
    "5 slicing planes x = const (6.67 apart)",
    planes=box_planes(0.0, 40.0, 0.0, 30.0, 0.0, 20.0),
)
def build_swiss_cheese():
    solid = cube(0.0, 0.0, 0.0, 40.0, 30.0, 20.0)
    spheres = [
        (8.0, 8.0, 20.0, 5.0),  # through the top
        (20.0, 15.0, 21.0, 4.0),
        (31.0, 22.0, 18.0, 6.0),
        (40.0, 15.0, 10.0, 7.0),  # through the +x side
        (0.0, 0.0, 0.0, 8.0),  # a corner
        (20.0, 0.0, 10.0, 5.5),  # through -y
        (25.0, 3.0, 12.0, 4.0),  # overlapping the previous
        (12.0, 30.0, 8.0, 4.5),  # through +y
        (30.0, 30.0, 20.0, 6.0),  # an edge
        (15.0, 20.0, -1.0, 3.0),  # through the bottom
        (34.0, 9.0, 2.5, 3.5),  # near the bottom edge
    ]
    for cx, cy, cz, r in spheres:
        solid = solid - mf.Manifold.sphere(r, 24).translate((cx, cy, cz))
    m = TriMesh.of_manifold(solid)
    m.snap_planes(box_planes(0.0, 40.0, 0.0, 30.0, 0.0, 20.0))
    m.slice_planes(0, uniform(0.0, 40.0, 5))
    return m


@part(
    "pipe_joint",
    "a hollow tee: a pipe along x (outer radius 8, inner 6, length 60) and a branch along z "
    "(outer 6, inner 4.5, up to z = 25), unioned at right angles, 40/32 facets",
    "the facets run the whole pipe (60 long, 1.26 wide); 11 slicing planes x = const graded "
    "by 1.6 from the branch (1.83 apart there to 12 at the ends); a T-like fan (20 vertices "
    "on one edge of the branch's end annulus)",
    planes=[(0, -30.0), (0, 30.0), (2, 25.0)],
)
def build_pipe_joint():
    def xcyl(r, n, x0, x1):
        along_z = mf.Manifold.cylinder(x1 - x0, r, -1.0, n)
        return along_z.rotate((0.0, 90.0, 0.0)).translate((x0, 0.0, 0.0))

    outer = xcyl(8.0, 40, -30.0, 30.0) + zcyl(0.0, 0.0, 0.0, 25.0, 6.0, 32)
    inner = xcyl(6.0, 40, -31.0, 31.0) + zcyl(0.0, 0.0, 0.0, 26.0, 4.5, 32)
    m = TriMesh.of_manifold(outer - inner)
    planes = [(0, -30.0), (0, 30.0), (2, 25.0)]
    m.snap_planes(planes)
    m.slice_planes(0, graded(0.0, -30.0, 5, 1.6) + graded(0.0, 30.0, 5, 1.6) + [0.37])
    a, b = m.edge_near((0.0, 5.25, 25.0), lambda p, q: p[2] == q[2] == 25.0)
    m.split_edge(a, b, uniform(0.0, 1.0, 20))
    return m


@part(
    "open_bracket",
    "an L-bracket (base 40 × 30 × 5, upright 5 × 30 × 35) with two holes (radius 3) in the "
    "base and one (radius 4) in the upright, its bottom face z = 0 removed: an open mesh whose "
    "boundary runs along the creases of the bottom rim and around the two holes' ends",
    "9 slicing planes y = const 3 apart (long strips along x and z); the removed face leaves "
    "the boundary meeting the creases of the sides at the bottom corners",
    planes=box_planes(0.0, 40.0, 0.0, 30.0, 0.0, 35.0)[:4] + [(2, 35.0), (0, 5.0), (2, 5.0)],
    open=True,
)
def build_open_bracket():
    solid = cube(0.0, 0.0, 0.0, 40.0, 30.0, 5.0) + cube(0.0, 0.0, 0.0, 5.0, 30.0, 35.0)
    solid = solid - zcyl(22.0, 8.0, -1.0, 6.0, 3.0, 24) - zcyl(30.0, 21.0, -1.0, 6.0, 3.0, 24)
    solid = solid - mf.Manifold.cylinder(8.0, 4.0, -1.0, 32).rotate((0.0, 90.0, 0.0)).translate(
        (-1.0, 15.0, 24.0)
    )
    m = TriMesh.of_manifold(solid)
    m.snap_planes(box_planes(0.0, 40.0, 0.0, 30.0, 0.0, 35.0) + [(0, 5.0), (2, 5.0)])
    m.slice_planes(1, uniform(0.0, 30.0, 9))
    m.remove_faces(lambda pts: all(x[2] == 0.0 for x in pts))
    return m


@part(
    "two_parts",
    "two disjoint parts in one file: a hexagonal nut (16 across flats, 8 high, bore radius 4.5, "
    "top outer rim chamfered by a cone) and a washer (radius 5 to 10, 2 thick) beside it",
    "3 slicing planes y = const through both; a T-like fan (16 vertices on one edge of the "
    "washer's top)",
    planes=[(2, 0.0), (2, 8.0), (2, 2.0)],
)
def build_two_parts():
    circumradius = 9.2376043070340135  # 8 / cos 30°: 16 across flats
    hexagon = [
        (circumradius * math.cos(math.pi * k / 3), circumradius * math.sin(math.pi * k / 3))
        for k in range(6)
    ]
    nut = mf.CrossSection([hexagon]).extrude(8.0)
    # The chamfer: keep what is inside a cone whose surface meets the top face at radius 7.6.
    # Turned by half a facet so that no cone edge runs through a corner of the hexagon.
    nut = nut ^ zcyl(0.0, 0.0, -0.01, 8.0, 7.6 + 8.01, 48, r_top=7.6).rotate((0.0, 0.0, 3.75))
    nut = nut - zcyl(0.0, 0.0, -1.0, 9.0, 4.5, 32)
    washer = zcyl(25.0, 0.0, 0.0, 2.0, 10.0, 48) - zcyl(25.0, 0.0, -1.0, 3.0, 5.0, 32)
    m = TriMesh.of_manifold(nut + washer)
    m.snap_planes([(2, 0.0), (2, 8.0), (2, 2.0)])
    m.slice_planes(1, [-6.1, 2.7, 7.9])
    a, b = m.edge_near((25.0, 7.5, 2.0), lambda p, q: p[2] == q[2] == 2.0)
    m.split_edge(a, b, uniform(0.0, 1.0, 16))
    return m


# --------------------------------------------------------------------------------------------
# Driver
# --------------------------------------------------------------------------------------------

TABLE_BEGIN = "<!-- begin generated: data/cad/generate.py writes this section -->"
TABLE_END = "<!-- end generated -->"


def fmt_angle(x):
    return f"{x:.3g}" if x < 1 else f"{x:.2f}"


def plane_text(planes):
    names = "xyz"
    return ", ".join(f"{names[a]} = {c:g}" for a, c in planes)


def readme_section(rows):
    out = [
        TABLE_BEGIN,
        "",
        "| mesh | faces | vertices | edges | dihedral > 40° | dihedral > 10° | min angle (°) | "
        "max angle (°) | max aspect | needles (< 1°) | caps (> 170°) | max valence | "
        "boundary edges | closed | components | faces on exact planes | bytes |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|",
    ]
    for part, st, on_planes, size in rows:
        out.append(
            f"| `{part.name}.ply` | {st['faces']} | {st['vertices']} | {st['edges']} | "
            f"{st['sharp']} | {st['mild']} | {fmt_angle(st['min_angle'])} | "
            f"{st['max_angle']:.3f} | {st['max_aspect']:.3g} | {st['needles']} | {st['caps']} | "
            f"{st['max_valence']} | {st['boundary']} | {'open' if st['boundary'] else 'closed'} | "
            f"{st['components']} | {on_planes[0]} | {size} |"
        )
    total = sum(r[3] for r in rows)
    out += ["", f"Total: {total} bytes in {len(rows)} files.", "", "### The meshes", ""]
    for part, st, on_planes, size in rows:
        out.append(f"- **`{part.name}.ply`**: {part.what}.")
        out.append(f"  Remeshed badly: {part.bad}.")
        if part.planes:
            out.append(
                f"  Exactly planar faces (every vertex's coordinate equal to the plane's in "
                f"binary64): {plane_text(part.planes)} ({on_planes[0]} faces)."
            )
        if on_planes[1]:
            out.append(
                f"  Also exactly flat (not named, found by the check): "
                f"{plane_text(sorted(on_planes[1]))} ({sum(on_planes[1].values())} faces)."
            )
    out += ["", TABLE_END]
    return "\n".join(out) + "\n"


def build_all():
    rows, files, meshes = [], {}, {}
    for part, build in PARTS:
        m = build()
        m.snap_planes(part.planes)
        m.canonical()
        p = np.asarray(m.p, dtype=np.float64)
        f = np.asarray(m.f, dtype=np.int64)
        st = stats(p, f)
        check_mesh(part.name, p, f, st, part)
        on_planes, extra = planar_report(p, f, part.planes)
        data = ply_bytes(p, f, part.name)
        files[part.name + ".ply"] = data
        rows.append((part, st, (on_planes, extra), len(data)))
        meshes[part.name] = (p, f)
    return rows, files, meshes


def splice_readme(text, section):
    i, j = text.find(TABLE_BEGIN), text.find(TABLE_END)
    if i < 0 or j < 0:
        raise SystemExit(f"README.md lacks the generated-section markers ({TABLE_BEGIN!r})")
    return text[:i] + section + text[j + len(TABLE_END) + 1 :]


def render(path, p, f, title):
    """Two views of the mesh, faces shaded by normal, edges drawn: the triangulation shows."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    tri = p[f]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.linalg.norm(n, axis=1)[:, None]
    fig = plt.figure(figsize=(12, 6), dpi=110)
    lo, hi = p.min(axis=0), p.max(axis=0)
    ctr, half = (lo + hi) / 2, (hi - lo).max() / 2
    for k, (elev, azim) in enumerate(((28, -60), (-25, 125))):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        # Back faces are culled: matplotlib sorts faces by depth, not pixels, and a back face
        # drawn over a front one would look like a hole.
        e, a = math.radians(elev), math.radians(azim)
        eye = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
        front = n @ eye > 0
        # A head light, turned a little up and to the left so that parallel faces differ.
        light = eye + np.array([-0.3 * math.sin(a), 0.3 * math.cos(a), 0.4])
        shade = 0.25 + 0.7 * np.clip(n @ (light / np.linalg.norm(light)), 0, 1)
        col = Poly3DCollection(tri[front], linewidths=0.15, edgecolors=(0.1, 0.1, 0.1, 0.6))
        col.set_facecolor(np.stack([shade * 0.55, shade * 0.7, shade * 0.95], axis=1)[front])
        ax.add_collection3d(col)
        for i, a in enumerate("xyz"):
            getattr(ax, f"set_{a}lim")(ctr[i] - half, ctr[i] + half)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=elev, azim=azim)
        ax.set_title(f"{title} (elev {elev}, azim {azim})")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--png", metavar="DIR", help="also render each mesh to DIR/NAME.png")
    ap.add_argument("--check", action="store_true", help="write nothing; fail on any difference")
    args = ap.parse_args()
    rows, files, meshes = build_all()
    for part, st, on_planes, size in rows:
        print(
            f"{part.name:17s} F {st['faces']:6d} V {st['vertices']:6d} >40° {st['sharp']:5d} "
            f">10° {st['mild']:5d} min {st['min_angle']:9.4g}° max {st['max_angle']:7.3f}° "
            f"aspect {st['max_aspect']:9.4g} needles {st['needles']:5d} caps {st['caps']:4d} "
            f"val {st['max_valence']:3d} bnd {st['boundary']:4d} comp {st['components']} "
            f"planar {on_planes[0]:5d}+{sum(on_planes[1].values())} {size:7d} B"
        )
    total = sum(r[3] for r in rows)
    print(f"total {total} bytes")
    readme_path = os.path.join(HERE, "README.md")
    with open(readme_path, encoding="utf-8") as fh:
        readme = fh.read()
    new_readme = splice_readme(readme, readme_section(rows))
    if args.check:
        bad = [n for n, d in files.items() if not os.path.exists(os.path.join(HERE, n))
               or open(os.path.join(HERE, n), "rb").read() != d]
        if new_readme != readme:
            bad.append("README.md")
        for n, d in files.items():
            print(f"{hashlib.sha256(d).hexdigest()[:16]}  {n}")
        if bad:
            raise SystemExit("differs from what generate.py makes: " + ", ".join(bad))
        print("every file is as generate.py makes it")
    else:
        for n, d in files.items():
            with open(os.path.join(HERE, n), "wb") as fh:
                fh.write(d)
        with open(readme_path, "w", encoding="utf-8") as fh:
            fh.write(new_readme)
    if args.png:
        os.makedirs(args.png, exist_ok=True)
        for name, (p, f) in meshes.items():
            render(os.path.join(args.png, name + ".png"), p, f, name)


if __name__ == "__main__":
    sys.exit(main())
