//! Section 4's corner measures (Mann 1994) on the derivative vectors of a patch at a corner,
//! with their exact gradients with respect to those vectors. The construction that produced the
//! patch supplies how the vectors move with its parameters; the chain rule is then one dot
//! product per vector (`surface::interior` does it for the split-domain scheme).
//!
//! # Curvature of a corner
//!
//! With `A` the first and `B` the second derivative of the patch along a direction at a corner,
//! `n` the vertex's unit normal and `S` its symmetric shape tensor, the measure is the patch's
//! normal curvature along `A` minus the vertex's:
//! `κ = ⟨n, B⟩/|A|² − tᵀ S t`, `t = A/|A|`. With `a = |A|²`:
//!
//! * `∂κ/∂B = n / a`;
//! * `∂κ/∂A = −2⟨n, B⟩ A / a² − 2 S A / a + 2 (Aᵀ S A) A / a²` (from `tᵀ S t = Aᵀ S A / a`).
//!
//! # Twist of a corner
//!
//! With `U`, `V` the first derivatives along the two edges at the corner and `W` the mixed
//! second derivative: `τ = ⟨n, W⟩/(|U||V|) − t_uᵀ S t_v`, `t_u = U/|U|`, `t_v = V/|V|`:
//!
//! * `∂τ/∂W = n / (|U||V|)`;
//! * `∂τ/∂U = −⟨n, W⟩ U / (|U|³|V|) − S V / (|U||V|) + (Uᵀ S V) U / (|U|³|V|)`;
//! * `∂τ/∂V` likewise with `U` and `V` exchanged.
//!
//! Both are checked against central differences at random points in `tests/corner.rs`.

use nalgebra::{Matrix3, Vector3};

/// The curvature measure and its gradients `(κ, ∂κ/∂A, ∂κ/∂B)` (module docs).
pub fn corner_curvature(
    n: &Vector3<f64>,
    s: &Matrix3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
) -> (f64, Vector3<f64>, Vector3<f64>) {
    let aa = a.norm_squared();
    let nb = n.dot(b);
    let sa = s * a;
    let asa = a.dot(&sa);
    let value = nb / aa - asa / aa;
    let grad_a = a * (-2.0 * nb / (aa * aa)) - sa * (2.0 / aa) + a * (2.0 * asa / (aa * aa));
    (value, grad_a, n / aa)
}

/// The twist measure and its gradients `(τ, ∂τ/∂U, ∂τ/∂V, ∂τ/∂W)` (module docs).
pub fn corner_twist(
    n: &Vector3<f64>,
    s: &Matrix3<f64>,
    u: &Vector3<f64>,
    v: &Vector3<f64>,
    w: &Vector3<f64>,
) -> (f64, Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let (lu, lv) = (u.norm(), v.norm());
    let nw = n.dot(w);
    let (su, sv) = (s * u, s * v);
    let usv = u.dot(&sv);
    let value = nw / (lu * lv) - usv / (lu * lv);
    let grad_u = u * (-nw / (lu.powi(3) * lv)) - sv / (lu * lv) + u * (usv / (lu.powi(3) * lv));
    let grad_v = v * (-nw / (lu * lv.powi(3))) - su / (lu * lv) + v * (usv / (lu * lv.powi(3)));
    (value, grad_u, grad_v, n / (lu * lv))
}
