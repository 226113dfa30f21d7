//! What a single-ball model can reach on TrackMan's tour table: carry against land angle. One ball (one set of
//! [`super::Aero`] coefficients, each inside its published range) flies every club; fitting with carry scaled by
//! 4 % of each club's carry and the land angle by a tolerance swept from tight to loose, with apex held to a
//! tolerance or left out, traces the front of what is reachable: for each largest land-angle error, the largest
//! carry error (percent) and apex error a ball inside the published ranges pairs with it.

use super::fit::{fit_with, predict, Tolerance, TourAverage, START};
use super::Aero;
use crate::math::Real;

/// The carry tolerance the sweep scales by (%): the accuracy asked of every club.
pub const CARRY_PCT: Real = 4.0;

/// The land-angle tolerances swept (deg).
pub const LAND_DEG: [Real; 8] = [1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0];

/// One point of the front: the fit's tolerance and what it reached.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TradeoffPoint {
    /// The apex tolerance the fit scaled by (yd), `None` when apex was left out.
    pub apex_tolerance_yd: Option<Real>,
    /// The land-angle tolerance the fit scaled by (deg).
    pub land_tolerance_deg: Real,
    /// Largest land-angle error over the clubs (deg).
    pub max_land_angle_error_deg: Real,
    /// Largest carry error over the clubs (% of the measured carry).
    pub max_carry_error_pct: Real,
    /// Largest apex error (yd).
    pub max_apex_error_yd: Real,
    /// The club with the largest carry error and the one with the largest land-angle error.
    pub worst_carry_club: usize,
    /// Index (in the rows) of the club with the largest land-angle error.
    pub worst_land_club: usize,
    /// The coefficients these errors are of.
    pub aero: Aero,
}

/// Largest errors of `aero` on `rows`: (land deg, carry %, apex yd, club of the carry, club of the land angle).
pub fn largest_errors(aero: &Aero, rows: &[TourAverage]) -> (Real, Real, Real, usize, usize) {
    let mut out = (0.0, 0.0, 0.0, 0, 0);
    for (i, r) in rows.iter().enumerate() {
        let (carry, apex, land) = predict(aero, r);
        let carry_pct = (100.0 * (carry - r.carry_yd) / r.carry_yd).abs();
        let land_err = (land - r.land_angle_deg).abs();
        if land_err > out.0 {
            out.0 = land_err;
            out.4 = i;
        }
        if carry_pct > out.1 {
            out.1 = carry_pct;
            out.3 = i;
        }
        out.2 = Real::max(out.2, (apex - r.max_height_yd).abs());
    }
    out
}

/// The front, one fit per land-angle tolerance of [`LAND_DEG`] (each from [`START`], `iterations` Nelder-Mead
/// iterations per restart, then minimax), apex scaled by `apex_yd` or left out; `progress` hears each point as
/// it is done.
pub fn front(
    rows: &[TourAverage],
    iterations: usize,
    apex_yd: Option<Real>,
    mut progress: impl FnMut(&TradeoffPoint),
) -> Vec<TradeoffPoint> {
    LAND_DEG
        .iter()
        .map(|&land| {
            let tol = Tolerance {
                carry_yd: 0.0,
                carry_pct: Some(CARRY_PCT),
                apex_yd,
                land_angle_deg: land,
                envelope: Some(super::fit::ENVELOPE),
            };
            let f = fit_with(rows, &START, iterations, &tol, |_| {});
            let (l, c, a, wc, wl) = largest_errors(&f.aero, rows);
            let p = TradeoffPoint {
                apex_tolerance_yd: apex_yd,
                land_tolerance_deg: land,
                max_land_angle_error_deg: l,
                max_carry_error_pct: c,
                max_apex_error_yd: a,
                worst_carry_club: wc,
                worst_land_club: wl,
                aero: f.aero,
            };
            progress(&p);
            p
        })
        .collect()
}

/// The apex tolerances of the two fronts `impactd flight-fit --tradeoff` draws: the table's 3 yd, and apex left out.
pub const APEX_YD: [Option<Real>; 2] = [super::fit::TOLERANCE.apex_yd, None];
