//! The native reference of issue 28: 10⁶ independent two-parameter Levenberg–Marquardt solves
//! written by hand in plain Rust (no solver crate, no workspace code), timed.
//!
//! ```sh
//! cargo build --release -p solver --example lm_reference
//! target/release/examples/lm_reference --count 1000000
//! ```
//!
//! `scripts/end_to_end.sh` times it against `experiments fit`; its tests (the `tests` module
//! below) run in `solver`'s test suite (`tests/suite/lm_reference.rs`).
//!
//! Each problem fits the model `y = a·exp(b·x)` to [`POINTS`] samples `(x_i, y_i)` in the least
//! squares sense, a two-parameter problem of the size and cost of a boundary curve's
//! tangent-length fit (a few residuals, each an exponential and a few products). Problem `k`'s
//! data come from a deterministic generator ([`SplitMix64`]): a true `(a, b)` drawn in
//! `[0.5, 2] × [-1, 1]` and each sample perturbed by at most [`NOISE`], so every problem differs
//! and the compiler cannot hoist the work out of the loop. The program prints its wall time and a
//! checksum (the sum of all solutions' `a + b`) on standard output, one `key value` a line:
//!
//! ```text
//! count 1000000
//! seconds 0.4498
//! per_solve_us 0.4498
//! mean_iterations 7.194
//! checksum 1249257.8534886707
//! ```
//!
//! (a release build on the 2-core development machine at load 3–4; the checksum is the same on
//! every run and machine that rounds as IEEE 754 does, `exp` aside).
//!
//! # The method (Madsen, Nielsen & Tingleff 2004, *Methods for non-linear least squares
//! problems*, Algorithm 3.16, with Nielsen's damping update)
//!
//! With residuals `r_i(p) = a·exp(b·x_i) − y_i`, `p = (a, b)`, the objective is
//! `F(p) = ½ Σ r_i²`. The Jacobian's row `i` is `J_i = (e_i, a·x_i·e_i)`, `e_i = exp(b·x_i)`,
//! the gradient is `g = Jᵀr` and the Gauss–Newton matrix `A = JᵀJ` (symmetric 2 × 2).
//! Near `p` the model `L(h) = F(p) + hᵀg + ½ hᵀAh` approximates `F(p + h)`, and the damped
//! step solves `(A + μI) h = −g`.
//!
//! **The 2 × 2 solve.** With `M = A + μI = [[m11, m12], [m12, m22]]`, `det = m11·m22 − m12²`
//! and `M⁻¹ = [[m22, −m12], [−m12, m11]] / det`, so `h = −M⁻¹g`:
//! `h_a = −(m22·g_a − m12·g_b)/det`, `h_b = −(m11·g_b − m12·g_a)/det`. `A` is positive
//! semidefinite and `μ > 0`, so `M` is positive definite and `det > 0`.
//!
//! **The gain ratio.** `ρ = (F(p) − F(p + h)) / (L(0) − L(h))` compares the actual decrease with
//! the model's. `L(0) − L(h) = −hᵀg − ½ hᵀAh`, and from `Ah = −g − μh`,
//! `−½ hᵀAh = ½ hᵀg + ½ μ hᵀh`, so `L(0) − L(h) = ½ hᵀ(μh − g)`, positive for `h ≠ 0`.
//!
//! **Nielsen's update.** Start with `μ = τ·max(A_jj)` and `ν = 2`. If `ρ > 0` the step is
//! accepted and `μ ← μ·max(⅓, 1 − (2ρ − 1)³)`, `ν ← 2` (a good model, `ρ` near 1, shrinks `μ`
//! by up to 3, towards Gauss–Newton); otherwise the step is rejected, `μ ← μ·ν` and `ν ← 2ν`
//! (the damping grows geometrically, towards short gradient steps).
//!
//! **Stopping.** At `‖g‖∞ ≤ ε₁` (a stationary point), at `‖h‖ ≤ ε₂(‖p‖ + ε₂)` (the step has
//! become negligible relative to `p`), or after `k_max` iterations ([`Tolerances`]).

use std::process::ExitCode;
use std::time::Instant;

/// Samples a problem: enough to overdetermine two parameters, few enough to stay in the
/// size of a curve's tangent-length fit.
pub const POINTS: usize = 4;

/// The largest perturbation of a sample from the true model.
pub const NOISE: f64 = 0.01;

/// The number of problems solved without `--count`.
pub const DEFAULT_COUNT: usize = 1_000_000;

/// The stopping rule of Algorithm 3.16.
#[derive(Clone, Copy, Debug)]
pub struct Tolerances {
    /// `ε₁`: stop when the gradient's largest component is at most this.
    pub gradient: f64,
    /// `ε₂`: stop when `‖h‖ ≤ ε₂(‖p‖ + ε₂)`.
    pub step: f64,
    /// `k_max`: the iteration cap.
    pub max_iterations: u32,
    /// `τ`: the initial damping relative to the largest diagonal entry of `A`.
    pub tau: f64,
}

impl Default for Tolerances {
    /// The book's suggested values: `τ = 10⁻³` for a start believed reasonable, and tight
    /// tolerances near the square root of machine precision for the step.
    fn default() -> Self {
        Self {
            gradient: 1e-12,
            step: 1e-10,
            max_iterations: 100,
            tau: 1e-3,
        }
    }
}

/// One problem's samples.
#[derive(Clone, Copy, Debug)]
pub struct Problem {
    /// The abscissae `x_i`.
    pub x: [f64; POINTS],
    /// The ordinates `y_i`.
    pub y: [f64; POINTS],
}

/// A solve's result.
#[derive(Clone, Copy, Debug)]
pub struct Solution {
    /// The fitted `(a, b)`.
    pub p: [f64; 2],
    /// Iterations taken (accepted and rejected steps).
    pub iterations: u32,
    /// `F(p)` at the solution.
    pub cost: f64,
}

/// `F(p) = ½ Σ r_i²`.
fn cost(problem: &Problem, p: [f64; 2]) -> f64 {
    let mut f = 0.0;
    for (&x, &y) in problem.x.iter().zip(&problem.y) {
        let r = p[0] * (p[1] * x).exp() - y;
        f += r * r;
    }
    0.5 * f
}

/// `F(p)`, the gradient `g = Jᵀr` and `A = JᵀJ` as `(a11, a12, a22)`.
fn linearize(problem: &Problem, p: [f64; 2]) -> (f64, [f64; 2], [f64; 3]) {
    let (mut f, mut g, mut a) = (0.0, [0.0; 2], [0.0; 3]);
    for (&x, &y) in problem.x.iter().zip(&problem.y) {
        let e = (p[1] * x).exp();
        let r = p[0] * e - y;
        let (ja, jb) = (e, p[0] * x * e);
        f += r * r;
        g[0] += ja * r;
        g[1] += jb * r;
        a[0] += ja * ja;
        a[1] += ja * jb;
        a[2] += jb * jb;
    }
    (0.5 * f, g, a)
}

/// Minimizes `F` from `start` by Algorithm 3.16 (the module's documentation derives each step).
pub fn solve(problem: &Problem, start: [f64; 2], tol: &Tolerances) -> Solution {
    let mut p = start;
    let (mut f, mut g, mut a) = linearize(problem, p);
    let mut mu = tol.tau * a[0].max(a[2]);
    let mut nu = 2.0_f64;
    let mut k = 0;
    let mut found = g[0].abs().max(g[1].abs()) <= tol.gradient;
    while !found && k < tol.max_iterations {
        k += 1;
        let (m11, m12, m22) = (a[0] + mu, a[1], a[2] + mu);
        let det = m11 * m22 - m12 * m12;
        if det.is_nan() || det <= 0.0 {
            // Only reachable when μ has underflowed or the data are not finite.
            break;
        }
        let h = [
            -(m22 * g[0] - m12 * g[1]) / det,
            -(m11 * g[1] - m12 * g[0]) / det,
        ];
        let h_norm = h[0].hypot(h[1]);
        if h_norm <= tol.step * (p[0].hypot(p[1]) + tol.step) {
            break;
        }
        let trial = [p[0] + h[0], p[1] + h[1]];
        let predicted = 0.5 * (h[0] * (mu * h[0] - g[0]) + h[1] * (mu * h[1] - g[1]));
        let rho = (f - cost(problem, trial)) / predicted;
        if rho > 0.0 {
            p = trial;
            (f, g, a) = linearize(problem, p);
            found = g[0].abs().max(g[1].abs()) <= tol.gradient;
            let s = 2.0 * rho - 1.0;
            mu *= (1.0_f64 / 3.0).max(1.0 - s * s * s);
            nu = 2.0;
        } else {
            mu *= nu;
            nu *= 2.0;
        }
    }
    Solution {
        p,
        iterations: k,
        cost: f,
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014): a 64-bit state advanced by a Weyl constant and mixed,
/// enough for varied, reproducible test data.
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`: the top 53 bits as a fraction.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * unit
    }
}

/// Problem data: a true `(a, b)` in `[0.5, 2] × [-1, 1]`, `x_i` evenly spaced on `[0, 1]` and
/// `y_i = a·exp(b·x_i) + δ_i`, `|δ_i| ≤` [`NOISE`].
pub fn generate(rng: &mut SplitMix64) -> Problem {
    let a = rng.uniform(0.5, 2.0);
    let b = rng.uniform(-1.0, 1.0);
    sampled(a, b, || rng.uniform(-NOISE, NOISE))
}

/// `y_i = a·exp(b·x_i) + noise()` at `x_i` evenly spaced on `[0, 1]`, `noise` called once a
/// sample in order.
pub fn sampled(a: f64, b: f64, mut noise: impl FnMut() -> f64) -> Problem {
    let mut problem = Problem {
        x: [0.0; POINTS],
        y: [0.0; POINTS],
    };
    for i in 0..POINTS {
        let x = i as f64 / (POINTS - 1) as f64;
        problem.x[i] = x;
        problem.y[i] = a * (b * x).exp() + noise();
    }
    problem
}

/// The start of every solve: `a = 1`, `b = 0` (a constant model), away from every true answer.
pub const START: [f64; 2] = [1.0, 0.0];

/// The seed of the problem generator.
const SEED: u64 = 28;

/// `--count N` from the arguments, or an error message.
fn parse_count(args: &[String]) -> Result<usize, String> {
    match args {
        [] => Ok(DEFAULT_COUNT),
        [flag, n] if flag == "--count" => n
            .parse()
            .map_err(|e| format!("--count {n}: {e}"))
            .and_then(|n: usize| {
                if n > 0 {
                    Ok(n)
                } else {
                    Err("--count must be positive".into())
                }
            }),
        _ => Err("usage: lm_reference [--count N]".into()),
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let count = match parse_count(&args) {
        Ok(n) => n,
        Err(message) => {
            eprintln!("lm_reference: {message}");
            return ExitCode::FAILURE;
        }
    };
    let tol = Tolerances::default();
    let mut rng = SplitMix64::new(SEED);
    let (mut checksum, mut iterations) = (0.0, 0u64);
    let start = Instant::now();
    for _ in 0..count {
        let problem = generate(&mut rng);
        let s = solve(&problem, START, &tol);
        checksum += s.p[0] + s.p[1];
        iterations += u64::from(s.iterations);
    }
    let seconds = start.elapsed().as_secs_f64();
    println!("count {count}");
    println!("seconds {seconds:.4}");
    println!("per_solve_us {:.4}", seconds / count as f64 * 1e6);
    println!("mean_iterations {:.3}", iterations as f64 / count as f64);
    println!("checksum {checksum:.10}");
    if checksum.is_finite() {
        ExitCode::SUCCESS
    } else {
        eprintln!("lm_reference: a solve did not stay finite");
        ExitCode::FAILURE
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Noise-free data are fitted exactly; the stopping tolerances leave the answer within a few
    /// thousand ulps of the truth (the step rule stops at a relative step of 1e-10, and the
    /// converging steps are quadratic, so the error left is far smaller than that).
    const EXACT_TOL: f64 = 1e-9;

    /// The noisy problems' answers are within this of the truth: four samples of noise at most
    /// 0.01 move `(a, b)` by a few hundredths at worst over `x ∈ [0, 1]`.
    const NOISY_TOL: f64 = 0.1;

    #[test]
    fn recovers_a_noise_free_exponential() {
        let (a, b) = (1.7, -0.6);
        let problem = sampled(a, b, || 0.0);
        let s = solve(&problem, START, &Tolerances::default());
        assert!((s.p[0] - a).abs() < EXACT_TOL, "a = {}", s.p[0]);
        assert!((s.p[1] - b).abs() < EXACT_TOL, "b = {}", s.p[1]);
        assert!(s.cost < EXACT_TOL * EXACT_TOL, "F = {}", s.cost);
        assert!(s.iterations < Tolerances::default().max_iterations);
    }

    #[test]
    fn generated_problems_converge_near_their_truth() {
        let tol = Tolerances::default();
        let mut rng = SplitMix64::new(SEED);
        for _ in 0..1000 {
            // The generator draws a and b first: replay them to know the truth.
            let mut replay = rng.clone();
            let a = replay.uniform(0.5, 2.0);
            let b = replay.uniform(-1.0, 1.0);
            let problem = generate(&mut rng);
            let s = solve(&problem, START, &tol);
            assert!(s.iterations < tol.max_iterations, "{problem:?}");
            assert!((s.p[0] - a).abs() < NOISY_TOL, "a {} vs {a}", s.p[0]);
            assert!((s.p[1] - b).abs() < NOISY_TOL, "b {} vs {b}", s.p[1]);
        }
    }

    #[test]
    fn parses_its_arguments() {
        assert_eq!(parse_count(&[]), Ok(DEFAULT_COUNT));
        let args = ["--count".to_string(), "10".to_string()];
        assert_eq!(parse_count(&args), Ok(10));
        assert!(parse_count(&["--count".to_string(), "0".to_string()]).is_err());
        assert!(parse_count(&["--bogus".to_string()]).is_err());
    }
}
