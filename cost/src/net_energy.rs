//! Sobolev energies of triangular Bézier nets over planar domain triangles: thin plate (bending)
//! and membrane (stretching), as least-squares objectives on the control points.
//!
//! * [`SobolevEnergy::ThinPlate`]: `∫ |r_xx|² + 2|r_xy|² + |r_yy|² dA`, the classical fairness
//!   functional (e.g. Greiner, "Variational design and fairing of spline surfaces", 1994);
//! * [`SobolevEnergy::Membrane`]: `∫ |r_x|² + |r_y|² dA`, which penalizes points pulled away
//!   from an even parametrization.
//!
//! # Derivation
//!
//! On a domain triangle with corners `c_0, c_1, c_2 ∈ ℝ²` the barycentric coordinates `λ_i` are
//! affine with constant gradients `g_i = ∇λ_i` (the first two columns of the inverse of
//! `[[x_0 x_1 x_2], [y_0 y_1 y_2], [1 1 1]]`). Differentiating `r = Σ B^n_β(λ) b_β` `k` times
//! along coordinate directions `d_1 … d_k ∈ {x, y}` gives a degree-`m = n − k` polynomial
//! `n!/m! Σ_γ B^m_γ Σ_{i_1…i_k} g_{i_1}[d_1] ⋯ g_{i_k}[d_k] b_{γ + e_{i_1} + … + e_{i_k}}`
//! (Farin, *Curves and Surfaces for CAGD*, §17). Its squared L² norm is `pᵀ G p` per
//! coordinate, with the Gram matrix of the degree-`m` Bernstein polynomials
//! `G_γδ = ∫ B^m_γ B^m_δ dA = 2A · C(m,γ) C(m,δ) / C(2m, γ+δ) / ((2m+1)(2m+2))`: the product
//! is `C(m,γ)C(m,δ)/C(2m,γ+δ)` times a degree-`2m` Bernstein polynomial, and each of those
//! integrates to `2A/((2m+1)(2m+2))`. With the Cholesky factor `G = L Lᵀ`, the energy is
//! `‖Lᵀ p‖²`, so the residuals are `r = √w · Lᵀ p` per derivative kind (weight `w`: 1, 2, 1
//! for xx, xy, yy) and per coordinate — linear in the control points. The derivative of a
//! residual with respect to a control point is therefore a constant weight times the unit
//! vector of its coordinate, and the gradient of the energy is `2 Σ r_a ∂r_a/∂P`.
//!
//! Tests (`tests/suite/net_energy.rs`): the membrane energy of the identity map is `2A`, the thin
//! plate energy of any degree-`n` net of a quadratic `r(x, y)` is its closed form, the energy
//! is invariant under rigid motions of the net, and the gradient matches finite differences at
//! random nets.

use nalgebra::{DMatrix, Matrix3, SVector, Vector2, Vector3};

use crate::net::{index, multi_indices, num_points, NetObjective};

/// Which energy.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SobolevEnergy {
    /// `∫ |r_x|² + |r_y|² dA`.
    Membrane,
    /// `∫ |r_xx|² + 2|r_xy|² + |r_yy|² dA`.
    ThinPlate,
}

impl SobolevEnergy {
    /// The order of the derivatives it integrates.
    pub fn order(self) -> usize {
        match self {
            SobolevEnergy::Membrane => 1,
            SobolevEnergy::ThinPlate => 2,
        }
    }

    /// Residuals per net of degree `n` (three coordinates, each derivative kind, each
    /// Bernstein coefficient of degree `n − order`); 0 when `n` is below the order.
    pub fn residuals_per_net(self, n: usize) -> usize {
        let Some(m) = n.checked_sub(self.order()) else {
            return 0;
        };
        3 * (self.order() + 1) * num_points(m)
    }
}

/// Why an energy could not be set up.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum NetEnergyError {
    /// A domain triangle has no area.
    #[error("domain triangle {0} has no area")]
    DegenerateDomain(usize),
    /// More residuals than the problem's fixed size.
    #[error("{needed} residuals do not fit a problem of {capacity}")]
    TooManyResiduals {
        /// Residuals the energy needs.
        needed: usize,
        /// The problem's size `M`.
        capacity: usize,
    },
}

/// One residual row: `(point, weight)` pairs, the same weights for each coordinate.
type Row = Vec<(usize, f64)>;

/// A Sobolev energy of one or several concatenated degree-`n` nets, each over its own planar
/// domain triangle, as `M` residuals (unused ones are zero).
#[derive(Clone, Debug, PartialEq)]
pub struct NetEnergy<const M: usize> {
    energy: SobolevEnergy,
    degree: usize,
    rows: Vec<Row>,
}

fn factorial(n: usize) -> f64 {
    (1..=n).map(|k| k as f64).product()
}

fn multinomial(m: usize, g: (usize, usize, usize)) -> f64 {
    factorial(m) / (factorial(g.0) * factorial(g.1) * factorial(g.2))
}

/// The barycentric gradients and the area of a domain triangle.
fn barycentric_gradients(c: [Vector2<f64>; 3]) -> Option<([Vector2<f64>; 3], f64)> {
    let mat = Matrix3::new(
        c[0].x, c[1].x, c[2].x, c[0].y, c[1].y, c[2].y, 1.0, 1.0, 1.0,
    );
    let area = 0.5 * mat.determinant().abs();
    if area.is_nan() || area <= 0.0 {
        return None;
    }
    let inv = mat.try_inverse()?;
    Some((
        std::array::from_fn(|i| Vector2::new(inv[(i, 0)], inv[(i, 1)])),
        area,
    ))
}

/// The residual rows of one net (points `offset..offset + num_points(n)`).
fn net_rows(
    energy: SobolevEnergy,
    n: usize,
    corners: [Vector2<f64>; 3],
    offset: usize,
) -> Option<Vec<Row>> {
    let k = energy.order();
    let m = n.checked_sub(k)?;
    let (grad, area) = barycentric_gradients(corners)?;
    let kinds: Vec<(Vec<usize>, f64)> = match energy {
        SobolevEnergy::Membrane => vec![(vec![0], 1.0), (vec![1], 1.0)],
        SobolevEnergy::ThinPlate => {
            vec![(vec![0, 0], 1.0), (vec![0, 1], 2.0), (vec![1, 1], 1.0)]
        }
    };
    let gs = multi_indices(m);
    let q = gs.len();
    let gram = DMatrix::from_fn(q, q, |a, b| {
        let s = (gs[a].0 + gs[b].0, gs[a].1 + gs[b].1, gs[a].2 + gs[b].2);
        2.0 * area * multinomial(m, gs[a]) * multinomial(m, gs[b])
            / multinomial(2 * m, s)
            / ((2 * m + 1) * (2 * m + 2)) as f64
    });
    let l = gram.cholesky()?.l();
    let scale = factorial(n) / factorial(m);
    let np = num_points(n);
    let mut rows = Vec::with_capacity(kinds.len() * q);
    for (dirs, weight) in &kinds {
        // p_γ = Σ_{i…} Π g_i[d] b_{γ + Σ e_i}, as dense weights on the net's points.
        let p: Vec<Vec<f64>> = gs
            .iter()
            .map(|&(a, b, c)| {
                let mut w = vec![0.0; np];
                fn walk(
                    w: &mut Vec<f64>,
                    n: usize,
                    t: [usize; 3],
                    coeff: f64,
                    dirs: &[usize],
                    grad: &[Vector2<f64>; 3],
                ) {
                    match dirs.split_first() {
                        None => w[index(n, t[0], t[1], t[2])] += coeff,
                        Some((d, rest)) => {
                            for (i, g) in grad.iter().enumerate() {
                                let mut u = t;
                                u[i] += 1;
                                walk(w, n, u, coeff * g[*d], rest, grad);
                            }
                        }
                    }
                }
                walk(&mut w, n, [a, b, c], 1.0, dirs, &grad);
                w
            })
            .collect();
        for col in 0..q {
            let mut dense = vec![0.0; np];
            for (a, pa) in p.iter().enumerate() {
                for (r, x) in dense.iter_mut().zip(pa) {
                    *r += l[(a, col)] * x;
                }
            }
            let f = scale * weight.sqrt();
            rows.push(
                dense
                    .iter()
                    .enumerate()
                    .filter(|(_, w)| **w != 0.0)
                    .map(|(i, w)| (offset + i, w * f))
                    .collect(),
            );
        }
    }
    Some(rows)
}

impl<const M: usize> NetEnergy<M> {
    /// The energy of `domains.len()` concatenated degree-`degree` nets, net `t` over the planar
    /// triangle `domains[t]` (its corners matching the net's corners `b_{n00}, b_{0n0}, b_{00n}`).
    pub fn new(
        energy: SobolevEnergy,
        degree: usize,
        domains: &[[Vector2<f64>; 3]],
    ) -> Result<Self, NetEnergyError> {
        let needed = energy.residuals_per_net(degree) * domains.len();
        if needed > M {
            return Err(NetEnergyError::TooManyResiduals {
                needed,
                capacity: M,
            });
        }
        let mut rows = Vec::new();
        for (t, dom) in domains.iter().enumerate() {
            rows.extend(
                net_rows(energy, degree, *dom, t * num_points(degree))
                    .ok_or(NetEnergyError::DegenerateDomain(t))?,
            );
        }
        Ok(NetEnergy {
            energy,
            degree,
            rows,
        })
    }

    /// Which energy.
    pub fn energy(&self) -> SobolevEnergy {
        self.energy
    }

    /// The degree of the nets.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Residuals in use (the rest of the `M` are zero).
    pub fn residuals_used(&self) -> usize {
        3 * self.rows.len()
    }
}

impl<const M: usize> NetObjective<M> for NetEnergy<M> {
    /// Residual `3a + c` is row `a` applied to coordinate `c`.
    fn residuals(&self, points: &[Vector3<f64>]) -> SVector<f64, M> {
        let mut r = SVector::<f64, M>::zeros();
        for (a, row) in self.rows.iter().enumerate() {
            let v: Vector3<f64> = row
                .iter()
                .map(|&(p, w)| points.get(p).map_or(Vector3::zeros(), |q| q * w))
                .sum();
            for c in 0..3 {
                r[3 * a + c] = v[c];
            }
        }
        r
    }

    fn for_each_derivative(
        &self,
        _points: &[Vector3<f64>],
        f: &mut dyn FnMut(usize, usize, Vector3<f64>),
    ) {
        for (a, row) in self.rows.iter().enumerate() {
            for &(p, w) in row {
                for c in 0..3 {
                    let mut d = Vector3::zeros();
                    d[c] = w;
                    f(3 * a + c, p, d);
                }
            }
        }
    }
}
