//! The functional (height-field) forms of `clough-tocher` and `powell-sabin`: on data
//! `z = f(x, y)` — a planar triangulation of `(x, y)` with values and gradients — the C1
//! interpolants the schemes are named after, as Bézier triangles in 3D whose `x, y` are linear
//! in the domain and whose `z` are the functional Bézier ordinates.
//!
//! # From the workbench's vertex data to functional data
//!
//! A vertex `(p, n)` with `n_z > 0` is the point `(x, y) = (p_x, p_y)` with value `z = p_z` and
//! gradient `∇f = (−n_x/n_z, −n_y/n_z)`: the tangent plane `n · (q − p) = 0` is the graph of
//! `z = p_z + ∇f · ((q_x, q_y) − (p_x, p_y))`. A control point of a functional Bézier triangle
//! over domain point `ξ` with ordinate `b` is the 3D point `(ξ_x, ξ_y, b)`; because every rule
//! below is an affine combination of control points whose domain points combine the same way,
//! the nets are the functional ones and the patches are graphs over their xy sub-triangles.
//!
//! # When data is a height field ([`detect`])
//!
//! The fit (`fitjob`) calls [`detect`] on the mesh it fits (in its working frame: a translation
//! and a uniform scale, which keep both the height-field property and the xy triangulation);
//! the data is a height field when
//!
//! 1. every face corner's unit normal has `n_z > 0` (strictly; the gradient is then finite);
//! 2. no edge is a crease (one normal per vertex: a functional interpolant has one gradient
//!    there);
//! 3. every face's xy projection is counter-clockwise with area above
//!    [`MIN_RELATIVE_AREA`] × (the xy bounding box's area): faces are counter-clockwise seen
//!    from their normals' side (docs/conventions.md), so an upward mesh projects without
//!    flipped triangles;
//! 4. the xy angles of every interior vertex's faces sum to `2π` (within [`ANGLE_SUM_TOL`]) and
//!    a boundary vertex's to less than `2π`: each fan covers its neighbourhood once;
//! 5. no two faces that share no vertex overlap in xy (separating-axis test on a bucket grid):
//!    no fold-over far apart either (a spiral ramp passes 1–4 and fails this).
//!
//! Then the xy projection is a planar triangulation without fold-overs (1–4 make it a local
//! homeomorphism, 5 injective). The fit prints the rule it applied ([`HeightField::note`]).
//!
//! [`Scheme::on_height_field`] gives a scheme's functional form for a mesh;
//! [`clough_tocher`] and [`powell_sabin`] have the constructions and their derivations.

pub mod clough_tocher;
pub mod graph;
pub mod powell_sabin;

use nalgebra::{Point3, Vector2};

use crate::fit::FaceFallbackReason;
use crate::mesh::Mesh;
use crate::scheme::{FaceInput, Scheme};
use crate::VertexData;

/// Smallest xy area of a face, relative to the area of the mesh's xy bounding box, for the face
/// to count as a triangle of the planar triangulation: a sliver below it has no usable
/// gradient rule (its rounding is of the order of its area), `1e-12` is six orders above
/// `f64` rounding of the box area.
pub const MIN_RELATIVE_AREA: f64 = 1e-12;

/// How far an interior vertex's xy angle sum may be from `2π`: the rounding of a few hundred
/// `atan2` (1e-13 each) stays far below it, a fan that covers its neighbourhood twice misses by
/// `2π`.
pub const ANGLE_SUM_TOL: f64 = 1e-6;

/// The functional data at one corner: the xy point, the value and the gradient.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node {
    /// `(x, y)`.
    pub xy: Vector2<f64>,
    /// `z = f(x, y)`.
    pub z: f64,
    /// `∇f = (−n_x/n_z, −n_y/n_z)`.
    pub grad: Vector2<f64>,
}

impl Node {
    /// The functional data of a vertex (module docs); `None` when its normal does not point
    /// up (`n_z ≤ 0`) or the data is not finite.
    pub fn of(v: &VertexData) -> Option<Node> {
        let n = v.n;
        let ok = n.z > 0.0 && n.iter().chain(v.p.iter()).all(|c| c.is_finite());
        let node = Node {
            xy: Vector2::new(v.p.x, v.p.y),
            z: v.p.z,
            grad: Vector2::new(-n.x / n.z, -n.y / n.z),
        };
        (ok && node.grad.iter().all(|c| c.is_finite())).then_some(node)
    }

    /// The tangent-plane point over `q`: `(q, z + ∇f · (q − xy))`.
    pub fn tangent(&self, q: &Vector2<f64>) -> Point3<f64> {
        point(q, self.z + self.grad.dot(&(q - self.xy)))
    }

    /// The data point itself.
    pub fn point(&self) -> Point3<f64> {
        point(&self.xy, self.z)
    }
}

/// The corner data of a face, or the fallback reason naming the first corner whose normal does
/// not point up ([`Node::of`]).
pub fn face_nodes(input: &FaceInput<'_>) -> Result<[Node; 3], FaceFallbackReason> {
    let mut nodes = [Node {
        xy: Vector2::zeros(),
        z: 0.0,
        grad: Vector2::zeros(),
    }; 3];
    for (corner, (slot, v)) in nodes.iter_mut().zip(input.vertices).enumerate() {
        *slot = Node::of(v).ok_or(FaceFallbackReason::Folded { corner })?;
    }
    Ok(nodes)
}

/// The corner data of a face, with a gradient of zero where a normal does not point up (only
/// for the fallback patches: [`detect`] admits no such data).
pub fn nodes_or_flat(input: &FaceInput<'_>) -> [Node; 3] {
    input.vertices.map(|v| {
        Node::of(v).unwrap_or(Node {
            xy: Vector2::new(v.p.x, v.p.y),
            z: v.p.z,
            grad: Vector2::zeros(),
        })
    })
}

/// The 3D point over `xy` at height `z`.
pub fn point(xy: &Vector2<f64>, z: f64) -> Point3<f64> {
    Point3::new(xy.x, xy.y, z)
}

/// The xy part of a point.
pub fn xy(p: &Point3<f64>) -> Vector2<f64> {
    Vector2::new(p.x, p.y)
}

/// Twice the signed xy area of `(a, b, c)`.
pub fn cross2(a: &Vector2<f64>, b: &Vector2<f64>, c: &Vector2<f64>) -> f64 {
    (b - a).perp(&(c - a))
}

/// What [`detect`] found: a height field, with its numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeightField {
    /// Faces checked.
    pub faces: usize,
    /// The smallest `n_z` of a unit corner normal.
    pub min_nz: f64,
    /// The largest gradient length `|∇f|` at a corner.
    pub max_slope: f64,
}

impl HeightField {
    /// The fit report's note: what was detected, by which rule.
    pub fn note(&self) -> String {
        format!(
            "detected a height field: every corner normal has n_z > 0 (smallest {:.3}, steepest slope |∇f| = {:.3}), no creases, and the xy projection of the {} faces is a planar triangulation (all counter-clockwise, interior fans summing to 2π, no two faces overlapping); fitted as z = f(x, y)",
            self.min_nz, self.max_slope, self.faces
        )
    }
}

/// Why a mesh is not a height field ([`detect`]'s rules, module docs).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum NotHeightField {
    /// A corner normal does not point up.
    #[error("the normal of vertex {vertex} (face {face}) has n_z = {nz:.3e}, not > 0")]
    NormalNotUp {
        /// The face.
        face: usize,
        /// The vertex.
        vertex: usize,
        /// Its unit normal's z.
        nz: f64,
    },
    /// An edge is a crease (two normals at a vertex).
    #[error("edge {edge} is a crease: a height field has one gradient per vertex")]
    Crease {
        /// The mesh edge.
        edge: usize,
    },
    /// A face's xy projection is clockwise or (relatively) degenerate.
    #[error("face {face} projects to the xy plane clockwise or degenerate (relative area {relative_area:.3e})")]
    Flipped {
        /// The face.
        face: usize,
        /// Its signed xy area over the bounding box's.
        relative_area: f64,
    },
    /// An interior vertex's fan does not cover its neighbourhood once.
    #[error(
        "the faces around vertex {vertex} cover its xy neighbourhood {turns:.3} times, not once"
    )]
    Fan {
        /// The vertex.
        vertex: usize,
        /// Its angle sum over `2π`.
        turns: f64,
    },
    /// Two faces overlap in xy.
    #[error("faces {0} and {1} overlap in the xy plane")]
    Overlap(usize, usize),
    /// The mesh has no faces.
    #[error("the mesh has no faces")]
    Empty,
}

/// Whether `mesh` is a height field by the rules of the module docs.
pub fn detect(mesh: &Mesh) -> Result<HeightField, NotHeightField> {
    let faces = mesh.faces();
    if faces.is_empty() {
        return Err(NotHeightField::Empty);
    }
    let mut min_nz = f64::INFINITY;
    let mut max_slope: f64 = 0.0;
    for (f, face) in faces.iter().enumerate() {
        for (c, &vertex) in face.iter().enumerate() {
            let data = mesh
                .corner_data(f, c)
                .unwrap_or(mesh.vertices()[vertex].data);
            let n = data.n.try_normalize(0.0).unwrap_or_default();
            let node = Node::of(&data);
            match node {
                Some(node) if n.z > 0.0 => {
                    min_nz = min_nz.min(n.z);
                    max_slope = max_slope.max(node.grad.norm());
                }
                _ => {
                    return Err(NotHeightField::NormalNotUp {
                        face: f,
                        vertex,
                        nz: n.z,
                    })
                }
            }
        }
    }
    if let Some(edge) = (0..mesh.num_edges()).find(|&e| mesh.is_crease(e)) {
        return Err(NotHeightField::Crease { edge });
    }
    let pts: Vec<Vector2<f64>> = mesh.vertices().iter().map(|v| xy(&v.data.p)).collect();
    let (mut lo, mut hi) = (pts[faces[0][0]], pts[faces[0][0]]);
    for p in &pts {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    let box_area = ((hi.x - lo.x) * (hi.y - lo.y)).max(f64::MIN_POSITIVE);
    let mut angle = vec![0.0; pts.len()];
    for (f, &[a, b, c]) in faces.iter().enumerate() {
        let relative_area = 0.5 * cross2(&pts[a], &pts[b], &pts[c]) / box_area;
        // NaN fails too.
        if relative_area.partial_cmp(&MIN_RELATIVE_AREA) != Some(std::cmp::Ordering::Greater) {
            return Err(NotHeightField::Flipped {
                face: f,
                relative_area,
            });
        }
        for (i, &v) in [a, b, c].iter().enumerate() {
            let (p, q) = (
                pts[[a, b, c][(i + 1) % 3]] - pts[v],
                pts[[a, b, c][(i + 2) % 3]] - pts[v],
            );
            angle[v] += p.perp(&q).atan2(p.dot(&q));
        }
    }
    let mut boundary = vec![false; pts.len()];
    for e in mesh.edges() {
        if e.is_boundary() {
            boundary[e.vertices[0]] = true;
            boundary[e.vertices[1]] = true;
        }
    }
    let used: Vec<bool> = {
        let mut u = vec![false; pts.len()];
        faces.iter().flatten().for_each(|&v| u[v] = true);
        u
    };
    let tau = std::f64::consts::TAU;
    for v in 0..pts.len() {
        let turns = angle[v] / tau;
        let bad = if boundary[v] {
            angle[v] >= tau - ANGLE_SUM_TOL
        } else {
            (angle[v] - tau).abs() > ANGLE_SUM_TOL
        };
        if used[v] && bad {
            return Err(NotHeightField::Fan { vertex: v, turns });
        }
    }
    if let Some((f, g)) = overlapping_faces(faces, &pts, (lo, hi)) {
        return Err(NotHeightField::Overlap(f, g));
    }
    Ok(HeightField {
        faces: faces.len(),
        min_nz,
        max_slope,
    })
}

/// The first pair of faces sharing no vertex whose xy interiors overlap, on a bucket grid of
/// about one face per cell.
fn overlapping_faces(
    faces: &[[usize; 3]],
    pts: &[Vector2<f64>],
    (lo, hi): (Vector2<f64>, Vector2<f64>),
) -> Option<(usize, usize)> {
    let cells = (faces.len() as f64).sqrt().ceil().clamp(1.0, 4096.0) as usize;
    let size = (hi - lo).map(|d| d.max(f64::MIN_POSITIVE));
    let cell = |p: &Vector2<f64>| -> (usize, usize) {
        let c = (p - lo).component_div(&size) * cells as f64;
        let clamp = |x: f64| (x.max(0.0) as usize).min(cells - 1);
        (clamp(c.x), clamp(c.y))
    };
    let mut buckets: Vec<Vec<usize>> = vec![Vec::new(); cells * cells];
    for (f, face) in faces.iter().enumerate() {
        let (mut a, mut b) = (pts[face[0]], pts[face[0]]);
        for &v in face {
            a = a.inf(&pts[v]);
            b = b.sup(&pts[v]);
        }
        let ((i0, j0), (i1, j1)) = (cell(&a), cell(&b));
        for i in i0..=i1 {
            for j in j0..=j1 {
                buckets[i * cells + j].push(f);
            }
        }
    }
    let scale = (hi - lo).norm();
    for bucket in &buckets {
        for (k, &f) in bucket.iter().enumerate() {
            for &g in &bucket[k + 1..] {
                let (a, b) = (faces[f], faces[g]);
                if a.iter().any(|v| b.contains(v)) {
                    continue;
                }
                let ta = a.map(|v| pts[v]);
                let tb = b.map(|v| pts[v]);
                if triangles_overlap(&ta, &tb, 1e-12 * scale) {
                    return Some((f.min(g), f.max(g)));
                }
            }
        }
    }
    None
}

/// Whether two xy triangles' interiors overlap by more than `eps` along every separating axis
/// candidate (their six edge normals).
fn triangles_overlap(a: &[Vector2<f64>; 3], b: &[Vector2<f64>; 3], eps: f64) -> bool {
    let separated_along = |axis: Vector2<f64>| {
        let n = axis.norm();
        if n == 0.0 {
            return false;
        }
        let axis = axis / n;
        let range = |t: &[Vector2<f64>; 3]| {
            t.iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                    let d = p.dot(&axis);
                    (l.min(d), h.max(d))
                })
        };
        let ((la, ha), (lb, hb)) = (range(a), range(b));
        ha <= lb + eps || hb <= la + eps
    };
    let axes = |t: &[Vector2<f64>; 3]| -> [Vector2<f64>; 3] {
        std::array::from_fn(|i| {
            let d = t[(i + 1) % 3] - t[i];
            Vector2::new(-d.y, d.x)
        })
    };
    !axes(a).into_iter().chain(axes(b)).any(separated_along)
}

/// What the fit does about height fields (`fit --heightfield`, `--no-heightfield`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum HeightFieldMode {
    /// Detect ([`detect`]); fit a detected height field with the scheme's functional form.
    #[default]
    Auto,
    /// The data must be a height field and the scheme must have a functional form, or the fit
    /// stops with the reason.
    On,
    /// Never: the parametric scheme, whatever the data.
    Off,
}

/// Why [`choose`] refused a fit asked to be functional ([`HeightFieldMode::On`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum HeightFieldError {
    /// The data is not a height field.
    #[error("--heightfield: the data is not a height field: {0}")]
    NotHeightField(#[from] NotHeightField),
    /// The scheme has no functional form.
    #[error("--heightfield: the `{0}` scheme has no functional form (clough-tocher and powell-sabin have)")]
    NoFunctionalForm(&'static str),
}

/// The scheme to fit `mesh` with under `mode`: `scheme` itself, or its functional form
/// ([`Scheme::on_height_field`]) when the mesh is a height field; with the note the fit prints
/// (what was detected, or why not when it was asked for).
pub fn choose(
    scheme: Box<dyn Scheme>,
    mesh: &Mesh,
    mode: HeightFieldMode,
) -> Result<(Box<dyn Scheme>, Option<String>), HeightFieldError> {
    if mode == HeightFieldMode::Off {
        return Ok((scheme, None));
    }
    let found = detect(mesh);
    match (found, mode) {
        (Ok(hf), _) => match scheme.on_height_field(mesh) {
            Some(functional) => Ok((functional, Some(hf.note()))),
            None if mode == HeightFieldMode::On => {
                Err(HeightFieldError::NoFunctionalForm(scheme.name()))
            }
            None => Ok((
                scheme,
                Some(format!(
                    "{} (the scheme has no functional form: fitted as it is)",
                    hf.note()
                )),
            )),
        },
        (Err(why), HeightFieldMode::On) => Err(why.into()),
        (Err(_), _) => Ok((scheme, None)),
    }
}
