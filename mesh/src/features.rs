//! Sharp features of a triangle mesh found from its geometry: **crease** edges (the dihedral
//! angle between the two faces' planes over a threshold), and the vertices they meet at, each
//! classified by the creases around it, with the **sectors** of its fan (the runs of faces
//! between two creases) that per-sector data is estimated on.
//!
//! # Rules
//!
//! * The dihedral angle of an interior edge is the angle between its two faces' unit normals,
//!   `θ = atan2(|n₁ × n₂|, n₁ · n₂)` ∈ [0, π] (0: coplanar, π: folded flat onto itself); it is
//!   computed only where both faces have a normal (a face of zero area has none: its edges are
//!   counted as *undefined* and never creases). A boundary edge has no dihedral angle and is not
//!   a crease (the fan already ends there).
//! * An edge is a crease when `θ > threshold` ([`DEFAULT_CREASE_ANGLE_DEG`] unless given).
//! * A vertex is [`VertexKind::Smooth`] with no crease edge, a [`VertexKind::Dart`] with one
//!   (a crease that ends inside a smooth region), a [`VertexKind::Crease`] with two whose
//!   directions turn by at most [`CORNER_TURN_DEG`] (the crease runs on through the vertex), and a
//!   [`VertexKind::Corner`] with three or more, or two that turn more sharply. A boundary
//!   vertex with any crease is a corner (the crease ends on the boundary, where the surface's
//!   edge is a curve of its own).
//! * The sectors of a vertex are the maximal runs of consecutive faces of its fan (counter-
//!   clockwise, `Mesh::faces_around_vertex`) not separated by a crease edge. A closed fan with
//!   `c ≥ 2` creases has `c` sectors; with 0 or 1 (a dart: the crease fades into the fan) it has
//!   one; an open fan (a boundary vertex) with `c` creases has `c + 1`.
//!
//! The same rules as Blender's "auto smooth" angle and CGAL's sharp-edge detection
//! (`CGAL::Polygon_mesh_processing::detect_sharp_edges`): a crease is where the piecewise-flat
//! data turns by more than a stated angle; Hoppe et al. 1994 ("Piecewise smooth surface
//! reconstruction") name the same vertex classes (smooth, dart, crease, corner).

use nalgebra::Vector3;
use rayon::prelude::*;

use crate::mesh::Mesh;

/// The default crease threshold, degrees: an edge whose faces' planes meet at more than this is
/// a crease. 40° keeps every edge of a box, a chamfer (45°) and a hexagonal prism (60°) as a
/// crease. A threshold alone does not tell a scan from a CAD part: on the committed scans
/// (`data/meshes/`, their dihedral angles measured with `Features::detect`) the median edge
/// turns by 7–12°, but 170 of the bunny's 5 511 interior edges, 174 of the teapot's 1 224 and
/// 4 446 of the 67 812 of `dragon_res3` (some at 179.9°: faces folded onto each other) are
/// over 40°: so by default ([`CreaseRule::Auto`]) geometric creases apply only to tessellated
/// models ([`TESSELLATED_FLAT_SHARE`]).
pub const DEFAULT_CREASE_ANGLE_DEG: f64 = 40.0;

/// How sharply two creases may turn at a vertex and still be one crease running through it,
/// degrees: the turn is `π − ∠(d₁, d₂)` between the two crease edges' directions away from the
/// vertex. 45° is the turn of a circle's rim meshed with eight segments: a rim meshed coarser
/// than that is a chain of corners.
pub const CORNER_TURN_DEG: f64 = 45.0;

/// What the creases around a vertex make it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum VertexKind {
    /// No crease edge.
    Smooth,
    /// One crease edge: a crease ends here inside a smooth region.
    Dart,
    /// Two crease edges running on through the vertex.
    Crease,
    /// Three or more crease edges, or two that turn sharply.
    Corner,
}

/// The sharp features of a mesh (see the module's rules).
#[derive(Clone, Debug, PartialEq)]
pub struct Features {
    /// The threshold used, radians.
    pub threshold: f64,
    /// Per edge (the mesh's edge indices): its dihedral angle, radians; `None` on a boundary
    /// edge or where a face has no normal.
    pub dihedral: Vec<Option<f64>>,
    /// Per edge: a crease.
    pub crease: Vec<bool>,
    /// Per vertex: its kind.
    pub kinds: Vec<VertexKind>,
    /// Interior edges whose dihedral angle is undefined (a face of zero area beside them).
    pub undefined: usize,
    /// Per edge: a crease because the file marks it (the geometry did not find it).
    pub by_file: Vec<bool>,
    /// Connected components (across interior edges).
    pub components: usize,
    /// Components taken as tessellated models ([`TESSELLATED_FLAT_SHARE`]).
    pub tessellated_components: usize,
}

/// Which geometric creases to find.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CreaseRule {
    /// The default: edges over [`DEFAULT_CREASE_ANGLE_DEG`] on components that are tessellated
    /// models (at least [`TESSELLATED_FLAT_SHARE`] of their interior edges flat to
    /// [`FLAT_EDGE_ANGLE`]); scans keep smooth. The file's creases apply everywhere.
    Auto,
    /// Edges over this many degrees, on every component (`--crease-angle DEG`), and the file's.
    Angle(f64),
    /// No creases at all, not even the file's (`--no-creases`).
    None,
}

/// An interior edge whose faces' normals differ by at most this (radians) is flat: coplanar
/// faces of a planar region of a model, whose normals agree to the rounding of the file's
/// coordinates (single precision: about 1e-7 on a unit-size part; a scanner's noise makes its
/// neighbouring faces differ by far more).
pub const FLAT_EDGE_ANGLE: f64 = 1e-6;

/// A component with at least this share of flat interior edges ([`FLAT_EDGE_ANGLE`]) is a
/// tessellated model (a CAD part, a modelled object) and gets geometric creases by default.
/// Measured: 0 flat edges on the committed scans (bunny, dragon at two resolutions), 19.5 % on
/// the tessellated teapot, 61–89 % on the fixtures' boxes and cone; a CAD tessellation puts two
/// coplanar triangles on every planar quad and every ruled strip (cylinders, cones, extrusions),
/// so a third or more of its edges are flat. 5 % leaves a wide margin on both sides.
pub const TESSELLATED_FLAT_SHARE: f64 = 0.05;

/// Per face its component (across interior edges), and per component whether it is a
/// tessellated model ([`TESSELLATED_FLAT_SHARE`]).
fn tessellated_components(mesh: &Mesh, dihedral: &[Option<f64>]) -> (Vec<usize>, Vec<bool>) {
    let nf = mesh.num_faces();
    let mut sets = crate::disjoint::DisjointSets::new(nf);
    for e in mesh.edges() {
        if let Some((g, _)) = e.second {
            sets.union(e.first.0, g);
        }
    }
    let mut label = vec![usize::MAX; nf];
    let mut count = 0;
    let component: Vec<usize> = (0..nf)
        .map(|f| {
            let r = sets.find(f);
            if label[r] == usize::MAX {
                label[r] = count;
                count += 1;
            }
            label[r]
        })
        .collect();
    let mut interior = vec![0usize; count];
    let mut flat = vec![0usize; count];
    for (e, d) in mesh.edges().zip(dihedral) {
        if let Some(t) = d {
            let c = component[e.first.0];
            interior[c] += 1;
            if *t <= FLAT_EDGE_ANGLE {
                flat[c] += 1;
            }
        }
    }
    let tessellated = interior
        .iter()
        .zip(&flat)
        .map(|(&i, &f)| i > 0 && f as f64 >= TESSELLATED_FLAT_SHARE * i as f64)
        .collect();
    (component, tessellated)
}

/// The kind of every vertex given the crease flags (module rules).
fn classify(mesh: &Mesh, crease: &[bool]) -> Vec<VertexKind> {
    let mut at_vertex: Vec<Vec<usize>> = vec![Vec::new(); mesh.num_vertices()];
    for (e, edge) in mesh.edges().enumerate() {
        if crease[e] {
            for &v in &edge.vertices {
                at_vertex[v].push(e);
            }
        }
    }
    let corner_turn = CORNER_TURN_DEG.to_radians();
    let mut on_boundary = vec![false; mesh.num_vertices()];
    for edge in mesh.edges().filter(|e| e.is_boundary()) {
        for &v in &edge.vertices {
            on_boundary[v] = true;
        }
    }
    at_vertex
        .iter()
        .enumerate()
        .map(|(v, creases)| match creases.len() {
            0 => VertexKind::Smooth,
            _ if on_boundary[v] => VertexKind::Corner,
            1 => VertexKind::Dart,
            2 => {
                let away = |e: usize| -> Option<Vector3<f64>> {
                    let [a, b] = mesh.edge(e).vertices;
                    let other = if a == v { b } else { a };
                    let d = mesh.vertex(other)?.data.p - mesh.vertex(v)?.data.p;
                    let len = d.norm();
                    (len > 0.0).then(|| d / len)
                };
                match (away(creases[0]), away(creases[1])) {
                    (Some(d1), Some(d2))
                        if std::f64::consts::PI - angle(&d1, &d2) <= corner_turn =>
                    {
                        VertexKind::Crease
                    }
                    _ => VertexKind::Corner,
                }
            }
            _ => VertexKind::Corner,
        })
        .collect()
}

/// The angle between two vectors, `atan2(|a × b|, a · b)`: accurate at 0 and π, where `acos`
/// of the dot product loses half the digits.
pub fn angle(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.cross(b).norm().atan2(a.dot(b))
}

impl Features {
    /// Detects the creases (dihedral angle over `threshold_deg` degrees, on every component)
    /// and classifies the vertices. `threshold_deg = 180` finds no crease (a dihedral angle is
    /// at most π).
    pub fn detect(mesh: &Mesh, threshold_deg: f64) -> Features {
        Features::find(mesh, CreaseRule::Angle(threshold_deg), &[])
    }

    /// The creases `rule` finds ([`CreaseRule`]), with the edges the file marks sharp
    /// (`file_creases`: vertex pairs of `mesh`; pairs that are not an edge are skipped), and the
    /// vertices classified.
    pub fn find(mesh: &Mesh, rule: CreaseRule, file_creases: &[[usize; 2]]) -> Features {
        let threshold = match rule {
            CreaseRule::Angle(deg) => deg.to_radians(),
            CreaseRule::Auto => DEFAULT_CREASE_ANGLE_DEG.to_radians(),
            CreaseRule::None => std::f64::consts::PI,
        };
        let normals: Vec<Option<Vector3<f64>>> = (0..mesh.num_faces())
            .into_par_iter()
            .map(|f| mesh.face_unit_normal(f))
            .collect();
        let dihedral: Vec<Option<f64>> = mesh
            .par_edges()
            .map(|e| {
                let (f2, _) = e.second?;
                Some(angle(&normals[e.first.0]?, &normals[f2]?))
            })
            .collect();
        let undefined = mesh
            .par_edges()
            .zip(&dihedral)
            .filter(|(e, d)| e.second.is_some() && d.is_none())
            .count();
        let (component, tessellated) = tessellated_components(mesh, &dihedral);
        let geometric = |e: usize, d: &Option<f64>| -> bool {
            let over = d.is_some_and(|t| t > threshold);
            match rule {
                CreaseRule::Angle(_) => over,
                CreaseRule::Auto => over && tessellated[component[mesh.edge(e).first.0]],
                CreaseRule::None => false,
            }
        };
        let mut crease: Vec<bool> = dihedral
            .iter()
            .enumerate()
            .map(|(e, d)| geometric(e, d))
            .collect();
        let mut by_file = vec![false; crease.len()];
        if rule != CreaseRule::None {
            for &[a, b] in file_creases {
                if let Some(e) = mesh.find_edge(a, b) {
                    if !mesh.edge(e).is_boundary() && !crease[e] {
                        crease[e] = true;
                        by_file[e] = true;
                    }
                }
            }
        }
        let kinds = classify(mesh, &crease);
        Features {
            threshold,
            dihedral,
            crease,
            kinds,
            undefined,
            by_file,
            components: tessellated.len(),
            tessellated_components: tessellated.iter().filter(|&&t| t).count(),
        }
    }

    /// No creases at all (`--no-creases`): every edge smooth, every vertex one sector; the
    /// dihedral angles are still measured.
    pub fn none(mesh: &Mesh) -> Features {
        Features::find(mesh, CreaseRule::None, &[])
    }

    /// The number of crease edges.
    pub fn num_creases(&self) -> usize {
        self.crease.iter().filter(|&&c| c).count()
    }

    /// The number of vertices of `kind`.
    pub fn count(&self, kind: VertexKind) -> usize {
        self.kinds.iter().filter(|&&k| k == kind).count()
    }

    /// The sectors of vertex `v`: its fan's faces (counter-clockwise, as
    /// `Mesh::faces_around_vertex` gives them) cut at every crease edge, each sector in fan
    /// order. One sector holding the whole fan where there is no crease or one (a dart); empty
    /// for an isolated vertex.
    pub fn sectors(&self, mesh: &Mesh, v: usize) -> Vec<Vec<usize>> {
        let fan = mesh.faces_around_vertex(v);
        if fan.is_empty() {
            return Vec::new();
        }
        // The edge at `v` that faces `f` and `g` share, if they share one.
        let shared = |f: usize, g: usize| -> Option<usize> {
            (0..3).find_map(|l| {
                let face = mesh.faces()[f];
                let (a, b) = (face[l], face[(l + 1) % 3]);
                if a != v && b != v {
                    return None;
                }
                match mesh.neighbour(f, l) {
                    Ok(Some((h, _))) if h == g => mesh.edge_index(f, l).ok(),
                    _ => None,
                }
            })
        };
        let cut = |f: usize, g: usize| shared(f, g).is_some_and(|e| self.crease[e]);
        let k = fan.len();
        // A closed fan: the last face shares an edge at `v` with the first.
        let closed = k > 2 && shared(fan[k - 1], fan[0]).is_some();
        let cuts: Vec<usize> = (0..k)
            .filter(|&i| {
                let next = i + 1;
                if next < k {
                    cut(fan[i], fan[next])
                } else {
                    closed && cut(fan[k - 1], fan[0])
                }
            })
            .collect();
        if cuts.is_empty() || (closed && cuts.len() == 1) {
            return vec![fan];
        }
        if !closed {
            let mut sectors = Vec::with_capacity(cuts.len() + 1);
            let mut start = 0;
            for &i in &cuts {
                sectors.push(fan[start..=i].to_vec());
                start = i + 1;
            }
            sectors.push(fan[start..].to_vec());
            return sectors;
        }
        // A closed fan cut `c ≥ 2` times: start after the last cut and go round once.
        let first = (cuts[cuts.len() - 1] + 1) % k;
        let mut sectors = Vec::with_capacity(cuts.len());
        let mut current = Vec::new();
        for step in 0..k {
            let i = (first + step) % k;
            current.push(fan[i]);
            if cuts.contains(&i) {
                sectors.push(std::mem::take(&mut current));
            }
        }
        if !current.is_empty() {
            sectors.push(current);
        }
        sectors
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)] // test fixtures fail loudly by design
    use super::*;
    use crate::mesh::Vertex;
    use nalgebra::{Point3, Vector3};

    /// Angles computed by `atan2` of exact-ish vectors agree with the closed form to this.
    const ANGLE_TOL: f64 = 1e-12;

    fn mesh(points: &[[f64; 3]], faces: Vec<[usize; 3]>) -> Mesh {
        let vertices = points
            .iter()
            .map(|p| Vertex::without_curvature(Point3::new(p[0], p[1], p[2]), Vector3::z()))
            .collect();
        Mesh::new(vertices, faces).expect("a valid mesh")
    }

    /// The unit cube, two triangles a side, outward.
    fn cube() -> Mesh {
        let p = [
            [0., 0., 0.],
            [1., 0., 0.],
            [1., 1., 0.],
            [0., 1., 0.],
            [0., 0., 1.],
            [1., 0., 1.],
            [1., 1., 1.],
            [0., 1., 1.],
        ];
        let quads = [
            [0, 3, 2, 1],
            [4, 5, 6, 7],
            [0, 1, 5, 4],
            [1, 2, 6, 5],
            [2, 3, 7, 6],
            [3, 0, 4, 7],
        ];
        let faces = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        mesh(&p, faces)
    }

    #[test]
    fn a_cube_has_twelve_creases_eight_corners_and_three_sectors_a_corner() {
        let m = cube();
        let f = Features::detect(&m, DEFAULT_CREASE_ANGLE_DEG);
        // 18 edges: 12 along the cube's edges (90°), 6 diagonals (0°).
        assert_eq!(m.num_edges(), 18);
        assert_eq!(f.num_creases(), 12);
        for (e, d) in f.dihedral.iter().enumerate() {
            let d = d.expect("a closed mesh of non-degenerate faces");
            let want = if f.crease[e] {
                std::f64::consts::FRAC_PI_2
            } else {
                0.0
            };
            assert!((d - want).abs() < ANGLE_TOL, "edge {e}: {d}");
        }
        assert_eq!(f.count(VertexKind::Corner), 8);
        for v in 0..8 {
            let sectors = f.sectors(&m, v);
            assert_eq!(sectors.len(), 3, "vertex {v}: {sectors:?}");
            // Every face of the fan in exactly one sector.
            let mut all: Vec<usize> = sectors.concat();
            all.sort_unstable();
            let mut fan = m.faces_around_vertex(v);
            fan.sort_unstable();
            assert_eq!(all, fan);
            // Each sector lies in one side of the cube: its faces are coplanar.
            for s in &sectors {
                let n0 = m.face_unit_normal(s[0]).unwrap();
                for &g in s {
                    assert!(angle(&n0, &m.face_unit_normal(g).unwrap()) < ANGLE_TOL);
                }
            }
        }
        assert_eq!(f.undefined, 0);
    }

    #[test]
    fn no_creases_leaves_one_sector_everywhere() {
        let m = cube();
        let f = Features::none(&m);
        assert_eq!(f.num_creases(), 0);
        assert_eq!(f.count(VertexKind::Smooth), 8);
        for v in 0..8 {
            assert_eq!(f.sectors(&m, v).len(), 1);
        }
    }

    /// A ridge: two slopes meeting at 90° along a line of three vertices. The middle one is
    /// interior, with the ridge running straight through it (a crease vertex, two sectors); the
    /// ridge's ends are on the strip's boundary (corners, their open fans cut in two).
    #[test]
    fn a_ridge_is_a_crease_through_its_inner_vertex_and_cuts_open_fans() {
        let p = [
            [0., 0., 1.],
            [1., 0., 1.],
            [2., 0., 1.],
            [0., 1., 0.],
            [1., 1., 0.],
            [2., 1., 0.],
            [0., -1., 0.],
            [1., -1., 0.],
            [2., -1., 0.],
        ];
        let faces = vec![
            [0, 4, 1],
            [0, 3, 4],
            [1, 5, 2],
            [1, 4, 5],
            [0, 1, 7],
            [0, 7, 6],
            [1, 2, 8],
            [1, 8, 7],
        ];
        let m = mesh(&p, faces);
        let f = Features::detect(&m, DEFAULT_CREASE_ANGLE_DEG);
        // The slopes' normals are (0, ±1, 1)/√2: they meet at 90°.
        for e in 0..m.num_edges() {
            let [a, b] = m.edge(e).vertices;
            let on_ridge = a <= 2 && b <= 2;
            assert_eq!(f.crease[e], on_ridge, "edge {a}–{b}");
            if on_ridge {
                let d = f.dihedral[e].unwrap();
                assert!((d - std::f64::consts::FRAC_PI_2).abs() < ANGLE_TOL, "{d}");
            }
        }
        assert_eq!(f.num_creases(), 2);
        assert_eq!(f.kinds[1], VertexKind::Crease);
        assert_eq!(f.kinds[0], VertexKind::Corner);
        assert_eq!(f.kinds[2], VertexKind::Corner);
        assert_eq!(f.kinds[4], VertexKind::Smooth);
        for (v, want) in [(1, 2), (0, 2), (2, 2), (4, 1)] {
            let sectors = f.sectors(&m, v);
            assert_eq!(sectors.len(), want, "vertex {v}: {sectors:?}");
            let mut all: Vec<usize> = sectors.concat();
            all.sort_unstable();
            let mut fan = m.faces_around_vertex(v);
            fan.sort_unstable();
            assert_eq!(all, fan, "vertex {v}");
        }
    }

    #[test]
    fn a_coarse_rim_turns_into_corners() {
        // A square pyramid's apex: four creases at 90° turns is a corner; a vertex where a
        // crease turns by 90° is a corner too.
        let p = [
            [0., 0., 1.],
            [1., 0., 0.],
            [0., 1., 0.],
            [-1., 0., 0.],
            [0., -1., 0.],
        ];
        let faces = vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]];
        let m = mesh(&p, faces);
        let f = Features::detect(&m, DEFAULT_CREASE_ANGLE_DEG);
        assert_eq!(f.num_creases(), 4);
        assert_eq!(f.kinds[0], VertexKind::Corner);
        assert_eq!(f.sectors(&m, 0).len(), 4);
    }

    #[test]
    fn a_face_of_zero_area_has_no_dihedral_angle_and_makes_no_crease() {
        // Two triangles and a needle collapsed onto an edge.
        let p = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0.5, 0., 0.]];
        let faces = vec![[0, 3, 2], [3, 1, 2], [0, 1, 3]];
        let m = Mesh::new_allowing_degenerate(
            p.iter()
                .map(|p| Vertex::without_curvature(Point3::new(p[0], p[1], p[2]), Vector3::z()))
                .collect(),
            faces,
        )
        .expect("a valid mesh with a degenerate face");
        let f = Features::detect(&m, DEFAULT_CREASE_ANGLE_DEG);
        // Edges 0–3 and 3–1 lie between the needle and a proper face.
        assert_eq!(f.undefined, 2);
        assert_eq!(f.num_creases(), 0);
    }
}
