//! The fixed-size fast path of the L-BFGS adapter: one run of argmin 0.11's `Executor` with
//! `LBFGS` (memory 7) and `MoreThuenteLineSearch` (its defaults), transcribed for `SVector`
//! parameters.
//!
//! The arithmetic is argmin's, operation for operation: the same nalgebra products and dot
//! products (argmin-math's nalgebra backend calls exactly these), the two-loop recursion in the
//! same order, Moré–Thuente's `cstep` copied verbatim, the executor's bookkeeping (best point by
//! strict decrease, `prev_cost`, termination tests in argmin's order). So a run returns the same
//! iterates, counts and termination as the argmin run (`tests/suite/fast_paths.rs` holds them equal).
//!
//! What is gone: the executor and the line search's own executor per iteration (state
//! construction, `HashMap` function counters keyed by `String`, observers, the timer, clones of
//! the solver and of the line search), the `Vec`s of the two-loop recursion and the `VecDeque`s
//! of the correction pairs (fixed arrays here), and repeated evaluations:
//!
//! - argmin asks for the cost and then the gradient at every line-search point; here one
//!   [`ObjectiveProblem::value_and_gradient`] call gives both (for least squares the residuals
//!   are computed once);
//! - after each line search argmin's L-BFGS evaluates the gradient again at the accepted point,
//!   where the line search has just evaluated it; here the line search's gradient is reused.
//!   That evaluation is still **counted**, so the report's counts are argmin's, the same as on
//!   the reference path.

use nalgebra::SVector;

use crate::bounds::SquareMap;
use crate::ObjectiveProblem;

/// Number of correction pairs (argmin's `m`).
const MEMORY: usize = super::lbfgs::MEMORY;

/// How a run ended (argmin's `TerminationReason`s that can occur).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Status {
    /// `SolverConverged`: the gradient or the cost test of L-BFGS.
    Converged,
    /// `MaxItersReached`.
    MaxIters,
    /// `SolverExit("Line search terminated with: …")`.
    LineSearch,
}

/// A finished run: what the adapter reads from argmin's final state.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Outcome<const N: usize> {
    pub status: Status,
    pub iterations: u64,
    pub cost_count: usize,
    pub gradient_count: usize,
    pub best_param: Option<SVector<f64, N>>,
    pub best_cost: f64,
    pub prev_cost: f64,
    pub cost: f64,
    pub gradient: Option<SVector<f64, N>>,
}

/// The transformed objective `f(l + y²)` with argmin's error rules: a non-finite cost or
/// gradient is an error.
struct Transformed<'a, P, const N: usize> {
    problem: &'a P,
    map: SquareMap<N>,
}

impl<P: ObjectiveProblem<N>, const N: usize> Transformed<'_, P, N> {
    /// Cost and gradient at `y` (argmin's `cost` then `gradient`); `None` where argmin's call
    /// would fail. `Err(())` when the cost fails (the gradient is then not asked).
    #[inline]
    fn eval(&self, y: &SVector<f64, N>) -> Result<(f64, Option<SVector<f64, N>>), ()> {
        let (f, g) = self.problem.value_and_gradient(&self.map.to_x(y));
        if !f.is_finite() {
            return Err(());
        }
        let g = g.component_mul(&self.map.dx_dy(y));
        Ok((f, g.iter().all(|v| v.is_finite()).then_some(g)))
    }
}

/// One point of the line search: step, value, derivative (argmin's `Step`).
#[derive(Clone, Copy, Debug)]
struct Step {
    x: f64,
    fx: f64,
    gx: f64,
}

impl Step {
    fn new(x: f64, fx: f64, gx: f64) -> Self {
        Step { x, fx, gx }
    }
}

/// Moré–Thuente's defaults in argmin 0.11.
const LS_FTOL: f64 = 1e-4;
const LS_GTOL: f64 = 0.9;
const LS_XTRAPF: f64 = 4.0;
const LS_XTOL: f64 = 1e-10;

/// The result of one line search: the accepted point with its cost and gradient and the number
/// of evaluations, or `None` where argmin's line search returns an error.
struct Accepted<const N: usize> {
    param: SVector<f64, N>,
    cost: f64,
    gradient: SVector<f64, N>,
    evaluations: usize,
}

/// argmin's `MoreThuenteLineSearch` from `param` along `d` (a fresh clone of the default line
/// search, as L-BFGS makes for every iteration).
fn line_search<P: ObjectiveProblem<N>, const N: usize>(
    problem: &Transformed<'_, P, N>,
    param: &SVector<f64, N>,
    grad: &SVector<f64, N>,
    cost: f64,
    d: &SVector<f64, N>,
) -> Option<Accepted<N>> {
    let stpmin = f64::EPSILON.sqrt();
    let stpmax = f64::INFINITY;
    // init
    let finit = cost;
    let dginit = grad.dot(d);
    if dginit >= 0.0 {
        return None;
    }
    let mut stage1 = true;
    let mut brackt = false;
    let dgtest = LS_FTOL * dginit;
    let mut width = stpmax - stpmin;
    let mut width1 = 2.0 * width;
    let mut stp = Step::new(1.0, f64::NAN, f64::NAN);
    let mut stx = Step::new(0.0, finit, dginit);
    let mut sty = Step::new(0.0, finit, dginit);
    let mut infoc = 1usize;
    let mut evaluations = 0usize;
    loop {
        // next_iter
        let mut info = 0;
        let (stmin, stmax) = if brackt {
            (stx.x.min(sty.x), stx.x.max(sty.x))
        } else {
            (stx.x, stp.x + LS_XTRAPF * (stp.x - stx.x))
        };
        stp.x = stp.x.max(stpmin);
        stp.x = stp.x.min(stpmax);
        #[allow(clippy::nonminimal_bool)] // argmin's condition as written
        if (brackt && (stp.x <= stmin || stp.x >= stmax))
            || (brackt && (stmax - stmin) <= LS_XTOL * stmax)
            || infoc == 0
        {
            stp.x = stx.x;
        }
        let new_param = param + d * stp.x;
        evaluations += 1;
        let (f, new_grad) = problem.eval(&new_param).ok()?;
        let new_grad = new_grad?;
        let dg = d.dot(&new_grad);
        let ftest1 = finit + stp.x * dgtest;
        if (brackt && (stp.x <= stmin || stp.x >= stmax)) || infoc == 0 {
            info = 6;
        }
        if (stp.x - stpmax).abs() < f64::EPSILON && f <= ftest1 && dg <= dgtest {
            info = 5;
        }
        if (stp.x - stpmin).abs() < f64::EPSILON && (f > ftest1 || dg >= dgtest) {
            info = 4;
        }
        if brackt && stmax - stmin <= LS_XTOL * stmax {
            info = 2;
        }
        if f <= ftest1 && dg.abs() <= LS_GTOL * (-dginit) {
            info = 1;
        }
        if info != 0 {
            return Some(Accepted {
                param: new_param,
                cost: f,
                gradient: new_grad,
                evaluations,
            });
        }
        if stage1 && f <= ftest1 && dg >= LS_FTOL.min(LS_GTOL) * dginit {
            stage1 = false;
        }
        if stage1 && f <= stp.fx && f > ftest1 {
            let fm = f - stp.x * dgtest;
            let fxm = stx.fx - stx.x * dgtest;
            let fym = sty.fx - sty.x * dgtest;
            let dgm = dg - dgtest;
            let dgxm = stx.gx - dgtest;
            let dgym = sty.gx - dgtest;
            let (stx1, sty1, stp1, brackt1, new_infoc) = cstep(
                Step::new(stx.x, fxm, dgxm),
                Step::new(sty.x, fym, dgym),
                Step::new(stp.x, fm, dgm),
                brackt,
                stmin,
                stmax,
            )?;
            stx.x = stx1.x;
            sty.x = sty1.x;
            stx.fx += stx1.x * dgtest;
            sty.fx += sty1.x * dgtest;
            stx.gx += dgtest;
            sty.gx += dgtest;
            brackt = brackt1;
            stp = stp1;
            infoc = new_infoc;
        } else {
            let (stx1, sty1, stp1, brackt1, new_infoc) =
                cstep(stx, sty, Step::new(stp.x, f, dg), brackt, stmin, stmax)?;
            stx = stx1;
            sty = sty1;
            stp = stp1;
            brackt = brackt1;
            infoc = new_infoc;
        }
        if brackt {
            if (sty.x - stx.x).abs() >= 0.66 * width1 {
                stp.x = stx.x + 0.5 * (sty.x - stx.x);
            }
            width1 = width;
            width = (sty.x - stx.x).abs();
        }
    }
}

/// The largest of three, as argmin picks it (`max_by` with `partial_cmp`: the last of equals).
#[inline]
fn max3(a: f64, b: f64, c: f64) -> f64 {
    let tmp = [a, b, c];
    #[allow(clippy::unwrap_used)] // NaN excluded by the caller, as in argmin
    *tmp.iter().max_by(|x, y| x.partial_cmp(y).unwrap()).unwrap()
}

/// argmin's `cstep` (Moré–Thuente's safeguarded step), verbatim; `None` where argmin returns its
/// NaN/Inf error. Returns `(stx, sty, stp, brackt, info)`.
#[allow(clippy::too_many_lines, clippy::similar_names)]
fn cstep(
    stx: Step,
    sty: Step,
    stp: Step,
    brackt: bool,
    stpmin: f64,
    stpmax: f64,
) -> Option<(Step, Step, Step, bool, usize)> {
    let info: usize;
    let bound: bool;
    let mut stpf: f64;
    let stpc: f64;
    let stpq: f64;
    let mut brackt = brackt;

    if (brackt && (stp.x <= stx.x.min(sty.x) || stp.x >= stx.x.max(sty.x)))
        || stx.gx * (stp.x - stx.x) >= 0.0
        || stpmax < stpmin
    {
        return Some((stx, sty, stp, brackt, 0));
    }

    let sgnd = stp.gx * (stx.gx / stx.gx.abs());
    let bad = |t: &[f64; 3]| t.iter().any(|n| n.is_nan() || n.is_infinite());

    if stp.fx > stx.fx {
        info = 1;
        bound = true;
        let theta = 3.0 * (stx.fx - stp.fx) / (stp.x - stx.x) + stx.gx + stp.gx;
        if bad(&[theta, stx.gx, stp.gx]) {
            return None;
        }
        let s = max3(theta, stx.gx, stp.gx);
        let mut gamma = s * ((theta / s).powi(2) - (stx.gx / s) * (stp.gx / s)).sqrt();
        if stp.x < stx.x {
            gamma = -gamma;
        }
        let p = (gamma - stx.gx) + theta;
        let q = ((gamma - stx.gx) + gamma) + stp.gx;
        let r = p / q;
        stpc = stx.x + r * (stp.x - stx.x);
        stpq = stx.x
            + ((stx.gx / ((stx.fx - stp.fx) / (stp.x - stx.x) + stx.gx)) / 2.0) * (stp.x - stx.x);
        if (stpc - stx.x).abs() < (stpq - stx.x).abs() {
            stpf = stpc;
        } else {
            stpf = stpc + (stpq - stpc) / 2.0;
        }
        brackt = true;
    } else if sgnd < 0.0 {
        info = 2;
        bound = false;
        let theta = 3.0 * (stx.fx - stp.fx) / (stp.x - stx.x) + stx.gx + stp.gx;
        if bad(&[theta, stx.gx, stp.gx]) {
            return None;
        }
        let s = max3(theta, stx.gx, stp.gx);
        let mut gamma = s * ((theta / s).powi(2) - (stx.gx / s) * (stp.gx / s)).sqrt();
        if stp.x > stx.x {
            gamma = -gamma;
        }
        let p = (gamma - stp.gx) + theta;
        let q = ((gamma - stp.gx) + gamma) + stx.gx;
        let r = p / q;
        stpc = stp.x + r * (stx.x - stp.x);
        stpq = stp.x + (stp.gx / (stp.gx - stx.gx)) * (stx.x - stp.x);
        if (stpc - stp.x).abs() > (stpq - stp.x).abs() {
            stpf = stpc;
        } else {
            stpf = stpq;
        }
        brackt = true;
    } else if stp.gx.abs() < stx.gx.abs() {
        info = 3;
        bound = true;
        let theta = 3.0 * (stx.fx - stp.fx) / (stp.x - stx.x) + stx.gx + stp.gx;
        if bad(&[theta, stx.gx, stp.gx]) {
            return None;
        }
        let s = max3(theta, stx.gx, stp.gx);
        let mut gamma = s * 0.0f64
            .max((theta / s).powi(2) - (stx.gx / s) * (stp.gx / s))
            .sqrt();
        if stp.x > stx.x {
            gamma = -gamma;
        }
        let p = (gamma - stp.gx) + theta;
        let q = (gamma + (stx.gx - stp.gx)) + gamma;
        let r = p / q;
        if r < 0.0 && gamma != 0.0 {
            stpc = stp.x + r * (stx.x - stp.x);
        } else if stp.x > stx.x {
            stpc = stpmax;
        } else {
            stpc = stpmin;
        }
        stpq = stp.x + (stp.gx / (stp.gx - stx.gx)) * (stx.x - stp.x);
        if brackt {
            if (stp.x - stpc).abs() < (stp.x - stpq).abs() {
                stpf = stpc;
            } else {
                stpf = stpq;
            }
        } else if (stp.x - stpc).abs() > (stp.x - stpq).abs() {
            stpf = stpc;
        } else {
            stpf = stpq;
        }
    } else {
        info = 4;
        bound = false;
        if brackt {
            let theta = 3.0 * (stp.fx - sty.fx) / (sty.x - stp.x) + sty.gx + stp.gx;
            if bad(&[theta, sty.gx, stp.gx]) {
                return None;
            }
            let s = max3(theta, sty.gx, stp.gx);
            let mut gamma = s * ((theta / s).powi(2) - (sty.gx / s) * (stp.gx / s)).sqrt();
            if stp.x > sty.x {
                gamma = -gamma;
            }
            let p = (gamma - stp.gx) + theta;
            let q = ((gamma - stp.gx) + gamma) + sty.gx;
            let r = p / q;
            stpc = stp.x + r * (sty.x - stp.x);
            stpf = stpc;
        } else if stp.x > stx.x {
            stpf = stpmax;
        } else {
            stpf = stpmin;
        }
    }

    let mut stx_o = stx;
    let mut sty_o = sty;
    let mut stp_o = stp;
    if stp_o.fx > stx_o.fx {
        sty_o = Step::new(stp_o.x, stp_o.fx, stp_o.gx);
    } else {
        if sgnd < 0.0 {
            sty_o = Step::new(stx_o.x, stx_o.fx, stx_o.gx);
        }
        stx_o = Step::new(stp_o.x, stp_o.fx, stp_o.gx);
    }
    stpf = stpmax.min(stpf);
    stpf = stpmin.max(stpf);
    stp_o.x = stpf;
    if brackt && bound {
        if sty_o.x > stx_o.x {
            stp_o.x = stp_o.x.min(stx_o.x + 0.66 * (sty_o.x - stx_o.x));
        } else {
            stp_o.x = stp_o.x.max(stx_o.x + 0.66 * (sty_o.x - stx_o.x));
        }
    }
    Some((stx_o, sty_o, stp_o, brackt, info))
}

/// One argmin run of L-BFGS from `y0`: `Err(())` where argmin's `Executor::run` returns an
/// error (the cost or the gradient fails at the start point). `history`, if given, receives the
/// cost after every iteration (the adapter's observer).
pub(crate) fn run<P: ObjectiveProblem<N>, const N: usize>(
    problem: &P,
    map: SquareMap<N>,
    y0: SVector<f64, N>,
    tol_grad: f64,
    tol_cost: f64,
    max_iters: u64,
    mut history: Option<&mut Vec<f64>>,
) -> Result<Outcome<N>, ()> {
    let problem = Transformed { problem, map };
    // LBFGS::init: cost, then gradient, at the start
    let (c0, g0) = problem.eval(&y0)?;
    let g0 = g0.ok_or(())?;
    let mut cost_count = 1usize;
    let mut gradient_count = 1usize;
    let mut param = Some(y0);
    let mut cost = c0;
    let mut prev_cost = f64::INFINITY;
    let mut gradient = Some(g0);
    // state.update() after init: c0 < ∞ (finite by the error rule)
    let mut best_param = Some(y0);
    let mut best_cost = c0;
    let mut iter = 0u64;
    let mut s = [SVector::<f64, N>::zeros(); MEMORY];
    let mut y = [SVector::<f64, N>::zeros(); MEMORY];
    let (mut head, mut len) = (0usize, 0usize);
    let at = |head: usize, i: usize| (head + i) % MEMORY;

    let status = loop {
        // terminate_internal: L-BFGS' tests, then the iteration limit (target cost −∞ never)
        #[allow(clippy::unwrap_used)] // set by init and every completed iteration
        let g_now = gradient.unwrap();
        if g_now.norm() < tol_grad || (prev_cost - cost).abs() < tol_cost {
            break Status::Converged;
        }
        if iter >= max_iters {
            break Status::MaxIters;
        }

        // LBFGS::next_iter
        #[allow(clippy::unwrap_used)]
        let x = param.take().unwrap();
        let cur_cost = cost;
        let prev_grad = g_now;
        gradient = None;
        let gamma = if len > 0 {
            let (sk, yk) = (&s[at(head, len - 1)], &y[at(head, len - 1)]);
            sk.dot(yk) / yk.dot(yk)
        } else {
            1.0
        };
        let mut q = prev_grad;
        let mut alpha = [0.0f64; MEMORY];
        let mut rho = [0.0f64; MEMORY];
        for i in (0..len).rev() {
            let (sk, yk) = (&s[at(head, i)], &y[at(head, i)]);
            let yksk = yk.dot(sk);
            let rho_t = 1.0 / yksk;
            let skq = sk.dot(&q);
            let alpha_t = skq * rho_t;
            q -= yk * alpha_t;
            rho[i] = rho_t;
            alpha[i] = alpha_t;
        }
        let mut r = q * gamma;
        for i in 0..len {
            let (sk, yk) = (&s[at(head, i)], &y[at(head, i)]);
            let beta = yk.dot(&r);
            let beta = beta * rho[i];
            r += sk * (alpha[i] - beta);
        }
        let d = r * -1.0;

        match line_search(&problem, &x, &prev_grad, cur_cost, &d) {
            None => {
                // argmin: state.terminate_with(SolverExit(..)); param and gradient were taken,
                // the line search's evaluations are not merged into the counts
                if cost < best_cost {
                    best_cost = cost;
                }
                if let Some(h) = history.as_deref_mut() {
                    h.push(cost);
                }
                iter += 1;
                break Status::LineSearch;
            }
            Some(acc) => {
                cost_count += acc.evaluations;
                gradient_count += acc.evaluations;
                if iter >= MEMORY as u64 {
                    head = at(head, 1);
                    len -= 1;
                }
                // argmin's L-BFGS evaluates the gradient again at the accepted point; the line
                // search's is the same number, so it is reused, and counted as argmin counts it
                gradient_count += 1;
                let grad = acc.gradient;
                let slot = at(head, len);
                s[slot] = acc.param - x;
                y[slot] = grad - prev_grad;
                len += 1;
                param = Some(acc.param);
                prev_cost = cost;
                cost = acc.cost;
                gradient = Some(grad);
                // state.update()
                if cost < best_cost {
                    best_param = param;
                    best_cost = cost;
                }
                if let Some(h) = history.as_deref_mut() {
                    h.push(cost);
                }
                iter += 1;
            }
        }
    };
    Ok(Outcome {
        status,
        iterations: iter,
        cost_count,
        gradient_count,
        best_param,
        best_cost,
        prev_cost,
        cost,
        gradient,
    })
}
