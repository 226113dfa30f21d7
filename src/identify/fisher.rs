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
//! criterion, whose efficiency under normal errors is 2/π, so its estimates scatter by about `sqrt(π/2)` = 1.25
//! times the bound.

use nalgebra::DMatrix;

use super::dataset::Shot;
use super::fit::evaluate;
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

/// The Fisher information of `shots` about the parameters of `space` at `values` (SI), with noise `sigma` per
/// launch field. Shots the model fails on at any of the evaluation points are left out.
pub fn information(
    space: &ParamSpace,
    club: &LoadedClub,
    ball: &BallSpec,
    shots: &[Shot],
    values: &[Real],
    sigma: &[Real; 5],
) -> Result<DMatrix<Real>, IdentifyError> {
    let d = space.defs.len();
    let predict = |v: &[Real]| evaluate(space, &space.club_with(club, v), ball, shots);
    // Per parameter: the two points and the distance between them.
    let mut derivatives: Vec<Vec<Option<[Real; 5]>>> = Vec::with_capacity(d);
    let base = predict(values)?;
    for (k, def) in space.defs.iter().enumerate() {
        let h = if def.log { STEP * values[k].abs() } else { STEP * (def.hi - def.lo) };
        let (lo, hi) = ((values[k] - h).max(def.lo), (values[k] + h).min(def.hi));
        let at = |x: Real| {
            let mut v = values.to_vec();
            v[k] = x;
            v
        };
        let (minus, plus) = (
            if lo < values[k] { predict(&at(lo))? } else { base.clone() },
            if hi > values[k] { predict(&at(hi))? } else { base.clone() },
        );
        let span = hi - lo;
        derivatives.push(
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
    let mut f = DMatrix::<Real>::zeros(d, d);
    for j in 0..shots.len() {
        let Some(row) = derivatives.iter().map(|g| g[j]).collect::<Option<Vec<[Real; 5]>>>() else { continue };
        for k in 0..d {
            for l in 0..d {
                f[(k, l)] += (0..5).map(|i| row[k][i] * row[l][i] / (sigma[i] * sigma[i])).sum::<Real>();
            }
        }
    }
    Ok(f)
}

/// The Cramér-Rao bounds of each parameter from a Fisher information matrix (SI).
pub fn bounds(f: &DMatrix<Real>) -> Vec<Bound> {
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

/// The standard deviation per field of the residuals (predicted - measured): the noise the fit leaves.
pub fn residual_sigma(predictions: &[Option<[Real; 5]>], shots: &[Shot]) -> [Real; 5] {
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
    sum.map(|v| if n > 0.0 { (v / n).sqrt() } else { Real::NAN })
}

#[cfg(test)]
mod tests {
    use super::*;

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
