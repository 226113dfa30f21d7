//! The seed's identification procedure (section 3.1.3): a global search of the parameters' bounds, then a local
//! refinement of the best point, minimising eq. 3.13 over the shots (or the launch monitor's noise likelihood,
//! [`super::objective`]); and k-fold cross-validation of the mean absolute errors before and after.

use serde::{Deserialize, Serialize};

use super::cost::{cost, evaluate, evaluate_with, field_stats, CostScales, FieldStats};
use super::dataset::Shot;
use super::fisher;
pub use super::local::LocalMethod;
use super::local::{refine, LocalMinimum};
use super::objective::Objective;
use super::optimize::{differential_evolution, DeOptions, Progress};
use super::params::{BuildFn, ParamSpace};
use super::IdentifyError;
use crate::equipment::{BallSpec, LoadedClub};
use crate::math::Real;
use crate::rng::Rng;

/// How to fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitOptions {
    pub seed: u64,
    /// Cross-validation folds (0 or 1: none).
    pub folds: usize,
    /// Differential evolution population (default: 10 per parameter, at least 20) and generations.
    pub population: Option<usize>,
    pub generations: usize,
    /// The local stage's passes over the shots at most (Nelder-Mead's evaluations; Levenberg-Marquardt's trial
    /// steps and Jacobian columns).
    pub local_evaluations: usize,
    /// The local stage's method (`None`: [`LocalMethod::for_space`]).
    pub local: Option<LocalMethod>,
    /// Whether each cross-validation fold runs the global search too (`None`: only for a model without a coarse
    /// step; a model resolved in time starts each fold's local stage from the fit on all shots).
    pub fold_global: Option<bool>,
    /// Shots the global stage evaluates (a seeded subsample); the local stage uses all. `None`: all shots for a
    /// model without a coarse step, [`GLOBAL_SHOTS_IN_TIME`] for one resolved in time.
    pub global_shots: Option<usize>,
    /// The global stage integrates a model resolved in time at its coarse step ([`super::params::COARSE_STEP_FACTOR`]);
    /// the local refinement and every reported number use the exact step.
    pub coarse_global: bool,
    /// The global stage stops when its best cost has gained less than 0.1 % in this many generations (0: it
    /// runs every generation).
    pub stall_generations: usize,
    /// What the fit minimises (eq. 3.13 by default).
    pub objective: Objective,
}

/// The global stage's subsample for a model resolved in time: enough shots to find the basin of eq. 3.13
/// (the local refinement then fits on all of them).
pub const GLOBAL_SHOTS_IN_TIME: usize = 150;

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            seed: 1,
            folds: 5,
            population: None,
            generations: 100,
            local_evaluations: 400,
            local: None,
            fold_global: None,
            global_shots: None,
            coarse_global: true,
            stall_generations: 10,
            objective: Objective::LeastAbsolute,
        }
    }
}

/// One fitted parameter, in its display unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParamReport {
    pub name: String,
    pub unit: String,
    pub start: Real,
    pub fitted: Real,
    pub lo: Real,
    pub hi: Real,
    /// The Cramér-Rao bound at the fitted values (display unit) with every parameter unknown, and with the
    /// others known ([`super::fisher`]; the noise is the residuals' standard deviation per field). `None`: no
    /// information (a flat direction of the cost).
    #[serde(default)]
    pub std_error: Option<Real>,
    #[serde(default)]
    pub std_error_alone: Option<Real>,
    /// The standard deviation of eq. 3.13's own estimate at this noise (display unit): least-absolute and
    /// weighted by the measured means, it scatters more than the bound ([`super::fisher::l1_scatter`]).
    #[serde(default)]
    pub scatter: Option<Real>,
}

/// The cross-validated errors: every shot predicted by the parameters fitted without its fold.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CvReport {
    pub folds: usize,
    /// With the club's starting parameters.
    pub before: Vec<FieldStats>,
    pub cost_before: Real,
    /// With each fold's fitted parameters, on the held-out fold.
    pub after: Vec<FieldStats>,
    pub cost_after: Real,
    /// The fitted values (display units) of each fold, in parameter order.
    pub fold_values: Vec<Vec<Real>>,
}

/// What `fit` did.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FitReport {
    pub model: String,
    pub club: String,
    pub shots: usize,
    pub seed: u64,
    pub params: Vec<ParamReport>,
    /// What the fit minimised ([`Objective::name`]) and its value per shot at the fitted parameters.
    #[serde(default = "eq_3_13")]
    pub objective: String,
    #[serde(default)]
    pub objective_value: Real,
    /// Eq. 3.13 on all shots with the starting and the fitted parameters (whatever the objective).
    pub cost_before: Real,
    pub cost: Real,
    pub evaluations: usize,
    /// Impacts simulated by the fit on all shots (evaluations x shots per stage), and by the cross-validation;
    /// the bounds' passes over the shots afterwards (at most 2 per parameter, and 3) are not counted.
    #[serde(default)]
    pub simulations: u64,
    #[serde(default)]
    pub cv_simulations: u64,
    /// Wall time of the fit on all shots (s), and of the cross-validation.
    pub fit_seconds: Real,
    pub cv_seconds: Real,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cv: Option<CvReport>,
}

fn eq_3_13() -> String {
    Objective::LeastAbsolute.name().to_string()
}

/// One fit's result: SI values, the objective's value and the evaluations spent.
#[derive(Debug, Clone, PartialEq)]
pub struct Fitted {
    pub values: Vec<Real>,
    pub cost: Real,
    pub evaluations: usize,
    /// Impacts simulated (each evaluation costs one per shot it covers).
    pub simulations: u64,
}

/// Minimises the objective (eq. 3.13 by default) over `shots` for the parameters of `space`, starting from
/// `club`'s values.
pub fn fit_once(
    space: &ParamSpace,
    club: &LoadedClub,
    ball: &BallSpec,
    shots: &[Shot],
    options: &FitOptions,
    progress: &mut dyn FnMut(Progress),
) -> Result<Fitted, IdentifyError> {
    if shots.is_empty() {
        return Err(IdentifyError::NoShots("fit"));
    }
    let coarse = space.model.coarse.filter(|_| options.coarse_global);
    let objective_on = |u: &[Real], shots: &[Shot], scales: &CostScales, coarse: Option<BuildFn>| {
        let candidate = space.club_with(club, &space.from_unit(u));
        evaluate_with(space, coarse, &candidate, ball, shots)
            .map_or(Real::INFINITY, |p| options.objective.value(&p, shots, scales))
    };
    let global_shots = options.global_shots.or(space.model.coarse.map(|_| GLOBAL_SHOTS_IN_TIME));
    let subsample: Vec<Shot> = match global_shots {
        Some(n) if n < shots.len() => {
            let fold = fold_of_each(shots.len(), shots.len(), options.seed);
            shots.iter().zip(fold).filter(|(_, f)| *f < n).map(|(s, _)| *s).collect()
        }
        _ => shots.to_vec(),
    };
    let sub_scales = CostScales::of(&subsample);
    let mut global_objective = |u: &[Real]| objective_on(u, &subsample, &sub_scales, coarse);
    let d = space.defs.len();
    let mut de = DeOptions::for_dimension(d, options.seed);
    de.generations = options.generations;
    de.stall_generations = options.stall_generations;
    if let Some(p) = options.population {
        de.population = p;
    }
    let start = space.to_unit(&space.get(club));
    let global = differential_evolution(&mut global_objective, d, Some(&start), &de, progress);
    let local = fit_local(space, club, ball, shots, options, &global.x, progress);
    Ok(Fitted {
        values: space.from_unit(&local.x),
        cost: local.cost,
        evaluations: global.evaluations + local.evaluations,
        simulations: global.evaluations as u64 * subsample.len() as u64 + local.simulations,
    })
}

/// The local stage alone from `x0` (unit cube) on `shots`: the refinement after the global search, and each
/// cross-validation fold of a model resolved in time, started from the fit on all shots.
pub fn fit_local(
    space: &ParamSpace,
    club: &LoadedClub,
    ball: &BallSpec,
    shots: &[Shot],
    options: &FitOptions,
    x0: &[Real],
    progress: &mut dyn FnMut(Progress),
) -> LocalMinimum {
    let method = options.local.unwrap_or_else(|| LocalMethod::for_space(space));
    refine(space, club, ball, shots, options.objective, method, options.local_evaluations, x0, progress)
}

/// The fold of each shot: a seeded shuffle dealt round-robin into `k` folds.
pub fn fold_of_each(n: usize, k: usize, seed: u64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..n).collect();
    let mut rng = Rng::new(seed ^ 0x5EED_F01D);
    for i in (1..n).rev() {
        order.swap(i, (rng.next_u64() % (i as u64 + 1)) as usize);
    }
    let mut fold = vec![0; n];
    for (position, &shot) in order.iter().enumerate() {
        fold[shot] = position % k;
    }
    fold
}

/// Fits on all shots and, with `options.folds >= 2`, cross-validates. `progress` receives a phase label
/// (`"fold 2/5"`, `"all shots"`) with each report.
pub fn run(
    space: &ParamSpace,
    club: &LoadedClub,
    ball: &BallSpec,
    shots: &[Shot],
    options: &FitOptions,
    progress: &mut dyn FnMut(&str, Progress),
) -> Result<(FitReport, LoadedClub), IdentifyError> {
    if shots.is_empty() {
        return Err(IdentifyError::NoShots("fit"));
    }
    let display =
        |values: &[Real]| -> Vec<Real> { space.defs.iter().zip(values).map(|(d, v)| v * d.display_factor).collect() };
    let started = std::time::Instant::now();
    let fitted = fit_once(space, club, ball, shots, options, &mut |p| progress("all shots", p))?;
    let fit_seconds = started.elapsed().as_secs_f64();
    let mut cv = None;
    let mut cv_simulations = 0;
    let cv_started = std::time::Instant::now();
    if options.folds >= 2 {
        let k = options.folds;
        if shots.len() < k {
            return Err(IdentifyError::TooFewShots(k));
        }
        let fold = fold_of_each(shots.len(), k, options.seed);
        let before = evaluate(space, club, ball, shots)?;
        let mut after = vec![None; shots.len()];
        let mut fold_values = Vec::new();
        // The starting parameters and each fold's fitted ones on its held-out shots: one pass over all shots each.
        cv_simulations = 2 * shots.len() as u64;
        let fold_global = options.fold_global.unwrap_or(space.model.coarse.is_none());
        let warm_start = space.to_unit(&fitted.values);
        for f in 0..k {
            let train: Vec<Shot> = shots.iter().zip(&fold).filter(|(_, &g)| g != f).map(|(s, _)| *s).collect();
            let label = format!("fold {}/{k}", f + 1);
            let mut report = |p| progress(&label, p);
            let (values, simulations) = if fold_global {
                let fitted = fit_once(space, club, ball, &train, options, &mut report)?;
                (fitted.values, fitted.simulations)
            } else {
                let local = fit_local(space, club, ball, &train, options, &warm_start, &mut report);
                (space.from_unit(&local.x), local.simulations)
            };
            fold_values.push(display(&values));
            cv_simulations += simulations;
            let fitted_club = space.club_with(club, &values);
            let held: Vec<usize> = (0..shots.len()).filter(|&i| fold[i] == f).collect();
            let held_shots: Vec<Shot> = held.iter().map(|&i| shots[i]).collect();
            for (i, p) in held.iter().zip(evaluate(space, &fitted_club, ball, &held_shots)?) {
                after[*i] = p;
            }
        }
        let scales = CostScales::of(shots);
        cv = Some(CvReport {
            folds: k,
            cost_before: cost(&before, shots, &scales),
            before: field_stats(&before, shots),
            cost_after: cost(&after, shots, &scales),
            after: field_stats(&after, shots),
            fold_values,
        });
    }
    let cv_seconds = cv_started.elapsed().as_secs_f64();
    let fitted_club = space.club_with(club, &fitted.values);
    let fitted_predictions = evaluate(space, &fitted_club, ball, shots)?;
    let sigma = fisher::residual_sigma(&fitted_predictions, shots, space.defs.len());
    let jacobian = fisher::jacobian(space, &fitted_club, ball, shots, &fitted.values)?;
    let bounds = fisher::bounds(&fisher::information_of(&jacobian, &sigma));
    let scales = CostScales::of(shots);
    let scatter = fisher::l1_scatter(&jacobian, &sigma, &scales.0);
    let cost_before = cost(&evaluate(space, club, ball, shots)?, shots, &scales);
    let start = display(&space.get(club));
    let fitted_display = display(&fitted.values);
    let params = space
        .defs
        .iter()
        .enumerate()
        .map(|(i, d)| ParamReport {
            name: d.name.to_string(),
            unit: d.unit.to_string(),
            start: start[i],
            fitted: fitted_display[i],
            lo: d.lo * d.display_factor,
            hi: d.hi * d.display_factor,
            // No bound when the model predicted none of the shots near the fitted values (empty information).
            std_error: bounds.get(i).map(|b| b.joint * d.display_factor).filter(|v| v.is_finite()),
            std_error_alone: bounds.get(i).map(|b| b.alone * d.display_factor).filter(|v| v.is_finite()),
            scatter: scatter.get(i).map(|v| v * d.display_factor).filter(|v| v.is_finite()),
        })
        .collect();
    let report = FitReport {
        model: space.model.name.to_string(),
        club: club.club.name.clone(),
        shots: shots.len(),
        seed: options.seed,
        params,
        objective: options.objective.name().to_string(),
        objective_value: fitted.cost,
        cost_before,
        cost: cost(&fitted_predictions, shots, &scales),
        evaluations: fitted.evaluations,
        simulations: fitted.simulations,
        cv_simulations,
        fit_seconds,
        cv_seconds,
        cv,
    };
    Ok((report, fitted_club))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folds_are_balanced_and_seeded() {
        let f = fold_of_each(103, 5, 9);
        let mut sizes = [0; 5];
        for g in &f {
            sizes[*g] += 1;
        }
        assert_eq!(sizes, [21, 21, 21, 20, 20]);
        assert_eq!(fold_of_each(103, 5, 9), f);
        assert_ne!(fold_of_each(103, 5, 10), f);
    }
}
