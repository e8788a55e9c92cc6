//! Limit stencils against many subdivision steps, limit normals against finite differences of
//! the limit surface, on irregular valences 3–8; and the locality the tests rely on.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use common::{angle, mixed_polygons, patch_after, track};
use nalgebra::Vector3;
use subdiv::shapes::{irregular_small, quad_grid};
use subdiv::{CatmullClark, Loop, LoopWeights, PolyMesh, Subdivision, VertexKind};

/// The task's bar for the converged position.
const CONVERGED: f64 = 1e-9;
/// Steps to reach it. About 12 suffice for valences up to 6; valence 8 converges like
/// (3/8 + ¼cos(2π/8))² ≈ 0.30 per step under Loop's β (0.25 under Warren's), and
/// Catmull–Clark at valence 8 like ≈ 0.41, so 12 steps leave ~10⁻⁷ there, 24 leave < 10⁻⁹.
const LEVELS: usize = 24;
/// What 12 steps must reach everywhere (valence 8 included, see [`LEVELS`]).
const AFTER_12: f64 = 1e-4;
/// Below this the differences are rounding (coordinates of order 1), and ratios mean nothing.
const ROUNDING: f64 = 1e-13;
/// Geometric shrinking: the position error decays like the largest eigenvalue of the
/// rotationally symmetric block below 1 (Loop: |5/8 − nβ| ≤ 1/4 + …; Catmull–Clark: ≤ 1/4 + …;
/// crease lines: 1/4), so a ratio above 0.7 per step would mean no convergence to this limit.
const RATIO: f64 = 0.7;

fn schemes() -> Vec<Box<dyn Subdivision>> {
    vec![
        Box::new(Loop {
            weights: LoopWeights::Loop,
        }),
        Box::new(Loop {
            weights: LoopWeights::Warren,
        }),
        Box::new(CatmullClark),
    ]
}

/// The closed irregular mesh (valences 3–8), the same with one crease edge (two darts) and a
/// crease path of three edges (crease vertices and two darts), and an open grid with a bump
/// (boundary vertices of valence 2, 3 and interior 4).
fn meshes() -> Vec<(&'static str, PolyMesh)> {
    let closed = irregular_small(7);
    let dart = PolyMesh::with_creases(
        closed.positions().to_vec(),
        &closed.to_raw().polygons,
        &[[0, 11]],
    )
    .unwrap();
    let crease = PolyMesh::with_creases(
        closed.positions().to_vec(),
        &closed.to_raw().polygons,
        &[[4, 9], [9, 8], [8, 7]],
    )
    .unwrap();
    let grid = quad_grid(3, 3);
    let mut pos = grid.positions().to_vec();
    pos[5].z = 0.7;
    pos[10].z = -0.4;
    let grid = grid.with_positions(pos).unwrap();
    vec![
        ("closed", closed),
        ("dart", dart),
        ("crease", crease),
        ("grid", grid),
    ]
}

#[test]
fn the_meshes_have_valences_three_to_eight() {
    let m = irregular_small(7);
    let mut valence = vec![0; m.num_vertices()];
    for [a, b] in m.edges() {
        valence[a] += 1;
        valence[b] += 1;
    }
    for n in 3..=8 {
        assert!(valence.contains(&n), "no vertex of valence {n}");
    }
    let kinds = |m: &PolyMesh| {
        (0..m.num_vertices())
            .map(|v| m.vertex_kind(v))
            .collect::<Vec<_>>()
    };
    let all = meshes();
    assert!(kinds(&all[1].1).contains(&VertexKind::Dart));
    assert!(kinds(&all[2].1).contains(&VertexKind::Crease));
    assert!(kinds(&all[3].1).contains(&VertexKind::Crease));
}

#[test]
fn one_ring_patches_follow_the_whole_mesh() {
    for scheme in schemes() {
        for (name, mesh) in meshes() {
            if scheme.name().starts_with("loop") && !mesh.all_triangles() {
                continue;
            }
            let mut whole = mesh.clone();
            let tracks: Vec<_> = (0..mesh.num_vertices())
                .map(|v| track(scheme.as_ref(), &mesh, v, 3))
                .collect();
            for level in 1..=3 {
                whole = scheme.step(&whole).unwrap();
                for (v, t) in tracks.iter().enumerate() {
                    let d = (whole.positions()[v] - t[level]).norm();
                    assert!(
                        d < 1e-14,
                        "{} {name} v{v} level {level}: {d:e}",
                        scheme.name()
                    );
                }
            }
        }
    }
}

#[test]
fn limit_positions_are_where_the_steps_converge() {
    for scheme in schemes() {
        for (name, mesh) in meshes() {
            if scheme.name().starts_with("loop") && !mesh.all_triangles() {
                continue;
            }
            let limit = scheme.limit_positions(&mesh).unwrap();
            for (v, lim) in limit.iter().enumerate() {
                // Darts converge more slowly (≈ 0.53 per step at the valence-8 dart).
                let levels = if mesh.vertex_kind(v) == VertexKind::Dart {
                    2 * LEVELS
                } else {
                    LEVELS
                };
                let t = track(scheme.as_ref(), &mesh, v, levels);
                let d: Vec<f64> = t.iter().map(|p| (p - lim).norm()).collect();
                let what = format!("{} {name} v{v} {:?}", scheme.name(), mesh.vertex_kind(v));
                assert!(
                    d[12] < AFTER_12,
                    "{what}: after 12 steps {:e} ({d:?})",
                    d[12]
                );
                assert!(
                    d[levels] < CONVERGED,
                    "{what}: after {levels} steps ({d:?})"
                );
                for k in 1..d.len() - 1 {
                    if d[k] > ROUNDING {
                        assert!(d[k + 1] <= RATIO * d[k], "{what}: step {k}: {d:?}");
                    }
                }
            }
        }
    }
}

/// Catmull–Clark on polygons other than quads: the limit of the input's vertices is found
/// through one step; it must agree with the steps all the same.
#[test]
fn catmull_clark_limits_on_mixed_polygons() {
    let mesh = mixed_polygons(&irregular_small(3));
    assert!(!mesh.all_quads() && !mesh.all_triangles());
    let limit = CatmullClark.limit_positions(&mesh).unwrap();
    for (v, lim) in limit.iter().enumerate() {
        let t = track(&CatmullClark, &mesh, v, LEVELS);
        let d: Vec<f64> = t.iter().map(|p| (p - lim).norm()).collect();
        assert!(d[LEVELS] < CONVERGED, "v{v}: {d:?}");
    }
}

/// The limit normal against the limit surface near the vertex: after `k` steps the one-ring
/// lies on the limit surface's control net at distance ~λᵏ; the limit positions of the ring
/// are not available from a patch, so the difference quotient uses the ring points themselves,
/// whose distance to the surface is O(λ²ᵏ): the normal of the fan (Σ of cross products of
/// consecutive ring offsets from the limit point) differs from the true normal by O(λᵏ).
#[test]
fn limit_normals_match_finite_differences() {
    for scheme in schemes() {
        for (name, mesh) in meshes() {
            if scheme.name().starts_with("loop") && !mesh.all_triangles() {
                continue;
            }
            let limit = scheme.limit_positions(&mesh).unwrap();
            let normals = scheme.limit_normals(&mesh).unwrap();
            for v in 0..mesh.num_vertices() {
                let kind = mesh.vertex_kind(v);
                if kind == VertexKind::Crease && name != "grid" {
                    // Two sectors: the reported normal is their average, not a tangent plane.
                    continue;
                }
                let mut errs = Vec::new();
                // Darts and boundary corners flatten more slowly (≈ 0.73 per step at the
                // valence-8 Catmull–Clark dart, ≈ 0.85 at a valence-2 boundary corner).
                let ks = if kind == VertexKind::Smooth {
                    [6, 10]
                } else {
                    [14, 22]
                };
                for k in ks {
                    let patch = patch_after(scheme.as_ref(), &mesh, v, k);
                    let mut fan = Vector3::zeros();
                    for f in patch.faces() {
                        let n = f.len();
                        for i in 0..n {
                            let a = patch.positions()[f[i] as usize] - limit[v];
                            let b = patch.positions()[f[(i + 1) % n] as usize] - limit[v];
                            fan += a.cross(&b);
                        }
                    }
                    errs.push(angle(&fan, &normals[v]));
                }
                let what = format!("{} {name} v{v} {kind:?}", scheme.name());
                assert!(errs[1] < 1e-2, "{what}: {errs:?}");
                assert!(
                    errs[1] < 0.5 * errs[0] || errs[1] < 1e-8,
                    "{what}: {errs:?}"
                );
            }
        }
    }
}
