//! What "physical" means for a set of coefficients, as numbers a fit can hold: over 20-90 m/s and 1,000-11,000
//! rpm the drag and lift stay between the lower and the higher of Bearman and Harvey's wind tunnel and Lyu et
//! al.'s free flight at the same airspeed and spin, widened by the ball-to-ball spread Lyu et al. report (0.05
//! above Re 10⁵, 0.10 below); above the drag crisis the drag at a fixed spin ratio (0.12, 0.15, 0.18) rises from
//! 40 to 88.1 m/s no more than Bearman and Harvey's does. `crates/golf-physics/tests/flight.rs` asserts the same of `Aero::FITTED`;
//! [`violations`] measures how far a set of coefficients is outside (0 inside), so a fit can be kept inside.

use super::aero::reynolds;
use super::reference::{bearman_harvey, lyu, BH_CD, BH_CL};
use super::{Aero, Flight};
use crate::math::Real;
use crate::units::{radps_to_rpm, rpm_to_radps};

/// The model's drag, lift and spin ratio at airspeed `v_mps` and `rpm` in the default (sea-level) air.
pub fn coefficients_at(aero: &Aero, v_mps: Real, rpm: Real) -> (Real, Real, Real) {
    let f = Flight::default();
    let c = f.conditions;
    let r = f.ball.radius_m;
    let re = reynolds(v_mps, 2.0 * r, c.density_kg_m3(), c.viscosity_pa_s());
    let s = r * rpm_to_radps(rpm) / v_mps;
    let (d, l) = aero.coefficients(re, s);
    (d, l, s)
}

/// The envelope of drag and lift at one airspeed and spin: ((drag low, high), (lift low, high)).
pub fn bounds_at(v_mps: Real, rpm: Real, spin_ratio: Real) -> ((Real, Real), (Real, Real)) {
    let (lyu_d, lyu_l) = lyu(v_mps, spin_ratio);
    let (bh_d, bh_l) = (bearman_harvey(&BH_CD, v_mps, rpm), bearman_harvey(&BH_CL, v_mps, rpm));
    let tol = if v_mps * 0.043 / 1.48e-5 >= 1e5 { 0.05 } else { 0.10 };
    ((bh_d.min(lyu_d) - tol, bh_d.max(lyu_d) + tol), (bh_l.min(lyu_l) - tol, bh_l.max(lyu_l) + tol))
}

/// The airspeeds (m/s) and spins (rpm) the envelope is checked at.
pub fn grid() -> impl Iterator<Item = (Real, Real)> {
    (20..=90).step_by(5).flat_map(|v| (1000..=11000).step_by(500).map(move |rpm| (Real::from(v), Real::from(rpm))))
}

/// How far inside its bounds [`violations`] asks a coefficient to stay: a fit that holds the violations to a
/// fraction of this lands strictly inside the envelope.
pub const MARGIN: Real = 1e-3;

fn outside(x: Real, (lo, hi): (Real, Real)) -> Real {
    (lo + MARGIN - x).max(0.0) + (x - (hi - MARGIN)).max(0.0)
}

/// How far `aero` is outside the envelope less [`MARGIN`], one number per check (coefficient units, 0 inside):
/// the drag and the lift at every point of [`grid`], then the drag's rise above the crisis at each spin ratio.
pub fn violations(aero: &Aero) -> Vec<Real> {
    let mut out = Vec::with_capacity(2 * 15 * 21 + 3);
    for (v, rpm) in grid() {
        let (d, l, s) = coefficients_at(aero, v, rpm);
        let (db, lb) = bounds_at(v, rpm, s);
        out.push(outside(d, db));
        out.push(outside(l, lb));
    }
    let r = Flight::default().ball.radius_m;
    for s in [0.12, 0.15, 0.18] {
        let rpm = |v: Real| radps_to_rpm(s * v / r);
        let bh_rise = bearman_harvey(&BH_CD, 88.1, rpm(88.1)) - bearman_harvey(&BH_CD, 40.0, rpm(40.0));
        let rise = coefficients_at(aero, 88.1, rpm(88.1)).0 - coefficients_at(aero, 40.0, rpm(40.0)).0;
        out.push((rise - (bh_rise.max(0.0) - MARGIN)).max(0.0));
    }
    out
}
