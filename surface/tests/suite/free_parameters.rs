//! Every free parameter of the modified Shirman–Séquin macro-patch (`surface::shirman_sequin`,
//! "Every free parameter"): each keeps the surface G1 over its range, and none is redundant —
//! the Jacobian of a face's control points in all of them has full rank on generic data. The
//! parameters: per edge the two end-derivative lengths `α` (shared), per corner `β`, per
//! (face, edge) Jensen's `c`; in the quadratic-field form the edge's middle vector `x` (three
//! components, shared) instead of `c`.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, CubicBez3, MethodOptions, VertexData};
use nalgebra::{DMatrix, Point3, Vector3};
use surface::curvature_cross::macro_patch_with_middles;
use surface::datasets::ring;
use surface::fit::FaceFallbackReason;
use surface::scheme::shirman_sequin::{ShirmanSequin, BETA, C};
use surface::scheme::{FaceInput, Layout, CENTROID_SPLIT};
use surface::{
    fit_scheme, macro_patch, measure_g1, Continuity, InteriorParameters, QuarticNet, Scheme,
};

/// G1 of a G1 construction, as `Continuity::G1` claims it (docs/conventions.md).
const G1_TOL: f64 = 1e-9;
/// Central-difference step of the Jacobians (parameters of order one).
const STEP: f64 = 1e-6;
/// The smallest singular value over the largest for full rank: the finite differences' error
/// is `~STEP²` relative, a dependent column would give that (measured here: 2.4e-2 for the
/// twelve, 1.6e-2 for the eighteen).
const RANK_TOL: f64 = 1e-6;

/// A face of the 16 × 8 ring off every symmetry (its corners' normals, shape tensors and edges
/// all differ) with its three chord-choice curves.
fn face() -> ([VertexData; 3], [CubicBez3; 3]) {
    let data = ring(16, 8).unwrap();
    let mesh = &data.mesh;
    let chord = method_by_name("chord", &MethodOptions::default()).unwrap();
    let f = surface::fit(mesh, chord.as_ref(), &|_| InteriorParameters::default()).unwrap();
    let face = 37;
    let v = mesh.face_data(face).unwrap().map(|d| *d);
    (v, f.face_curves(mesh, face).unwrap())
}

/// The curves with each end-derivative length scaled: `lengths[2e]` at the start of edge `e`,
/// `lengths[2e + 1]` at its end.
fn scaled(edges: &[CubicBez3; 3], lengths: &[f64]) -> [CubicBez3; 3] {
    std::array::from_fn(|e| {
        let [a, e1, e2, b] = edges[e].points;
        CubicBez3::new([
            a,
            a + (e1 - a) * lengths[2 * e],
            b + (e2 - b) * lengths[2 * e + 1],
            b,
        ])
    })
}

fn flat(nets: &[QuarticNet; 3]) -> Vec<f64> {
    nets.iter()
        .flatten()
        .flat_map(|p| [p.x, p.y, p.z])
        .collect()
}

/// `σ_min / σ_max` of the central-difference Jacobian of `net(p)` at `p0`.
fn conditioning(p0: &[f64], net: &dyn Fn(&[f64]) -> Vec<f64>) -> f64 {
    let rows = net(p0).len();
    let mut j = DMatrix::zeros(rows, p0.len());
    for k in 0..p0.len() {
        let (mut plus, mut minus) = (p0.to_vec(), p0.to_vec());
        plus[k] += STEP;
        minus[k] -= STEP;
        let (a, b) = (net(&plus), net(&minus));
        for r in 0..rows {
            j[(r, k)] = (a[r] - b[r]) / (2.0 * STEP);
        }
    }
    let s = j.singular_values();
    s.min() / s.max()
}

#[test]
fn beta_c_and_the_lengths_are_twelve_independent_parameters() {
    let (v, edges) = face();
    let vr = [&v[0], &v[1], &v[2]];
    // p = (β0, β1, β2, c0, c1, c2, α scale at the six edge ends).
    let mut p0 = vec![1.0 / 3.0; 3];
    p0.extend([1.0; 3]);
    p0.extend([1.0; 6]);
    let net = |p: &[f64]| {
        let params = InteriorParameters {
            beta: [p[0], p[1], p[2]],
            c: [p[3], p[4], p[5]],
        };
        flat(&macro_patch(vr, &scaled(&edges, &p[6..]), &params).unwrap())
    };
    let cond = conditioning(&p0, &net);
    eprintln!("12 parameters: σ_min/σ_max = {cond:.3e}");
    assert!(cond > RANK_TOL, "{cond:e}");
}

#[test]
fn the_quadratic_field_form_has_eighteen_independent_parameters() {
    let (v, edges) = face();
    let vr = [&v[0], &v[1], &v[2]];
    // p = (β0, β1, β2, α scale at the six edge ends, the three middle vectors).
    let mut p0 = vec![1.0 / 3.0; 3];
    p0.extend([1.0; 6]);
    p0.extend([0.0; 9]);
    let net = |p: &[f64]| {
        let params = InteriorParameters {
            beta: [p[0], p[1], p[2]],
            c: [1.0; 3],
        };
        let middles =
            std::array::from_fn(|e| Vector3::new(p[9 + 3 * e], p[10 + 3 * e], p[11 + 3 * e]));
        flat(
            &macro_patch_with_middles(vr, &scaled(&edges, &p[3..9]), &params, [false; 3], middles)
                .unwrap(),
        )
    };
    let cond = conditioning(&p0, &net);
    eprintln!("18 parameters: σ_min/σ_max = {cond:.3e}");
    assert!(cond > RANK_TOL, "{cond:e}");
}

/// β and c drawn per face over their whole declared ranges (log-uniform), the scheme as
/// registered otherwise: G1 on the ring.
#[test]
fn beta_and_c_keep_g1_over_their_whole_ranges() {
    let data = ring(16, 8).unwrap();
    let chord = method_by_name("chord", &MethodOptions::default()).unwrap();
    let log_uniform = |lo: f64, hi: f64, u: f64| (lo.ln() + (hi.ln() - lo.ln()) * u).exp();
    let unit = |f: usize, k: usize| {
        let mut r = fixtures::SplitMix64::new((f * 7 + k) as u64 + 1);
        r.uniform(0.0, 1.0)
    };
    let params = move |f: usize| InteriorParameters {
        beta: std::array::from_fn(|k| log_uniform(BETA.range.0, BETA.range.1, unit(f, k))),
        c: std::array::from_fn(|k| log_uniform(C.range.0, C.range.1, unit(f, 3 + k))),
    };
    let scheme = ShirmanSequin::per_face(&params);
    let fit = fit_scheme(&data.mesh, &scheme, chord.as_ref()).unwrap();
    assert_eq!(fit.fallbacks, 0);
    let g1 = measure_g1(&data.mesh, &fit, 9);
    eprintln!("β, c over their ranges: G1 {:.2e} rad", g1.max_angle());
    assert!(g1.max_angle() < G1_TOL, "{g1:?}");
}

/// The middle vectors as a scheme: each face edge's from its curve's end points by an odd
/// function, so the neighbour, travelling the edge the other way, gives the negative.
struct Middles;

fn middle(curve: &CubicBez3) -> Vector3<f64> {
    let [a, _, _, b] = curve.points;
    let (d, s) = (b - a, a.coords + b.coords);
    // Odd under a ↔ b: d changes sign, s does not.
    d.cross(&s) * 0.7 + d * (0.3 * s.norm()) + d.cross(&Vector3::new(0.2, -0.5, 0.9))
}

impl Scheme for Middles {
    fn name(&self) -> &'static str {
        "middles"
    }
    fn layout(&self) -> Layout {
        Layout::bezier(4, &CENTROID_SPLIT)
    }
    fn continuity(&self) -> Continuity {
        Continuity::G1
    }
    fn uses_curves(&self) -> bool {
        true
    }
    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason> {
        let middles = std::array::from_fn(|e| middle(&input.edges[e]));
        let nets = macro_patch_with_middles(
            input.vertices,
            input.edges,
            &InteriorParameters::default(),
            [false; 3],
            middles,
        )
        .map_err(FaceFallbackReason::Scheme)?;
        for (chunk, net) in out.chunks_exact_mut(15).zip(&nets) {
            chunk.copy_from_slice(net);
        }
        Ok(())
    }
}

#[test]
fn any_shared_middle_vectors_keep_g1() {
    let data = ring(16, 8).unwrap();
    let optimized = method_by_name("optimized", &MethodOptions::default()).unwrap();
    let fit = fit_scheme(&data.mesh, &Middles, optimized.as_ref()).unwrap();
    assert_eq!(fit.fallbacks, 0);
    let g1 = measure_g1(&data.mesh, &fit, 9);
    eprintln!(
        "arbitrary shared middle vectors: G1 {:.2e} rad",
        g1.max_angle()
    );
    assert!(g1.max_angle() < G1_TOL, "{g1:?}");
    // They did change the surface: not the Chiyokura–Kimura one.
    let ck = fit_scheme(
        &data.mesh,
        &ShirmanSequin::uniform(InteriorParameters::default()),
        optimized.as_ref(),
    )
    .unwrap();
    let moved = fit
        .points
        .iter()
        .zip(&ck.points)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(moved > 1e-3, "{moved}");
}
