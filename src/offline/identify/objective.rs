//! What `fit` minimises over the shots: eq. 3.13, the seed's least-absolute criterion (the default), or the
//! likelihood of the launch monitor's noise.
//!
//! With independent zero-mean normal errors of standard deviation `σ_i` per launch field, the negative
//! log-likelihood of the shots is, up to a constant,
//!
//! `L = Σ_j Σ_i (x_sim,i,j − x_exp,i,j)² / (2 σ_i²)`   (σ given: weighted least squares)
//!
//! and with the `σ_i` unknown, maximised out of the likelihood at `σ_i² = mean_j r_i,j²` (the noise estimated
//! from the residuals), the profile likelihood
//!
//! `L = (n / 2) Σ_i ln(mean_j r_i,j²)`.
//!
//! Its minimiser is the maximum-likelihood estimate, which is asymptotically efficient: its scatter is the
//! Cramér-Rao bound of [`super::fisher`]. Eq. 3.13 is least-absolute (efficiency 2/π under normal noise) and
//! weights each field by its measured mean rather than its noise, so it scatters more
//! ([`super::fisher::l1_scatter`]; docs/identify.md).
//!
//! Both are reported per shot (divided by `n`), and a shot the model cannot predict counts as missing every
//! field by its measured mean (as [`super::cost::FAILED_PENALTY`] does for eq. 3.13).

use super::cost::{cost, CostScales};
use super::dataset::Shot;
use super::IdentifyError;
use crate::math::Real;

/// The objective of a fit.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Objective {
    /// Eq. 3.13: mean absolute residuals over the measured means (the seed's).
    #[default]
    LeastAbsolute,
    /// The normal likelihood of the launch monitor's noise: `noise` per field (ball speed mph, launch deg,
    /// direction deg, backspin rpm, sidespin rpm), or estimated from the residuals when `None`.
    Likelihood { noise: Option<[Real; 5]> },
}

impl Objective {
    /// The likelihood with a given noise, each standard deviation checked (positive and finite).
    pub fn likelihood(noise: Option<[Real; 5]>) -> Result<Self, IdentifyError> {
        if let Some(sigma) = noise {
            for ((name, _), s) in super::FIELDS.iter().zip(sigma) {
                if !(s.is_finite() && s > 0.0) {
                    return Err(IdentifyError::Noise(format!("{name} must be a positive standard deviation, got {s}")));
                }
            }
        }
        Ok(Objective::Likelihood { noise })
    }

    /// The name reports carry.
    pub fn name(&self) -> &'static str {
        match self {
            Objective::LeastAbsolute => "eq_3_13",
            Objective::Likelihood { noise: Some(_) } => "likelihood",
            Objective::Likelihood { noise: None } => "likelihood_estimated_noise",
        }
    }

    /// The objective of `predictions` against `shots` (`scales`: eq. 3.13's measured means).
    pub fn value(&self, predictions: &[Option<[Real; 5]>], shots: &[Shot], scales: &CostScales) -> Real {
        match self {
            Objective::LeastAbsolute => cost(predictions, shots, scales),
            Objective::Likelihood { noise } => {
                let n = shots.len().max(1) as Real;
                let mut sum_sq = [0.0; 5];
                for (p, s) in predictions.iter().zip(shots) {
                    for i in 0..5 {
                        let r = p.map_or(scales.0[i], |x| x[i] - s.measured[i]);
                        sum_sq[i] += r * r;
                    }
                }
                match noise {
                    Some(sigma) => (0..5).map(|i| sum_sq[i] / (2.0 * sigma[i] * sigma[i])).sum::<Real>() / n,
                    // In units of the measured means, so the value does not depend on the fields' units; the floor
                    // keeps a field the model fits exactly finite.
                    None => {
                        (0..5).map(|i| 0.5 * (sum_sq[i] / (n * scales.0[i] * scales.0[i]) + 1e-300).ln()).sum::<Real>()
                    }
                }
            }
        }
    }
}

impl Objective {
    /// Each residual's part in a Gauss-Newton step at `predictions` (the Levenberg-Marquardt refinement's): the
    /// weight of its square in the cost's local curvature and its slope, `(w, ψ)`, so that the step solves
    /// `Σ w g g' δ = -Σ ψ g` (`g` the residual's derivatives by the parameters). For the likelihoods `ψ = w r`
    /// with `w = 1 / σ_i²`, the given noise's or the current residuals' (`mean_j r_i,j²`: the profile
    /// likelihood's gradient is that of weighted squares with the noise estimated at the current point). Eq.
    /// 3.13's `|r| / s_i` has slope `sign(r) / s_i` and no curvature but at `r = 0`: over residuals scattered by
    /// noise of density `f_i` its expected curvature is `2 f_i(0) / s_i`, and for normal noise `f_i(0) =
    /// 1 / (π MAE_i)` with the field's current mean absolute residual (the sandwich's `A` in
    /// [`super::fisher::l1_scatter`]). A failed shot weighs nothing.
    pub fn step_weights(
        &self,
        predictions: &[Option<[Real; 5]>],
        shots: &[Shot],
        scales: &CostScales,
    ) -> Vec<[(Real, Real); 5]> {
        let residuals: Vec<Option<[Real; 5]>> = predictions
            .iter()
            .zip(shots)
            .map(|(p, s)| p.map(|x| std::array::from_fn(|i| x[i] - s.measured[i])))
            .collect();
        let predicted = residuals.iter().flatten().count().max(1) as Real;
        let mean_of = |f: &dyn Fn(Real) -> Real| -> [Real; 5] {
            std::array::from_fn(|i| residuals.iter().flatten().map(|r| f(r[i])).sum::<Real>() / predicted)
        };
        let curvature: [Real; 5] = match self {
            Objective::LeastAbsolute => {
                let mae = mean_of(&|r| r.abs());
                std::array::from_fn(|i| 2.0 / (std::f64::consts::PI * scales.0[i] * mae[i].max(1e-300)))
            }
            Objective::Likelihood { noise: Some(sigma) } => sigma.map(|s| 1.0 / (s * s)),
            Objective::Likelihood { noise: None } => mean_of(&|r| r * r).map(|m| 1.0 / m.max(1e-300)),
        };
        residuals
            .iter()
            .map(|r| match r {
                None => [(0.0, 0.0); 5],
                Some(r) => std::array::from_fn(|i| match self {
                    Objective::LeastAbsolute => (curvature[i], r[i].signum() / scales.0[i]),
                    Objective::Likelihood { .. } => (curvature[i], curvature[i] * r[i]),
                }),
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::ImpactState;
    use crate::math::{Isometry3, Vector3};

    fn shots(measured: &[[Real; 5]]) -> Vec<Shot> {
        let state = ImpactState {
            world_from_club: Isometry3::identity(),
            cg_velocity_mps: Vector3::zeros(),
            angular_velocity_radps: Vector3::zeros(),
            impact_h_m: 0.0,
            impact_v_m: 0.0,
        };
        measured.iter().map(|m| Shot { state, measured: *m }).collect()
    }

    #[test]
    fn weighted_least_squares_and_the_profile_likelihood() {
        let s = shots(&[[100.0, 10.0, 1.0, 3000.0, 100.0], [110.0, 12.0, -1.0, 3200.0, -100.0]]);
        let scales = CostScales::of(&s);
        let p = vec![Some([101.0, 10.0, 1.0, 3000.0, 100.0]), Some([110.0, 12.0, -1.0, 3000.0, -100.0])];
        // Residuals 1 mph (shot 1) and 200 rpm (shot 2): (1/0.5² + 200²/150²) / 2 / 2 shots.
        let wls = Objective::likelihood(Some([0.5, 0.2, 0.3, 150.0, 150.0])).unwrap();
        let want = (4.0 + (200.0f64 / 150.0).powi(2)) / 2.0 / 2.0;
        assert!((wls.value(&p, &s, &scales) - want).abs() < 1e-12);
        // The profile likelihood falls as any field's residuals shrink, whatever the others do.
        let profile = Objective::likelihood(None).unwrap();
        let better = vec![Some([100.5, 10.0, 1.0, 3000.0, 100.0]), p[1]];
        assert!(profile.value(&better, &s, &scales) < profile.value(&p, &s, &scales));
        assert!(profile.value(&p, &s, &scales).is_finite());
        // A failed shot costs as much as missing every field by its mean.
        let failed = vec![None, p[1]];
        assert!(wls.value(&failed, &s, &scales) > 1e3);
        assert!(Objective::likelihood(Some([0.5, 0.0, 0.3, 150.0, 150.0])).unwrap_err().to_string().contains("launch"));
        assert_eq!(Objective::default().name(), "eq_3_13");
    }

    #[test]
    fn gauss_newton_weights() {
        let s = shots(&[[100.0, 10.0, 1.0, 3000.0, 100.0], [110.0, 12.0, -1.0, 3200.0, -100.0]]);
        let scales = CostScales::of(&s);
        let p = vec![Some([102.0, 10.0, 0.5, 3100.0, 100.0]), None];
        let w = Objective::LeastAbsolute.step_weights(&p, &s, &scales);
        assert_eq!(w[1], [(0.0, 0.0); 5], "a failed shot weighs nothing");
        // Eq. 3.13: slope sign(r) / s_i; curvature 2 / (π s_i MAE_i), here MAE = |r| on the one predicted shot.
        assert_eq!(w[0][0].1, 1.0 / 105.0);
        assert_eq!(w[0][2].1, -1.0 / 1.0);
        assert!((w[0][3].0 - 2.0 / (std::f64::consts::PI * 3100.0 * 100.0)).abs() < 1e-18);
        // The normal density's 2 f(0) with σ = MAE sqrt(π/2): 2 / (σ sqrt(2π)) = 2 / (π MAE).
        let sigma = 2.0 * (std::f64::consts::PI / 2.0).sqrt();
        assert!((w[0][0].0 * 105.0 - 2.0 / (sigma * (2.0 * std::f64::consts::PI).sqrt())).abs() < 1e-15);
        let given = Objective::likelihood(Some([0.5, 0.2, 0.3, 150.0, 150.0])).unwrap().step_weights(&p, &s, &scales);
        for ((w, slope), want) in given[0].iter().zip([4.0, 25.0, 1.0 / 0.09, 1.0 / 22500.0, 1.0 / 22500.0]) {
            assert!((w / want - 1.0).abs() < 1e-12, "{w} against {want}");
            assert!(slope.is_finite());
        }
        assert!((given[0][0].1 - 4.0 * 2.0).abs() < 1e-12 && (given[0][3].1 - 100.0 / 22500.0).abs() < 1e-15);
        // Estimated noise: 1 / mean r² over the predicted shots.
        let estimated = Objective::likelihood(None).unwrap().step_weights(&p, &s, &scales);
        assert!((estimated[0][0].0 - 0.25).abs() < 1e-15 && (estimated[0][3].0 - 1e-4).abs() < 1e-18);
        assert!((estimated[0][2].1 - 4.0 * -0.5).abs() < 1e-12 && (estimated[0][2].0 - 4.0).abs() < 1e-12);
    }
}
