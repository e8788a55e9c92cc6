//! Shape objectives that do depend on the interior parameters β and c, and their minimization
//! per data triangle (beyond Mann's Section 4, whose corner measures do not move: see
//! [`crate::interior`]).
//!
//! The energies themselves — thin plate `∫ |r_xx|² + 2|r_xy|² + |r_yy|² dA` and membrane
//! `∫ |r_x|² + |r_y|² dA` — are stated on control nets over planar domains in
//! [`cost::net_energy`] (derivation, closed-form and finite-difference tests there). This module
//! supplies only the construction: the macro-patch's three quartic nets as functions of
//! `(β_0, β_1, β_2, c_0, c_1, c_2)` with their exact derivatives
//! ([`crate::shirman_sequin::macro_patch_with_derivatives`]), over the data triangle laid flat in
//! its own plane and split at its centroid. [`cost::Composed`] applies the chain rule.

use nalgebra::{SMatrix, SVector, Vector2};
use solver::LeastSquaresProblem;

use crate::shirman_sequin::{macro_patch_with_derivatives, InteriorParameters};
use cost::{BuiltNets, Composed, NetConstruction, NetEnergy};
use curves::{CubicBez3, VertexData};

pub use cost::SobolevEnergy as Energy;

/// Residuals of one macro-patch's energy: 3 sub-patches × up to 60 (membrane: 2 kinds × 10
/// Bernstein coefficients of degree 3 × 3 coordinates; thin plate uses 3 × 6 × 3 = 54 and pads
/// with zeros).
pub const RESIDUALS: usize = 180;

/// Lower bounds of the optimization: β ≥ 0.05 and c ≥ 0.1 keep the construction away from its
/// degenerate limits (β → 0 collapses the interior boundaries, c → 0 the cross-boundary field).
pub const LOWER: [f64; 6] = [0.05, 0.05, 0.05, 0.1, 0.1, 0.1];

/// The split-domain construction of one face as a [`NetConstruction`] in `(β, c)`: the three
/// quartic nets concatenated in sub-patch order.
#[derive(Clone, Debug)]
pub struct MacroPatchConstruction {
    vertices: [VertexData; 3],
    edges: [CubicBez3; 3],
}

impl MacroPatchConstruction {
    /// The face's vertex data and its edge curves oriented along the face.
    pub fn new(vertices: [VertexData; 3], edges: [CubicBez3; 3]) -> Self {
        MacroPatchConstruction { vertices, edges }
    }

    /// The interior parameters a point of the search space stands for.
    pub fn params(x: &SVector<f64, 6>) -> InteriorParameters {
        InteriorParameters {
            beta: [x[0], x[1], x[2]],
            c: [x[3], x[4], x[5]],
        }
    }

    /// The three sub-patch domains: the data triangle in its own plane, split at the centroid,
    /// in the sub-patches' corner order `(V_e, V_{e+1}, S)`. `None` for a face without area.
    pub fn domains(&self) -> Option<[[Vector2<f64>; 3]; 3]> {
        let (p0, p1, p2) = (self.vertices[0].p, self.vertices[1].p, self.vertices[2].p);
        let ex = (p1 - p0).try_normalize(0.0)?;
        let nrm = ex.cross(&(p2 - p0)).try_normalize(0.0)?;
        let ey = nrm.cross(&ex);
        let flat = |p: &nalgebra::Point3<f64>| Vector2::new((p - p0).dot(&ex), (p - p0).dot(&ey));
        let c = [flat(&p0), flat(&p1), flat(&p2)];
        let s = (c[0] + c[1] + c[2]) / 3.0;
        Some(std::array::from_fn(|e| [c[e], c[(e + 1) % 3], s]))
    }
}

impl NetConstruction<6> for MacroPatchConstruction {
    fn build(&self, x: &SVector<f64, 6>) -> Option<BuiltNets<6>> {
        let v = [&self.vertices[0], &self.vertices[1], &self.vertices[2]];
        let (nets, d) = macro_patch_with_derivatives(v, &self.edges, &Self::params(x)).ok()?;
        let mut built = BuiltNets {
            points: Vec::with_capacity(45),
            jacobian: Vec::with_capacity(45),
        };
        for e in 0..3 {
            for (p, dp) in nets[e].iter().zip(&d[e]) {
                built.points.push(p.coords);
                built
                    .jacobian
                    .push(SMatrix::<f64, 3, 6>::from_fn(|c, k| dp[k][c]));
            }
        }
        Some(built)
    }

    fn lower_bounds(&self) -> SVector<f64, 6> {
        SVector::from(LOWER)
    }
}

/// The energy of one macro-patch as a least-squares problem in `(β_0, β_1, β_2, c_0, c_1, c_2)`:
/// a net energy of [`cost`] composed with the split-domain construction.
pub type MacroPatchEnergy = Composed<NetEnergy<RESIDUALS>, MacroPatchConstruction>;

/// The problem for one face (vertex data and its edge curves oriented along the face).
/// `None` if the face is degenerate in its own plane.
pub fn macro_patch_energy(
    energy: Energy,
    vertices: [VertexData; 3],
    edges: [CubicBez3; 3],
) -> Option<MacroPatchEnergy> {
    let construction = MacroPatchConstruction::new(vertices, edges);
    let objective = NetEnergy::new(energy, 4, &construction.domains()?).ok()?;
    Some(Composed::new(objective, construction))
}

/// How the interior parameters of every face are set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum InteriorChoice {
    /// The Shirman–Séquin defaults β = 1/3, c = 1.
    #[default]
    Default,
    /// β and c minimizing each macro-patch's thin-plate energy.
    ThinPlate,
    /// β and c minimizing each macro-patch's membrane energy.
    Membrane,
}

impl InteriorChoice {
    /// Every choice, in the order studies list them.
    pub const ALL: [InteriorChoice; 3] = [
        InteriorChoice::Default,
        InteriorChoice::ThinPlate,
        InteriorChoice::Membrane,
    ];
}

impl std::str::FromStr for InteriorChoice {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "default" => Ok(InteriorChoice::Default),
            "thin-plate" => Ok(InteriorChoice::ThinPlate),
            "membrane" => Ok(InteriorChoice::Membrane),
            _ => Err(format!(
                "unknown interior setting `{s}` (expected default, thin-plate or membrane)"
            )),
        }
    }
}

impl std::fmt::Display for InteriorChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            InteriorChoice::Default => "default",
            InteriorChoice::ThinPlate => "thin-plate",
            InteriorChoice::Membrane => "membrane",
        })
    }
}

/// What the per-face optimization did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct InteriorStats {
    /// Faces optimized.
    pub faces: usize,
    /// Faces whose solver reported convergence.
    pub converged: usize,
    /// Faces kept at the defaults (degenerate domain, or the solver refused).
    pub kept_default: usize,
    /// Sum over faces of the energy at the defaults (`‖r‖²`).
    pub energy_default: f64,
    /// Sum over faces of the energy at the chosen parameters.
    pub energy_chosen: f64,
    /// Iterations summed over faces.
    pub iterations: usize,
}

/// Interior parameters for every face of `mesh` given the boundary curves of `fit` (which must
/// be a fit of `mesh`): the defaults, or per face the minimizer of an energy, by the exact-penalty
/// adapter (β ≥ 0.05, c ≥ 0.1; start at the defaults).
pub fn choose_interior(
    mesh: &crate::mesh::Mesh,
    fit: &crate::fit::Fit,
    choice: InteriorChoice,
) -> (Vec<InteriorParameters>, InteriorStats) {
    choose_interior_with(mesh, fit, choice, solver::SolverKind::ExactPenalty)
}

/// [`choose_interior`] with any solver adapter (`solver::solve_any`: Levenberg–Marquardt runs
/// the 162- and 180-residual energies through its dynamic-size path).
pub fn choose_interior_with(
    mesh: &crate::mesh::Mesh,
    fit: &crate::fit::Fit,
    choice: InteriorChoice,
    kind: solver::SolverKind,
) -> (Vec<InteriorParameters>, InteriorStats) {
    use rayon::prelude::*;
    let energy = match choice {
        InteriorChoice::Default => {
            return (
                vec![InteriorParameters::default(); mesh.num_faces()],
                InteriorStats {
                    faces: mesh.num_faces(),
                    ..InteriorStats::default()
                },
            )
        }
        InteriorChoice::ThinPlate => Energy::ThinPlate,
        InteriorChoice::Membrane => Energy::Membrane,
    };
    let options = solver::SolveOptions {
        record_history: false,
        max_iterations: 100,
        ..solver::SolveOptions::default()
    };
    let x0 = SVector::<f64, 6>::new(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 1.0, 1.0, 1.0);
    let per_face: Vec<(InteriorParameters, bool, bool, f64, f64, usize)> = (0..mesh.num_faces())
        .into_par_iter()
        .map(|f| {
            let kept = (InteriorParameters::default(), false, true, 0.0, 0.0, 0);
            let Ok(edges) = fit.face_curves(mesh, f) else {
                return kept;
            };
            let (Some(a), Some(b), Some(c)) = (
                mesh.corner_data(f, 0),
                mesh.corner_data(f, 1),
                mesh.corner_data(f, 2),
            ) else {
                return kept;
            };
            let verts = [a, b, c];
            let Some(problem) = macro_patch_energy(energy, verts, edges) else {
                return kept;
            };
            let e0 = problem.objective(&x0);
            match solver::solve_any(kind, &problem, x0, &options) {
                Ok(s) if problem.objective(&s.x) <= e0 => (
                    MacroPatchConstruction::params(&s.x),
                    s.report.converged(),
                    false,
                    e0,
                    problem.objective(&s.x),
                    s.report.iterations,
                ),
                _ => (InteriorParameters::default(), false, true, e0, e0, 0),
            }
        })
        .collect();
    let mut stats = InteriorStats {
        faces: per_face.len(),
        ..InteriorStats::default()
    };
    for p in &per_face {
        stats.converged += usize::from(p.1);
        stats.kept_default += usize::from(p.2);
        stats.energy_default += p.3;
        stats.energy_chosen += p.4;
        stats.iterations += p.5;
    }
    (per_face.into_iter().map(|p| p.0).collect(), stats)
}

/// `mesh` fitted again with the interior parameters `choice` picks per face from a first fit
/// `first` (the defaults return `first` as it is). The boundary curves do not depend on β and
/// c, so the refit rebuilds the same curves and only the interiors change.
pub fn refit_interior(
    mesh: &crate::mesh::Mesh,
    method: &dyn curves::CurveMethod,
    first: crate::fit::Fit,
    choice: InteriorChoice,
    kind: solver::SolverKind,
) -> Result<(crate::fit::Fit, InteriorStats), crate::fit::FitError> {
    let (params, stats) = choose_interior_with(mesh, &first, choice, kind);
    if choice == InteriorChoice::Default {
        return Ok((first, stats));
    }
    let refit = crate::fit::fit(mesh, method, &|f| params[f])?;
    Ok((refit, stats))
}

/// `mesh` fitted with `scheme` (its curves from `method`); for the split-domain scheme
/// (`shirman-sequin`) the interior parameters are then chosen per face by `choice` with the
/// solver `kind` ([`refit_interior`]). Any other scheme has no interior parameters: a choice
/// other than [`InteriorChoice::Default`] is refused
/// ([`crate::fit::FitError::NoInteriorParameters`]).
pub fn fit_surface(
    mesh: &crate::mesh::Mesh,
    scheme: &dyn crate::scheme::Scheme,
    method: &dyn curves::CurveMethod,
    choice: InteriorChoice,
    kind: solver::SolverKind,
) -> Result<(crate::fit::Fit, InteriorStats), crate::fit::FitError> {
    let first = crate::fit::fit_scheme(mesh, scheme, method)?;
    if choice == InteriorChoice::Default {
        let stats = InteriorStats {
            faces: mesh.num_faces(),
            ..InteriorStats::default()
        };
        return Ok((first, stats));
    }
    if !scheme.has_interior_parameters() {
        return Err(crate::fit::FitError::NoInteriorParameters {
            scheme: scheme.name(),
        });
    }
    refit_interior(mesh, method, first, choice, kind)
}
