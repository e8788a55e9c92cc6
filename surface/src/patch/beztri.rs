//! Triangular Bézier patches of any degree, with derivatives and differential geometry.
//!
//! A patch of degree `n` maps barycentric coordinates `(u, v, w)`, `u + v + w = 1`, to
//! `b(u, v, w) = Σ_{i+j+k=n} B^n_{ijk}(u, v, w) b_{ijk}` with Bernstein polynomials
//! `B^n_{ijk} = n!/(i! j! k!) u^i v^j w^k` (Farin, *Curves and Surfaces for CAGD*, ch. 17
//! "Triangular Bézier patches"). Corner `u` (`(1,0,0)`) is `b_{n00}`, corner `v` is `b_{0n0}`,
//! corner `w` is `b_{00n}`.
//!
//! # Control-net order (docs/conventions.md)
//!
//! Rows `k = 0..n`; within a row `i` runs from `n − k` down to 0 (and `j = n − k − i` up).
//! Row 0 is the edge from the `u` corner to the `v` corner. The position of `b_{ijk}` is
//! [`index`]`(n, i, j, k) = k(n + 1) − k(k − 1)/2 + j`. For `n = 2`:
//! `b200, b110, b020, b101, b011, b002`.
//!
//! # Edges
//!
//! Edge 0 is `w = 0` from corner `u` to corner `v`, edge 1 is `u = 0` from `v` to `w`, edge 2
//! is `v = 0` from `w` to `u` — the local edges of a mesh face `[u, v, w]` in [`crate::mesh`].
//!
//! # Derivatives
//!
//! [`BezierTriangle::derivatives`] gives partials with respect to `(u, v)` with
//! `w = 1 − u − v`: `∂/∂u` is the directional derivative along the barycentric direction
//! `(1, 0, −1)`, `∂/∂v` along `(0, 1, −1)`. A derivative along barycentric directions
//! `d_1, …, d_r` (each summing to 0) is `n!/(n − r)!` times the blossom
//! `b[d_1, …, d_r, p, …, p]`, evaluated by de Casteljau steps with the directions as weights
//! (Farin ch. 17; [`BezierTriangle::directional`]).
//!
//! # Curvature
//!
//! With `r_u, r_v` the partials, the patch normal `n = (r_u × r_v)/|r_u × r_v|`, first
//! fundamental form `E = r_u·r_u, F = r_u·r_v, G = r_v·r_v` and second `L = r_uu·n,
//! M = r_uv·n, N = r_vv·n` (do Carmo, *Differential Geometry of Curves and Surfaces*, §3-3):
//! `K = (LN − M²)/(EG − F²)`, `H = (EN − 2FM + GL)/(2(EG − F²))`. Since `II(a)/I(a)` is the
//! normal component of a surface curve's curvature vector, it is positive where the surface bends
//! towards `n`: the docs/conventions.md sign (a paraboloid `z = x² + y²` with upward normal has `K = 4`,
//! `H = 2` at its apex). The world shape tensor is `S = J I⁻¹ II I⁻¹ Jᵀ` with `J = [r_u r_v]`,
//! so that `dᵀ S d = II(a)/I(a)` for `d = J a/|J a|`, and `S n = 0`.

use nalgebra::{Matrix2, Matrix3, Matrix3x2, Point3, Vector3};

/// Below this ratio `|r_u × r_v| / (|r_u| |r_v|)` (the sine of the angle between the partials)
/// the normal is undefined: the patch is singular there (a collapsed edge or a fold).
pub const SINGULAR_SINE: f64 = 1e-10;

// The net order (`index`, `multi_indices`, `num_points`) is stated once, in `cost::net`, where
// the objectives on nets read it.
pub use cost::net::{index, multi_indices, num_points};

/// Why a patch could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BezTriError {
    /// The number of control points does not match the degree.
    #[error("degree {degree} needs {expected} control points, got {got}")]
    WrongCount {
        /// The degree.
        degree: usize,
        /// `(n + 1)(n + 2)/2`.
        expected: usize,
        /// How many were given.
        got: usize,
    },
    /// A control point has a NaN or infinite coordinate.
    #[error("control point {index} is not finite")]
    NonFinite {
        /// Its position in the net.
        index: usize,
    },
}

/// A Bézier curve of any degree in space (the boundary of a patch).
#[derive(Clone, Debug, PartialEq)]
pub struct BezierCurve {
    /// Control points, first and last interpolated.
    pub points: Vec<Point3<f64>>,
}

impl BezierCurve {
    /// Degree (number of points − 1; 0 for a single point or none).
    pub fn degree(&self) -> usize {
        self.points.len().saturating_sub(1)
    }

    /// Position at `t` by de Casteljau's algorithm (the origin for an empty curve).
    pub fn eval(&self, t: f64) -> Point3<f64> {
        let mut pts: Vec<Vector3<f64>> = self.points.iter().map(|p| p.coords).collect();
        while pts.len() > 1 {
            for i in 0..pts.len() - 1 {
                pts[i] = pts[i] * (1.0 - t) + pts[i + 1] * t;
            }
            pts.pop();
        }
        Point3::from(pts.first().copied().unwrap_or_else(Vector3::zeros))
    }
}

/// Position and first and second partial derivatives with respect to `(u, v)`, `w = 1 − u − v`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Derivatives {
    /// Position.
    pub p: Point3<f64>,
    /// `∂b/∂u`.
    pub du: Vector3<f64>,
    /// `∂b/∂v`.
    pub dv: Vector3<f64>,
    /// `∂²b/∂u²`.
    pub duu: Vector3<f64>,
    /// `∂²b/∂u∂v`.
    pub duv: Vector3<f64>,
    /// `∂²b/∂v²`.
    pub dvv: Vector3<f64>,
}

impl From<[Vector3<f64>; 6]> for Derivatives {
    /// `[p, du, dv, duu, duv, dvv]`, the order of [`SampleWeights`]' weights.
    fn from(d: [Vector3<f64>; 6]) -> Self {
        Derivatives {
            p: Point3::from(d[0]),
            du: d[1],
            dv: d[2],
            duu: d[3],
            duv: d[4],
            dvv: d[5],
        }
    }
}

/// Differential geometry at a regular point of a patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Curvature {
    /// Unit normal `(r_u × r_v)/|r_u × r_v|`.
    pub normal: Vector3<f64>,
    /// Gaussian curvature `K`.
    pub gaussian: f64,
    /// Mean curvature `H = (κ1 + κ2)/2`, docs/conventions.md sign.
    pub mean: f64,
    /// Principal curvatures `κ1 ≤ κ2`.
    pub principal: [f64; 2],
    /// World shape tensor `S` (`κn(d) = dᵀ S d`, `S n = 0`).
    pub shape: Matrix3<f64>,
}

/// The Bernstein weights of position and the five partials at one domain point, for every
/// control point of a degree-`n` net: `b(u, v) = Σ_c w_c[0] b_c`, `∂b/∂u = Σ_c w_c[1] b_c`, …
/// (order `p, du, dv, duu, duv, dvv`). Evaluating a patch at a point then costs six weighted
/// sums and no allocation; a tessellation computes the table once per (degree, sample) and
/// shares it by every patch ([`BezierTriangle::derivatives_with`]).
///
/// The weights are the derivatives of the basis nets (one control point 1, the others 0)
/// computed by the blossom ([`BezierTriangle::derivatives`]), so they are exactly what the
/// general evaluation gives, by linearity.
#[derive(Clone, Debug, PartialEq)]
pub struct SampleWeights {
    degree: usize,
    /// At `(u, v)`.
    pub at: (f64, f64),
    weights: Vec<[f64; 6]>,
    /// The control points whose six weights are not all zero, with their weights: on a patch
    /// edge only the two rows next to it count, at a corner six points of fifteen (quartic).
    /// Leaving the others out changes no bit of the sums: each of them adds `b · 0 = ±0` to an
    /// accumulator that starts at `+0` and never becomes `−0` (a sum of products that cancels
    /// rounds to `+0`).
    nonzero: Vec<(usize, [f64; 6])>,
}

/// The blossom of a basis net (control point `c` is 1, the others 0) on scalars: the steps of
/// [`BezierTriangle::blossom`] with the source indices of every level computed once.
struct BasisBlossom {
    degree: usize,
    /// Per step, from degree `m` down to `m − 1`: for each point of the lower net (net order),
    /// the indices of `b_{i+1,j,k}`, `b_{i,j+1,k}`, `b_{i,j,k+1}` in the upper one.
    sources: Vec<Vec<[usize; 3]>>,
}

/// The index table of de Casteljau's steps from degree `from` down to degree `to − 1`
/// (`m = from, …, to`): per step, for each point `(i, j, k)` of the lower net of degree `m − 1`
/// (net order), the indices of `b_{i+1,j,k}`, `b_{i,j+1,k}`, `b_{i,j,k+1}` in the net of
/// degree `m`; empty when `to > from`.
pub fn casteljau_steps(from: usize, to: usize) -> Vec<Vec<[usize; 3]>> {
    (to.max(1)..=from)
        .rev()
        .map(|m| {
            multi_indices(m - 1)
                .into_iter()
                .map(|(i, j, k)| {
                    [
                        index(m, i + 1, j, k),
                        index(m, i, j + 1, k),
                        index(m, i, j, k + 1),
                    ]
                })
                .collect()
        })
        .collect()
}

impl BasisBlossom {
    fn new(degree: usize) -> Self {
        BasisBlossom {
            degree,
            sources: casteljau_steps(degree, 1),
        }
    }

    /// `b[args]` for the basis nets of all control points at once (`args` as long as the
    /// degree): the nets side by side, point `t` of a level holding the `m` basis nets' values
    /// at `t`, with `a` and `b` as scratch. Each value is computed as `x·a₀ + y·a₁ + z·a₂`, in
    /// the order `step` uses, so it is the general evaluation's number.
    fn eval_all(&self, args: &[[f64; 3]], a: &mut Vec<f64>, b: &mut Vec<f64>) -> Vec<f64> {
        let m = num_points(self.degree);
        a.clear();
        a.resize(m * m, 0.0);
        for c in 0..m {
            a[c * m + c] = 1.0;
        }
        for (src, arg) in self.sources.iter().zip(args) {
            b.clear();
            b.resize(src.len() * m, 0.0);
            for (out, s) in b.chunks_exact_mut(m).zip(src) {
                let (x, y, z) = (
                    &a[s[0] * m..(s[0] + 1) * m],
                    &a[s[1] * m..(s[1] + 1) * m],
                    &a[s[2] * m..(s[2] + 1) * m],
                );
                for (((o, x), y), z) in out.iter_mut().zip(x).zip(y).zip(z) {
                    *o = x * arg[0] + y * arg[1] + z * arg[2];
                }
            }
            std::mem::swap(a, b);
        }
        a.truncate(m);
        a.clone()
    }
}

impl SampleWeights {
    /// The weights of a degree-`n` net at `(u, v)` (`w = 1 − u − v`).
    ///
    /// Each weight is the blossom of a basis net run on scalars (the arithmetic of
    /// [`BezierTriangle::derivatives`] on the one non-zero coordinate, in the same order, so the
    /// same bits), all basis nets side by side over index tables built once: 2.0 µs at degree
    /// 4, where running the general evaluation on fifteen basis nets took about 16 µs (the G1
    /// measurement prepares 84 of them, a fixed 1.4 ms before, 0.23 ms now).
    pub fn new(degree: usize, u: f64, v: f64) -> Self {
        let m = num_points(degree);
        let blossom = BasisBlossom::new(degree);
        let at = [u, v, 1.0 - u - v];
        let (eu, ev) = ([1.0, 0.0, -1.0], [0.0, 1.0, -1.0]);
        // The argument lists of p, du, dv, duu, duv, dvv: directions, then `at` up to the degree.
        let args: [Vec<[f64; 3]>; 6] = [
            vec![],
            vec![eu],
            vec![ev],
            vec![eu, eu],
            vec![eu, ev],
            vec![ev, ev],
        ]
        .map(|mut dirs| {
            dirs.resize(degree.max(dirs.len()), at);
            dirs
        });
        let (mut a, mut b) = (Vec::with_capacity(m * m), Vec::with_capacity(m * m));
        // Per partial, the values of all basis nets (zero where the order exceeds the degree).
        let orders = [0, 1, 1, 2, 2, 2];
        let values: [Vec<f64>; 6] = std::array::from_fn(|d| {
            let r = orders[d];
            if r > degree {
                return vec![0.0; m];
            }
            let mut v = blossom.eval_all(&args[d], &mut a, &mut b);
            if r > 0 {
                let factor: f64 = ((degree - r + 1)..=degree).map(|x| x as f64).product();
                for x in &mut v {
                    *x *= factor;
                }
            }
            v
        });
        let weights = (0..m)
            .map(|c| std::array::from_fn(|d| values[d][c]))
            .collect::<Vec<[f64; 6]>>();
        let nonzero = weights
            .iter()
            .enumerate()
            .filter(|(_, w)| w.iter().any(|x| *x != 0.0))
            .map(|(i, w)| (i, *w))
            .collect();
        SampleWeights {
            degree,
            at: (u, v),
            weights,
            nonzero,
        }
    }

    /// The weights of every sample `(i/s, j/s)` of a degree-`n` patch with `s` segments an
    /// edge, rows by `j` (the order of the tessellations' sample grid): computed once and
    /// shared by every patch of that degree.
    pub fn grid(degree: usize, s: usize) -> Vec<SampleWeights> {
        let mut t = Vec::with_capacity((s + 1) * (s + 2) / 2);
        for j in 0..=s {
            for i in 0..=s - j {
                t.push(SampleWeights::new(
                    degree,
                    i as f64 / s as f64,
                    j as f64 / s as f64,
                ));
            }
        }
        t
    }

    /// The degree of the nets the weights are for.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Per control point (net order), the weights of `[p, r_u, r_v, r_uu, r_uv, r_vv]`.
    pub fn weights(&self) -> &[[f64; 6]] {
        &self.weights
    }
}

/// Position and partials of the net `points` (net order, of the weights' degree) at the
/// weights' sample: six weighted sums, no allocation. For nets held in a shared buffer (a
/// [`crate::fit::Fit`]'s points) without building a [`BezierTriangle`].
pub fn net_derivatives(points: &[Point3<f64>], weights: &SampleWeights) -> Derivatives {
    let mut acc = [Vector3::zeros(); 6];
    for (i, w) in &weights.nonzero {
        let Some(b) = points.get(*i) else {
            continue;
        };
        for (a, wk) in acc.iter_mut().zip(w) {
            *a += b.coords * *wk;
        }
    }
    Derivatives::from(acc)
}

/// The first partials `(r_u, r_v)` of the net `points` at the weights' sample: the second and
/// third of [`net_derivatives`]'s six sums, the same products added in the same order (so the
/// same bits, for any points), a third of the work. For tests that need only the tangent plane
/// (the fold test, [`crate::folds`]).
pub fn net_partials(
    points: &[Point3<f64>],
    weights: &SampleWeights,
) -> (Vector3<f64>, Vector3<f64>) {
    let (mut du, mut dv) = (Vector3::zeros(), Vector3::zeros());
    for (i, w) in &weights.nonzero {
        let Some(b) = points.get(*i) else {
            continue;
        };
        du += b.coords * w[1];
        dv += b.coords * w[2];
    }
    (du, dv)
}

/// A triangular Bézier patch of degree `n ≥ 0` in space.
#[derive(Clone, Debug, PartialEq)]
pub struct BezierTriangle {
    degree: usize,
    points: Vec<Point3<f64>>,
}

type Net = Vec<Vector3<f64>>;

/// One de Casteljau step from degree `m` to `m − 1` with weights `a` (may be a direction).
fn step(net: &[Vector3<f64>], m: usize, a: [f64; 3]) -> Net {
    multi_indices(m - 1)
        .into_iter()
        .map(|(i, j, k)| {
            net[index(m, i + 1, j, k)] * a[0]
                + net[index(m, i, j + 1, k)] * a[1]
                + net[index(m, i, j, k + 1)] * a[2]
        })
        .collect()
}

impl BezierTriangle {
    /// A patch of degree `degree` from its control net in the order of the module docs.
    pub fn new(degree: usize, points: Vec<Point3<f64>>) -> Result<Self, BezTriError> {
        let expected = num_points(degree);
        if points.len() != expected {
            return Err(BezTriError::WrongCount {
                degree,
                expected,
                got: points.len(),
            });
        }
        if let Some(index) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(BezTriError::NonFinite { index });
        }
        Ok(BezierTriangle { degree, points })
    }

    /// A patch whose control point `b_{ijk}` is `f(i, j, k)`.
    pub fn from_fn(degree: usize, f: impl Fn(usize, usize, usize) -> Point3<f64>) -> Self {
        BezierTriangle {
            degree,
            points: multi_indices(degree)
                .into_iter()
                .map(|(i, j, k)| f(i, j, k))
                .collect(),
        }
    }

    /// The degree `n`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The control net in order.
    pub fn points(&self) -> &[Point3<f64>] {
        &self.points
    }

    /// Control point `b_{ijk}`, `None` unless `i + j + k = n`.
    pub fn point(&self, i: usize, j: usize, k: usize) -> Option<Point3<f64>> {
        (i + j + k == self.degree).then(|| self.points[index(self.degree, i, j, k)])
    }

    fn net(&self) -> Net {
        self.points.iter().map(|p| p.coords).collect()
    }

    /// The blossom `b[a_1, …, a_n]` of barycentric arguments (weights need not sum to 1; with
    /// directions summing to 0 it gives derivative vectors up to `n!/(n − r)!`).
    pub fn blossom(&self, args: &[[f64; 3]]) -> Vector3<f64> {
        let mut net = self.net();
        let mut m = self.degree;
        for a in args.iter().take(self.degree) {
            net = step(&net, m, *a);
            m -= 1;
        }
        net.first().copied().unwrap_or_else(Vector3::zeros)
    }

    /// Position at barycentric `(u, v, w)` by de Casteljau's algorithm.
    pub fn eval(&self, u: f64, v: f64, w: f64) -> Point3<f64> {
        Point3::from(self.blossom(&vec![[u, v, w]; self.degree]))
    }

    /// Derivative at barycentric point `at` along the barycentric directions `dirs` (each
    /// summing to 0): `n!/(n − r)! · b[dirs, at, …, at]`; zero when `r > n`.
    pub fn directional(&self, at: [f64; 3], dirs: &[[f64; 3]]) -> Vector3<f64> {
        let (n, r) = (self.degree, dirs.len());
        if r > n {
            return Vector3::zeros();
        }
        let factor: f64 = ((n - r + 1)..=n).map(|x| x as f64).product();
        let mut args = dirs.to_vec();
        args.resize(n, at);
        self.blossom(&args) * factor
    }

    /// Position and partials up to second order with respect to `(u, v)`, `w = 1 − u − v`.
    pub fn derivatives(&self, u: f64, v: f64) -> Derivatives {
        let at = [u, v, 1.0 - u - v];
        let (eu, ev) = ([1.0, 0.0, -1.0], [0.0, 1.0, -1.0]);
        Derivatives {
            p: self.eval(at[0], at[1], at[2]),
            du: self.directional(at, &[eu]),
            dv: self.directional(at, &[ev]),
            duu: self.directional(at, &[eu, eu]),
            duv: self.directional(at, &[eu, ev]),
            dvv: self.directional(at, &[ev, ev]),
        }
    }

    /// [`BezierTriangle::derivatives`] at the point of precomputed `weights` (same degree), by
    /// six weighted sums; `None` when the degrees differ.
    pub fn derivatives_with(&self, weights: &SampleWeights) -> Option<Derivatives> {
        (weights.degree == self.degree).then(|| net_derivatives(&self.points, weights))
    }

    /// Unit normal `(r_u × r_v)/|r_u × r_v|` at `(u, v)`; `None` at a singular point
    /// ([`SINGULAR_SINE`]).
    pub fn normal(&self, u: f64, v: f64) -> Option<Vector3<f64>> {
        let d = self.derivatives(u, v);
        regular_normal(&d.du, &d.dv)
    }

    /// Normal, Gaussian and mean curvature, principal curvatures and shape tensor at `(u, v)`;
    /// `None` at a singular point.
    pub fn curvature(&self, u: f64, v: f64) -> Option<Curvature> {
        curvature_of(&self.derivatives(u, v))
    }

    /// The same surface as a patch of degree `n + 1`:
    /// `b'_{ijk} = (i b_{i−1,j,k} + j b_{i,j−1,k} + k b_{i,j,k−1})/(n + 1)`.
    pub fn elevate(&self) -> BezierTriangle {
        let n = self.degree;
        let net = self.net();
        let get = |i: usize, j: usize, k: usize| net[index(n, i, j, k)];
        BezierTriangle::from_fn(n + 1, |i, j, k| {
            let mut s = Vector3::zeros();
            if i > 0 {
                s += get(i - 1, j, k) * i as f64;
            }
            if j > 0 {
                s += get(i, j - 1, k) * j as f64;
            }
            if k > 0 {
                s += get(i, j, k - 1) * k as f64;
            }
            Point3::from(s / (n + 1) as f64)
        })
    }

    /// Splits the patch at the barycentric point `p = (u, v, w)` into the three patches over
    /// the domain triangles `(p, v-corner, w-corner)`, `(u-corner, p, w-corner)` and
    /// `(u-corner, v-corner, p)`, in that order; each keeps the parent's orientation when `p` is
    /// inside the domain. From the de Casteljau pyramid `b^r_{ijk}(p)`: the first has control
    /// points `b^i_{0jk}`, the second `b^j_{i0k}`, the third `b^k_{ij0}` (Farin ch. 17).
    pub fn subdivide(&self, u: f64, v: f64, w: f64) -> [BezierTriangle; 3] {
        let n = self.degree;
        let mut levels = vec![self.net()];
        for r in 1..=n {
            let next = step(&levels[r - 1], n - r + 1, [u, v, w]);
            levels.push(next);
        }
        let pick =
            |r: usize, i: usize, j: usize, k: usize| Point3::from(levels[r][index(n - r, i, j, k)]);
        [
            BezierTriangle::from_fn(n, |i, j, k| pick(i, 0, j, k)),
            BezierTriangle::from_fn(n, |i, j, k| pick(j, i, 0, k)),
            BezierTriangle::from_fn(n, |i, j, k| pick(k, i, j, 0)),
        ]
    }

    /// Boundary curve `edge` (0: `w = 0` from `u` to `v`; 1: `u = 0` from `v` to `w`; 2:
    /// `v = 0` from `w` to `u`) as a Bézier curve of degree `n`; `None` for `edge > 2`.
    pub fn boundary_curve(&self, edge: usize) -> Option<BezierCurve> {
        let n = self.degree;
        let idx = |m: usize| match edge {
            0 => Some(index(n, n - m, m, 0)),
            1 => Some(index(n, 0, n - m, m)),
            2 => Some(index(n, m, 0, n - m)),
            _ => None,
        };
        (0..=n)
            .map(|m| idx(m).map(|i| self.points[i]))
            .collect::<Option<Vec<_>>>()
            .map(|points| BezierCurve { points })
    }
}

fn regular_normal(du: &Vector3<f64>, dv: &Vector3<f64>) -> Option<Vector3<f64>> {
    let c = du.cross(dv);
    let scale = du.norm() * dv.norm();
    (c.norm() > SINGULAR_SINE * scale && scale > 0.0).then(|| c.normalize())
}

/// Curvature from position derivatives (module docs); `None` where `r_u × r_v` vanishes.
pub fn curvature_of(d: &Derivatives) -> Option<Curvature> {
    let n = regular_normal(&d.du, &d.dv)?;
    let first = Matrix2::new(
        d.du.dot(&d.du),
        d.du.dot(&d.dv),
        d.du.dot(&d.dv),
        d.dv.dot(&d.dv),
    );
    let second = Matrix2::new(d.duu.dot(&n), d.duv.dot(&n), d.duv.dot(&n), d.dvv.dot(&n));
    let inv = first.try_inverse()?;
    let det = first.determinant();
    let gaussian = second.determinant() / det;
    let (e, f, g) = (first[(0, 0)], first[(0, 1)], first[(1, 1)]);
    let (l, m, nn) = (second[(0, 0)], second[(0, 1)], second[(1, 1)]);
    let mean = (e * nn - 2.0 * f * m + g * l) / (2.0 * det);
    let disc = (mean * mean - gaussian).max(0.0).sqrt();
    let j = Matrix3x2::from_columns(&[d.du, d.dv]);
    let s = j * inv * second * inv * j.transpose();
    Some(Curvature {
        normal: n,
        gaussian,
        mean,
        principal: [mean - disc, mean + disc],
        shape: (s + s.transpose()) * 0.5,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point2;
    use proptest::prelude::*;

    /// Closed forms evaluated through a few de Casteljau steps: rounding only.
    const EXACT: f64 = 1e-12;
    /// Central differences with step `FD_STEP` have error O(h²) ≈ 1e-8 on these unit-size
    /// polynomials, plus rounding ε/h ≈ 1e-11.
    const FD_STEP: f64 = 1e-4;
    /// Tolerance for derivatives checked by central differences.
    const FD_TOL: f64 = 1e-6;

    /// The sample weights are the general evaluation's numbers bit for bit: each weight against
    /// [`BezierTriangle::derivatives`] of the basis net, for degrees 0 to 6 at corners, edge
    /// points, inner points and points outside the domain.
    #[test]
    fn sample_weights_are_the_basis_nets_derivatives_bit_for_bit() {
        let points = [
            (0.0, 0.0),
            (1.0, 0.0),
            (0.0, 1.0),
            (0.5, 0.0),
            (0.25, 0.75),
            (1.0 / 3.0, 1.0 / 3.0),
            (0.1, 0.7),
            (0.123_456_789, 0.456_789_123),
            (-0.2, 1.3),
            (2.0, -0.5),
        ];
        for degree in 0..=6 {
            let m = num_points(degree);
            for &(u, v) in &points {
                let sw = SampleWeights::new(degree, u, v);
                for c in 0..m {
                    let mut pts = vec![Point3::origin(); m];
                    pts[c] = Point3::new(1.0, 0.0, 0.0);
                    let d = BezierTriangle {
                        degree,
                        points: pts,
                    }
                    .derivatives(u, v);
                    let want = [d.p.x, d.du.x, d.dv.x, d.duu.x, d.duv.x, d.dvv.x];
                    for (k, (got, want)) in sw.weights()[c].iter().zip(want).enumerate() {
                        assert_eq!(
                            got.to_bits(),
                            want.to_bits(),
                            "degree {degree} at ({u}, {v}), point {c}, partial {k}: {got} vs {want}"
                        );
                    }
                }
            }
        }
    }

    /// The quadratic patch of the paraboloid `z = x² + y²` over the domain triangle `abc` in the
    /// plane: control points are the blossom `F(p, q) = (mid x, mid y, p·q)` at the corners.
    fn paraboloid(a: Point2<f64>, b: Point2<f64>, c: Point2<f64>) -> BezierTriangle {
        let corner = |i: usize, j: usize, k: usize| {
            let mut v = Vec::new();
            v.extend(std::iter::repeat_n(a, i));
            v.extend(std::iter::repeat_n(b, j));
            v.extend(std::iter::repeat_n(c, k));
            let (p, q) = (v[0], v[1]);
            Point3::new(
                0.5 * (p.x + q.x),
                0.5 * (p.y + q.y),
                p.coords.dot(&q.coords),
            )
        };
        BezierTriangle::from_fn(2, corner)
    }

    fn tri() -> [Point2<f64>; 3] {
        [
            Point2::new(1.0, 0.0),
            Point2::new(-0.5, 0.8),
            Point2::new(-0.5, -0.8),
        ]
    }

    fn cubic() -> BezierTriangle {
        // An arbitrary non-degenerate cubic.
        BezierTriangle::from_fn(3, |i, j, k| {
            let (x, y) = (i as f64 + 0.5 * j as f64, 0.9 * j as f64 + 0.1 * k as f64);
            Point3::new(
                x,
                y,
                (i * j) as f64 * 0.3 - (k * k) as f64 * 0.2 + 0.1 * j as f64,
            )
        })
    }

    #[test]
    fn index_follows_the_row_order() {
        let order = multi_indices(2);
        assert_eq!(
            order,
            vec![
                (2, 0, 0),
                (1, 1, 0),
                (0, 2, 0),
                (1, 0, 1),
                (0, 1, 1),
                (0, 0, 2)
            ]
        );
        for n in 0..7 {
            for (pos, (i, j, k)) in multi_indices(n).into_iter().enumerate() {
                assert_eq!(index(n, i, j, k), pos);
            }
            assert_eq!(multi_indices(n).len(), num_points(n));
        }
        // Row 0 is the edge from the u corner to the v corner.
        let p = cubic();
        let e0 = p.boundary_curve(0).unwrap();
        assert_eq!(e0.points, p.points()[0..4].to_vec());
        assert_eq!(e0.points[0], p.eval(1.0, 0.0, 0.0));
        assert_eq!(e0.points[3], p.eval(0.0, 1.0, 0.0));
    }

    #[test]
    fn rejects_wrong_nets() {
        assert_eq!(
            BezierTriangle::new(2, vec![Point3::origin(); 5]),
            Err(BezTriError::WrongCount {
                degree: 2,
                expected: 6,
                got: 5
            })
        );
        let mut pts = vec![Point3::origin(); 3];
        pts[2].y = f64::NAN;
        assert_eq!(
            BezierTriangle::new(1, pts),
            Err(BezTriError::NonFinite { index: 2 })
        );
    }

    #[test]
    fn paraboloid_has_known_curvature() {
        let [a, b, c] = tri();
        let patch = paraboloid(a, b, c);
        // The apex (0, 0) is the centroid of abc.
        let third = 1.0 / 3.0;
        let p = patch.eval(third, third, third);
        assert!(p.coords.norm() < EXACT);
        let k = patch.curvature(third, third).unwrap();
        assert!((k.normal - Vector3::z()).norm() < EXACT);
        assert!((k.gaussian - 4.0).abs() < 1e-10);
        assert!((k.mean - 2.0).abs() < 1e-10);
        assert!((k.principal[0] - 2.0).abs() < 1e-6 && (k.principal[1] - 2.0).abs() < 1e-6);
        assert!((k.shape * k.normal).norm() < 1e-10);
        // Away from the apex: K = 4/(1 + 4ρ²)², H = (2 + 4ρ²)/(1 + 4ρ²)^{3/2}.
        for (u, v) in [(0.6, 0.1), (0.2, 0.5), (0.1, 0.15)] {
            let w = 1.0 - u - v;
            let x = a * u + b.coords * v + c.coords * w;
            let q = patch.eval(u, v, w);
            assert!((q.z - x.coords.norm_squared()).abs() < EXACT);
            let r2 = x.coords.norm_squared();
            let k = patch.curvature(u, v).unwrap();
            assert!((k.gaussian - 4.0 / (1.0 + 4.0 * r2).powi(2)).abs() < 1e-10);
            assert!((k.mean - (2.0 + 4.0 * r2) / (1.0 + 4.0 * r2).powf(1.5)).abs() < 1e-10);
            // The shape tensor gives K and H back as its invariants on the tangent plane.
            let kn = |d: Vector3<f64>| d.dot(&(k.shape * d));
            let t1 = k.normal.cross(&Vector3::x()).normalize();
            let t2 = k.normal.cross(&t1);
            assert!((0.5 * (kn(t1) + kn(t2)) - k.mean).abs() < 1e-10);
        }
    }

    #[test]
    fn planar_patches_are_flat_and_linear_precision_holds() {
        let (a, b, c) = (
            Point3::new(0.0, 0.0, 1.0),
            Point3::new(2.0, 0.5, 1.0),
            Point3::new(0.3, 1.7, 1.0),
        );
        for n in 1..6 {
            let lin = BezierTriangle::from_fn(n, |i, j, k| {
                Point3::from(
                    (a.coords * i as f64 + b.coords * j as f64 + c.coords * k as f64) / n as f64,
                )
            });
            for (u, v) in [(0.2, 0.3), (0.7, 0.1), (0.0, 0.0)] {
                let w = 1.0 - u - v;
                let expect = a.coords * u + b.coords * v + c.coords * w;
                assert!((lin.eval(u, v, w).coords - expect).norm() < EXACT);
                let k = lin.curvature(u, v).unwrap();
                assert!(k.gaussian.abs() < EXACT && k.mean.abs() < EXACT);
                assert!((k.normal - Vector3::z()).norm() < EXACT);
            }
        }
        // A planar but non-linearly parametrized patch is flat too.
        let warped = BezierTriangle::from_fn(3, |i, j, k| {
            Point3::new(
                (i * i) as f64 * 0.2 + j as f64,
                (j * k) as f64 * 0.3 + k as f64,
                0.0,
            )
        });
        let k = warped.curvature(0.3, 0.3).unwrap();
        assert!(k.gaussian.abs() < EXACT && k.mean.abs() < EXACT);
    }

    #[test]
    fn precomputed_weights_give_the_blossom_derivatives() {
        /// Weighted sums against de Casteljau steps: rounding of a few dozen operations.
        const SAME: f64 = 1e-12;
        let p = cubic();
        for (u, v) in [
            (0.0, 0.0),
            (1.0, 0.0),
            (0.2, 0.3),
            (0.25, 0.75),
            (1.0 / 3.0, 1.0 / 3.0),
        ] {
            let w = SampleWeights::new(3, u, v);
            let a = p.derivatives_with(&w).expect("same degree");
            let b = p.derivatives(u, v);
            assert!((a.p - b.p).norm() < SAME);
            for (x, y) in [
                (a.du, b.du),
                (a.dv, b.dv),
                (a.duu, b.duu),
                (a.duv, b.duv),
                (a.dvv, b.dvv),
            ] {
                assert!((x - y).norm() < SAME * y.norm().max(1.0), "{x} vs {y}");
            }
        }
        assert!(p
            .derivatives_with(&SampleWeights::new(4, 0.1, 0.1))
            .is_none());
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let p = cubic();
        for (u, v) in [(0.3, 0.3), (0.1, 0.7), (0.6, 0.2)] {
            let d = p.derivatives(u, v);
            let at = |u: f64, v: f64| p.eval(u, v, 1.0 - u - v).coords;
            let h = FD_STEP;
            let fu = (at(u + h, v) - at(u - h, v)) / (2.0 * h);
            let fv = (at(u, v + h) - at(u, v - h)) / (2.0 * h);
            assert!((fu - d.du).norm() < FD_TOL, "{fu} vs {}", d.du);
            assert!((fv - d.dv).norm() < FD_TOL);
            let du = |u: f64, v: f64| p.derivatives(u, v).du;
            let dv = |u: f64, v: f64| p.derivatives(u, v).dv;
            assert!(((du(u + h, v) - du(u - h, v)) / (2.0 * h) - d.duu).norm() < FD_TOL);
            assert!(((du(u, v + h) - du(u, v - h)) / (2.0 * h) - d.duv).norm() < FD_TOL);
            assert!(((dv(u, v + h) - dv(u, v - h)) / (2.0 * h) - d.dvv).norm() < FD_TOL);
        }
        // Third derivatives of a quadratic vanish.
        let [a, b, c] = tri();
        let q = paraboloid(a, b, c);
        let e = [1.0, 0.0, -1.0];
        assert_eq!(q.directional([0.2, 0.3, 0.5], &[e, e, e]), Vector3::zeros());
    }

    #[test]
    fn boundary_curves_trace_the_edges() {
        let p = cubic();
        for t in [0.0, 0.25, 0.8, 1.0] {
            let s = 1.0 - t;
            let cases = [(0, (s, t, 0.0)), (1, (0.0, s, t)), (2, (t, 0.0, s))];
            for (edge, (u, v, w)) in cases {
                let c = p.boundary_curve(edge).unwrap();
                assert_eq!(c.degree(), 3);
                assert!((c.eval(t) - p.eval(u, v, w)).norm() < EXACT);
            }
        }
        assert!(p.boundary_curve(3).is_none());
    }

    fn bary() -> impl Strategy<Value = (f64, f64, f64)> {
        (0.0..1.0f64, 0.0..1.0f64).prop_map(|(a, b)| {
            let (a, b) = if a + b > 1.0 {
                (1.0 - a, 1.0 - b)
            } else {
                (a, b)
            };
            (a, b, 1.0 - a - b)
        })
    }

    proptest! {
        #[test]
        fn net_partials_are_the_full_evaluations_partials_bit_for_bit(
            (u, v, _) in bary(),
            degree in 1usize..=5,
            coords in proptest::collection::vec(-1e3f64..1e3, 63),
            bad in proptest::option::of((0usize..21, prop_oneof![Just(f64::NAN), Just(f64::INFINITY)])),
        ) {
            let mut points: Vec<Point3<f64>> = coords
                .chunks(3)
                .take(num_points(degree))
                .map(|c| Point3::new(c[0], c[1], c[2]))
                .collect();
            // A non-finite point, where it falls inside the net: the same NaNs either way.
            if let Some((i, x)) = bad {
                if let Some(p) = points.get_mut(i) {
                    p.y = x;
                }
            }
            // Samples on the edges too, where rows of zero weights are skipped.
            for (a, b) in [(u, v), (0.0, v), (u, 0.0), (1.0, 0.0), (0.0, 0.0)] {
                let w = SampleWeights::new(degree, a, b);
                let d = net_derivatives(&points, &w);
                let (du, dv) = net_partials(&points, &w);
                for (x, y) in du.iter().chain(dv.iter()).zip(d.du.iter().chain(d.dv.iter())) {
                    prop_assert_eq!(x.to_bits(), y.to_bits());
                }
            }
        }

        #[test]
        fn elevation_preserves_the_surface((u, v, w) in bary()) {
            let p = cubic();
            let e = p.elevate();
            prop_assert_eq!(e.degree(), 4);
            prop_assert!((p.eval(u, v, w) - e.eval(u, v, w)).norm() < EXACT);
            let e2 = e.elevate();
            prop_assert!((p.eval(u, v, w) - e2.eval(u, v, w)).norm() < EXACT);
        }

        #[test]
        fn subdivision_pieces_reproduce_the_parent(
            (pu, pv, pw) in bary(), (a, b, c) in bary()
        ) {
            let p = cubic();
            let parts = p.subdivide(pu, pv, pw);
            // Piece 0 is over (P, e_v, e_w): its (a, b, c) is a·P + b·e_v + c·e_w.
            let at = [
                (a * pu, a * pv + b, a * pw + c),
                (a + b * pu, b * pv, b * pw + c),
                (a + c * pu, b + c * pv, c * pw),
            ];
            for (part, (u, v, w)) in parts.iter().zip(at) {
                prop_assert!((part.eval(a, b, c) - p.eval(u, v, w)).norm() < 1e-11);
            }
        }
    }

    #[test]
    fn subdivision_keeps_orientation() {
        let [a, b, c] = tri();
        let q = paraboloid(a, b, c);
        for part in q.subdivide(0.2, 0.5, 0.3) {
            let n = part.normal(1.0 / 3.0, 1.0 / 3.0).unwrap();
            assert!(n.z > 0.0);
        }
    }
}
