//! The testbed's `G1` module: measured continuity of a fitted surface, for any scheme.
//!
//! Along every boundary shared by two patches — the interior boundaries inside a face (where the
//! scheme's [`Layout`] splits it) and the exterior edges between faces — the unit normals of both
//! patches are compared at `samples` equally spaced points (ends included; an exterior edge is
//! sampled as a whole even when two sub-patches share it), and the largest angle is reported
//! with where it occurred. The angle is `atan2(|n₁ × n₂|, n₁ · n₂)`, accurate near zero where `acos` is not.
//! Interpolation is measured at the same time: patch corners against vertex positions and
//! normals.
//!
//! Faces fitted with the fallback patch ([`crate::fit::Fit::face_fallbacks`]) promise only C0:
//! their interior boundaries and every exterior edge touching them are measured separately
//! (`fallback_*`), so the regular figures stay what the scheme guarantees; their corner normals
//! are left out of the interpolation error.

use ::mesh::features::angle;
use nalgebra::{Point3, Vector3};
use rayon::prelude::*;

use crate::beztri::SampleWeights;
use crate::fit::Fit;
use crate::mesh::Mesh;
use crate::patch;
use crate::scheme::{Bary, Form, Layout};

/// Where a G1 defect was measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Boundary {
    /// Interior boundary `boundary` of face `face`, in the order of [`interior_boundaries`].
    Interior {
        /// Face index.
        face: usize,
        /// Index into the layout's interior boundaries.
        boundary: usize,
    },
    /// The exterior edge between two faces.
    Exterior {
        /// Mesh edge index.
        edge: usize,
    },
}

/// The result of a G1 measurement.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct G1Report {
    /// Largest normal angle (radians) along interior boundaries of regular faces.
    pub interior_max: f64,
    /// Where it occurred (boundary and its parameter from its first end).
    pub interior_at: Option<(Boundary, f64)>,
    /// Largest normal angle (radians) along exterior edges between two regular faces.
    pub exterior_max: f64,
    /// Where it occurred (boundary and curve parameter).
    pub exterior_at: Option<(Boundary, f64)>,
    /// Largest distance between a patch corner and its data vertex.
    pub position_error: f64,
    /// Largest angle (radians) between a patch's corner normal and its data vertex normal.
    pub normal_error: f64,
    /// Samples where a patch normal was undefined (degenerate derivatives), skipped.
    pub undefined_normals: usize,
    /// Largest normal angle (radians) along interior boundaries of fallback faces.
    pub fallback_interior_max: f64,
    /// Largest normal angle (radians) along exterior edges touching a fallback face.
    pub fallback_exterior_max: f64,
    /// Exterior edges touching a fallback face (shared by two faces).
    pub fallback_edges: usize,
    /// Crease edges ([`crate::mesh::Mesh::is_crease`]): C0 by construction, not measured.
    pub crease_edges: usize,
}

impl G1Report {
    /// The largest normal angle anywhere.
    pub fn max_angle(&self) -> f64 {
        self.interior_max.max(self.exterior_max)
    }

    fn empty() -> Self {
        G1Report {
            interior_max: 0.0,
            interior_at: None,
            exterior_max: 0.0,
            exterior_at: None,
            position_error: 0.0,
            normal_error: 0.0,
            undefined_normals: 0,
            fallback_interior_max: 0.0,
            fallback_exterior_max: 0.0,
            fallback_edges: 0,
            crease_edges: 0,
        }
    }

    /// `self` then `later` (a later part of the scan): maxima combine, and where a maximum is
    /// tied the earlier location is kept, so the parallel scan reports what a sequential one
    /// would.
    fn merge(mut self, later: G1Report) -> G1Report {
        if later.interior_at.is_some()
            && (self.interior_at.is_none() || later.interior_max > self.interior_max)
        {
            self.interior_max = later.interior_max;
            self.interior_at = later.interior_at;
        }
        if later.exterior_at.is_some()
            && (self.exterior_at.is_none() || later.exterior_max > self.exterior_max)
        {
            self.exterior_max = later.exterior_max;
            self.exterior_at = later.exterior_at;
        }
        self.position_error = self.position_error.max(later.position_error);
        self.normal_error = self.normal_error.max(later.normal_error);
        self.undefined_normals += later.undefined_normals;
        self.fallback_interior_max = self.fallback_interior_max.max(later.fallback_interior_max);
        self.fallback_exterior_max = self.fallback_exterior_max.max(later.fallback_exterior_max);
        self.fallback_edges += later.fallback_edges;
        self.crease_edges += later.crease_edges;
        self
    }

    fn interior(&mut self, d: f64, at: (Boundary, f64)) {
        if d > self.interior_max || self.interior_at.is_none() {
            self.interior_max = self.interior_max.max(d);
            self.interior_at = Some(at);
        }
    }

    fn exterior(&mut self, d: f64, at: (Boundary, f64)) {
        if d > self.exterior_max || self.exterior_at.is_none() {
            self.exterior_max = self.exterior_max.max(d);
            self.exterior_at = Some(at);
        }
    }
}

/// How to get the normal of one patch at one local point: for a Bézier net, the weights of
/// `r_u` and `r_v` for the control points whose weights are not zero (on a patch edge only the
/// two rows next to it count); for a sampled form ([`crate::patch`]), the prepared point.
#[derive(Clone, Debug)]
pub(crate) struct Tangents {
    patch: usize,
    how: How,
}

#[derive(Clone, Debug)]
enum How {
    Bezier(Vec<(usize, [f64; 2])>),
    Sampled(&'static dyn patch::SampledForm, Vec<f64>),
}

impl Tangents {
    fn new(layout: &Layout, patch: usize, local: Bary) -> Self {
        // Coordinates that are zero up to the rounding of the inverse are made exactly zero,
        // so the rows away from an edge get exactly zero weight and are skipped.
        let l = local.map(|c| if c.abs() < 1e-13 { 0.0 } else { c });
        let how = match layout.form {
            Form::Bezier => {
                let sw = SampleWeights::new(layout.degree, l[0], l[1]);
                How::Bezier(
                    sw.weights()
                        .iter()
                        .enumerate()
                        .filter(|(_, w)| w[1] != 0.0 || w[2] != 0.0)
                        .map(|(i, w)| (i, [w[1], w[2]]))
                        .collect(),
                )
            }
            Form::Sampled(form) => How::Sampled(form, form.prepare(l)),
        };
        Tangents { patch, how }
    }

    /// The patch's position (sampled forms only: Bézier corners are read off the net) and unit
    /// normal `r_u × r_v` here (no threshold: any non-zero cross product), from one evaluation.
    fn point_and_normal(
        &self,
        face: &[Point3<f64>],
        np: usize,
    ) -> (Option<Point3<f64>>, Option<Vector3<f64>>) {
        match self.point_and_cross(face, np) {
            Some((p, c)) => (p, unit_normal(&c)),
            None => (None, None),
        }
    }

    /// The position (sampled forms only) and `r_u × r_v`, not normalized; `None` where the
    /// face's points do not hold the patch.
    fn point_and_cross(
        &self,
        face: &[Point3<f64>],
        np: usize,
    ) -> Option<(Option<Point3<f64>>, Vector3<f64>)> {
        let net = face.get(self.patch * np..(self.patch + 1) * np)?;
        let (p, du, dv) = match &self.how {
            How::Bezier(w) => {
                let (mut du, mut dv) = (Vector3::zeros(), Vector3::zeros());
                for (i, w) in w {
                    let p = net.get(*i)?;
                    du += p.coords * w[0];
                    dv += p.coords * w[1];
                }
                (None, du, dv)
            }
            How::Sampled(form, p) => {
                let d = form.eval(net, p);
                (Some(d.p), d.du, d.dv)
            }
        };
        Some((p, du.cross(&dv)))
    }

    /// `r_u × r_v` of the face's patch, not normalized ([`unit_normal`] makes it the normal).
    fn cross(&self, face: &[Point3<f64>], np: usize) -> Option<Vector3<f64>> {
        self.point_and_cross(face, np).map(|(_, c)| c)
    }

    /// Unit normal `r_u × r_v` of the face's patch (see [`Tangents::point_and_normal`]).
    pub(crate) fn normal(&self, face: &[Point3<f64>], np: usize) -> Option<Vector3<f64>> {
        self.point_and_normal(face, np).1
    }
}

/// `c / |c|`: the unit normal of a cross product `r_u × r_v`, `None` where it is zero or not
/// finite (no threshold).
fn unit_normal(c: &Vector3<f64>) -> Option<Vector3<f64>> {
    let len = c.norm();
    (len > 0.0 && len.is_finite()).then(|| c / len)
}

/// Samples of one boundary whose normals are computed together ([`chord_pairs`]).
const BATCH: usize = 16;

/// The squared chords between the unit normals of two sides at pairs of samples (`None` where
/// either is undefined), given to `at` in order with the pair's index. The cross products of a
/// batch of pairs first, then their normalization: the square roots and divisions of
/// different samples overlap in the processor where one sample at a time waited on each. The
/// same operations on the same numbers as normalizing each pair at once: the same bits.
fn chord_pairs<'a>(
    pairs: impl ExactSizeIterator<
        Item = (
            &'a Tangents,
            &'a [Point3<f64>],
            &'a Tangents,
            &'a [Point3<f64>],
        ),
    >,
    np: usize,
    flip_b: bool,
    mut at: impl FnMut(usize, Option<f64>),
) {
    let mut cross = [(None, None); BATCH];
    let mut pairs = pairs.peekable();
    let mut k = 0;
    while pairs.peek().is_some() {
        let mut n = 0;
        for (slot, (ta, pa, tb, pb)) in cross.iter_mut().zip(pairs.by_ref()) {
            *slot = (ta.cross(pa, np), tb.cross(pb, np));
            n += 1;
        }
        for (ca, cb) in &cross[..n] {
            let c = match (
                ca.and_then(|c| unit_normal(&c)),
                cb.and_then(|c| unit_normal(&c)),
            ) {
                (Some(x), Some(y)) => Some(chord2(&x, &if flip_b { -y } else { y })),
                _ => None,
            };
            at(k, c);
            k += 1;
        }
    }
}

/// A monotone stand-in for the angle between unit vectors, cheap and accurate near zero: the
/// chord `|a − b| = 2 sin(θ/2)`, compared as its square; [`from_chord2`] turns the largest
/// back into radians.
pub(crate) fn chord2(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    (a - b).norm_squared()
}

/// The angle whose squared chord is `c2`: `θ = 2 asin(√c2 / 2)`.
pub(crate) fn from_chord2(c2: f64) -> f64 {
    2.0 * (c2.sqrt() / 2.0).min(1.0).asin()
}

/// Local barycentric coordinates of the face point `x` in sub-triangle `sub`.
fn local(sub: &[Bary; 3], x: Bary) -> Option<Bary> {
    let m = nalgebra::Matrix3::from_fn(|r, c| sub[c][r]);
    let l = m.try_inverse()? * nalgebra::Vector3::from(x);
    Some([l[0], l[1], l[2]])
}

fn lerp(a: Bary, b: Bary, t: f64) -> Bary {
    std::array::from_fn(|c| a[c] * (1.0 - t) + b[c] * t)
}

fn same(a: Bary, b: Bary) -> bool {
    (0..3).all(|c| (a[c] - b[c]).abs() < 1e-12)
}

/// The boundaries two sub-triangles of `layout` share inside a face: `(patch a, its local edge
/// from corner l to l + 1, patch b)`, in order of `a`, then `l`. For the centroid split:
/// `V_1 → S`, `S → V_0`, `V_2 → S`.
pub fn interior_boundaries(layout: &Layout) -> Vec<(usize, usize, usize)> {
    let subs = layout.subs;
    let mut out = Vec::new();
    for (a, sa) in subs.iter().enumerate() {
        for l in 0..3 {
            let (p, q) = (sa[l], sa[(l + 1) % 3]);
            let partner = subs
                .iter()
                .enumerate()
                .skip(a + 1)
                .find(|(_, sb)| (0..3).any(|m| same(sb[m], q) && same(sb[(m + 1) % 3], p)));
            if let Some((b, _)) = partner {
                out.push((a, l, b));
            }
        }
    }
    out
}

/// Everything about a layout that does not depend on the face: where to sample and the weights
/// there.
pub(crate) struct Plan {
    pub(crate) np: usize,
    /// Per interior boundary, per sample: `(t, side a, side b)`.
    interior: Vec<Vec<(f64, Tangents, Tangents)>>,
    /// Per face edge `l` (from corner `l` to `l + 1`), per sample `t`: the tangents there.
    pub(crate) exterior: [Vec<(f64, Tangents)>; 3],
    /// Per face corner: the control point that interpolates it and the tangents there.
    corners: [(usize, Tangents); 3],
}

impl Plan {
    pub(crate) fn new(layout: &Layout, samples: usize) -> Option<Plan> {
        let np = layout.points_per_patch();
        let ts: Vec<f64> = (0..samples)
            .map(|s| s as f64 / (samples - 1) as f64)
            .collect();
        let subs = layout.subs;
        let mut interior = Vec::new();
        for (a, l, b) in interior_boundaries(layout) {
            let (p, q) = (subs[a][l], subs[a][(l + 1) % 3]);
            let mut row = Vec::with_capacity(ts.len());
            for &t in &ts {
                let x = lerp(p, q, t);
                row.push((
                    t,
                    Tangents::new(layout, a, local(&subs[a], x)?),
                    Tangents::new(layout, b, local(&subs[b], x)?),
                ));
            }
            interior.push(row);
        }
        let corner = |i: usize| -> Bary { std::array::from_fn(|c| f64::from(u8::from(c == i))) };
        let mut exterior: [Vec<(f64, Tangents)>; 3] = Default::default();
        for (l, row) in exterior.iter_mut().enumerate() {
            let opposite = (l + 2) % 3;
            for &t in &ts {
                let x = lerp(corner(l), corner((l + 1) % 3), t);
                // The first sub-triangle with an edge on the face edge that contains x.
                let s = subs.iter().position(|sub| {
                    (0..3).any(|m| {
                        sub[m][opposite].abs() < 1e-12 && sub[(m + 1) % 3][opposite].abs() < 1e-12
                    }) && local(sub, x).is_some_and(|b| b.iter().all(|c| *c >= -1e-12))
                })?;
                row.push((t, Tangents::new(layout, s, local(&subs[s], x)?)));
            }
        }
        let mut corners_v = Vec::with_capacity(3);
        for i in 0..3 {
            let (s, m) = subs
                .iter()
                .enumerate()
                .find_map(|(s, sub)| (0..3).find(|m| same(sub[*m], corner(i))).map(|m| (s, m)))?;
            let mut idx = [0usize; 3];
            idx[m] = layout.degree;
            let point = s * np + crate::beztri::index(layout.degree, idx[0], idx[1], idx[2]);
            corners_v.push((point, Tangents::new(layout, s, corner(m))));
        }
        let corners: [(usize, Tangents); 3] = corners_v.try_into().ok()?;
        Some(Plan {
            np,
            interior,
            exterior,
            corners,
        })
    }
}

/// Measures G1 continuity and interpolation of `fit` over `mesh` at `samples ≥ 2` points per
/// boundary. Sample weights are computed once per layout; faces and edges are measured in
/// parallel, with the same result as a sequential scan.
pub fn measure(mesh: &Mesh, fit: &Fit, samples: usize) -> G1Report {
    let Some(plan) = Plan::new(&fit.layout, samples.max(2)) else {
        return G1Report::empty();
    };
    let per_face = fit.layout.points_per_face();
    let fallback = fit.fallback_mask(mesh.num_faces());
    let face_points = |f: usize| fit.points.get(f * per_face..(f + 1) * per_face);
    let faces = (0..mesh.num_faces())
        .into_par_iter()
        .fold(G1Report::empty, |mut r, f| {
            if let Some(pts) = face_points(f) {
                plan.face(mesh, f, pts, fallback[f], &mut r);
            }
            r
        })
        .reduce(G1Report::empty, G1Report::merge);
    let edges = mesh
        .par_edges()
        .enumerate()
        .fold(G1Report::empty, |mut r, (ei, e)| {
            let (Some((g, _)), (f, _)) = (e.second, e.first) else {
                return r;
            };
            if let (Some(pf), Some(pg)) = (face_points(f), face_points(g)) {
                plan.edge(mesh, ei, [pf, pg], [fallback[f], fallback[g]], &mut r);
            }
            r
        })
        .reduce(G1Report::empty, G1Report::merge);
    faces.merge(edges).into_angles()
}

impl G1Report {
    /// The scans compare squared chords of the normals; this reports angles.
    fn into_angles(mut self) -> G1Report {
        for x in [
            &mut self.interior_max,
            &mut self.exterior_max,
            &mut self.fallback_interior_max,
            &mut self.fallback_exterior_max,
        ] {
            *x = from_chord2(*x);
        }
        self
    }

    /// Merges a part of the exterior scan measured out of edge order: where maxima tie, the
    /// location earlier in the sequential scan (smaller edge, then smaller parameter) wins, as
    /// [`G1Report::merge`] gives for parts in order. Only the exterior figures may differ
    /// from a merge in order, so the rest is [`G1Report::merge`].
    fn merge_unordered(self, other: G1Report) -> G1Report {
        let key = |r: &G1Report| match r.exterior_at {
            Some((Boundary::Exterior { edge }, t)) => Some((edge, t)),
            _ => None,
        };
        let (mine, theirs) = (key(&self), key(&other));
        let exterior = match (mine, theirs) {
            (_, None) => (self.exterior_max, self.exterior_at),
            (None, Some(_)) => (other.exterior_max, other.exterior_at),
            (Some(a), Some(b)) => {
                if other.exterior_max > self.exterior_max
                    || (other.exterior_max == self.exterior_max && b < a)
                {
                    (other.exterior_max, other.exterior_at)
                } else {
                    (self.exterior_max, self.exterior_at)
                }
            }
        };
        let mut r = self.merge(other);
        (r.exterior_max, r.exterior_at) = exterior;
        r
    }
}

/// G1 measured as a fit's faces are built, a range of faces at a time, without the whole
/// [`Fit`]'s nets ([`crate::stream`]). Give it every face exactly once, in order of ranges
/// ([`StreamingG1::faces`]), and each exterior edge exactly once from either side
/// ([`StreamingG1::edge`], any order); [`StreamingG1::finish`] then returns the report
/// [`measure`] gives for the whole fit, bit for bit.
pub struct StreamingG1 {
    plan: Option<Plan>,
    /// The merged report of the face ranges so far (in order) and of the edges.
    faces: G1Report,
    edges: G1Report,
}

impl StreamingG1 {
    /// A measurement of fits with `layout` at `samples ≥ 2` points per boundary.
    pub fn new(layout: &Layout, samples: usize) -> Self {
        StreamingG1 {
            plan: Plan::new(layout, samples.max(2)),
            faces: G1Report::empty(),
            edges: G1Report::empty(),
        }
    }

    /// The part of the report from faces `first..first + fallback.len()`, whose points
    /// (`points_per_face` each, in face order) are `points`: interior boundaries and
    /// interpolation. Parts are independent; merge them in face order with
    /// [`StreamingG1::add_faces`].
    pub fn faces(
        &self,
        mesh: &Mesh,
        first: usize,
        points: &[Point3<f64>],
        fallback: &[bool],
    ) -> G1Report {
        let mut r = G1Report::empty();
        let Some(plan) = &self.plan else {
            return r;
        };
        let per_face = points.len() / fallback.len().max(1);
        for (i, (pts, fb)) in points
            .chunks_exact(per_face.max(1))
            .zip(fallback)
            .enumerate()
        {
            plan.face(mesh, first + i, pts, *fb, &mut r);
        }
        r
    }

    /// The part of the report from exterior edge `edge` (two faces) given both faces' points
    /// and fallback flags, `[first face, second face]` as the mesh's edge lists them. Parts
    /// merge in any order with [`StreamingG1::add_edges`].
    pub fn edge(
        &self,
        mesh: &Mesh,
        edge: usize,
        points: [&[Point3<f64>]; 2],
        fallback: [bool; 2],
        into: &mut G1Report,
    ) {
        if let Some(plan) = &self.plan {
            plan.edge(mesh, edge, points, fallback, into);
        }
    }

    /// An empty part to accumulate edges into.
    pub fn empty_part() -> G1Report {
        G1Report::empty()
    }

    /// Merges the next range of faces (ranges must come in face order).
    pub fn add_faces(&mut self, part: G1Report) {
        self.faces = std::mem::replace(&mut self.faces, G1Report::empty()).merge(part);
    }

    /// Merges a part of the edges (any order, ties resolved as the sequential scan would).
    pub fn add_edges(&mut self, part: G1Report) {
        self.edges = std::mem::replace(&mut self.edges, G1Report::empty()).merge_unordered(part);
    }

    /// Merges two edge parts (any order; see [`StreamingG1::add_edges`]).
    pub fn merge_edges(a: G1Report, b: G1Report) -> G1Report {
        a.merge_unordered(b)
    }

    /// The report.
    pub fn finish(self) -> G1Report {
        self.faces.merge(self.edges).into_angles()
    }
}

impl Plan {
    /// Face `f`'s interior boundaries and interpolation, its points `pts`.
    fn face(&self, mesh: &Mesh, f: usize, pts: &[Point3<f64>], fallback: bool, r: &mut G1Report) {
        let np = self.np;
        for (bi, row) in self.interior.iter().enumerate() {
            let pairs = row.iter().map(|(_, a, b)| (a, pts, b, pts));
            chord_pairs(pairs, np, false, |k, c| match c {
                Some(c) if fallback => {
                    r.fallback_interior_max = r.fallback_interior_max.max(c);
                }
                Some(c) => r.interior(
                    c,
                    (
                        Boundary::Interior {
                            face: f,
                            boundary: bi,
                        },
                        row[k].0,
                    ),
                ),
                None => r.undefined_normals += 1,
            });
        }
        for (i, (point, tangents)) in self.corners.iter().enumerate() {
            let Some(v) = mesh.corner_data(f, i) else {
                continue;
            };
            let (at, normal) = tangents.point_and_normal(pts, np);
            let at = at.unwrap_or(pts[*point]);
            r.position_error = r.position_error.max((at - v.p).norm());
            if fallback {
                continue;
            }
            match normal {
                Some(n) => r.normal_error = r.normal_error.max(angle(&n, &v.n.normalize())),
                None => r.undefined_normals += 1,
            }
        }
    }

    /// Exterior edge `ei` between its first face (points `pts[0]`) and second (`pts[1]`).
    fn edge(
        &self,
        mesh: &Mesh,
        ei: usize,
        pts: [&[Point3<f64>]; 2],
        fallback: [bool; 2],
        r: &mut G1Report,
    ) {
        let e = &mesh.edge(ei);
        let (Some((_, lg)), (_, lf)) = (e.second, e.first) else {
            return;
        };
        if mesh.is_crease(ei) {
            // C0 by construction, the data's dihedral kept: not a G1 boundary.
            r.crease_edges += 1;
            return;
        }
        let np = self.np;
        let [pf, pg] = pts;
        let touches_fallback = fallback[0] || fallback[1];
        r.fallback_edges += usize::from(touches_fallback);
        // Face f's edge runs from its corner lf to lf + 1; g's runs backwards.
        let (f, g) = ((&self.exterior[lf][..], pf), (&self.exterior[lg][..], pg));
        boundary_chords(f, g, np, true, false, |t, c| match c {
            Some(c) if touches_fallback => {
                r.fallback_exterior_max = r.fallback_exterior_max.max(c);
            }
            Some(c) => r.exterior(c, (Boundary::Exterior { edge: ei }, t)),
            None => r.undefined_normals += 1,
        });
    }
}

/// Samples along one side of a boundary: the tangents at each parameter of a patch edge (a
/// row of [`Plan`]'s `exterior`) and the points they weigh (a face's, or one patch's, net).
pub(crate) type Side<'a> = (&'a [(f64, Tangents)], &'a [Point3<f64>]);

/// The measurement of one boundary shared by two patches, used by [`measure`] for the edges
/// between faces and by [`crate::patch_g1`] for boundaries matched by position: at each sample
/// of side `a` (its parameter `t` along `a`'s edge), the squared chord between the unit normals
/// of both sides ([`chord2`]; `None` where either normal is undefined) is given to `at`.
/// `reversed`: `b`'s edge runs the other way (the usual case, neighbours traversing their
/// common edge in opposite directions), so `a`'s sample `k` meets `b`'s sample `n − 1 − k`;
/// `flip_b`: `b`'s normal is reversed first (oppositely oriented patches). `np` is the points
/// per patch of the nets.
pub(crate) fn boundary_chords(
    a: Side<'_>,
    b: Side<'_>,
    np: usize,
    reversed: bool,
    flip_b: bool,
    mut at: impl FnMut(f64, Option<f64>),
) {
    let ((sa, pa), (sb, pb)) = (a, b);
    let n = sa.len().min(sb.len());
    let pairs = (0..n).map(|k| {
        let tb = &sb[if reversed { n - 1 - k } else { k }].1;
        (&sa[k].1, pa, tb, pb)
    });
    chord_pairs(pairs, np, flip_b, |k, c| at(sa[k].0, c));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn exterior(edge: usize, t: f64, chord2: f64) -> G1Report {
        let mut r = G1Report::empty();
        r.exterior(chord2, (Boundary::Exterior { edge }, t));
        r
    }

    /// Edge parts merged out of order name what the sequential scan names: the largest defect,
    /// and among equal ones the smallest edge, then the smallest parameter.
    #[test]
    fn unordered_edge_parts_resolve_ties_as_the_sequential_scan() {
        let parts = [
            exterior(9, 0.0, 0.5),
            exterior(5, 0.75, 1.0),
            exterior(7, 0.0, 1.0),
            exterior(5, 0.25, 1.0),
            exterior(2, 0.5, 0.25),
        ];
        let sequential = {
            let mut sorted = parts;
            sorted.sort_by(|a, b| {
                let key = |r: &G1Report| match r.exterior_at {
                    Some((Boundary::Exterior { edge }, t)) => (edge, t),
                    _ => (usize::MAX, 0.0),
                };
                key(a)
                    .partial_cmp(&key(b))
                    .unwrap_or(std::cmp::Ordering::Equal)
            });
            sorted.into_iter().fold(G1Report::empty(), G1Report::merge)
        };
        assert_eq!(
            sequential.exterior_at,
            Some((Boundary::Exterior { edge: 5 }, 0.25))
        );
        for order in [[0, 1, 2, 3, 4], [4, 3, 2, 1, 0], [2, 0, 4, 1, 3]] {
            let mut s = StreamingG1::new(&Layout::bezier(4, &crate::scheme::CENTROID_SPLIT), 9);
            for i in order {
                s.add_edges(parts[i]);
            }
            assert_eq!(s.edges, sequential, "order {order:?}");
        }
    }
}
