//! The local stage of a fit: from one point of the unit cube to the nearby minimum of the objective over the
//! shots, by Nelder-Mead ([`super::optimize::nelder_mead`], derivative-free: the impulse models, cheap and with
//! few parameters) or by Levenberg-Marquardt on reweighted residuals ([`super::least_squares`]: a model resolved
//! in time, whose launch is smooth in its parameters and whose every pass over the shots is dear).

use super::cost::{evaluate_with, CostScales};
use super::dataset::Shot;
use super::least_squares::{levenberg_marquardt, LmOptions, Predictions, Problem};
use super::objective::Objective;
use super::optimize::{nelder_mead, NmOptions, Progress};
use super::params::ParamSpace;
use crate::equipment::{BallSpec, LoadedClub};
use crate::math::Real;

/// How the local stage searches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LocalMethod {
    NelderMead,
    LevenbergMarquardt,
}

impl LocalMethod {
    /// The method for a model: Levenberg-Marquardt for one resolved in time (it has a cheaper variant to
    /// differentiate), Nelder-Mead otherwise.
    pub fn for_space(space: &ParamSpace) -> Self {
        if space.model.coarse.is_some() {
            LocalMethod::LevenbergMarquardt
        } else {
            LocalMethod::NelderMead
        }
    }
}

/// The local stage's minimum and what it cost.
#[derive(Debug, Clone, PartialEq)]
pub struct LocalMinimum {
    pub x: Vec<Real>,
    pub cost: Real,
    /// Passes over the shots (each evaluation of the objective, or a Jacobian column).
    pub evaluations: usize,
    /// Impacts simulated: one per shot per pass.
    pub simulations: u64,
}

/// The local search from `x0` (unit cube) on all of `shots`, with at most `max_evaluations` passes over them.
#[allow(clippy::too_many_arguments)]
pub fn refine(
    space: &ParamSpace,
    club: &LoadedClub,
    ball: &BallSpec,
    shots: &[Shot],
    objective: Objective,
    method: LocalMethod,
    max_evaluations: usize,
    x0: &[Real],
    progress: &mut dyn FnMut(Progress),
) -> LocalMinimum {
    let scales = CostScales::of(shots);
    let n = shots.len() as u64;
    let predict = |u: &[Real], coarse| {
        let candidate = space.club_with(club, &space.from_unit(u));
        evaluate_with(space, coarse, &candidate, ball, shots).ok()
    };
    match method {
        LocalMethod::NelderMead => {
            let mut f = |u: &[Real]| predict(u, None).map_or(Real::INFINITY, |p| objective.value(&p, shots, &scales));
            let x0_cost = f(x0);
            let nm = NmOptions { max_evaluations, ..Default::default() };
            let m = nelder_mead(&mut f, x0, &nm, progress);
            let evaluations = m.evaluations + 1;
            let (x, cost) = if m.cost <= x0_cost { (m.x, m.cost) } else { (x0.to_vec(), x0_cost) };
            LocalMinimum { x, cost, evaluations, simulations: evaluations as u64 * n }
        }
        LocalMethod::LevenbergMarquardt => {
            // Parameters the model refuses: every shot failed (the objective's penalty), no weight in a step.
            let all_failed = || vec![None; shots.len()];
            let mut exact = |u: &[Real]| -> Predictions { predict(u, None).unwrap_or_else(all_failed) };
            let mut linearised =
                |u: &[Real]| -> Predictions { predict(u, space.model.coarse).unwrap_or_else(all_failed) };
            let value = |p: &[Option<[Real; 5]>]| objective.value(p, shots, &scales);
            let weights = |p: &[Option<[Real; 5]>]| objective.step_weights(p, shots, &scales);
            let mut problem =
                Problem { exact: &mut exact, linearised: &mut linearised, value: &value, weights: &weights };
            let lm = LmOptions { max_evaluations: max_evaluations.max(1), ..Default::default() };
            let m = levenberg_marquardt(&mut problem, x0, &lm, progress);
            let evaluations = m.exact_passes + m.linearised_passes;
            LocalMinimum { x: m.x, cost: m.cost, evaluations, simulations: evaluations as u64 * n }
        }
    }
}
