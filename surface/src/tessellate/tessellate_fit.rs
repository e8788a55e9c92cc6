#![allow(clippy::needless_range_loop)] // corners and edges are indexed 0..3 across several parallel arrays
//! Tessellation of a fitted mesh with welding by topology: the testbed's `Tess` at full speed.
//!
//! [`crate::tessellate::tessellate`] takes any list of patches and welds boundary samples by
//! position (a spatial hash). A [`Fit`] knows more: which patches meet where. Every sample of
//! every patch sits at a point of its face's barycentric domain; with the layouts in use
//! (corners on the lattice of sixths) and `s` segments per patch edge, that point lies on the
//! lattice `q/(6s)`, `q ∈ ℕ³`, `|q| = 6s`. A lattice point with two zero coordinates is a
//! mesh vertex, one with one zero coordinate lies on a mesh edge (the same point for both faces
//! on it, at mirrored positions), the rest are inside the face. So every sample gets its
//! output vertex from arithmetic alone:
//!
//! * a mesh vertex's sample belongs to the lowest-numbered face around it, a mesh edge's
//!   samples to the edge's first face, a face's inner samples to the face;
//! * each face's owned samples form one contiguous block of the output (prefix sums), so the
//!   faces are evaluated in parallel into disjoint slices, each sample exactly once;
//! * triangles are written per face (a fixed number per face, in patch order) with the ids the
//!   arithmetic gives.
//!
//! The result is the same welded mesh the positional weld gives for a watertight fit (the
//! vertex order differs), computed without hashing and without evaluating any sample twice.
//! A welded vertex carries the geometry of its owner's patch ([`Tessellation::welds`] counts
//! the samples that were not evaluated because another patch owns them;
//! [`Tessellation::max_weld_normal_angle`] is not measured here and stays 0: `measure_g1`
//! reports normal jumps along every shared boundary). Sample weights are computed once per
//! layout ([`SampleWeights`]); singular samples are nudged as in
//! [`crate::tessellate`](mod@crate::tessellate).
//!
//! A layout whose corners are not on the sixths lattice is tessellated by the positional weld.

use std::borrow::Cow;

use curves::CubicBez3;
use nalgebra::{Point3, Vector3};
use rayon::prelude::*;

use crate::beztri::{curvature_of, BezierTriangle, Curvature};
use crate::fit::{build_face, Fit};
use crate::mesh::Mesh;
use crate::patch::{self, Prepared};
use crate::scheme::{Layout, Scheme};
use crate::tessellate::{flat_curvature, nudged_geometry, tessellate, TessError, Tessellation};

/// Where a sample of a face goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Slot {
    /// The mesh vertex at face corner `c`.
    Corner(usize),
    /// Sample `k` (from corner `l`) of the face's edge `l` (from corner `l` to `l + 1`).
    Edge(usize, usize),
    /// Inner sample `k` of the face.
    Inner(usize),
}

/// What does not depend on the face.
struct Plan {
    /// Samples per patch (`(s + 1)(s + 2)/2`), prepared for evaluation ([`patch::prepare`]).
    weights: Vec<Prepared>,
    /// Barycentric `(u, v, w)` of each local sample.
    local: Vec<(f64, f64, f64)>,
    /// Per patch of the layout, per local sample: its slot.
    slots: Vec<Vec<Slot>>,
    /// Samples inside a mesh edge (excluding its ends).
    per_edge: usize,
    /// Samples inside a face.
    per_face_inner: usize,
    /// For each slot kind, the first (patch, local sample) that lands there: corners, edge
    /// samples (per edge `l`, from corner `l`), inner samples.
    corner_src: [(usize, usize); 3],
    edge_src: [Vec<(usize, usize)>; 3],
    inner_src: Vec<(usize, usize)>,
    /// Triangles per patch as local sample indices.
    triangles: Vec<[usize; 3]>,
}

/// Local index of sample `(i, j, s − i − j)` (rows by `j`, as in the positional tessellation).
fn local_index(s: usize, i: usize, j: usize) -> usize {
    j * (s + 1) - j * j.saturating_sub(1) / 2 + i
}

impl Plan {
    fn new(layout: &Layout, s: usize) -> Option<Plan> {
        let lattice = 6 * s as i64;
        // Corners on the lattice of sixths.
        let corners: Vec<[[i64; 3]; 3]> = layout
            .subs
            .iter()
            .map(|sub| {
                let mut out = [[0i64; 3]; 3];
                for (c, corner) in sub.iter().enumerate() {
                    for (k, x) in corner.iter().enumerate() {
                        let q = x * 6.0;
                        if (q - q.round()).abs() > 1e-9 {
                            return None;
                        }
                        out[c][k] = q.round() as i64;
                    }
                }
                Some(out)
            })
            .collect::<Option<_>>()?;
        let n = (s + 1) * (s + 2) / 2;
        let mut local = vec![(0.0, 0.0, 0.0); n];
        let mut weights = Vec::with_capacity(n);
        for j in 0..=s {
            for i in 0..=s - j {
                let (u, v) = (i as f64 / s as f64, j as f64 / s as f64);
                local[local_index(s, i, j)] = (u, v, 1.0 - u - v);
            }
        }
        for &(u, v, w) in &local {
            weights.push(patch::prepare(layout, [u, v, w]));
        }
        // Face lattice point of every (patch, sample).
        let mut edge_points: [Vec<i64>; 3] = Default::default();
        let mut inner_points: Vec<[i64; 3]> = Vec::new();
        let mut points = vec![vec![[0i64; 3]; n]; corners.len()];
        for (p, c) in corners.iter().enumerate() {
            for j in 0..=s {
                for i in 0..=s - j {
                    let k = s - i - j;
                    let q: [i64; 3] = std::array::from_fn(|d| {
                        i as i64 * c[0][d] + j as i64 * c[1][d] + k as i64 * c[2][d]
                    });
                    points[p][local_index(s, i, j)] = q;
                    let zeros = q.iter().filter(|x| **x == 0).count();
                    match zeros {
                        2 => {}
                        1 => {
                            let l = (q.iter().position(|x| *x == 0)? + 1) % 3;
                            edge_points[l].push(q[(l + 1) % 3]);
                        }
                        _ => inner_points.push(q),
                    }
                }
            }
        }
        for e in &mut edge_points {
            e.sort_unstable();
            e.dedup();
        }
        inner_points.sort_unstable();
        inner_points.dedup();
        // Both faces on an edge must see the same samples at mirrored positions.
        let per_edge = edge_points[0].len();
        for e in &edge_points {
            if e.len() != per_edge || e.iter().zip(e.iter().rev()).any(|(a, b)| a + b != lattice) {
                return None;
            }
        }
        let mut slots = vec![vec![Slot::Inner(0); n]; corners.len()];
        let mut corner_src = [(usize::MAX, 0); 3];
        let mut edge_src: [Vec<(usize, usize)>; 3] =
            std::array::from_fn(|_| vec![(usize::MAX, 0); per_edge]);
        let mut inner_src = vec![(usize::MAX, 0); inner_points.len()];
        for (p, pts) in points.iter().enumerate() {
            for (li, q) in pts.iter().enumerate() {
                let zeros = q.iter().filter(|x| **x == 0).count();
                let (slot, src) = match zeros {
                    2 => {
                        let c = q.iter().position(|x| *x != 0)?;
                        (Slot::Corner(c), &mut corner_src[c])
                    }
                    1 => {
                        let l = (q.iter().position(|x| *x == 0)? + 1) % 3;
                        let k = edge_points[l].binary_search(&q[(l + 1) % 3]).ok()?;
                        (Slot::Edge(l, k), &mut edge_src[l][k])
                    }
                    _ => {
                        let k = inner_points.binary_search(q).ok()?;
                        (Slot::Inner(k), &mut inner_src[k])
                    }
                };
                slots[p][li] = slot;
                if src.0 == usize::MAX {
                    *src = (p, li);
                }
            }
        }
        if corner_src.iter().any(|c| c.0 == usize::MAX) {
            return None;
        }
        let mut triangles = Vec::with_capacity(s * s);
        for j in 0..s {
            for i in 0..s - j {
                triangles.push([
                    local_index(s, i + 1, j),
                    local_index(s, i, j + 1),
                    local_index(s, i, j),
                ]);
                if i + j + 2 <= s {
                    triangles.push([
                        local_index(s, i + 1, j),
                        local_index(s, i + 1, j + 1),
                        local_index(s, i, j + 1),
                    ]);
                }
            }
        }
        Some(Plan {
            weights,
            local,
            slots,
            per_edge,
            per_face_inner: inner_points.len(),
            corner_src,
            edge_src,
            inner_src,
            triangles,
        })
    }
}

/// One evaluated sample.
#[derive(Clone, Copy, Debug)]
struct Sample {
    p: Point3<f64>,
    c: Curvature,
    nudged: bool,
}

/// Position and differential geometry of one sample of a patch (any form, [`patch`]); nudged
/// towards the centre where the patch is singular, as the positional tessellation does.
fn evaluate(
    layout: &Layout,
    net: &[Point3<f64>],
    prepared: &Prepared,
    (u, v, w): (f64, f64, f64),
) -> Sample {
    let d = patch::eval(layout, net, prepared);
    if let Some(c) = curvature_of(&d) {
        return Sample {
            p: d.p,
            c,
            nudged: false,
        };
    }
    // Rare: the general rules only here.
    let c = if layout.is_bezier() {
        let degree = layout.degree;
        let bez = BezierTriangle::from_fn(degree, |i, j, k| {
            net.get(crate::beztri::index(degree, i, j, k))
                .copied()
                .unwrap_or_else(Point3::origin)
        });
        nudged_geometry(&bez, u, v)
    } else {
        patch::nudged_curvature(layout, net, [u, v, w])
            .unwrap_or_else(|| flat_curvature(d.du.cross(&d.dv)))
    };
    Sample {
        p: d.p,
        c,
        nudged: true,
    }
}

/// Faces per parallel task: enough to amortize the task (a few microseconds of work at s = 1),
/// few enough that two threads share the work evenly from 10⁴ faces on.
const FACES_PER_TASK: usize = 512;

/// `n` copies of `value`, written by all threads: the first touch of a large output (page
/// faults, which dominate at 10⁶ faces) is shared instead of done by one thread before the
/// parallel evaluation.
fn par_filled<T: Copy + Send + Sync>(value: T, n: usize) -> Vec<T> {
    let mut v = Vec::with_capacity(n);
    v.par_extend(rayon::iter::repeat_n(value, n));
    v
}

/// `v` cut into consecutive blocks `start[f]..start[f + 1]`.
fn split_blocks<'a, T>(mut v: &'a mut [T], start: &[usize]) -> Vec<&'a mut [T]> {
    let mut out = Vec::with_capacity(start.len().saturating_sub(1));
    for w in start.windows(2) {
        let (head, tail) = v.split_at_mut(w[1] - w[0]);
        out.push(head);
        v = tail;
    }
    out
}

/// Tessellates `fit` (a fit of `mesh`) at `s` segments per patch edge into one welded mesh,
/// welding by topology (module docs). Falls back to the positional weld of
/// [`crate::tessellate::tessellate`] for a layout whose corners are not on the sixths lattice.
pub fn tessellate_fit(mesh: &Mesh, fit: &Fit, s: usize) -> Result<Tessellation, TessError> {
    if s == 0 {
        return Err(TessError::ZeroDensity);
    }
    let layout = fit.layout;
    let Some(plan) = Plan::new(&layout, s) else {
        return tessellate(&fit.bezier_patches(), s);
    };
    let per_face = layout.patches_per_face() * layout.points_per_patch();
    if fit.points.len() != mesh.num_faces() * per_face {
        return tessellate(&fit.bezier_patches(), s);
    }
    tessellate_by_topology(mesh, &layout, &plan, s, Nets::Whole(&fit.points), Keep::ALL)
}

/// Whether [`tessellate_fit`] welds `layout`'s patches at `s` segments by topology (its corners
/// on the lattice of sixths), which is what [`tessellate_fit_rebuilt`] needs.
pub fn welds_by_topology(layout: &Layout, s: usize) -> bool {
    s > 0 && Plan::new(layout, s).is_some()
}

/// [`tessellate_fit`] for a fit whose nets are not held ([`crate::stream`] leaves
/// [`Fit::points`] empty): each face's patches are built again from `fit`'s curves by
/// `scheme` ([`build_face`]) just before its samples are evaluated, in the task that evaluates
/// them, so no more than a face's nets per thread are held. A face's patches depend only on
/// its own corners, its curves and the scheme, so this is the tessellation [`tessellate_fit`]
/// gives for the whole fit, bit for bit, for one more build of every face (about 0.45 µs a
/// face of three quartics); the whole fit's nets (1.08 kB a face) are never held. Errors
/// ([`TessError::Rebuild`]) where the layout is not welded by topology
/// ([`welds_by_topology`]) or a face cannot be built.
pub fn tessellate_fit_rebuilt(
    mesh: &Mesh,
    fit: &Fit,
    scheme: &dyn Scheme,
    s: usize,
) -> Result<Tessellation, TessError> {
    tessellate_fit_rebuilt_with(mesh, fit, scheme, s, Keep::ALL)
}

/// Which of a tessellation's optional arrays to store ([`tessellate_fit_rebuilt_with`]): a
/// caller that writes a file needs at most the principal directions, not the shape tensors
/// (72 bytes a vertex) nor each triangle's patch (8 bytes a triangle).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Keep {
    /// [`Tessellation::shapes`].
    pub shapes: bool,
    /// [`Tessellation::directions`], of each sample's shape tensor divided by this scale (the
    /// working frame's, `mesh::Frame::scale`: the tensor [`Tessellation::to_world`] gives) and
    /// its normal (`estimate::principal_frame`), so they are, bit for bit, the directions of
    /// the tessellation's tensors once mapped to world coordinates; 48 bytes a vertex.
    pub directions: Option<f64>,
    /// [`Tessellation::patch_of_face`].
    pub patches: bool,
}

impl Keep {
    /// Every array (what [`tessellate_fit_rebuilt`] stores): the tensors, no directions, the
    /// patches.
    pub const ALL: Keep = Keep {
        shapes: true,
        directions: None,
        patches: true,
    };
}

/// [`tessellate_fit_rebuilt`], storing the optional arrays `keep` asks for (the others are
/// left empty; at 10⁶ faces and `s = 1`, the tensors are 0.11 GB and the patches 24 MB).
/// Every other array is the same, bit for bit (the tensors are computed either way: `K` and
/// `H` come from them).
pub fn tessellate_fit_rebuilt_with(
    mesh: &Mesh,
    fit: &Fit,
    scheme: &dyn Scheme,
    s: usize,
    keep: Keep,
) -> Result<Tessellation, TessError> {
    rebuilt(mesh, fit, scheme, s, keep, Cow::Borrowed(&fit.curves))
}

/// [`tessellate_fit_rebuilt_with`] for a caller done with the fit's curves: they are taken from
/// `fit` (left empty) and freed as soon as every sample is evaluated, before the triangles are
/// allocated, so the curves (96 B an edge) and the triangles (72 B a face at `s = 1`) are
/// never held together. The same tessellation, bit for bit.
pub fn tessellate_fit_rebuilt_taking(
    mesh: &Mesh,
    fit: &mut Fit,
    scheme: &dyn Scheme,
    s: usize,
    keep: Keep,
) -> Result<Tessellation, TessError> {
    let curves = std::mem::take(&mut fit.curves);
    rebuilt(mesh, fit, scheme, s, keep, Cow::Owned(curves))
}

/// The rebuilt tessellation of `fit` from `curves` (its own, borrowed or taken).
fn rebuilt(
    mesh: &Mesh,
    fit: &Fit,
    scheme: &dyn Scheme,
    s: usize,
    keep: Keep,
    curves: Cow<'_, [CubicBez3]>,
) -> Result<Tessellation, TessError> {
    if s == 0 {
        return Err(TessError::ZeroDensity);
    }
    let layout = fit.layout;
    let Some(plan) = Plan::new(&layout, s) else {
        return Err(TessError::Rebuild(format!(
            "the layout of `{}` is not welded by topology at {s} segments",
            fit.scheme
        )));
    };
    tessellate_by_topology(
        mesh,
        &layout,
        &plan,
        s,
        Nets::Rebuilt { scheme, curves },
        keep,
    )
}

/// Where the tessellation reads a face's nets.
#[derive(Clone)]
enum Nets<'a> {
    /// A whole fit's points, face after face.
    Whole(&'a [Point3<f64>]),
    /// Built again per face from the fit's curves (freed after the samples when owned).
    Rebuilt {
        scheme: &'a dyn Scheme,
        curves: Cow<'a, [CubicBez3]>,
    },
}

/// The tessellation welded by topology (module docs), each face's nets from `nets`; the
/// optional arrays those `keep` asks for.
fn tessellate_by_topology(
    mesh: &Mesh,
    layout: &Layout,
    plan: &Plan,
    s: usize,
    nets: Nets<'_>,
    keep: Keep,
) -> Result<Tessellation, TessError> {
    debug_assert!(s > 0);
    let layout = *layout;
    let faces = mesh.faces();
    let nf = faces.len();
    let ppf = layout.patches_per_face();
    let np = layout.points_per_patch();
    // Owners: a vertex belongs to the lowest-numbered face around it, an edge to its first face.
    // Along a crease the surface has two tangent planes: each sector of a vertex is a vertex of
    // its own (its slot, `mesh::sectors`), and each face owns its side of a crease edge, so the
    // normals are not averaged over the crease (the positions still coincide).
    let sectors = mesh.sectors();
    let corner_key = |f: usize, c: usize| -> usize {
        match sectors.and_then(|s| s.slot(f, c)) {
            Some(slot) => slot,
            None => faces[f][c],
        }
    };
    let keys = sectors.map_or(mesh.num_vertices(), |s| s.num_slots());
    let mut vertex_owner = vec![usize::MAX; keys];
    let mut owned_corners = vec![[false; 3]; nf];
    for f in 0..nf {
        for c in 0..3 {
            let v = corner_key(f, c);
            if vertex_owner[v] == usize::MAX {
                vertex_owner[v] = f;
                owned_corners[f][c] = true;
            }
        }
    }
    let mut owned_edges = vec![[false; 3]; nf];
    for (ei, e) in mesh.edges().enumerate() {
        owned_edges[e.first.0][e.first.1] = true;
        if let Some((g, lg)) = e.second.filter(|_| mesh.is_crease(ei)) {
            owned_edges[g][lg] = true;
        }
    }
    // Blocks: per face, owned corners, then owned edges' samples (along the edge's own
    // direction), then inner samples.
    let mut start = Vec::with_capacity(nf + 1);
    let mut total = 0usize;
    for f in 0..nf {
        start.push(total);
        total += owned_corners[f].iter().filter(|x| **x).count()
            + owned_edges[f].iter().filter(|x| **x).count() * plan.per_edge
            + plan.per_face_inner;
    }
    start.push(total);
    let mut vertex_id = vec![usize::MAX; keys];
    // Per edge: the samples' first id for its first face, and for its second on a crease.
    let mut edge_base = vec![usize::MAX; mesh.num_edges()];
    let mut crease_base = vec![usize::MAX; mesh.num_edges()];
    for f in 0..nf {
        let mut at = start[f];
        for c in 0..3 {
            if owned_corners[f][c] {
                vertex_id[corner_key(f, c)] = at;
                at += 1;
            }
        }
        for l in 0..3 {
            if owned_edges[f][l] {
                let ei = mesh.edge_index(f, l).map_err(TessError::Mesh)?;
                if mesh.edge(ei).first == (f, l) {
                    edge_base[ei] = at;
                } else {
                    crease_base[ei] = at;
                }
                at += plan.per_edge;
            }
        }
    }
    // The global id of each slot of face f.
    let per_edge = plan.per_edge;
    let slot_id = |f: usize, slot: Slot| -> Result<usize, TessError> {
        Ok(match slot {
            Slot::Corner(c) => vertex_id[corner_key(f, c)],
            Slot::Edge(l, k) => {
                let ei = mesh.edge_index(f, l).map_err(TessError::Mesh)?;
                let edge = mesh.edge(ei);
                // Samples are stored along the edge from `vertices[0]`.
                let forward = edge.vertices[0] == faces[f][l];
                let base = if edge.first == (f, l) || crease_base[ei] == usize::MAX {
                    edge_base[ei]
                } else {
                    crease_base[ei]
                };
                base + if forward { k } else { per_edge - 1 - k }
            }
            Slot::Inner(k) => start[f + 1] - plan.per_face_inner + k,
        })
    };

    // Evaluate every face's owned samples straight into its block of the output arrays (no
    // intermediate copy: at 10⁶ faces the output is hundreds of megabytes and page faults
    // dominate). Faces go in chunks of `FACES_PER_TASK`, whose blocks are consecutive; the
    // arrays are first touched in parallel ([`par_filled`]).
    let mut positions = par_filled(Point3::origin(), total);
    let mut normals = par_filled(Vector3::zeros(), total);
    let mut gaussian = vec![0.0; total];
    let mut mean = vec![0.0; total];
    let mut shapes = if keep.shapes {
        par_filled(nalgebra::Matrix3::zeros(), total)
    } else {
        Vec::new()
    };
    let mut directions = if keep.directions.is_some() {
        par_filled([Vector3::zeros(); 2], total)
    } else {
        Vec::new()
    };
    let mut nudged = vec![false; total];
    let chunk_start: Vec<usize> = (0..nf)
        .step_by(FACES_PER_TASK)
        .chain(std::iter::once(nf))
        .map(|f| start[f])
        .collect();
    // An array not kept gives every task an empty block.
    let blocks = |kept: bool| {
        if kept {
            chunk_start.clone()
        } else {
            vec![0; chunk_start.len()]
        }
    };
    let (shape_start, direction_start) = (blocks(keep.shapes), blocks(keep.directions.is_some()));
    split_blocks(&mut positions, &chunk_start)
        .into_par_iter()
        .zip(split_blocks(&mut normals, &chunk_start))
        .zip(split_blocks(&mut gaussian, &chunk_start))
        .zip(split_blocks(&mut mean, &chunk_start))
        .zip(split_blocks(&mut shapes, &shape_start))
        .zip(split_blocks(&mut directions, &direction_start))
        .zip(split_blocks(&mut nudged, &chunk_start))
        .enumerate()
        .try_for_each(
            |(chunk, ((((((ps, ns), ks), hs), ss), ds), nu))| -> Result<(), TessError> {
                let mut at = 0;
                let first = chunk * FACES_PER_TASK;
                // One face's nets, reused by the task's faces (rebuilt nets only).
                let mut built = match &nets {
                    Nets::Whole(_) => Vec::new(),
                    Nets::Rebuilt { .. } => vec![Point3::origin(); ppf * np],
                };
                for f in first..(first + FACES_PER_TASK).min(nf) {
                    let face_nets: &[Point3<f64>] = match &nets {
                        Nets::Whole(points) => &points[f * ppf * np..(f + 1) * ppf * np],
                        Nets::Rebuilt { scheme, curves } => {
                            build_face(mesh, *scheme, curves, f, &mut built)
                                .map_err(|e| TessError::Rebuild(format!("face {f}: {e}")))?;
                            &built
                        }
                    };
                    let mut put = |(p, li): (usize, usize)| {
                        let net = &face_nets[p * np..(p + 1) * np];
                        let x = evaluate(&layout, net, &plan.weights[li], plan.local[li]);
                        ps[at] = x.p;
                        ns[at] = x.c.normal;
                        ks[at] = x.c.gaussian;
                        hs[at] = x.c.mean;
                        if let Some(shape) = ss.get_mut(at) {
                            *shape = x.c.shape;
                        }
                        if let (Some(d), Some(scale)) = (ds.get_mut(at), keep.directions) {
                            let p = estimate::principal_frame(&(x.c.shape / scale), &x.c.normal);
                            *d = [p.d1, p.d2];
                        }
                        nu[at] = x.nudged;
                        at += 1;
                    };
                    for c in 0..3 {
                        if owned_corners[f][c] {
                            put(plan.corner_src[c]);
                        }
                    }
                    if per_edge > 0 {
                        for l in 0..3 {
                            if owned_edges[f][l] {
                                let ei = mesh.edge_index(f, l).map_err(TessError::Mesh)?;
                                let forward = mesh.edge(ei).vertices[0] == faces[f][l];
                                for k in 0..per_edge {
                                    let kk = if forward { k } else { per_edge - 1 - k };
                                    put(plan.edge_src[l][kk]);
                                }
                            }
                        }
                    }
                    for &src in &plan.inner_src {
                        put(src);
                    }
                }
                Ok(())
            },
        )?;

    // Every sample is evaluated: curves taken from the fit go now, before the triangles.
    drop(nets);

    // Along a crease each side has its own samples (its own normals), evaluated from its own
    // patch; their positions agree only to rounding. The copies take the first side's position
    // bit for bit, so a writer's rounding (single precision) keeps them equal and a reader that
    // merges coincident vertices closes the surface up again.
    if sectors.is_some() {
        for (base, second) in edge_base.iter().zip(&crease_base) {
            if *second != usize::MAX && *base != usize::MAX {
                for k in 0..per_edge {
                    positions[second + k] = positions[base + k];
                }
            }
        }
        let mut first_copy = vec![usize::MAX; mesh.num_vertices()];
        for f in 0..nf {
            for c in 0..3 {
                let (v, id) = (faces[f][c], vertex_id[corner_key(f, c)]);
                match first_copy[v] {
                    usize::MAX => first_copy[v] = id,
                    first if first != id => positions[id] = positions[first],
                    _ => {}
                }
            }
        }
    }

    // Triangles, a fixed number per face.
    let per_patch = plan.triangles.len();
    let mut tris = vec![[0usize; 3]; nf * ppf * per_patch];
    tris.par_chunks_mut(ppf * per_patch.max(1))
        .enumerate()
        .try_for_each_init(Vec::new, |ids, (f, chunk)| -> Result<(), TessError> {
            for p in 0..ppf {
                ids.clear();
                for slot in &plan.slots[p] {
                    ids.push(slot_id(f, *slot)?);
                }
                for (t, tri) in plan.triangles.iter().enumerate() {
                    chunk[p * per_patch + t] = tri.map(|li| ids[li]);
                }
            }
            Ok(())
        })?;

    // The numbering is done: its tables (about 46 B a face) go before the last array is
    // allocated, so they are not part of the tessellation's peak.
    drop((
        vertex_owner,
        owned_corners,
        owned_edges,
        start,
        vertex_id,
        edge_base,
        crease_base,
    ));
    let patch_of_face = if keep.patches {
        (0..tris.len())
            .into_par_iter()
            .map(|t| t / per_patch.max(1))
            .collect()
    } else {
        Vec::new()
    };
    let out = Tessellation {
        positions,
        normals,
        gaussian,
        mean,
        shapes,
        directions,
        faces: tris,
        patch_of_face,
        welds: nf * ppf * plan.local.len() - total,
        max_weld_normal_angle: 0.0,
        singular_samples: nudged.par_iter().filter(|x| **x).count(),
        collapsed_faces: 0,
    };
    Ok(out)
}
