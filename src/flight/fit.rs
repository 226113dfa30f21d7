//! Fitting the aerodynamic coefficients to the TrackMan PGA Tour averages: every club's carry, apex (max height)
//! and land angle at once, by Nelder-Mead on ten coefficients (the logarithms of the eight that must stay
//! positive, the two airspeed slopes as they are), minimising the sum of squared errors scaled by the accuracy each
//! must reach (3 yd, 2 yd, 2 deg) plus a strong penalty on any error beyond 90 % of it. Deterministic: the same
//! table gives the same coefficients.

use super::{Aero, Conditions, Flight};
use crate::math::Real;
use crate::units::mph_to_mps;

/// One row of the TrackMan table.
#[derive(Debug, Clone, PartialEq)]
pub struct TourAverage {
    pub club: String,
    pub ball_speed_mph: Real,
    pub launch_angle_deg: Real,
    pub spin_rpm: Real,
    pub max_height_yd: Real,
    pub land_angle_deg: Real,
    pub carry_yd: Real,
}

/// The table shipped with the tests (`tests/data/trackman-pga-tour-averages.csv`).
pub const TRACKMAN_CSV: &str = include_str!("../../tests/data/trackman-pga-tour-averages.csv");

/// Parses the CSV (comment lines start with `#`).
pub fn parse_table(csv: &str) -> Result<Vec<TourAverage>, String> {
    let mut lines = csv.lines().filter(|l| !l.trim().is_empty() && !l.starts_with('#'));
    let header: Vec<&str> = lines.next().ok_or("empty table")?.split(',').map(str::trim).collect();
    let col = |name: &str| header.iter().position(|h| *h == name).ok_or(format!("no column `{name}`"));
    let (c_club, c_bs, c_la, c_spin, c_h, c_land, c_carry) = (
        col("club")?,
        col("ball_speed_mph")?,
        col("launch_angle_deg")?,
        col("spin_rpm")?,
        col("max_height_yd")?,
        col("land_angle_deg")?,
        col("carry_yd")?,
    );
    lines
        .enumerate()
        .map(|(i, line)| {
            let f: Vec<&str> = line.split(',').map(str::trim).collect();
            let num =
                |c: usize| f.get(c).and_then(|v| v.parse::<Real>().ok()).ok_or(format!("row {}: column {c}", i + 1));
            Ok(TourAverage {
                club: f.get(c_club).ok_or("no club")?.to_string(),
                ball_speed_mph: num(c_bs)?,
                launch_angle_deg: num(c_la)?,
                spin_rpm: num(c_spin)?,
                max_height_yd: num(c_h)?,
                land_angle_deg: num(c_land)?,
                carry_yd: num(c_carry)?,
            })
        })
        .collect()
}

/// The model's carry, apex and land angle for one row, all spin taken as backspin.
pub fn predict(aero: &Aero, row: &TourAverage) -> (Real, Real, Real) {
    let f = Flight { aero: *aero, conditions: Conditions::default(), ..Flight::default() };
    let t = f.fly_metrics(mph_to_mps(row.ball_speed_mph), row.launch_angle_deg, 0.0, row.spin_rpm, 0.0);
    (t.carry_yd, t.apex_yd, t.land_angle_deg)
}

/// The fit's objective for a set of coefficients.
pub fn cost(aero: &Aero, rows: &[TourAverage]) -> Real {
    rows.iter()
        .map(|r| {
            let (carry, apex, land) = predict(aero, r);
            let e = [(carry - r.carry_yd) / 3.0, (apex - r.max_height_yd) / 2.0, (land - r.land_angle_deg) / 2.0];
            e.iter()
                .map(|x| if x.is_finite() { x * x + PENALTY * (x.abs() - PENALTY_FROM).max(0.0).powi(2) } else { 1e6 })
                .sum::<Real>()
        })
        .sum()
}

/// An error beyond `PENALTY_FROM` of its accuracy costs `PENALTY` times its square beyond it more: the fit trades
/// the sum of squares for keeping every club within reach of the targets.
const PENALTY: Real = 1000.0;
const PENALTY_FROM: Real = 0.9;

const N: usize = 10;

/// The narrowest drag-crisis transition the fit may use (a Reynolds number span of about 5,500 at sea level): the
/// fit would otherwise sharpen it into a step placed at one club's descent speed.
pub const MIN_CRISIS_WIDTH_MPS: Real = 2.0;

/// The spin decay, measured, not fitted: a time constant of 22 s at 50 m/s, Smits and Smith's (1994) decay rate
/// `0.0004 · V[mph] · ω` per second (about 4.5 % of the spin per second at 50 m/s). Left free, the fit swings
/// between no decay at all and spin gone within two seconds, neither of which any measurement shows.
pub const SPIN_TAU_S: Real = 22.0;

/// Where the fit starts: textbook magnitudes (drag 0.2-0.3, lift rising with spin to about 0.3, a drag crisis near
/// 32 m/s, Re 9·10⁴, no airspeed dependence beyond it), so that `impactd flight-fit` reproduces `Aero::FITTED` from the table alone.
pub const START: Aero = Aero {
    c_d0: 0.2,
    c_ds: 0.3,
    c_dq: 1.0,
    c_dc: 0.15,
    c_dv: 0.0,
    v_crisis_mps: 32.0,
    v_width_mps: 3.0,
    c_l1: 2.4,
    c_l2: 5.3,
    c_lv: 0.0,
    spin_tau_s: SPIN_TAU_S,
};

fn to_aero(x: &[Real; N]) -> Aero {
    Aero {
        c_d0: x[0].exp(),
        c_ds: x[1].exp(),
        c_dq: x[2].exp(),
        c_dc: x[3].exp(),
        v_crisis_mps: x[4].exp(),
        v_width_mps: MIN_CRISIS_WIDTH_MPS + x[5].exp(),
        c_l1: x[6].exp(),
        c_l2: x[7].exp(),
        c_dv: x[8],
        c_lv: x[9],
        spin_tau_s: SPIN_TAU_S,
    }
}

fn from_aero(a: &Aero) -> [Real; N] {
    [
        a.c_d0.ln(),
        a.c_ds.ln(),
        a.c_dq.max(1e-6).ln(),
        a.c_dc.max(1e-6).ln(),
        a.v_crisis_mps.ln(),
        (a.v_width_mps - MIN_CRISIS_WIDTH_MPS).max(1e-4).ln(),
        a.c_l1.ln(),
        a.c_l2.ln(),
        a.c_dv,
        a.c_lv,
    ]
}

const RESTARTS: usize = 8;

/// Nelder-Mead from `start`, restarted from its own best point up to `RESTARTS` times (a fresh simplex escapes the
/// collapses that stall a single run); returns the best coefficients and their cost. `progress` hears the cost after
/// each run (run number from 1, cost).
pub fn fit(
    rows: &[TourAverage],
    start: &Aero,
    iterations: usize,
    mut progress: impl FnMut(usize, Real),
) -> (Aero, Real) {
    let mut best = (*start, cost(start, rows));
    for run in 1..=RESTARTS {
        let next = nelder_mead(rows, &best.0, iterations);
        progress(run, next.1);
        if next.1 >= best.1 - 1e-9 {
            break;
        }
        best = next;
    }
    best
}

fn nelder_mead(rows: &[TourAverage], start: &Aero, iterations: usize) -> (Aero, Real) {
    let f = |x: &[Real; N]| cost(&to_aero(x), rows);
    let x0 = from_aero(start);
    let mut simplex: Vec<([Real; N], Real)> = vec![(x0, f(&x0))];
    for i in 0..N {
        let mut x = x0;
        x[i] += 0.25;
        simplex.push((x, f(&x)));
    }
    for _ in 0..iterations {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let n = simplex.len() - 1;
        let mut centroid = [0.0; N];
        for (x, _) in &simplex[..n] {
            for k in 0..N {
                centroid[k] += x[k] / n as Real;
            }
        }
        let worst = simplex[n];
        let along = |t: Real| {
            let mut x = [0.0; N];
            for k in 0..N {
                x[k] = centroid[k] + t * (worst.0[k] - centroid[k]);
            }
            x
        };
        let xr = along(-1.0);
        let fr = f(&xr);
        if fr < simplex[0].1 {
            let xe = along(-2.0);
            let fe = f(&xe);
            simplex[n] = if fe < fr { (xe, fe) } else { (xr, fr) };
        } else if fr < simplex[n - 1].1 {
            simplex[n] = (xr, fr);
        } else {
            let xc = if fr < worst.1 { along(-0.5) } else { along(0.5) };
            let fc = f(&xc);
            if fc < worst.1.min(fr) {
                simplex[n] = (xc, fc);
            } else {
                let best = simplex[0].0;
                for (x, fx) in simplex.iter_mut().skip(1) {
                    for k in 0..N {
                        x[k] = best[k] + 0.5 * (x[k] - best[k]);
                    }
                    *fx = f(x);
                }
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    (to_aero(&simplex[0].0), simplex[0].1)
}
