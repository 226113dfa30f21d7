//! Leave-one-club-out cross-validation of the fit ([`super::fit`]): for each club of the table, the coefficients
//! are fitted from [`super::fit::START`] to the other eleven and the left-out club is predicted with them. The
//! errors measure how the fit generalises to a launch it has not seen, not how well it interpolates its own data.

use super::fit::{self, TourAverage};
use crate::math::Real;

/// One club of the table against the model.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ClubError {
    /// The club's name in the table.
    pub club: String,
    /// Measured carry (yd).
    pub carry_yd: Real,
    /// Predicted − measured carry (yd).
    pub carry_error_yd: Real,
    /// Measured apex (yd).
    pub apex_yd: Real,
    /// Predicted − measured apex (yd).
    pub apex_error_yd: Real,
    /// Measured land angle (deg).
    pub land_angle_deg: Real,
    /// Predicted − measured land angle (deg).
    pub land_angle_error_deg: Real,
}

impl ClubError {
    /// Whether carry, apex and land angle are all within the given errors.
    pub fn within(&self, carry_yd: Real, apex_yd: Real, land_deg: Real) -> bool {
        self.carry_error_yd.abs() <= carry_yd
            && self.apex_error_yd.abs() <= apex_yd
            && self.land_angle_error_deg.abs() <= land_deg
    }

    /// The carry error in percent of the measured carry.
    pub fn carry_error_pct(&self) -> Real {
        let measured = self.carry_yd - self.carry_error_yd;
        100.0 * self.carry_error_yd / measured
    }

    /// Whether carry (in percent of the measured), apex and land angle are all within the given errors.
    pub fn within_pct(&self, carry_pct: Real, apex_yd: Real, land_deg: Real) -> bool {
        self.carry_error_pct().abs() <= carry_pct
            && self.apex_error_yd.abs() <= apex_yd
            && self.land_angle_error_deg.abs() <= land_deg
    }
}

/// Every club's predicted carry, apex and land angle with `aero`, and the errors against the table.
pub fn club_errors(aero: &super::Aero, rows: &[TourAverage]) -> Vec<ClubError> {
    rows.iter()
        .map(|r| {
            let (carry, apex, land) = fit::predict(aero, r);
            ClubError {
                club: r.club.clone(),
                carry_yd: carry,
                carry_error_yd: carry - r.carry_yd,
                apex_yd: apex,
                apex_error_yd: apex - r.max_height_yd,
                land_angle_deg: land,
                land_angle_error_deg: land - r.land_angle_deg,
            }
        })
        .collect()
}

/// One left-out club: what the table says and what the fit without it predicts.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Holdout {
    /// The club left out.
    pub club: String,
    /// Its measured carry (yd).
    pub carry_yd: Real,
    /// Its carry predicted by the fit to the other clubs (yd).
    pub predicted_carry_yd: Real,
    /// `100 (predicted − measured) / measured`.
    pub carry_error_pct: Real,
    /// Predicted − measured apex (yd).
    pub apex_error_yd: Real,
    /// Predicted − measured land angle (deg).
    pub land_angle_error_deg: Real,
}

/// The cross-validation: every club left out once, and the largest errors.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CrossValidation {
    /// Every club, left out once, in the table's order.
    pub holdouts: Vec<Holdout>,
    /// Largest carry error over the holdouts (% of the measured carry, absolute).
    pub max_carry_error_pct: Real,
    /// Largest apex error (yd, absolute).
    pub max_apex_error_yd: Real,
    /// Largest land-angle error (deg, absolute).
    pub max_land_angle_error_deg: Real,
}

/// Leaves each club out in turn, fitting the rest with `iterations` Nelder-Mead iterations per restart (as
/// [`fit::fit`]); `progress` hears each club as it is done.
pub fn leave_one_out(rows: &[TourAverage], iterations: usize, mut progress: impl FnMut(&Holdout)) -> CrossValidation {
    let holdouts = (0..rows.len())
        .map(|i| {
            let h = hold_out(rows, i, iterations);
            progress(&h);
            h
        })
        .collect();
    CrossValidation::of(holdouts)
}

/// Club `i` of `rows` left out: the fit to the others (`iterations` as [`leave_one_out`]) and its prediction of
/// the club. Each is independent of the others, so a caller may run them side by side.
pub fn hold_out(rows: &[TourAverage], i: usize, iterations: usize) -> Holdout {
    let held = &rows[i];
    let rest: Vec<TourAverage> = rows.iter().enumerate().filter(|(j, _)| *j != i).map(|(_, r)| r.clone()).collect();
    let fitted = fit::fit(&rest, &fit::START, iterations, |_| {});
    let (carry, apex, land) = fit::predict(&fitted.aero, held);
    Holdout {
        club: held.club.clone(),
        carry_yd: held.carry_yd,
        predicted_carry_yd: carry,
        carry_error_pct: 100.0 * (carry - held.carry_yd) / held.carry_yd,
        apex_error_yd: apex - held.max_height_yd,
        land_angle_error_deg: land - held.land_angle_deg,
    }
}

impl CrossValidation {
    /// The cross-validation of these holdouts (in the table's order): they and their largest errors.
    pub fn of(holdouts: Vec<Holdout>) -> CrossValidation {
        let max = |f: fn(&Holdout) -> Real| holdouts.iter().map(|h| f(h).abs()).fold(0.0, Real::max);
        CrossValidation {
            max_carry_error_pct: max(|h| h.carry_error_pct),
            max_apex_error_yd: max(|h| h.apex_error_yd),
            max_land_angle_error_deg: max(|h| h.land_angle_error_deg),
            holdouts,
        }
    }
}
