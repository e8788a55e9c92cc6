//! The [`Subdivision`] trait, the registry of schemes by name ([`SCHEMES`]), repeated
//! subdivision under a size limit ([`subdivide`]), and what both schemes share for limit
//! normals at vertices without a closed-form stencil (`local_limit`, crate-internal).

use meshio::Polygons;
use nalgebra::{Point3, Vector3};

use crate::catmull_clark::CatmullClark;
use crate::error::SubdivError;
use crate::loop_scheme::{Loop, LoopWeights};
use crate::mesh::{PolyMesh, VertexKind};

/// Default limit on the number of faces [`subdivide`] may produce: 2²⁴ = 16 777 216 faces.
///
/// A level of either scheme holds, per face, about 100 bytes (corner indices, offsets, the
/// half-edge arrays, and the face's share of vertex positions and edges), and a step holds two
/// levels at once, so the default bounds the memory of a call at roughly 3 GB. Faces grow 4×
/// per level (Loop: `F·4ᵏ`; Catmull–Clark: `C·4ᵏ⁻¹` with `C` the number of corners, since the
/// first step makes one quad per corner).
pub const DEFAULT_MAX_FACES: u64 = 1 << 24;

/// A subdivision scheme.
pub trait Subdivision: Send + Sync {
    /// The registered name (`"loop"`, `"catmull-clark"`, …).
    fn name(&self) -> &'static str;

    /// One refinement step. Vertices of the input keep their indices (their new positions come
    /// first), followed by the new vertices in a scheme-specific documented order; crease tags
    /// are carried to the two halves of each crease edge.
    fn step(&self, mesh: &PolyMesh) -> Result<PolyMesh, SubdivError>;

    /// Number of faces after `levels` steps, or `None` if that overflows `u64`.
    fn faces_after(&self, mesh: &PolyMesh, levels: u32) -> Option<u64>;

    /// The limit position of every vertex: where it goes under infinitely many steps.
    fn limit_positions(&self, mesh: &PolyMesh) -> Result<Vec<Point3<f64>>, SubdivError>;

    /// The unit limit normal at every vertex, oriented like the faces (counter-clockwise seen
    /// from the side it points to); zero for isolated vertices.
    fn limit_normals(&self, mesh: &PolyMesh) -> Result<Vec<Vector3<f64>>, SubdivError>;
}

/// A registered scheme.
pub struct SchemeEntry {
    /// Its name.
    pub name: &'static str,
    /// One line on what it is.
    pub summary: &'static str,
    /// Builds it.
    pub build: fn() -> Box<dyn Subdivision>,
}

/// Every scheme, by name.
pub const SCHEMES: &[SchemeEntry] = &[
    SchemeEntry {
        name: "loop",
        summary: "Loop (1987): triangles, β = (5/8 − (3/8 + ¼cos 2π/n)²)/n",
        build: || {
            Box::new(Loop {
                weights: LoopWeights::Loop,
            })
        },
    },
    SchemeEntry {
        name: "loop-warren",
        summary: "Loop with Warren's weights: β = 3/(8n) for n > 3, 3/16 for n = 3",
        build: || {
            Box::new(Loop {
                weights: LoopWeights::Warren,
            })
        },
    },
    SchemeEntry {
        name: "catmull-clark",
        summary: "Catmull–Clark (1978): any polygons, all quads after one step",
        build: || Box::new(CatmullClark),
    },
];

/// The scheme registered under `name`.
pub fn scheme_by_name(name: &str) -> Result<Box<dyn Subdivision>, SubdivError> {
    SCHEMES
        .iter()
        .find(|e| e.name == name)
        .map(|e| (e.build)())
        .ok_or_else(|| SubdivError::UnknownScheme {
            name: name.to_string(),
            known: SCHEMES
                .iter()
                .map(|e| e.name)
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// `levels` steps of `scheme`, refused before any work if the output would have more than
/// `max_faces` faces ([`DEFAULT_MAX_FACES`] is a sensible limit).
pub fn subdivide(
    scheme: &dyn Subdivision,
    mesh: &PolyMesh,
    levels: u32,
    max_faces: u64,
) -> Result<PolyMesh, SubdivError> {
    let faces = scheme.faces_after(mesh, levels).unwrap_or(u64::MAX);
    if faces > max_faces {
        return Err(SubdivError::TooLarge {
            levels,
            faces,
            limit: max_faces,
        });
    }
    let mut current = mesh.clone();
    for _ in 0..levels {
        current = scheme.step(&current)?;
    }
    Ok(current)
}

/// `n · 4^k`, `None` on overflow.
pub(crate) fn times_four_pow(n: u64, k: u32) -> Option<u64> {
    let factor = 4u64.checked_pow(k)?;
    n.checked_mul(factor)
}

/// Number of local steps [`local_limit`] takes for a normal. The one-ring shrinks like the
/// subdominant eigenvalue λ (½ on a boundary or crease, about ½ to ⅗ elsewhere) and the
/// normal's error like (μ/λ)ᵏ with μ the next one (at most ½ of λ for both schemes' boundary
/// and crease rules), so 26 steps leave an error near 2⁻²⁶ ≈ 1.5·10⁻⁸ while the ring is still
/// about 10⁻⁸ of the mesh's size, well above rounding.
const NORMAL_STEPS: usize = 26;

/// Largest number of local steps for a limit position; the loop stops earlier when the
/// vertex moves by less than 10⁻¹⁶ of the size of its position and one-ring.
const POSITION_STEPS: usize = 200;

/// The limit position and unit normal at `v` by subdividing only its one-ring, for vertices
/// without a closed-form stencil (darts; normals at crease, boundary and corner vertices).
///
/// Why the one-ring is enough: after a step, the new position of `v` depends on its one-ring,
/// and the new one-ring of `v` (the points of the edges at `v` and, for Catmull–Clark, of the
/// faces at `v`) depends only on the faces at `v`, whatever happens at the ring's own rim. So
/// the faces at `v` are cut out, stepped, the new faces at `v` cut out again, and so on: the
/// ring is exactly the ring the whole mesh would have at that level.
///
/// The normal is the sum of the (Newell) normals of the faces at `v` after
/// [`NORMAL_STEPS`] steps: on a smooth sector it converges to the limit normal; at a crease
/// vertex with two sectors it is the average of both sides' normals (weighted by the shrunken
/// faces' areas), at a corner the average of all sectors'.
pub(crate) fn local_limit(
    scheme: &dyn Subdivision,
    mesh: &PolyMesh,
    v: usize,
    want_normal: bool,
) -> Result<(Point3<f64>, Vector3<f64>), SubdivError> {
    if mesh.vertex_kind(v) == VertexKind::Isolated {
        return Ok((mesh.positions()[v], Vector3::zeros()));
    }
    // The patch is kept centred on the vertex (vertex 0, at the origin; the scheme is affine
    // invariant), so its shrinking faces keep full relative precision however small they get.
    let mut origin = mesh.positions()[v].coords;
    let mut patch = recentre(one_ring_patch(mesh, v)?, origin)?;
    // Absolute scale of the answer: a move below 10⁻¹⁶ of it no longer changes it.
    let scale = origin.norm()
        + patch
            .positions()
            .iter()
            .map(|q| q.coords.norm())
            .fold(0.0, f64::max);
    let steps = if want_normal {
        NORMAL_STEPS
    } else {
        POSITION_STEPS
    };
    for _ in 0..steps {
        let fine = scheme.step(&patch)?;
        // The centre keeps its index 0 through a step; it was at the origin before it.
        let shift = fine.positions()[0].coords;
        origin += shift;
        patch = recentre(one_ring_patch(&fine, 0)?, shift)?;
        if !want_normal && shift.norm() <= 1e-16 * scale {
            break;
        }
    }
    let last = Point3::from(origin);
    let mut normal = Vector3::zeros();
    if want_normal {
        for face in patch.faces() {
            normal += newell(patch.positions(), face);
        }
        let len = normal.norm();
        if len > 0.0 {
            normal /= len;
        }
    }
    Ok((last, normal))
}

/// `mesh` moved by `−by`.
fn recentre(mesh: PolyMesh, by: Vector3<f64>) -> Result<PolyMesh, SubdivError> {
    let moved = mesh.positions().iter().map(|p| p - by).collect();
    mesh.with_positions(moved)
}

/// The faces at `v` as a mesh of their own with `v` as vertex 0, crease tags kept.
fn one_ring_patch(mesh: &PolyMesh, v: usize) -> Result<PolyMesh, SubdivError> {
    let mut hs = Vec::new();
    mesh.outgoing(v, &mut hs);
    let mut local: Vec<(u32, usize)> = vec![(v as u32, 0)];
    let mut positions = vec![mesh.positions()[v]];
    let mut polygons = Polygons::new();
    let mut corners = Vec::new();
    let mut lookup = |g: u32, positions: &mut Vec<Point3<f64>>| -> usize {
        if let Some(&(_, l)) = local.iter().find(|(x, _)| *x == g) {
            return l;
        }
        let l = positions.len();
        positions.push(mesh.positions()[g as usize]);
        local.push((g, l));
        l
    };
    // Only the edges at `v` matter for the centre's next ring: crease tags are kept on those,
    // and corners away from `v` and its edge neighbours get a copy per face, so the patch is
    // manifold even where two faces at `v` meet again away from it.
    let mut creases = Vec::new();
    for &h in &hs {
        corners.clear();
        let (first, last) = (mesh.next(h), mesh.prev(h));
        let mut g = h;
        loop {
            let local_index = if g == h || g == first || g == last {
                lookup(mesh.tail(g), &mut positions)
            } else {
                positions.push(mesh.positions()[mesh.tail(g) as usize]);
                positions.len() - 1
            };
            corners.push(local_index);
            g = mesh.next(g);
            if g == h {
                break;
            }
        }
        if mesh.topo.crease[mesh.topo.edge[h as usize] as usize] {
            creases.push([0, corners[1]]);
        }
        polygons.push(&corners);
    }
    PolyMesh::with_creases(positions, &polygons, &creases)
}

/// Newell's vector of a polygon: twice its area times its unit normal (for a planar polygon).
/// Computed from offsets to the first corner, so a polygon far smaller than its distance to
/// the origin keeps its precision.
pub(crate) fn newell(positions: &[Point3<f64>], face: &[u32]) -> Vector3<f64> {
    let mut n = Vector3::zeros();
    let k = face.len();
    let o = positions[face[0] as usize];
    for i in 1..k.saturating_sub(1) {
        let a = positions[face[i] as usize] - o;
        let b = positions[face[i + 1] as usize] - o;
        n += a.cross(&b);
    }
    n
}
