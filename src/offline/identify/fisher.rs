//! How well launch data can pin each parameter down: the Fisher information of the shots and its Cramér-Rao
//! bound.
//!
//! With independent normal launch-monitor errors of standard deviation `σ_i` per field, the Fisher information
//! of the parameters `θ` over the shots `j` is
//!
//! `F_kl = Σ_j Σ_i (∂x_sim,i,j/∂θ_k)(∂x_sim,i,j/∂θ_l) / σ_i²`
//!
//! (the derivatives by central differences of the model's launch), and no unbiased estimate of `θ_k` has a
//! standard deviation below `sqrt((F⁻¹)_kk)` (the Cramér-Rao bound), the bound when every parameter is
//! unknown; `1 / sqrt(F_kk)` is the bound when the others are known. Where the two differ by a large factor,
//! the parameter trades against others along a nearly flat direction of the cost. Eq. 3.13 is a least-absolute
//! criterion, whose efficiency under normal errors is 2/π, and it weights each field by `1 / mean|x_exp,i|`
//! rather than by `1 / σ_i`, so its estimates scatter more than the bound: [`l1_scatter`] gives their
//! asymptotic standard deviation, the sandwich `A⁻¹ B A⁻¹` of an M-estimator with
//! `A = Σ_j Σ_i w_i 2 f_i(0) g g'`, `B = Σ_j Σ_i w_i² g g'` (`g = ∂x_sim,i,j/∂θ`, `w_i = 1 / mean|x_exp,i|`,
//! `f_i(0) = 1 / (σ_i sqrt(2π))` the noise's density at zero, and `Var(sign ε) = 1`).

use crate::math::DMatrix;

use super::cost::evaluate;
use super::dataset::Shot;
use super::params::ParamSpace;
use super::IdentifyError;
use crate::equipment::{BallSpec, LoadedClub};
use crate::math::Real;

/// The bounds of one parameter (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bound {
    /// Every parameter unknown: `sqrt((F⁻¹)_kk)` (infinite for a singular information matrix).
    pub joint: Real,
    /// The others known: `1 / sqrt(F_kk)`.
    pub alone: Real,
}

/// The relative step of the central differences, of each parameter's bounds (linear) or value (logarithmic).
const STEP: Real = 1e-3;

/// The derivatives of each shot's five launch fields by each parameter of `space` at `values` (SI), by central
/// differences (one-sided at a bound): per shot, one row per parameter, `None` where the model failed.
pub fn jacobian(
    space: &ParamSpace,
    club: &LoadedClub,
    ball: &BallSpec,
    shots: &[Shot],
    values: &[Real],
) -> Result<Vec<Option<Vec<[Real; 5]>>>, IdentifyError> {
    let predict = |v: &[Real]| evaluate(space, &space.club_with(club, v), ball, shots);
    let base = predict(values)?;
    let mut per_param: Vec<Vec<Option<[Real; 5]>>> = Vec::with_capacity(space.defs.len());
    for (k, def) in space.defs.iter().enumerate() {
        let h = if def.log { STEP * values[k].abs() } else { STEP * (def.hi - def.lo) };
        let (lo, hi) = ((values[k] - h).max(def.lo), (values[k] + h).min(def.hi));
        let at = |x: Real| {
            let mut v = values.to_vec();
            v[k] = x;
            v
        };
        let minus = if lo < values[k] { predict(&at(lo))? } else { base.clone() };
        let plus = if hi > values[k] { predict(&at(hi))? } else { base.clone() };
        let span = hi - lo;
        per_param.push(
            minus
                .iter()
                .zip(&plus)
                .map(|(m, p)| match (m, p) {
                    (Some(m), Some(p)) if span > 0.0 => Some(std::array::from_fn(|i| (p[i] - m[i]) / span)),
                    _ => None,
                })
                .collect(),
        );
    }
    Ok((0..shots.len()).map(|j| per_param.iter().map(|g| g[j]).collect::<Option<Vec<_>>>()).collect())
}

/// `Σ_j Σ_i weight_i g_ik g_il` over the shots the model predicted.
fn weighted_gram(jacobian: &[Option<Vec<[Real; 5]>>], weight: &[Real; 5]) -> DMatrix {
    let d = jacobian.iter().flatten().next().map_or(0, Vec::len);
    let mut m = DMatrix::zeros(d, d);
    for row in jacobian.iter().flatten() {
        for k in 0..d {
            for l in 0..d {
                m[(k, l)] += (0..5).map(|i| weight[i] * row[k][i] * row[l][i]).sum::<Real>();
            }
        }
    }
    m
}

/// The Fisher information from a [`jacobian`] with noise `sigma` per launch field.
pub fn information_of(jacobian: &[Option<Vec<[Real; 5]>>], sigma: &[Real; 5]) -> DMatrix {
    weighted_gram(jacobian, &sigma.map(|s| 1.0 / (s * s)))
}

/// The Fisher information of `shots` about the parameters of `space` at `values` (SI), with noise `sigma` per
/// launch field. Shots the model fails on at any of the evaluation points are left out.
pub fn information(
    space: &ParamSpace,
    club: &LoadedClub,
    ball: &BallSpec,
    shots: &[Shot],
    values: &[Real],
    sigma: &[Real; 5],
) -> Result<DMatrix, IdentifyError> {
    Ok(information_of(&jacobian(space, club, ball, shots, values)?, sigma))
}

/// The asymptotic standard deviation of each parameter as eq. 3.13 estimates it (SI): the sandwich covariance
/// of a least-absolute fit weighted by `1 / scales` under normal noise `sigma` (module docs). Infinite where
/// the matrix is singular.
pub fn l1_scatter(jacobian: &[Option<Vec<[Real; 5]>>], sigma: &[Real; 5], scales: &[Real; 5]) -> Vec<Real> {
    let w: [Real; 5] = std::array::from_fn(|i| 1.0 / scales[i]);
    let density: [Real; 5] = std::array::from_fn(|i| 1.0 / (sigma[i] * (2.0 * std::f64::consts::PI).sqrt()));
    let a = weighted_gram(jacobian, &std::array::from_fn(|i| 2.0 * w[i] * density[i]));
    let b = weighted_gram(jacobian, &w.map(|x| x * x));
    let d = a.nrows();
    // Scaled to a unit diagonal before inverting, as in `bounds`.
    let scale: Vec<Real> = (0..d).map(|k| if a[(k, k)] > 0.0 { 1.0 / a[(k, k)].sqrt() } else { 0.0 }).collect();
    let scaled = DMatrix::from_fn(d, d, |k, l| a[(k, l)] * scale[k] * scale[l]);
    let Some(inv) = scaled.try_inverse() else { return vec![Real::INFINITY; d] };
    let a_inv = DMatrix::from_fn(d, d, |k, l| inv[(k, l)] * scale[k] * scale[l]);
    let cov = &a_inv * b * &a_inv;
    (0..d).map(|k| if cov[(k, k)] > 0.0 { cov[(k, k)].sqrt() } else { Real::INFINITY }).collect()
}

/// The Cramér-Rao bounds of each parameter from a Fisher information matrix (SI).
pub fn bounds(f: &DMatrix) -> Vec<Bound> {
    let d = f.nrows();
    // Inverted as a correlation-like matrix (unit diagonal), which keeps parameters of very different scales
    // (N/m³ beside mm) well conditioned.
    let scale: Vec<Real> = (0..d).map(|k| if f[(k, k)] > 0.0 { 1.0 / f[(k, k)].sqrt() } else { 0.0 }).collect();
    let scaled = DMatrix::from_fn(d, d, |k, l| f[(k, l)] * scale[k] * scale[l]);
    let inverse = scaled.try_inverse();
    (0..d)
        .map(|k| {
            let alone = if scale[k] > 0.0 { scale[k] } else { Real::INFINITY };
            let joint = match &inverse {
                Some(inv) if inv[(k, k)] > 0.0 && scale[k] > 0.0 => inv[(k, k)].sqrt() * scale[k],
                _ => Real::INFINITY,
            };
            Bound { joint, alone }
        })
        .collect()
}

/// The standard deviation per field of the residuals (predicted - measured): the noise the fit leaves, with the
/// `params` fitted parameters' degrees of freedom taken out (`Σ r² / (n - params)`). With no more predicted shots
/// than parameters the residuals say nothing about the noise (one shot is fitted exactly): the noise is then
/// unknown, returned as infinite, so no bound claims a parameter is pinned down (a bound of 0).
pub fn residual_sigma(predictions: &[Option<[Real; 5]>], shots: &[Shot], params: usize) -> [Real; 5] {
    let mut sum = [0.0; 5];
    let mut n = 0.0;
    for (p, s) in predictions.iter().zip(shots) {
        if let Some(p) = p {
            for i in 0..5 {
                sum[i] += (p[i] - s.measured[i]).powi(2);
            }
            n += 1.0;
        }
    }
    let dof = n - params as Real;
    sum.map(|v| if dof > 0.0 { (v / dof).sqrt() } else { Real::INFINITY })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_least_absolute_fit_of_a_mean_scatters_sqrt_pi_over_2_times_the_bound() {
        // One parameter moving one field by 1 per unit over n shots: the bound is σ / sqrt(n), and the median
        // (the least-absolute estimate of a location) scatters sqrt(π/2) times more.
        let n = 400;
        let jac: Vec<Option<Vec<[Real; 5]>>> = (0..n).map(|_| Some(vec![[1.0, 0.0, 0.0, 0.0, 0.0]])).collect();
        let sigma = [2.0, 1.0, 1.0, 1.0, 1.0];
        let bound = bounds(&information_of(&jac, &sigma))[0].joint;
        assert!((bound - 2.0 / (n as Real).sqrt()).abs() < 1e-12);
        let scatter = l1_scatter(&jac, &sigma, &[150.0, 1.0, 1.0, 1.0, 1.0])[0];
        assert!((scatter / bound - (std::f64::consts::PI / 2.0).sqrt()).abs() < 1e-9, "{scatter} {bound}");
    }

    #[test]
    fn the_bounds_of_a_diagonal_and_a_correlated_information() {
        // Diagonal: each bound is 1/sqrt(F_kk), alone or jointly.
        let f = DMatrix::from_row_slice(2, 2, &[4.0, 0.0, 0.0, 100.0]);
        let b = bounds(&f);
        assert!((b[0].joint - 0.5).abs() < 1e-12 && (b[1].alone - 0.1).abs() < 1e-12);
        // Correlation 0.99: the joint bound is 1/sqrt(1 - 0.99²) = 7.09 times the bound alone.
        let f = DMatrix::from_row_slice(2, 2, &[1.0, 0.99, 0.99, 1.0]);
        let b = bounds(&f);
        assert!((b[0].joint / b[0].alone - 1.0 / (1.0 - 0.99f64.powi(2)).sqrt()).abs() < 1e-9);
        // Singular: the joint bound is infinite.
        let f = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0]);
        assert!(bounds(&f)[0].joint.is_infinite() || bounds(&f)[0].joint > 1e6);
    }
}
