//! The two Shirman–Séquin variants (`shirman-sequin-1987`, `shirman-sequin-testbed`,
//! `surface::ss_variants`): G1 across mesh edges on every data set with random `α₂`, the
//! derivative jump across the interior split edges (zero for the testbed's fitter and for
//! `α₂ = 9/4`, the closed form `(μ(t) − 3) P'(t)` otherwise), linear precision, the identity
//! of the 1987 construction with Mann's at `β = 3/(4α₂)`, `c = 1`, and the distance of the
//! testbed's fitter from every Mann β, c.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, MethodOptions, VertexData};
use fixtures::SplitMix64;
use nalgebra::{Matrix3, Point3, Vector3};
use surface::beztri::BezierTriangle;
use surface::mesh::Vertex;
use surface::scheme::shirman_sequin::{ShirmanSequin, Unfold};
use surface::scheme::shirman_sequin_1987::{ShirmanSequin1987, ALPHA2};
use surface::scheme::shirman_sequin_testbed::ShirmanSequinTestbed;
use surface::scheme::{Bary, Scheme, CENTROID_SPLIT};
use surface::shirman_sequin::InteriorParameters;
use surface::ss_variants::{shirman_sequin_1987, DEFAULT_ALPHA2};
use surface::{dataset_by_name, fit_scheme, measure_g1, Fit, Mesh};

/// The bound for a G1 claim (docs/conventions.md).
const G1_TOL: f64 = 1e-9;
/// Derivative jumps across interior edges, relative to the size of the derivatives (order
/// one on the data sets): rounding of nets built in a dozen affine steps.
const C1_TOL: f64 = 1e-11;
/// Two constructions of the same nets by different formulas agree to rounding (coordinates of
/// order one).
const SAME_NETS: f64 = 1e-12;
/// Planar data reproduced to rounding.
const PRECISION: f64 = 1e-12;
/// The testbed's fitter and Mann's at β = ⅓, c = 1 share rows 0 and 1 and the middle points of
/// the interior edges to rounding.
const SHARED_ROWS: f64 = 1e-12;
/// What "different" means for two nets on the data sets (sizes of order one): well above any
/// rounding.
const DIFFERENT: f64 = 1e-4;

const DATA_SETS: [&str; 4] = ["sphere", "ring", "capsule", "octa"];

/// `α₂` drawn log-uniformly over its whole range.
fn draw_alpha2(rng: &mut SplitMix64) -> f64 {
    let (lo, hi) = ALPHA2.range;
    (lo.ln() + rng.next_f64() * (hi.ln() - lo.ln())).exp()
}

fn chord() -> Box<dyn curves::CurveMethod> {
    method_by_name("chord", &MethodOptions::default()).unwrap()
}

#[test]
fn both_variants_are_g1_across_edges_on_every_data_set() {
    let mut rng = SplitMix64::new(1987);
    for name in DATA_SETS {
        let data = dataset_by_name(name, None).unwrap();
        for method in ["chord", "dbhs", "optimized"] {
            let m = method_by_name(method, &MethodOptions::default()).unwrap();
            let mut schemes: Vec<Box<dyn Scheme>> = vec![Box::new(ShirmanSequinTestbed)];
            for _ in 0..3 {
                schemes.push(Box::new(ShirmanSequin1987 {
                    alpha2: draw_alpha2(&mut rng),
                }));
            }
            for s in &schemes {
                let f = fit_scheme(&data.mesh, s.as_ref(), m.as_ref()).unwrap();
                let g1 = measure_g1(&data.mesh, &f, 9);
                assert_eq!(g1.undefined_normals, 0, "{name}/{method}/{}", s.name());
                assert!(
                    g1.exterior_max < G1_TOL,
                    "{name}/{method}/{}: {g1:?}",
                    s.name()
                );
                assert!(
                    g1.interior_max < G1_TOL,
                    "{name}/{method}/{}: {g1:?}",
                    s.name()
                );
                eprintln!(
                    "{name}/{method}/{}: exterior {:.2e} rad, interior {:.2e} rad, {} fallback faces",
                    s.name(),
                    g1.exterior_max,
                    g1.interior_max,
                    f.face_fallbacks.len()
                );
            }
        }
    }
}

/// The derivative of sub-patch `s` of the fit's face `face` along the face-domain direction
/// `d` at the face-domain point `x`.
fn face_derivative(f: &Fit, face: usize, s: usize, x: Bary, d: Bary) -> Vector3<f64> {
    let sub = CENTROID_SPLIT[s];
    let m = Matrix3::from_fn(|r, c| sub[c][r]).try_inverse().unwrap();
    let local = m * Vector3::from(x);
    let dir = m * Vector3::from(d);
    let net = BezierTriangle::new(4, f.net(face * 3 + s).unwrap().to_vec()).unwrap();
    net.directional([local[0], local[1], local[2]], &[[dir[0], dir[1], dir[2]]])
}

/// Along interior edge `a` (from `V_a` to the centroid) of every fitted face, at `t`: the jump
/// of the derivative across the edge, `D_left − D_right` along `V_{a+1} − V_a`, and the
/// derivative `P'` along the edge.
fn interior_jumps(f: &Fit, mesh: &Mesh) -> Vec<(f64, Vector3<f64>, Vector3<f64>)> {
    let fallen: Vec<usize> = f.face_fallbacks.iter().map(|x| x.face).collect();
    let mut out = Vec::new();
    for face in (0..mesh.num_faces()).filter(|g| !fallen.contains(g)) {
        for a in 0..3 {
            let (b, c) = ((a + 1) % 3, (a + 2) % 3);
            for t in [0.0, 0.2, 0.5, 0.7, 1.0] {
                let mut x = [t / 3.0; 3];
                x[a] += 1.0 - t;
                let mut across = [0.0; 3];
                across[a] = -1.0;
                across[b] = 1.0;
                let mut along = [1.0 / 3.0; 3];
                along[a] -= 1.0;
                let left = face_derivative(f, face, a, x, across);
                let right = face_derivative(f, face, c, x, across);
                let p = face_derivative(f, face, a, x, along);
                let p_right = face_derivative(f, face, c, x, along);
                assert!((p - p_right).norm() < C1_TOL, "the edge is shared");
                out.push((t, left - right, p));
            }
        }
    }
    out
}

#[test]
fn the_testbed_fitter_and_the_default_1987_construction_are_c1_inside() {
    for name in DATA_SETS {
        let data = dataset_by_name(name, None).unwrap();
        for s in [
            Box::new(ShirmanSequinTestbed) as Box<dyn Scheme>,
            Box::new(ShirmanSequin1987 {
                alpha2: DEFAULT_ALPHA2,
            }),
        ] {
            let f = fit_scheme(&data.mesh, s.as_ref(), chord().as_ref()).unwrap();
            let jumps = interior_jumps(&f, &data.mesh);
            assert!(!jumps.is_empty());
            let worst = jumps
                .iter()
                .map(|(_, j, p)| j.norm() / p.norm().max(1.0))
                .fold(0.0, f64::max);
            eprintln!(
                "{name}/{}: largest interior derivative jump {worst:.2e}",
                s.name()
            );
            assert!(worst < C1_TOL, "{name}/{}: {worst:e}", s.name());
        }
    }
}

#[test]
fn away_from_nine_quarters_the_1987_jump_is_the_closed_form() {
    let mut rng = SplitMix64::new(9);
    for name in DATA_SETS {
        let data = dataset_by_name(name, None).unwrap();
        let alpha2 = draw_alpha2(&mut rng);
        let f = fit_scheme(&data.mesh, &ShirmanSequin1987 { alpha2 }, chord().as_ref()).unwrap();
        let mut largest = 0.0_f64;
        for (t, jump, p) in interior_jumps(&f, &data.mesh) {
            // D_L + D_R = μ P' with μ linear from 4α₂/3 at the corner to 3 at the centroid,
            // so the jump D_L − (3P' − D_R) is (μ − 3) P'.
            let mu = (1.0 - t) * 4.0 * alpha2 / 3.0 + 3.0 * t;
            let want = p * (mu - 3.0);
            assert!(
                (jump - want).norm() < C1_TOL * p.norm().max(1.0) * mu.max(1.0),
                "{name} α₂ = {alpha2}, t = {t}: {jump:?} vs {want:?}"
            );
            largest = largest.max(jump.norm());
        }
        assert!(
            largest > DIFFERENT,
            "{name}: α₂ = {alpha2} should not be C1"
        );
    }
}

#[test]
fn the_1987_construction_is_manns_at_beta_three_over_four_alpha2_and_c_one() {
    let mut rng = SplitMix64::new(42);
    for name in DATA_SETS {
        let data = dataset_by_name(name, None).unwrap();
        for _ in 0..3 {
            let alpha2 = draw_alpha2(&mut rng);
            let a =
                fit_scheme(&data.mesh, &ShirmanSequin1987 { alpha2 }, chord().as_ref()).unwrap();
            // At the given β (no unfolding: the constructions are compared as they are).
            let mann = ShirmanSequin::uniform(InteriorParameters {
                beta: [3.0 / (4.0 * alpha2); 3],
                c: [1.0; 3],
            })
            .with_unfold_rule(Unfold::Off);
            let b = fit_scheme(&data.mesh, &mann, chord().as_ref()).unwrap();
            assert_eq!(a.face_fallbacks.len(), b.face_fallbacks.len(), "{name}");
            let scale = a.points.iter().map(|p| p.coords.norm()).fold(1.0, f64::max);
            for (p, q) in a.points.iter().zip(&b.points) {
                assert!(
                    (p - q).norm() < SAME_NETS * scale,
                    "{name} α₂ = {alpha2}: {p} vs {q}"
                );
            }
        }
    }
}

/// An irregular planar mesh with normals +z and zero shape tensors.
fn planar() -> Mesh {
    let pts = [
        (0.0, 0.0),
        (1.0, 0.1),
        (2.1, -0.2),
        (0.3, 1.2),
        (1.4, 0.9),
        (2.3, 1.1),
        (0.9, 2.0),
    ];
    let verts = pts
        .iter()
        .map(|&(x, y)| {
            Vertex::new(VertexData::new(
                Point3::new(x, y, 0.0),
                Vector3::z(),
                Matrix3::zeros(),
            ))
        })
        .collect();
    let faces = vec![
        [0, 1, 4],
        [0, 4, 3],
        [1, 2, 5],
        [1, 5, 4],
        [3, 4, 6],
        [4, 5, 6],
    ];
    Mesh::new(verts, faces).unwrap()
}

/// Linear precision (the plane and its linear parametrization) for the testbed's fitter and
/// the default 1987 construction; for every `α₂` the plane itself: the corner points `S` move
/// along the plane by `3/(4α₂)` of the edge points' sum, so the parametrization is linear only
/// at `α₂ = 9/4`, but every control point stays in the plane.
#[test]
fn both_variants_reproduce_a_plane() {
    let mesh = planar();
    let mut rng = SplitMix64::new(7);
    let linear: Vec<Box<dyn Scheme>> = vec![
        Box::new(ShirmanSequinTestbed),
        Box::new(ShirmanSequin1987 {
            alpha2: DEFAULT_ALPHA2,
        }),
    ];
    for s in &linear {
        let f = fit_scheme(&mesh, s.as_ref(), chord().as_ref()).unwrap();
        assert!(f.face_fallbacks.is_empty(), "{}", s.name());
        for (face, corners) in mesh.faces().iter().enumerate() {
            let v = corners.map(|i| mesh.vertices()[i].data.p);
            for (sp, sub) in CENTROID_SPLIT.iter().enumerate() {
                let net = BezierTriangle::new(4, f.net(face * 3 + sp).unwrap().to_vec()).unwrap();
                for l in [
                    [0.2, 0.3, 0.5],
                    [0.6, 0.2, 0.2],
                    [0.0, 0.5, 0.5],
                    [0.1, 0.1, 0.8],
                ] {
                    let x: Bary = std::array::from_fn(|c| {
                        l[0] * sub[0][c] + l[1] * sub[1][c] + l[2] * sub[2][c]
                    });
                    let want = v[0].coords * x[0] + v[1].coords * x[1] + v[2].coords * x[2];
                    let got = net.eval(l[0], l[1], l[2]);
                    assert!(
                        (got.coords - want).norm() < PRECISION,
                        "{} face {face}",
                        s.name()
                    );
                }
            }
        }
    }
    for _ in 0..4 {
        let alpha2 = draw_alpha2(&mut rng);
        let f = fit_scheme(&mesh, &ShirmanSequin1987 { alpha2 }, chord().as_ref()).unwrap();
        assert!(f.face_fallbacks.is_empty(), "α₂ = {alpha2}");
        let off = f.points.iter().map(|p| p.z.abs()).fold(0.0, f64::max);
        assert!(off < PRECISION, "α₂ = {alpha2}: {off:e} off the plane");
    }
}

#[test]
fn the_testbed_fitter_is_no_choice_of_manns_beta_and_c() {
    let data = dataset_by_name("sphere", None).unwrap();
    let tb = fit_scheme(&data.mesh, &ShirmanSequinTestbed, chord().as_ref()).unwrap();
    let mann_at = |beta: f64, c: f64| {
        let s = ShirmanSequin::uniform(InteriorParameters {
            beta: [beta; 3],
            c: [c; 3],
        })
        .with_unfold_rule(Unfold::Off);
        fit_scheme(&data.mesh, &s, chord().as_ref()).unwrap()
    };
    // β = ⅓, c = 1: rows 0 and 1 and the interior edges' middle points (net indices 0..=9 and
    // 11) agree; N, U and Z (10, 12, 13, 14) do not.
    let m = mann_at(1.0 / 3.0, 1.0);
    let (mut shared, mut apart) = (0.0_f64, 0.0_f64);
    for (p, q) in tb.points.chunks(15).zip(m.points.chunks(15)) {
        for k in 0..15 {
            let d = (p[k] - q[k]).norm();
            if k <= 9 || k == 11 {
                shared = shared.max(d);
            } else {
                apart = apart.max(d);
            }
        }
    }
    eprintln!("β = ⅓, c = 1: shared points {shared:.2e} apart, N/U/Z up to {apart:.3e}");
    assert!(shared < SHARED_ROWS, "{shared:e}");
    assert!(apart > DIFFERENT, "{apart:e}");
    // Over a grid of β and c, the largest control point distance stays well above rounding.
    let mut closest = f64::INFINITY;
    for beta in [0.2, 0.3, 1.0 / 3.0, 0.36, 0.5] {
        for c in [0.5, 0.9, 1.0, 1.1, 2.0] {
            let m = mann_at(beta, c);
            let d = tb
                .points
                .iter()
                .zip(&m.points)
                .map(|(p, q)| (p - q).norm())
                .fold(0.0, f64::max);
            closest = closest.min(d);
        }
    }
    eprintln!("closest Mann net over the grid: {closest:.3e}");
    assert!(closest > DIFFERENT, "{closest:e}");
}

#[test]
fn a_bad_alpha2_is_an_error_not_a_panic() {
    let data = dataset_by_name("sphere", None).unwrap();
    let face = data.mesh.faces()[0].map(|i| data.mesh.vertices()[i].data);
    let edges = std::array::from_fn(|e| {
        let (a, b) = (&face[e], &face[(e + 1) % 3]);
        curves::CubicBez3::new([a.p, a.p + (b.p - a.p) / 3.0, b.p - (b.p - a.p) / 3.0, b.p])
    });
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let err = shirman_sequin_1987([&face[0], &face[1], &face[2]], &edges, bad).unwrap_err();
        assert!(err.to_string().contains("alpha2"), "{err}");
    }
    assert!(!ALPHA2.accepts(0.0) && !ALPHA2.accepts(100.0) && ALPHA2.accepts(DEFAULT_ALPHA2));
}
