//! Eq. 3.13 and the seed's accuracy tables (Tables 3.2-3.7), evaluated in parallel over shots.
//!
//! Predictions are computed shot by shot on rayon's pool and collected in shot order; every sum below runs
//! sequentially over that ordered vector, so a cost is bit-identical however many threads computed it.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::dataset::{fields_of, Shot};
use super::params::{BuildFn, ParamSpace};
use super::IdentifyError;
use crate::equipment::{BallSpec, LoadedClub};
use crate::impact::{Equipment, ImpactModel, LaunchMetrics};
use crate::math::Real;

pub use crate::pairing::fields::FIELDS;

/// What a shot the model cannot predict adds to eq. 3.13: one measured mean per field, as if it had missed each
/// field by 100 %.
pub const FAILED_PENALTY: Real = 1.0;

/// The denominators of eq. 3.13: the mean absolute measured value per field.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CostScales(pub [Real; 5]);

impl CostScales {
    /// `mean(|x_exp,i|)` over the shots (1 for a field whose mean is 0, so the cost stays finite).
    pub fn of(shots: &[Shot]) -> Self {
        Self::of_measured(&shots.iter().map(|s| s.measured).collect::<Vec<_>>())
    }

    /// The same over measured fields.
    pub fn of_measured(measured: &[[Real; 5]]) -> Self {
        let mut s = [0.0; 5];
        for m in measured {
            for (acc, x) in s.iter_mut().zip(m) {
                *acc += x.abs();
            }
        }
        let n = measured.len().max(1) as Real;
        CostScales(s.map(|v| if v > 0.0 { v / n } else { 1.0 }))
    }
}

/// The five fields the model predicts for each shot (`None`: the model failed on it), in shot order.
pub fn predict_all(model: &dyn ImpactModel, equipment: &Equipment, shots: &[Shot]) -> Vec<Option<[Real; 5]>> {
    shots
        .par_iter()
        .with_min_len(8)
        .map(|shot| {
            model
                .predict(&shot.state, equipment)
                .ok()
                .map(|launch| fields_of(&LaunchMetrics::from_ball(&launch.ball_velocity_mps, &launch.ball_spin_radps)))
        })
        .collect()
}

/// Eq. 3.13 for predictions against their shots.
pub fn cost(predictions: &[Option<[Real; 5]>], shots: &[Shot], scales: &CostScales) -> Real {
    cost_of(predictions, shots.iter().map(|s| &s.measured), scales)
}

/// Eq. 3.13 for predictions against measured fields.
pub fn cost_of<'a>(
    predictions: &[Option<[Real; 5]>],
    measured: impl ExactSizeIterator<Item = &'a [Real; 5]>,
    scales: &CostScales,
) -> Real {
    let n = measured.len().max(1) as Real;
    let mut c = 0.0;
    for (p, m) in predictions.iter().zip(measured) {
        match p {
            Some(x) => {
                for i in 0..5 {
                    c += (x[i] - m[i]).abs() / scales.0[i];
                }
            }
            None => c += 5.0 * FAILED_PENALTY,
        }
    }
    c / n
}

/// One row of the seed's tables.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FieldStats {
    pub field: String,
    /// Mean of the measured magnitudes (the seed's "Exp." column).
    pub measured_mean: Real,
    /// Mean absolute error, and as a percentage of `measured_mean`.
    pub mae: Real,
    pub mae_pct: Real,
    /// Standard deviation of the absolute errors, and as a percentage of `measured_mean`.
    pub std: Real,
    pub std_pct: Real,
    /// Mean signed residual (predicted − measured).
    pub bias: Real,
}

/// One model's column of the seed's tables.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelTable {
    pub model: String,
    pub shots: usize,
    /// Shots the model could not predict (left out of the statistics, penalised in the cost).
    pub failed: usize,
    pub fields: Vec<FieldStats>,
    /// Eq. 3.13.
    pub cost: Real,
    /// Wall time per shot of the predictions (us), all threads together.
    pub time_per_shot_us: Real,
}

/// Per-field statistics of predictions against shots.
pub fn field_stats(predictions: &[Option<[Real; 5]>], shots: &[Shot]) -> Vec<FieldStats> {
    field_stats_of(predictions, &shots.iter().map(|s| s.measured).collect::<Vec<_>>())
}

/// Per-field statistics of predictions against measured fields.
pub fn field_stats_of(predictions: &[Option<[Real; 5]>], measured: &[[Real; 5]]) -> Vec<FieldStats> {
    let scales = CostScales::of_measured(measured);
    (0..5)
        .map(|i| {
            let errors: Vec<Real> =
                predictions.iter().zip(measured).filter_map(|(p, m)| p.map(|x| x[i] - m[i])).collect();
            let n = errors.len().max(1) as Real;
            let mae = errors.iter().map(|e| e.abs()).sum::<Real>() / n;
            let var = errors.iter().map(|e| (e.abs() - mae).powi(2)).sum::<Real>() / n;
            let bias = errors.iter().sum::<Real>() / n;
            let mean = scales.0[i];
            FieldStats {
                field: FIELDS[i].0.to_string(),
                measured_mean: mean,
                mae,
                mae_pct: 100.0 * mae / mean,
                std: var.sqrt(),
                std_pct: 100.0 * var.sqrt() / mean,
                bias,
            }
        })
        .collect()
}

/// The model's table over the shots, timing its predictions.
pub fn model_table(name: &str, model: &dyn ImpactModel, equipment: &Equipment, shots: &[Shot]) -> ModelTable {
    let started = std::time::Instant::now();
    let predictions = predict_all(model, equipment, shots);
    let elapsed_us = started.elapsed().as_secs_f64() * 1e6;
    ModelTable {
        model: name.to_string(),
        shots: shots.len(),
        failed: predictions.iter().filter(|p| p.is_none()).count(),
        fields: field_stats(&predictions, shots),
        cost: cost(&predictions, shots, &CostScales::of(shots)),
        time_per_shot_us: elapsed_us / shots.len().max(1) as Real,
    }
}

/// A table of recorded predictions against their measurements (no model run; no time per shot).
pub fn recorded_table(name: &str, predictions: &[Option<[Real; 5]>], measured: &[[Real; 5]]) -> ModelTable {
    ModelTable {
        model: name.to_string(),
        shots: measured.len(),
        failed: predictions.iter().filter(|p| p.is_none()).count(),
        fields: field_stats_of(predictions, measured),
        cost: cost_of(predictions, measured.iter(), &CostScales::of_measured(measured)),
        time_per_shot_us: 0.0,
    }
}

/// The mean absolute error of a zero-mean normal noise of standard deviation `sigma`: `σ √(2/π)`.
pub fn normal_mae(sigma: Real) -> Real {
    sigma * (2.0 / std::f64::consts::PI).sqrt()
}

/// The predictions of the model with `club`'s parameters on `shots` (an error: parameters the model refuses).
pub fn evaluate(
    space: &ParamSpace,
    club: &LoadedClub,
    ball: &BallSpec,
    shots: &[Shot],
) -> Result<Vec<Option<[Real; 5]>>, IdentifyError> {
    evaluate_with(space, None, club, ball, shots)
}

/// The same with the model from `build` (a coarse variant) instead of the exact one.
pub(super) fn evaluate_with(
    space: &ParamSpace,
    build: Option<BuildFn>,
    club: &LoadedClub,
    ball: &BallSpec,
    shots: &[Shot],
) -> Result<Vec<Option<[Real; 5]>>, IdentifyError> {
    let model = match build {
        Some(b) => b(club, ball)?,
        None => space.model.build(club, ball)?,
    };
    let equipment = Equipment { club: club.club.clone(), ball: *ball };
    Ok(predict_all(model.as_ref(), &equipment, shots))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::ImpactState;
    use crate::math::{Isometry3, Vector3};

    fn shot(measured: [Real; 5]) -> Shot {
        let state = ImpactState {
            world_from_club: Isometry3::identity(),
            cg_velocity_mps: Vector3::zeros(),
            angular_velocity_radps: Vector3::zeros(),
            impact_h_m: 0.0,
            impact_v_m: 0.0,
        };
        Shot { state, measured }
    }

    #[test]
    fn eq_3_13_by_hand() {
        // Two shots; means of magnitudes: 150 mph, 10 deg, 2 deg, 3000 rpm, 300 rpm.
        let shots = [shot([140.0, 9.0, 1.0, 2800.0, -200.0]), shot([160.0, 11.0, -3.0, 3200.0, 400.0])];
        let preds = [Some([141.5, 9.0, 1.0, 2800.0, -200.0]), Some([160.0, 12.0, -3.0, 3200.0, 100.0])];
        let scales = CostScales::of(&shots);
        assert_eq!(scales.0, [150.0, 10.0, 2.0, 3000.0, 300.0]);
        // (1.5/150 + 1/10 + 300/300) / 2 = 0.555
        assert!((cost(&preds, &shots, &scales) - 0.555).abs() < 1e-12);
        // A failed shot costs one measured mean per field: (5 + 1/10 + 1) / 2.
        let failed = [None, Some([160.0, 12.0, -3.0, 3200.0, 100.0])];
        assert!((cost(&failed, &shots, &scales) - 3.05).abs() < 1e-12);
        let stats = field_stats(&preds, &shots);
        assert!((stats[0].mae - 0.75).abs() < 1e-12 && (stats[0].std - 0.75).abs() < 1e-12);
        assert!((stats[4].mae_pct - 50.0).abs() < 1e-9 && (stats[4].bias + 150.0).abs() < 1e-9);
    }

    #[test]
    fn the_mae_of_a_normal() {
        // E|X| = σ √(2/π) for X ~ N(0, σ²).
        assert!((normal_mae(1.0) - 0.797_884_560_802_865_4).abs() < 1e-15);
    }
}
