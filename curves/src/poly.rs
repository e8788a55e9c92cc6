//! Real roots of low-degree polynomials on an interval.
//!
//! Used by the de Boor–Höllig–Sabin construction, whose two quadratic equations reduce to one
//! quartic. The method is root isolation by derivatives (the classical approach for low degree,
//! see e.g. Collins & Loos, "Real zeros of polynomials", 1982): the real roots of `p'` cut the
//! interval into pieces on which `p` is monotone, so each piece holds at most one root, found by
//! a safeguarded Newton–bisection iteration. A critical point where `|p|` is at rounding level is
//! reported as a (double) root, because a tangential root has no sign change to bracket.
//!
//! Everything lives in fixed-size arrays: no heap allocation, which matters when millions of
//! edges are solved.

/// Highest degree handled (the dBHS quartic).
pub const MAX_DEGREE: usize = 4;

/// A relative size below which `|p(x)|` at a critical point counts as zero: the value is then
/// within a few hundred rounding errors of the sum of the magnitudes of the terms at `x`, which
/// is as well as Horner evaluation can resolve a double root. Candidates found this way are
/// verified by the caller against the system they came from.
const DOUBLE_ROOT_RELATIVE: f64 = 1e-12;

/// Bisection/Newton steps on one monotone piece; bisection alone halves the bracket each step,
/// so 200 steps resolve any bracket of finite `f64` width to the last bit.
const MAX_REFINE_STEPS: usize = 200;

/// Roots found, at most [`MAX_DEGREE`], in increasing order.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Roots {
    values: [f64; MAX_DEGREE],
    len: usize,
}

impl Roots {
    /// The roots as a slice, ascending.
    pub fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }

    fn push(&mut self, x: f64) {
        if self.len < MAX_DEGREE {
            self.values[self.len] = x;
            self.len += 1;
        }
    }
}

/// A polynomial `c[0] + c[1] x + … + c[deg] x^deg` with `deg ≤ MAX_DEGREE`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Poly {
    c: [f64; MAX_DEGREE + 1],
    deg: usize,
}

impl Poly {
    /// Builds a polynomial from ascending coefficients; trailing exact zeros lower the degree.
    /// Returns `None` if more than `MAX_DEGREE + 1` coefficients are given.
    pub fn new(coeffs: &[f64]) -> Option<Self> {
        if coeffs.len() > MAX_DEGREE + 1 {
            return None;
        }
        let mut c = [0.0; MAX_DEGREE + 1];
        c[..coeffs.len()].copy_from_slice(coeffs);
        let mut deg = coeffs.len().saturating_sub(1);
        while deg > 0 && c[deg] == 0.0 {
            deg -= 1;
        }
        Some(Poly { c, deg })
    }

    /// Degree after dropping exact zero leading coefficients.
    pub fn degree(&self) -> usize {
        self.deg
    }

    /// True when every coefficient is exactly zero.
    pub fn is_zero(&self) -> bool {
        self.deg == 0 && self.c[0] == 0.0
    }

    /// Value at `x` (Horner).
    pub fn eval(&self, x: f64) -> f64 {
        let mut v = self.c[self.deg];
        for i in (0..self.deg).rev() {
            v = v * x + self.c[i];
        }
        v
    }

    /// Sum of the magnitudes of the terms at `x`: the scale against which rounding in
    /// [`Poly::eval`] is measured.
    pub fn magnitude(&self, x: f64) -> f64 {
        let ax = x.abs();
        let mut v = self.c[self.deg].abs();
        for i in (0..self.deg).rev() {
            v = v * ax + self.c[i].abs();
        }
        v
    }

    /// The derivative.
    pub fn derivative(&self) -> Poly {
        let mut c = [0.0; MAX_DEGREE + 1];
        for i in 1..=self.deg {
            c[i - 1] = self.c[i] * i as f64;
        }
        Poly {
            c,
            deg: self.deg.saturating_sub(1),
        }
    }

    /// All real roots in the closed interval `[lo, hi]`, ascending, simple and double roots
    /// alike (a root of multiplicity > 1 is reported once). A zero polynomial has no isolated
    /// roots and gives an empty set: callers must test [`Poly::is_zero`] themselves.
    pub fn roots_in(&self, lo: f64, hi: f64) -> Roots {
        let mut out = Roots::default();
        if self.deg == 0 || lo.partial_cmp(&hi).is_none_or(|o| o.is_gt()) {
            return out;
        }
        if self.deg == 1 {
            let x = -self.c[0] / self.c[1];
            if x >= lo && x <= hi {
                out.push(x);
            }
            return out;
        }
        let crit = self.derivative().roots_in(lo, hi);
        // Breakpoints: lo, the critical points, hi.
        let mut pts = [0.0; MAX_DEGREE + 1];
        let mut n = 0;
        pts[n] = lo;
        n += 1;
        for &x in crit.as_slice() {
            if x > pts[n - 1] && x < hi {
                pts[n] = x;
                n += 1;
            }
        }
        pts[n] = hi;
        n += 1;
        let vals: [f64; MAX_DEGREE + 1] =
            std::array::from_fn(|i| if i < n { self.eval(pts[i]) } else { 0.0 });
        let is_zero_at = |i: usize| -> bool {
            vals[i] == 0.0
                || (i > 0
                    && i < n - 1
                    && vals[i].abs() <= DOUBLE_ROOT_RELATIVE * self.magnitude(pts[i]))
        };
        let mut last_added = f64::NEG_INFINITY;
        let mut add = |x: f64, out: &mut Roots| {
            if x > last_added {
                out.push(x);
                last_added = x;
            }
        };
        for i in 0..n {
            if is_zero_at(i) {
                add(pts[i], &mut out);
            }
            if i + 1 < n {
                let (a, b) = (pts[i], pts[i + 1]);
                let (fa, fb) = (vals[i], vals[i + 1]);
                if !is_zero_at(i) && !is_zero_at(i + 1) && (fa < 0.0) != (fb < 0.0) {
                    add(self.refine(a, b, fa), &mut out);
                }
            }
        }
        out
    }

    /// Root in `[a, b]` where `p` is monotone and changes sign; `fa = p(a)`.
    fn refine(&self, mut a: f64, mut b: f64, fa: f64) -> f64 {
        let d = self.derivative();
        let neg_at_a = fa < 0.0;
        let mut x = 0.5 * (a + b);
        for _ in 0..MAX_REFINE_STEPS {
            let fx = self.eval(x);
            if fx == 0.0 {
                return x;
            }
            if (fx < 0.0) == neg_at_a {
                a = x;
            } else {
                b = x;
            }
            let dx = d.eval(x);
            let newton = x - fx / dx;
            let next = if newton > a && newton < b && dx != 0.0 {
                newton
            } else {
                0.5 * (a + b)
            };
            if next == x || b - a <= f64::EPSILON * a.abs().max(b.abs()) {
                return next;
            }
            x = next;
        }
        x
    }
}

/// An upper bound on the magnitude of every real root (Cauchy's bound `1 + max |c_i / c_n|`).
pub fn cauchy_bound(p: &Poly) -> f64 {
    let lead = p.c[p.deg];
    if p.deg == 0 || lead == 0.0 {
        return 0.0;
    }
    1.0 + (0..p.deg)
        .map(|i| (p.c[i] / lead).abs())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Roots of products of known linear factors are recovered to this relative accuracy.
    const ROOT_TOL: f64 = 1e-10;

    fn from_roots(rs: &[f64], lead: f64) -> Poly {
        let mut c = vec![lead];
        for &r in rs {
            let mut next = vec![0.0; c.len() + 1];
            for (i, &ci) in c.iter().enumerate() {
                next[i + 1] += ci;
                next[i] -= r * ci;
            }
            c = next;
        }
        Poly::new(&c).expect("degree ≤ 4")
    }

    #[test]
    fn four_simple_roots() {
        let p = from_roots(&[-2.0, 0.5, 1.0, 7.0], 3.0);
        let b = cauchy_bound(&p);
        let r = p.roots_in(-b, b);
        assert_eq!(r.as_slice().len(), 4);
        for (x, e) in r.as_slice().iter().zip([-2.0, 0.5, 1.0, 7.0]) {
            assert!((x - e).abs() <= ROOT_TOL * e.abs().max(1.0), "{x} vs {e}");
        }
    }

    #[test]
    fn double_root_is_found_once() {
        let p = from_roots(&[1.5, 1.5, -1.0], 1.0);
        let r = p.roots_in(0.0, 10.0);
        assert_eq!(r.as_slice().len(), 1);
        assert!((r.as_slice()[0] - 1.5).abs() < 1e-7);
    }

    #[test]
    fn no_real_roots() {
        let p = Poly::new(&[1.0, 0.0, 1.0]).expect("quadratic");
        assert!(p.roots_in(-10.0, 10.0).as_slice().is_empty());
    }

    #[test]
    fn interval_is_respected_and_degree_drops() {
        let p = from_roots(&[-3.0, 2.0], 1.0);
        assert_eq!(p.roots_in(0.0, 5.0).as_slice(), &[2.0]);
        let q = Poly::new(&[2.0, -1.0, 0.0, 0.0]).expect("linear");
        assert_eq!(q.degree(), 1);
        assert_eq!(q.roots_in(0.0, 5.0).as_slice(), &[2.0]);
        assert!(Poly::new(&[0.0, 0.0]).expect("zero").is_zero());
    }

    #[test]
    fn widely_spread_roots() {
        let p = from_roots(&[1e-4, 1.0, 1e4], 1.0);
        let b = cauchy_bound(&p);
        let r = p.roots_in(0.0, b);
        assert_eq!(r.as_slice().len(), 3);
        for (x, e) in r.as_slice().iter().zip([1e-4, 1.0, 1e4]) {
            assert!((x - e).abs() <= ROOT_TOL * e, "{x} vs {e}");
        }
    }
}
