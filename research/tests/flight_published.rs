//! An independent check of the TrackMan tour table: published ball flights with published coefficients and no
//! fitting at all.
//!
//! - The wind-tunnel ball: drag and lift are Bearman and Harvey's measurements of a dimpled ball (1976, as
//!   tabulated over airspeed and spin rate in `impactd::flight::reference`, bilinear between their points and held
//!   at the edge of what they measured), the spin decays at Smits and Smith's measured rate (`0.0004 · V[mph] · ω`
//!   per second, as quoted by Dewhurst, *The Science of the Perfect Swing*); the trajectory model of NTNU's TKT4140
//!   course material, which ships those tables.
//! - Nathan's golf trajectory model with the coefficients libgolf publishes for it (`reference::nathan`).
//!
//! Both fly the same ball in the same air as the model. What they show (`research/flight-fit.md`, "Is the table within
//! physical reach?"): both carry the slower drives of TrackMan's optimal-driver chart within 4 %, and both leave
//! the table's driver-to-3-wood gap (275 − 243 = 32 yd) 10-14 yd short, as the fitted model leaves it 11.2 yd
//! short: the conflict between those two rows is in the table's launches, not in the fitted model's shape. Neither
//! the air density of the table's unstated conditions (1.15-1.225 kg/m³) nor the spin decay (none to twice Smits
//! and Smith's) closes it: the gap stays 11.5-14.3 yd short.

#![allow(clippy::unwrap_used)]

use impactd::equipment::BallSpec;
use impactd::flight::reference::{bearman_harvey, nathan, BH_CD, BH_CL};
use impactd::flight::{fit, Aero, Conditions};
use impactd::units::{m_to_yd, mph_to_mps};

const G: f64 = 9.80665;

/// Spin decay: Smits and Smith's `dω/dt = −k · V[mph] · ω` with `k` = 0.0004 per mph per second.
const SMITS_SMITH_PER_MPH_S: f64 = 0.0004;

/// Carry (yd), apex (yd) and land angle (deg) of a ball launched at `speed_mps`, `launch_deg`, `spin_rpm` of
/// backspin, in air of density `rho`, with drag and lift `coefficients(airspeed m/s, spin rpm)` and the spin
/// decaying at `decay_per_s(airspeed m/s)` of itself per second. Classical RK4 at 1 ms on (x, y, vx, vy, ω), the
/// landing interpolated linearly within the last millisecond.
fn fly_with(
    speed_mps: f64,
    launch_deg: f64,
    spin_rpm: f64,
    rho: f64,
    coefficients: impl Fn(f64, f64) -> (f64, f64),
    decay_per_s: impl Fn(f64) -> f64,
) -> (f64, f64, f64) {
    let ball = BallSpec::SEED;
    let k = 0.5 * rho * std::f64::consts::PI * ball.radius_m * ball.radius_m / ball.mass_kg;
    let rate = |s: [f64; 5]| {
        let [_, _, vx, vy, rpm] = s;
        let v = vx.hypot(vy);
        let (cd, cl) = coefficients(v, rpm);
        [vx, vy, -k * v * (cd * vx + cl * vy), -G + k * v * (cl * vx - cd * vy), -decay_per_s(v) * rpm]
    };
    let add = |s: [f64; 5], d: [f64; 5], h: f64| std::array::from_fn::<f64, 5, _>(|i| s[i] + h * d[i]);
    let th = launch_deg.to_radians();
    let mut s = [0.0, 0.0, speed_mps * th.cos(), speed_mps * th.sin(), spin_rpm];
    let (h, mut apex) = (1e-3, 0.0_f64);
    for _ in 0..20_000 {
        let k1 = rate(s);
        let k2 = rate(add(s, k1, h / 2.0));
        let k3 = rate(add(s, k2, h / 2.0));
        let k4 = rate(add(s, k3, h));
        let n: [f64; 5] = std::array::from_fn(|i| s[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
        if n[1] < 0.0 && n[3] < 0.0 {
            let u = s[1] / (s[1] - n[1]);
            let at = |i: usize| s[i] + u * (n[i] - s[i]);
            return (m_to_yd(at(0)), m_to_yd(apex), (-at(3)).atan2(at(2)).to_degrees());
        }
        apex = apex.max(n[1]);
        s = n;
    }
    panic!("the ball never landed");
}

/// The wind-tunnel ball: Bearman and Harvey's drag and lift, the spin decaying `decay` times Smits and Smith's
/// rate.
fn fly_published(speed_mps: f64, launch_deg: f64, spin_rpm: f64, rho: f64, decay: f64) -> (f64, f64, f64) {
    fly_with(
        speed_mps,
        launch_deg,
        spin_rpm,
        rho,
        |v, rpm| (bearman_harvey(&BH_CD, v, rpm), bearman_harvey(&BH_CL, v, rpm)),
        |v| decay * SMITS_SMITH_PER_MPH_S * impactd::units::mps_to_mph(v),
    )
}

/// Nathan's coefficients ([`nathan`]) at airspeed `speed_mps` and spin `rpm`, in the model's air.
fn nathan_coefficients(speed_mps: f64, rpm: f64) -> (f64, f64) {
    let c = Conditions::default();
    let r = BallSpec::SEED.radius_m;
    let re = impactd::flight::aero::reynolds(speed_mps, 2.0 * r, c.density_kg_m3(), c.viscosity_pa_s());
    nathan(re, r * impactd::units::rpm_to_radps(rpm) / speed_mps)
}

/// Nathan's model: his coefficients and spin decay time constant `r / (2·10⁻⁵ v)`.
fn fly_nathan(speed_mps: f64, launch_deg: f64, spin_rpm: f64) -> (f64, f64, f64) {
    let r = BallSpec::SEED.radius_m;
    fly_with(speed_mps, launch_deg, spin_rpm, rho(), nathan_coefficients, |v| 2e-5 * v / r)
}

fn rows() -> Vec<fit::TourAverage> {
    fit::parse_table(fit::TRACKMAN_CSV).unwrap()
}

fn rho() -> f64 {
    Conditions::default().density_kg_m3()
}

/// The wind-tunnel ball against the tour table: the driver 13 yd short (its measured drag and lift give the
/// 167 mph, 2,686 rpm launch no more carry), every other club within 4 yd of carry and 3 yd of apex; land angles
/// 3-7 deg shallower than the table's for the clubs from the 3-wood to the pitching wedge.
#[test]
fn the_wind_tunnel_ball_misses_the_tour_driver() {
    let rows = rows();
    let mut errors = Vec::new();
    for r in &rows {
        let (carry, apex, land) =
            fly_published(mph_to_mps(r.ball_speed_mph), r.launch_angle_deg, r.spin_rpm, rho(), 1.0);
        eprintln!(
            "{:7} carry {carry:6.1} ({:+5.1})  apex {apex:5.1} ({:+4.1})  land {land:5.1} ({:+4.1})",
            r.club,
            carry - r.carry_yd,
            apex - r.max_height_yd,
            land - r.land_angle_deg
        );
        errors.push((carry - r.carry_yd, apex - r.max_height_yd, land - r.land_angle_deg));
    }
    let (driver, rest) = errors.split_first().unwrap();
    assert!((-14.5..=-11.5).contains(&driver.0), "driver carry error {:+.1} yd", driver.0);
    assert!(driver.1.abs() <= 1.5 && driver.2.abs() <= 1.5, "driver apex and land {driver:?}");
    for (r, e) in rows[1..].iter().zip(rest) {
        assert!(e.0.abs() <= 4.0 && e.1.abs() <= 3.1, "{}: {e:?}", r.club);
        assert!((-7.5..=-2.5).contains(&e.2), "{}: land {:+.1}", r.club, e.2);
    }
}

/// The driver-to-3-wood carry gap (the table: 275 − 243 = 32 yd) is short by more in the wind-tunnel ball
/// (about 14 yd) than in the best model inside the measured ranges fitted in yards (11.2 yd, `research/flight-fit.md`),
/// whatever the air density between a warm day and the standard atmosphere and whatever the spin decay from none
/// to twice Smits and Smith's. The shipped fit, scaled in percent of carry, leaves 13.5 yd.
#[test]
fn no_density_or_spin_decay_closes_the_driver_gap() {
    let rows = rows();
    let gap_error = |rho: f64, decay: f64| {
        let carry = |r: &fit::TourAverage| {
            fly_published(mph_to_mps(r.ball_speed_mph), r.launch_angle_deg, r.spin_rpm, rho, decay).0
        };
        (carry(&rows[0]) - carry(&rows[1])) - (rows[0].carry_yd - rows[1].carry_yd)
    };
    let fitted = {
        let (d, w) = (fit::predict(&Aero::FITTED, &rows[0]).0, fit::predict(&Aero::FITTED, &rows[1]).0);
        (d - w) - (rows[0].carry_yd - rows[1].carry_yd)
    };
    assert!((-13.8..=-13.2).contains(&fitted), "fitted model's gap error {fitted:+.1} yd");
    // The best gap error of a bounded fit in yards (flight-fit before the fit was scaled in percent).
    let best_bounded_fit = -11.2;
    for rho in [1.15, rho(), 1.225] {
        for decay in [0.0, 0.5, 1.0, 2.0] {
            let e = gap_error(rho, decay);
            eprintln!("rho {rho:.3} kg/m3, decay x{decay}: driver - 3-wood gap error {e:+.1} yd");
            assert!(e < best_bounded_fit && e > -16.0, "rho {rho}, decay x{decay}: {e:+.1} yd");
        }
    }
}

/// Slower players' drives: the wind-tunnel ball against TrackMan's optimal-driver chart (85, 90, 95 mph of
/// club speed: 126, 133, 140 mph of ball speed at 14.6, 14.2, 13.7 deg, 1,900-2,200 rpm, carrying 193, 209 and
/// 225 yd) is within 4 % (1.7-3.6 % short), and the fitted model within 5 % of the wind-tunnel ball at the same
/// launches: the two published models (TrackMan's and Bearman and Harvey's) and the fit agree where the table's
/// driver does not.
#[test]
fn slower_drives_agree_with_the_wind_tunnel_ball() {
    let f = impactd::flight::Flight::default();
    for (ball_mph, launch, chart) in [(126.0, 14.6, 193.0), (133.0, 14.2, 209.0), (140.0, 13.7, 225.0)] {
        for spin in [1900.0, 2050.0, 2200.0] {
            let (published, _, _) = fly_published(mph_to_mps(ball_mph), launch, spin, rho(), 1.0);
            let model = f.fly_metrics(mph_to_mps(ball_mph), launch, 0.0, spin, 0.0).carry_yd;
            eprintln!("{ball_mph} mph {spin} rpm: chart {chart}, wind tunnel {published:.1}, model {model:.1}");
            assert!((published / chart - 1.0).abs() <= 0.04, "{ball_mph} mph: {published:.1} vs {chart}");
            assert!((model / published - 1.0).abs() <= 0.05, "{ball_mph} mph: {model:.1} vs {published:.1}");
        }
    }
}

/// Nathan's model with libgolf's coefficients on the tour table: the driver within 2 yd of carry but the 3-wood
/// 7-12 yd long, so the driver-to-3-wood gap is again about 10 yd short of the table's 32 yd; clubs from the
/// 3-wood to the 6-iron land 4-10 deg shallower than the table says. Its slower drives are within 4 % of
/// TrackMan's optimal-driver chart.
#[test]
fn nathans_model_also_misses_the_driver_gap() {
    let rows = rows();
    let mut carry_errors = Vec::new();
    for r in &rows {
        let (carry, apex, land) = fly_nathan(mph_to_mps(r.ball_speed_mph), r.launch_angle_deg, r.spin_rpm);
        eprintln!(
            "{:7} carry {carry:6.1} ({:+5.1})  apex {apex:5.1} ({:+4.1})  land {land:5.1} ({:+4.1})",
            r.club,
            carry - r.carry_yd,
            apex - r.max_height_yd,
            land - r.land_angle_deg
        );
        carry_errors.push(carry - r.carry_yd);
    }
    assert!(carry_errors[0].abs() <= 2.0, "driver {:+.1}", carry_errors[0]);
    assert!((7.0..=12.0).contains(&carry_errors[1]), "3-wood {:+.1}", carry_errors[1]);
    let gap = carry_errors[0] - carry_errors[1];
    assert!((-12.0..=-8.0).contains(&gap), "driver - 3-wood gap error {gap:+.1} yd");
    for (ball_mph, launch, chart) in [(126.0, 14.6, 193.0), (133.0, 14.2, 209.0), (140.0, 13.7, 225.0)] {
        for spin in [1900.0, 2200.0] {
            let (carry, _, _) = fly_nathan(mph_to_mps(ball_mph), launch, spin);
            eprintln!("{ball_mph} mph {spin} rpm: chart {chart}, Nathan {carry:.1}");
            assert!((carry / chart - 1.0).abs() <= 0.04, "{ball_mph} mph: {carry:.1} vs {chart}");
        }
    }
}

/// The spin decay the check uses is the model's: Smits and Smith's `0.0004 · V[mph]` per second is a time
/// constant of `1 / (0.0004 · 111.85)` = 22.4 s at 50 m/s, the value `docs/flight.md` quotes (22 s).
#[test]
fn smits_and_smith_decay_is_22_s_at_50_mps() {
    let tau = 1.0 / (SMITS_SMITH_PER_MPH_S * impactd::units::mps_to_mph(50.0));
    assert!((tau - 22.35).abs() < 0.05, "{tau}");
}
