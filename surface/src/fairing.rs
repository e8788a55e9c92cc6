//! Shape objectives that do depend on the interior parameters β and c, and their minimization
//! per data triangle (beyond Mann's Section 4, whose corner measures do not move: see
//! [`crate::interior`]).
//!
//! Two Sobolev energies of the macro-patch over its planar domain (the data triangle laid flat,
//! split at its centroid):
//!
//! * [`Energy::ThinPlate`]: `∫ |r_xx|² + 2|r_xy|² + |r_yy|² dA` — bending, the classical fairness
//!   functional (e.g. Greiner, "Variational design and fairing of spline surfaces", 1994);
//! * [`Energy::Membrane`]: `∫ |r_x|² + |r_y|² dA` — stretching, which penalizes interior points
//!   pulled away from an even parametrization.
//!
//! Each is a quadratic form in the control points: with barycentric gradients `g_i = ∇λ_i`, the
//! order-`k` derivatives are `n!/(n−k)! Σ_γ B^{n−k}_γ Σ g_{i₁}…g_{i_k} b_{γ+e_{i₁}+…}`, and
//! `∫_T B^m_γ B^m_δ dA = 2A · C(m,γ) C(m,δ) / C(2m, γ+δ) / ((2m+1)(2m+2))` (Farin, *Curves and
//! Surfaces for CAGD*, §17; the product of Bernstein polynomials is a scaled Bernstein
//! polynomial of twice the degree, whose integral is `2A/((2m+1)(2m+2))`). With the Gram matrix
//! `G = L Lᵀ`, the energy is `‖r‖²` for the residuals `r = Lᵀ P` (per derivative kind and
//! coordinate), and the Jacobian follows from the exact net derivatives of
//! [`crate::shirman_sequin::macro_patch_with_derivatives`].

use nalgebra::{Matrix3, SMatrix, SVector, Vector2, Vector3};
use solver::LeastSquaresProblem;

use crate::beztri::index;
use crate::shirman_sequin::{macro_patch_with_derivatives, InteriorParameters, SchemeError};
use curves::{CubicBez3, VertexData};

/// Residuals of one macro-patch's energy: 3 sub-patches × up to 60 (membrane: 2 kinds × 10
/// Bernstein coefficients of degree 3 × 3 coordinates; thin plate uses 3 × 6 × 3 = 54 and pads
/// with zeros).
pub const RESIDUALS: usize = 180;

/// Lower bounds of the optimization: β ≥ 0.05 and c ≥ 0.1 keep the construction away from its
/// degenerate limits (β → 0 collapses the interior boundaries, c → 0 the cross-boundary field).
pub const LOWER: [f64; 6] = [0.05, 0.05, 0.05, 0.1, 0.1, 0.1];

/// Which energy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Energy {
    /// `∫ |r_x|² + |r_y|²`.
    Membrane,
    /// `∫ |r_xx|² + 2|r_xy|² + |r_yy|²`.
    ThinPlate,
}

fn factorial(n: usize) -> f64 {
    (1..=n).map(|k| k as f64).product()
}

fn multinomial(m: usize, g: [usize; 3]) -> f64 {
    factorial(m) / (factorial(g[0]) * factorial(g[1]) * factorial(g[2]))
}

fn multi(m: usize) -> Vec<[usize; 3]> {
    let mut out = Vec::new();
    for k in 0..=m {
        for i in (0..=m - k).rev() {
            out.push([i, m - k - i, k]);
        }
    }
    out
}

/// One sub-patch's linear map from the 15 control points to the scaled residual coefficients:
/// `rows[r][idx]`, each row a weight per control point (the same for x, y, z).
fn residual_rows(energy: Energy, corners: [Vector2<f64>; 3]) -> Option<Vec<[f64; 15]>> {
    let n = 4usize;
    let (k, kinds): (usize, Vec<(Vec<usize>, f64)>) = match energy {
        Energy::Membrane => (1, vec![(vec![0], 1.0), (vec![1], 1.0)]),
        Energy::ThinPlate => (
            2,
            vec![(vec![0, 0], 1.0), (vec![0, 1], 2.0), (vec![1, 1], 1.0)],
        ),
    };
    let m = n - k;
    // Barycentric gradients: rows of the inverse of [[x0 x1 x2], [y0 y1 y2], [1 1 1]].
    let mat = Matrix3::new(
        corners[0].x,
        corners[1].x,
        corners[2].x,
        corners[0].y,
        corners[1].y,
        corners[2].y,
        1.0,
        1.0,
        1.0,
    );
    let inv = mat.try_inverse()?;
    let grad: [Vector2<f64>; 3] = std::array::from_fn(|i| Vector2::new(inv[(i, 0)], inv[(i, 1)]));
    let area = 0.5 * mat.determinant().abs();
    let gs = multi(m);
    let q = gs.len();
    // Gram matrix of degree-m Bernstein polynomials and its Cholesky factor.
    let gram = nalgebra::DMatrix::from_fn(q, q, |a, b| {
        let s = [
            gs[a][0] + gs[b][0],
            gs[a][1] + gs[b][1],
            gs[a][2] + gs[b][2],
        ];
        2.0 * area * multinomial(m, gs[a]) * multinomial(m, gs[b])
            / multinomial(2 * m, s)
            / ((2 * m + 1) * (2 * m + 2)) as f64
    });
    let l = gram.cholesky()?.l();
    let scale = factorial(n) / factorial(m);
    let mut rows = Vec::new();
    for (dirs, weight) in &kinds {
        // P_γ = Σ_{i…} Π g_i[dir] b_{γ + Σ e_i}, as weights on the 15 points.
        let p: Vec<[f64; 15]> = gs
            .iter()
            .map(|g| {
                let mut w = [0.0; 15];
                let mut add = |idx: [usize; 3], c: f64| w[index(n, idx[0], idx[1], idx[2])] += c;
                match dirs.len() {
                    1 => {
                        for i in 0..3 {
                            let mut t = *g;
                            t[i] += 1;
                            add(t, grad[i][dirs[0]]);
                        }
                    }
                    _ => {
                        for i in 0..3 {
                            for j in 0..3 {
                                let mut t = *g;
                                t[i] += 1;
                                t[j] += 1;
                                add(t, grad[i][dirs[0]] * grad[j][dirs[1]]);
                            }
                        }
                    }
                }
                w
            })
            .collect();
        for col in 0..q {
            let mut row = [0.0; 15];
            for (a, pa) in p.iter().enumerate() {
                for (r, x) in row.iter_mut().zip(pa) {
                    *r += l[(a, col)] * x;
                }
            }
            rows.push(row.map(|x| x * scale * weight.sqrt()));
        }
    }
    Some(rows)
}

/// The energy of one macro-patch as a least-squares problem in `(β_0, β_1, β_2, c_0, c_1, c_2)`.
#[derive(Clone, Debug)]
pub struct MacroPatchEnergy {
    vertices: [VertexData; 3],
    edges: [CubicBez3; 3],
    rows: [Vec<[f64; 15]>; 3],
}

impl MacroPatchEnergy {
    /// The problem for one face (vertex data and its edge curves oriented along the face).
    /// `None` if the face is degenerate in its own plane.
    pub fn new(energy: Energy, vertices: [VertexData; 3], edges: [CubicBez3; 3]) -> Option<Self> {
        // The domain: the data triangle in its own plane, split at the centroid.
        let (p0, p1, p2) = (vertices[0].p, vertices[1].p, vertices[2].p);
        let ex = (p1 - p0).try_normalize(0.0)?;
        let nrm = ex.cross(&(p2 - p0)).try_normalize(0.0)?;
        let ey = nrm.cross(&ex);
        let flat = |p: &nalgebra::Point3<f64>| Vector2::new((p - p0).dot(&ex), (p - p0).dot(&ey));
        let c = [flat(&p0), flat(&p1), flat(&p2)];
        let s = (c[0] + c[1] + c[2]) / 3.0;
        let mut rows: [Vec<[f64; 15]>; 3] = Default::default();
        for (e, slot) in rows.iter_mut().enumerate() {
            *slot = residual_rows(energy, [c[e], c[(e + 1) % 3], s])?;
        }
        Some(MacroPatchEnergy {
            vertices,
            edges,
            rows,
        })
    }

    fn params(x: &SVector<f64, 6>) -> InteriorParameters {
        InteriorParameters {
            beta: [x[0], x[1], x[2]],
            c: [x[3], x[4], x[5]],
        }
    }

    fn eval(
        &self,
        x: &SVector<f64, 6>,
    ) -> Result<(SVector<f64, RESIDUALS>, SMatrix<f64, RESIDUALS, 6>), SchemeError> {
        let v = [&self.vertices[0], &self.vertices[1], &self.vertices[2]];
        let (nets, d) = macro_patch_with_derivatives(v, &self.edges, &Self::params(x))?;
        let mut r = SVector::<f64, RESIDUALS>::zeros();
        let mut jac = SMatrix::<f64, RESIDUALS, 6>::zeros();
        let mut at = 0;
        for e in 0..3 {
            for row in &self.rows[e] {
                for coord in 0..3 {
                    let mut val = 0.0;
                    let mut der = [0.0; 6];
                    for (idx, w) in row.iter().enumerate() {
                        if *w == 0.0 {
                            continue;
                        }
                        val += w * nets[e][idx][coord];
                        for (k, dk) in der.iter_mut().enumerate() {
                            *dk += w * d[e][idx][k][coord];
                        }
                    }
                    if at < RESIDUALS {
                        r[at] = val;
                        for k in 0..6 {
                            jac[(at, k)] = der[k];
                        }
                    }
                    at += 1;
                }
            }
        }
        Ok((r, jac))
    }
}

impl LeastSquaresProblem<6, RESIDUALS> for MacroPatchEnergy {
    /// Non-finite where the construction fails (the solvers treat that as a rejected point).
    fn residuals(&self, x: &SVector<f64, 6>) -> SVector<f64, RESIDUALS> {
        self.eval(x)
            .map(|e| e.0)
            .unwrap_or_else(|_| SVector::from_element(f64::NAN))
    }

    fn jacobian(&self, x: &SVector<f64, 6>) -> SMatrix<f64, RESIDUALS, 6> {
        self.eval(x)
            .map(|e| e.1)
            .unwrap_or_else(|_| SMatrix::from_element(f64::NAN))
    }

    fn lower_bounds(&self) -> SVector<f64, 6> {
        SVector::from(LOWER)
    }
}

/// The quartic net of a plane `z = a x + b y` over a domain is linear, so its bending energy
/// vanishes: used by tests; also the closed form `∫|∇r|²` of the identity map is `2A`.
pub fn gram_check_area(corners: [Vector2<f64>; 3]) -> Option<f64> {
    // Membrane energy of r(x, y) = (x, y, 0), whose gradient norm² is 2 everywhere.
    let rows = residual_rows(Energy::Membrane, corners)?;
    let pt = |i: usize, j: usize, k: usize| {
        let p = (corners[0] * i as f64 + corners[1] * j as f64 + corners[2] * k as f64) / 4.0;
        Vector3::new(p.x, p.y, 0.0)
    };
    let net: Vec<Vector3<f64>> = multi(4).iter().map(|g| pt(g[0], g[1], g[2])).collect();
    Some(
        rows.iter()
            .map(|row| {
                let v: Vector3<f64> = row.iter().zip(&net).map(|(w, p)| p * *w).sum();
                v.norm_squared()
            })
            .sum(),
    )
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
            let (Ok(face), Ok(edges)) = (mesh.face(f), fit.face_curves(mesh, f)) else {
                return kept;
            };
            let verts = face.map(|i| mesh.vertices()[i].data);
            let Some(problem) = MacroPatchEnergy::new(energy, verts, edges) else {
                return kept;
            };
            let e0 = problem.objective(&x0);
            match solver::solve_any(kind, &problem, x0, &options) {
                Ok(s) if problem.objective(&s.x) <= e0 => (
                    MacroPatchEnergy::params(&s.x),
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
