//! `hybrid`: per vertex, the fourth-order jet where the sampling resolves the surface, the
//! Rusinkiewicz tensor (with Max-weighted normals) where it does not.
//!
//! # Why
//!
//! The `estimation` study (`results/estimation/`) shows two regimes. Where the neighbourhood a
//! degree-4 jet needs (about three rings) is small against the radius of curvature, `jet4` is
//! the most accurate estimator of all, libigl's included (fourth order in the normals, K and H,
//! on regular and irregular meshes alike). Where it is not — coarse samplings, as in the seeds'
//! 16 × 8 ring — a height-field polynomial over three rings wraps around the surface and
//! `jet4` is the worst, while Rusinkiewicz's per-face tensors from Max-weighted normals (which
//! use one ring only, and are exact on spheres) are the best.
//!
//! # The rule
//!
//! At vertex `v` with Rusinkiewicz principal curvatures `κ1, κ2` and mean incident edge length
//! `ℓ`, the resolution is `ρ = max(|κ1|, |κ2|) · ℓ` (the angle, in radians, the normal turns
//! over one edge). `ρ ≤` [`RESOLVED`] takes `jet4`'s normal and tensor, otherwise
//! Rusinkiewicz's. A vertex where `jet4` had to fall back (lower degree or planar) takes
//! Rusinkiewicz's estimate too. Given normals are kept by both.
//!
//! # Cost
//!
//! Both estimators share one [`Topology`], and their vertex normals (Max-weighted for
//! Rusinkiewicz, angle-weighted as the jet's first normals) are computed in one pass over the
//! corners ([`crate::normals::vertex_normals_many`]). Rusinkiewicz's estimate is computed first, then the
//! jet is fitted only at the vertices whose resolution test passes, in the same parallel pass
//! that writes its result over Rusinkiewicz's: a jet's estimate at a vertex reads only the
//! mesh and the first (angle-weighted) normals, so it is bit for bit the one a fit at every
//! vertex gives there, and no second full estimate is held (about 35 MB less at the peak at
//! 10⁶ triangles).

use mesh::Mesh;
use nalgebra::Vector3;
use rayon::prelude::*;

use crate::fit::Workspace;
use crate::jet::{fit_at, FIRST_WEIGHTING};
use crate::multiscale::{mean_incident_edge, noise_level, MULTISCALE};
use crate::normals::vertex_normals_many;
use crate::{principal_curvatures, Estimate, Estimator, Topology, JET4, RUSINKIEWICZ};

/// The largest normal turn per edge (radians) at which the degree-4 jet is trusted: chosen by
/// the `estimation` study (at 0.1 the jet is used only from about ring 128 × 64 on and loses
/// to Rusinkiewicz's O(h) tensors on irregular 64 × 32 meshes; at 0.4 it reaches the coarse
/// rings, where its three-ring fit wraps around the tube).
pub const RESOLVED: f64 = 0.2;

/// The hybrid estimator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Hybrid;

/// The registered `hybrid`.
pub static HYBRID: Hybrid = Hybrid;

impl Estimator for Hybrid {
    fn name(&self) -> &'static str {
        "hybrid"
    }

    fn description(&self) -> &'static str {
        "per vertex: jet4 where one edge turns the normal by at most 0.2 rad, Rusinkiewicz elsewhere"
    }

    fn estimate(&self, mesh: &Mesh, given: Option<&[Vector3<f64>]>) -> Estimate {
        let topo = Topology::new(mesh);
        let [max, first] = vertex_normals_many(
            mesh,
            &topo,
            [RUSINKIEWICZ.weighting, FIRST_WEIGHTING],
            given,
        );
        let ell = mean_incident_edge(mesh);
        let noise = noise_level(mesh, &topo, &first.normals, &ell);
        if noise.is_noisy() {
            return MULTISCALE.estimate_with(mesh, &topo, &first, &ell, noise.sigma, given);
        }
        let mut out = RUSINKIEWICZ.estimate_with(mesh, &topo, max);
        // The result is Rusinkiewicz's (its fallbacks too: the jet's are used only where its
        // estimate is, and by the rule none are, but for normal fallbacks, which both share),
        // with the jet's estimate where the rule takes it. Vertex v's test reads only v's
        // Rusinkiewicz values, replaced only after it. The jet is fitted only where the
        // resolution test passes: its estimate at a vertex reads only the mesh and the first
        // normals, so it is the one a fit at every vertex would give there.
        let spec = JET4.spec();
        out.normals
            .par_iter_mut()
            .zip(out.shapes.par_iter_mut())
            .enumerate()
            .with_min_len(256)
            .for_each_init(Workspace::default, |ws, (v, (normal, shape))| {
                let [k1, k2] = principal_curvatures(shape, normal);
                let rho = k1.abs().max(k2.abs()) * ell[v];
                if !(rho <= RESOLVED && ell[v] > 0.0) {
                    return;
                }
                if let Some((jn, js)) = fit_at(mesh, &topo, &first, given, &spec, v, ws) {
                    *normal = jn;
                    *shape = js;
                }
            });
        out
    }
}
