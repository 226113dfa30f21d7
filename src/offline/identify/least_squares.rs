//! The local refinement for a model resolved in time: Levenberg-Marquardt steps (Levenberg 1944, Marquardt 1963)
//! on the shots' launch residuals, in the unit cube `[0, 1]^d`, with iteratively reweighted least squares for a
//! criterion that is not a sum of squares.
//!
//! Each iteration weighs every residual by what the objective makes of it at the current point
//! ([`super::objective::Objective::step_weights`]): the likelihoods are weighted squares already; eq. 3.13's
//! `|r| / s` takes its slope `sign(r) / s` and its expected curvature over the noise (a Newton step on the
//! least-absolute cost as its sandwich covariance sees it; reweighting by `1 / |r|` instead, the classic
//! iteratively reweighted least squares, overstates the curvature by about `ln(σ / floor)` and crawls). The
//! Jacobian is by forward differences of a cheaper model (the coarse step, whose launch differs from the exact
//! one's by far less than the noise, and whose derivatives differ less still), one pass over the shots per
//! parameter; every step is judged by the objective itself on the exact model, and kept only if it lowers it
//! (else the damping grows and the step shrinks toward the gradient's). A parameter at a bound whose step points
//! outward is held there.
//!
//! Nelder-Mead ([`super::optimize::nelder_mead`]) spends 400 passes over the shots on seven parameters and
//! still stops short along the flat directions of eq. 3.13; a Gauss-Newton step sees the whole quadratic
//! model of the cost from `d + 1` cheap passes, so the refinement converges in a few dozen.
//! Written here rather than taken from a crate: the crates' Levenberg-Marquardt solvers (`levenberg-marquardt`,
//! `argmin`'s) minimise a fixed sum of squares with the Jacobian of the same function; this one reweights per
//! iteration, differentiates a cheaper model than it judges, and keeps bounds, each a few lines here.
//!
//! Deterministic: the predictions come back in shot order and every sum runs sequentially over them.

use super::optimize::Progress;
use crate::math::{DMatrix, DVector, Real};

/// Each shot's five launch fields, `None` where the model failed (as [`super::cost::predict_all`] gives them).
pub type Predictions = Vec<Option<[Real; 5]>>;

/// The objective's value of predictions.
pub type ValueFn<'a> = &'a dyn Fn(&[Option<[Real; 5]>]) -> Real;

/// Per residual of predictions: the weight of its square in the curvature and its slope.
pub type WeightsFn<'a> = &'a dyn Fn(&[Option<[Real; 5]>]) -> Vec<[(Real, Real); 5]>;

/// Settings of the refinement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmOptions {
    /// Passes over the shots at most: the exact model's (one per trial step) and the Jacobian's (`d + 1` each).
    pub max_evaluations: usize,
    /// Forward-difference step, in unit-cube coordinates.
    pub step: Real,
    /// Stop once an accepted step lowers the objective by less than this (relative).
    pub f_tolerance: Real,
    /// Initial damping (relative to the normal matrix's diagonal).
    pub damping: Real,
}

impl Default for LmOptions {
    fn default() -> Self {
        LmOptions { max_evaluations: 400, step: 1e-3, f_tolerance: 1e-5, damping: 1e-3 }
    }
}

/// What the refinement needs of the fit: predictions from the exact model and from the model it
/// differentiates, the objective and its weights.
pub struct Problem<'a> {
    pub exact: &'a mut dyn FnMut(&[Real]) -> Predictions,
    pub linearised: &'a mut dyn FnMut(&[Real]) -> Predictions,
    pub value: ValueFn<'a>,
    /// Per residual: the weight of its square in the curvature and its slope (a residual `r` of weighted
    /// squares: `(w, w r)`).
    pub weights: WeightsFn<'a>,
}

/// Where the refinement ended.
#[derive(Debug, Clone, PartialEq)]
pub struct LmMinimum {
    pub x: Vec<Real>,
    pub cost: Real,
    /// Passes over the shots: the exact model's and the differentiated model's.
    pub exact_passes: usize,
    pub linearised_passes: usize,
}

/// Levenberg-Marquardt from `x0` in `[0, 1]^d`.
pub fn levenberg_marquardt(
    problem: &mut Problem<'_>,
    x0: &[Real],
    options: &LmOptions,
    progress: &mut dyn FnMut(Progress),
) -> LmMinimum {
    let d = x0.len();
    let mut x: Vec<Real> = x0.iter().map(|v| v.clamp(0.0, 1.0)).collect();
    let mut p = (problem.exact)(&x);
    let mut cost = (problem.value)(&p);
    let (mut exact_passes, mut linearised_passes) = (1, 0);
    let mut damping = options.damping;
    let spent = |e: usize, l: usize| e + l;
    'outer: while d > 0 && spent(exact_passes, linearised_passes) + d + 2 <= options.max_evaluations {
        let (a, g) = normal_equations(problem, &x, &p, options.step);
        linearised_passes += d + 1;
        loop {
            let Some(delta) = bounded_step(&a, &g, &x, damping) else { break 'outer };
            let trial: Vec<Real> = x.iter().zip(&delta).map(|(v, s)| (v + s).clamp(0.0, 1.0)).collect();
            if trial == x {
                break 'outer;
            }
            let q = (problem.exact)(&trial);
            exact_passes += 1;
            let c = (problem.value)(&q);
            let evaluations = spent(exact_passes, linearised_passes);
            progress(Progress {
                stage: "local",
                step: evaluations,
                steps: options.max_evaluations,
                evaluations,
                best_cost: cost.min(c),
            });
            if c < cost {
                let gain = (cost - c) / cost.abs().max(1e-300);
                (x, p, cost) = (trial, q, c);
                damping = (damping / 3.0).max(1e-9);
                if gain < options.f_tolerance {
                    break 'outer;
                }
                break;
            }
            damping *= 4.0;
            if damping > 1e8 || evaluations + 1 > options.max_evaluations {
                break 'outer;
            }
        }
    }
    LmMinimum { x, cost, exact_passes, linearised_passes }
}

/// The Gauss-Newton normal equations `A = Jᵀ W J`, `g = Jᵀ ψ` at `x`: `W` and `ψ` the objective's curvature
/// weights and slopes at the exact model's predictions `p`, `J` forward differences of the linearised model. Shots any pass failed on
/// are left out.
fn normal_equations(problem: &mut Problem<'_>, x: &[Real], p: &[Option<[Real; 5]>], step: Real) -> (DMatrix, DVector) {
    let d = x.len();
    let weights = (problem.weights)(p);
    let base = (problem.linearised)(x);
    let mut signed_steps = Vec::with_capacity(d);
    let mut columns = Vec::with_capacity(d);
    for k in 0..d {
        let h = if x[k] + step <= 1.0 { step } else { -step };
        let mut moved = x.to_vec();
        moved[k] += h;
        columns.push((problem.linearised)(&moved));
        signed_steps.push(h);
    }
    let mut a = DMatrix::zeros(d, d);
    let mut g = DVector::zeros(d);
    let mut row = vec![[0.0; 5]; d];
    for j in 0..p.len() {
        let (Some(_), Some(bj)) = (p[j], base[j]) else { continue };
        let mut complete = true;
        for k in 0..d {
            match columns[k][j] {
                Some(c) => row[k] = std::array::from_fn(|i| (c[i] - bj[i]) / signed_steps[k]),
                None => complete = false,
            }
        }
        if !complete {
            continue;
        }
        for i in 0..5 {
            let (w, slope) = weights[j][i];
            for k in 0..d {
                g[k] += slope * row[k][i];
                for l in 0..=k {
                    a[(k, l)] += w * row[k][i] * row[l][i];
                }
            }
        }
    }
    for k in 0..d {
        for l in 0..k {
            a[(l, k)] = a[(k, l)];
        }
    }
    (a, g)
}

/// The damped Gauss-Newton step `(A + λ diag A) δ = -g`, with every coordinate at a bound whose step points out
/// of the cube held there (solved again without it). `None`: no coordinate can move.
fn bounded_step(a: &DMatrix, g: &DVector, x: &[Real], damping: Real) -> Option<Vec<Real>> {
    let d = x.len();
    let largest = (0..d).map(|k| a[(k, k)]).fold(0.0, Real::max).max(1e-300);
    let mut free: Vec<bool> = vec![true; d];
    loop {
        let index: Vec<usize> = (0..d).filter(|&k| free[k]).collect();
        if index.is_empty() {
            return None;
        }
        let m = index.len();
        let system = DMatrix::from_fn(m, m, |r, c| {
            let (k, l) = (index[r], index[c]);
            let diagonal = a[(k, k)].max(1e-12 * largest);
            if r == c {
                diagonal * (1.0 + damping)
            } else {
                a[(k, l)]
            }
        });
        let rhs = DVector::from_fn(m, |r, _| -g[index[r]]);
        let solved = system.cholesky()?.solve(&rhs);
        let mut delta = vec![0.0; d];
        for (r, &k) in index.iter().enumerate() {
            delta[k] = solved[r];
        }
        let outward: Vec<usize> = index
            .iter()
            .copied()
            .filter(|&k| (x[k] <= 0.0 && delta[k] < 0.0) || (x[k] >= 1.0 && delta[k] > 0.0))
            .collect();
        if outward.is_empty() {
            return Some(delta);
        }
        for k in outward {
            free[k] = false;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Shots of a smooth two-parameter "model": launch fields `(a + b t, a b, t, a², b)` for shot `t`.
    fn model(x: &[Real], n: usize) -> Predictions {
        (0..n)
            .map(|j| {
                let t = j as Real / n as Real;
                Some([x[0] + x[1] * t, x[0] * x[1], t, x[0] * x[0], x[1]])
            })
            .collect()
    }

    /// Measured at `(a, b) = (0.3, 0.6)`, every fifth shot's first field 0.5 too high (an outlier).
    /// An objective of predictions against measured fields: its value and its step weights.
    type TestObjective<'a> = &'a dyn Fn(&[Option<[Real; 5]>], &[[Real; 5]]) -> (Real, Vec<[(Real, Real); 5]>);

    fn run(objective: TestObjective<'_>) -> LmMinimum {
        let n = 40;
        let measured: Vec<[Real; 5]> = model(&[0.3, 0.6], n)
            .into_iter()
            .flatten()
            .enumerate()
            .map(|(j, mut f)| {
                f[0] += if j % 5 == 0 { 0.5 } else { 0.0 };
                f
            })
            .collect();
        let mut exact = |x: &[Real]| model(x, n);
        let mut linearised = |x: &[Real]| model(x, n);
        let value = |p: &[Option<[Real; 5]>]| objective(p, &measured).0;
        let weights = |p: &[Option<[Real; 5]>]| objective(p, &measured).1;
        let mut problem = Problem { exact: &mut exact, linearised: &mut linearised, value: &value, weights: &weights };
        let options = LmOptions { f_tolerance: 1e-12, ..Default::default() };
        levenberg_marquardt(&mut problem, &[0.9, 0.1], &options, &mut |_| {})
    }

    fn residuals(p: &[Option<[Real; 5]>], m: &[[Real; 5]]) -> Vec<[Real; 5]> {
        p.iter().zip(m).map(|(p, m)| p.map_or([0.0; 5], |f| std::array::from_fn(|i| f[i] - m[i]))).collect()
    }

    #[test]
    fn reweighted_least_absolute_ignores_outliers_that_pull_least_squares() {
        let squares = |p: &[Option<[Real; 5]>], m: &[[Real; 5]]| {
            let r = residuals(p, m);
            (r.iter().flatten().map(|v| v * v).sum(), r.iter().map(|f| f.map(|v| (1.0, v))).collect())
        };
        let ls = run(&squares);
        // Least squares: the outliers pull the fit off the clean shots' point.
        assert!((ls.x[0] - 0.3).abs() + (ls.x[1] - 0.6).abs() > 1e-2, "{ls:?}");
        // Least absolute by reweighting (weights 1 / |r|, floored; slopes sign r): the clean shots' point, which fits 32 of 40
        // shots exactly and is eq. 3.13's kind of minimum.
        let absolute = |p: &[Option<[Real; 5]>], m: &[[Real; 5]]| {
            let r = residuals(p, m);
            let w = r.iter().map(|f| f.map(|v| (1.0 / v.abs().max(1e-9), v.signum()))).collect();
            (r.iter().flatten().map(|v| v.abs()).sum(), w)
        };
        let m = run(&absolute);
        assert!((m.x[0] - 0.3).abs() < 1e-6 && (m.x[1] - 0.6).abs() < 1e-6, "{m:?}");
        assert!((m.cost - 8.0 * 0.5).abs() < 1e-4, "{m:?}");
        // Far fewer passes than a simplex would spend, and repeatable.
        assert!(m.exact_passes + m.linearised_passes < 400, "{m:?}");
        assert_eq!(run(&absolute), m);
    }

    #[test]
    fn a_bound_holds_a_parameter_the_data_push_outside() {
        // The measured point's a is 1.4: outside the cube, so the fit ends on a = 1 with b fitted.
        let n = 20;
        let measured: Vec<[Real; 5]> = model(&[1.4, 0.6], n).into_iter().flatten().collect();
        let mut exact = |x: &[Real]| model(x, n);
        let mut linearised = |x: &[Real]| model(x, n);
        let value = |p: &[Option<[Real; 5]>]| residuals(p, &measured).iter().flatten().map(|v| v * v).sum::<Real>();
        let weights = |p: &[Option<[Real; 5]>]| residuals(p, &measured).iter().map(|f| f.map(|v| (1.0, v))).collect();
        let mut problem = Problem { exact: &mut exact, linearised: &mut linearised, value: &value, weights: &weights };
        let m = levenberg_marquardt(&mut problem, &[0.5, 0.5], &LmOptions::default(), &mut |_| {});
        assert_eq!(m.x[0], 1.0, "{m:?}");
        assert!(m.x[1] > 0.5 && m.x[1] < 1.0, "{m:?}");
        assert!(m.cost < value(&model(&[0.5, 0.5], n)));
    }
}
