//! Ball flight: closed forms, symmetry, the landing's accuracy, the aerodynamic coefficients against published
//! measurements, the fit to the TrackMan tour averages and its cross-validation, slower players' drives against
//! TrackMan's model, and bounce and roll.

#![allow(clippy::unwrap_used)]

use golf_physics::flight::reference::{bearman_harvey, lyu, BH_CD, BH_CL};
use golf_physics::flight::{cv, fit, Aero, Conditions, Flight, Turf};
use golf_physics::units::{mph_to_mps, rpm_to_radps};

/// Closed form: with no drag and no lift the ball flies the vacuum parabola: range v² sin 2θ / g, apex
/// v² sin² θ / (2g), time 2 v sin θ / g, landing at the launch angle and speed.
#[test]
fn vacuum_parabola() {
    let f = Flight { aero: Aero::VACUUM, ..Flight::default() };
    let g = 9.80665;
    for (v, theta_deg) in [(70.0f64, 12.0f64), (50.0, 20.0), (30.0, 45.0)] {
        let t = f.fly_metrics(v, theta_deg, 0.0, 3000.0, 0.0);
        let th = theta_deg.to_radians();
        assert!((t.carry_m - v * v * (2.0 * th).sin() / g).abs() < 1e-6, "{v} {theta_deg}: {}", t.carry_m);
        assert!((t.apex_m - (v * th.sin()).powi(2) / (2.0 * g)).abs() < 1e-3);
        assert!((t.hang_time_s - 2.0 * v * th.sin() / g).abs() < 1e-9);
        assert!((t.land_angle_deg - theta_deg).abs() < 1e-6);
        assert!((t.land_speed_mps - v).abs() < 1e-6);
    }
}

#[test]
fn more_backspin_raises_the_apex() {
    let f = Flight::default();
    let mut last = 0.0;
    for spin in [1500.0, 2500.0, 3500.0, 4500.0] {
        let t = f.fly_metrics(mph_to_mps(160.0), 11.0, 0.0, spin, 0.0);
        assert!(t.apex_m > last + 1.0, "{spin} rpm: apex {}", t.apex_m);
        last = t.apex_m;
    }
}

#[test]
fn mirrored_sidespin_mirrors_offline() {
    let f = Flight::default();
    for (dir, side) in [(0.0, 600.0), (2.0, -900.0), (-3.0, 300.0)] {
        let a = f.fly_metrics(65.0, 14.0, dir, 5000.0, side);
        let b = f.fly_metrics(65.0, 14.0, -dir, 5000.0, -side);
        assert!((a.offline_m + b.offline_m).abs() < 1e-9 && (a.carry_m - b.carry_m).abs() < 1e-9);
        if side > 0.0 && dir >= 0.0 {
            assert!(a.offline_m > 5.0, "fade spin curves right");
        }
    }
}

/// The landing found on the last step's cubic interpolant is within 1 cm of a 0.05 ms reference.
#[test]
fn landing_interpolation_is_within_a_centimetre() {
    for (v, la, back, side) in [(75.0, 11.0, 2600.0, -300.0), (55.0, 17.0, 7000.0, 400.0), (45.0, 25.0, 9000.0, 0.0)] {
        let coarse = Flight::default().fly_metrics(v, la, 1.0, back, side);
        let fine = Flight { step_s: 5e-5, ..Flight::default() }.fly_metrics(v, la, 1.0, back, side);
        let d = (coarse.carry_m - fine.carry_m).hypot(coarse.offline_m - fine.offline_m);
        assert!(d < 0.01, "{v} m/s: {d} m");
        assert!((coarse.hang_time_s - fine.hang_time_s).abs() < 1e-3);
    }
}

/// Thin air: a drive carries 6-10 % further at 1600 m (Denver) than at sea level, as measured on course.
#[test]
fn thinner_air_and_a_tailwind_carry_further() {
    let base = Flight::default().fly_metrics(mph_to_mps(167.0), 10.9, 0.0, 2686.0, 0.0);
    let high = Flight { conditions: Conditions { altitude_m: 1600.0, ..Default::default() }, ..Flight::default() }
        .fly_metrics(mph_to_mps(167.0), 10.9, 0.0, 2686.0, 0.0);
    let tail = Flight {
        conditions: Conditions { wind_mps: 5.0, wind_dir_deg: 0.0, ..Default::default() },
        ..Flight::default()
    }
    .fly_metrics(mph_to_mps(167.0), 10.9, 0.0, 2686.0, 0.0);
    let cross = Flight {
        conditions: Conditions { wind_mps: 5.0, wind_dir_deg: 90.0, ..Default::default() },
        ..Flight::default()
    }
    .fly_metrics(mph_to_mps(167.0), 10.9, 0.0, 2686.0, 0.0);
    let gain = high.carry_m / base.carry_m - 1.0;
    assert!((0.06..=0.10).contains(&gain), "carry at 1600 m: {:+.1} %", 100.0 * gain);
    assert!(tail.carry_m > base.carry_m + 3.0);
    assert!(cross.offline_m > 3.0, "a left-to-right wind moves the ball right");
}

/// Model coefficients at sea level (the fit's air) for airspeed `v` and spin `rpm`, with the spin ratio.
fn model(v: f64, rpm: f64) -> (f64, f64, f64) {
    let f = Flight::default();
    let c = f.conditions;
    let r = f.ball.radius_m;
    let re = golf_physics::flight::aero::reynolds(v, 2.0 * r, c.density_kg_m3(), c.viscosity_pa_s());
    let s = r * rpm_to_radps(rpm) / v;
    let (d, l) = Aero::FITTED.coefficients(re, s);
    (d, l, s)
}

/// Over 20-90 m/s and 1,000-11,000 rpm the fitted drag and lift stay within the published measurements: between
/// the lower and the higher of Bearman and Harvey's wind tunnel and Lyu et al.'s free flight at the same airspeed
/// and spin (each held at the edge of what it measured), widened by the ball-to-ball spread Lyu et al. report
/// (under 0.05 above Re 10⁵, over 0.1 below, here 0.05 and 0.10).
#[test]
fn drag_and_lift_stay_within_the_published_measurements() {
    for v in (20..=90).step_by(5).map(f64::from) {
        for rpm in (1000..=11000).step_by(500).map(f64::from) {
            let (drag, lift, s) = model(v, rpm);
            let (lyu_d, lyu_l) = lyu(v, s);
            let (bh_d, bh_l) = (bearman_harvey(&BH_CD, v, rpm), bearman_harvey(&BH_CL, v, rpm));
            let tol = if v * 0.043 / 1.48e-5 >= 1e5 { 0.05 } else { 0.10 };
            let (d_lo, d_hi) = (bh_d.min(lyu_d) - tol, bh_d.max(lyu_d) + tol);
            let (l_lo, l_hi) = (bh_l.min(lyu_l) - tol, bh_l.max(lyu_l) + tol);
            assert!(
                (d_lo..=d_hi).contains(&drag),
                "C_D {drag:.3} at {v} m/s, {rpm} rpm (S {s:.2}): {d_lo:.3}-{d_hi:.3}"
            );
            assert!(
                (l_lo..=l_hi).contains(&lift),
                "C_L {lift:.3} at {v} m/s, {rpm} rpm (S {s:.2}): {l_lo:.3}-{l_hi:.3}"
            );
        }
    }
}

/// Above the drag crisis the drag at a fixed spin ratio does not rise with airspeed more than the strictest
/// source, Bearman and Harvey's wind tunnel, shows between 40 and 88 m/s (Lyu et al.'s free-flight fit rises
/// far more, 0.19 to 0.40): the model's rise is at most theirs.
#[test]
fn drag_above_the_crisis_rises_no_more_than_measured() {
    let r = 0.0213;
    for s in [0.12, 0.15, 0.18] {
        let rpm = |v: f64| golf_physics::units::radps_to_rpm(s * v / r);
        let bh_rise = bearman_harvey(&BH_CD, 88.1, rpm(88.1)) - bearman_harvey(&BH_CD, 40.0, rpm(40.0));
        let (lo, _, _) = model(40.0, rpm(40.0));
        let (hi, _, _) = model(88.1, rpm(88.1));
        assert!(hi - lo <= bh_rise.max(0.0) + 1e-9, "S {s}: model {:+.3}, Bearman and Harvey {bh_rise:+.3}", hi - lo);
    }
}

/// The fit to the TrackMan tour averages with the coefficients in `Aero::FITTED`: the largest of carry / 4 %,
/// apex / 4.5 yd and land angle / 4 deg over the twelve clubs, minimised with the drag and lift held inside the
/// published envelope (`flight::envelope`; the test above). Every club within 3.31 % of carry, 3.73 yd of apex
/// and 3.31 deg of land angle (`impactd flight-fit`; `research/flight-fit.md` lists every club). No ball inside the
/// envelope reaches land angles within 3 deg and carry within 4 % together: `impactd flight-fit --tradeoff`
/// traces what each costs (research/flight-fit.md, "Carry against land angle").
#[test]
fn every_club_is_near_the_trackman_table() {
    let rows = fit::parse_table(fit::TRACKMAN_CSV).unwrap();
    assert_eq!(rows.len(), 12);
    for c in cv::club_errors(&Aero::FITTED, &rows) {
        assert!(c.within_pct(3.31, 3.73, 3.31), "{c:?}");
    }
    assert!(fit::worst(&Aero::FITTED, &rows) < 0.83);
    // Inside the envelope less its margin, but for less than the margin: strictly inside the envelope.
    assert!(golf_physics::flight::envelope::violations(&Aero::FITTED)
        .iter()
        .all(|v| *v < golf_physics::flight::envelope::MARGIN));
}

/// The fit is reproducible: from `fit::START` and the table, `impactd flight-fit` lands on `Aero::FITTED`.
#[test]
fn the_fit_from_its_start_reproduces_the_shipped_coefficients() {
    let rows = fit::parse_table(fit::TRACKMAN_CSV).unwrap();
    let (mut runs, mut minimax) = (0, 0);
    let result = fit::fit(&rows, &fit::START, fit::ITERATIONS, |step| match step {
        fit::Step::Run(..) => runs += 1,
        fit::Step::Minimax(..) => minimax += 1,
    });
    let bounds = golf_physics::flight::aero::BOUNDS;
    for ((got, shipped), (lo, hi)) in result.aero.to_array().iter().zip(Aero::FITTED.to_array()).zip(bounds) {
        assert!((got - shipped).abs() <= 1e-6 * (hi - lo), "{got} vs {shipped}");
    }
    assert!((result.worst - fit::worst(&Aero::FITTED, &rows)).abs() < 1e-6 && runs >= 1 && minimax >= 1);
}

/// Leave-one-club-out: each club predicted by a fit to the other eleven. Measured: carry within 7.2 %, apex
/// within 3.9 yd, land angle within 6.1 deg, the driver the worst (issue 19 asks 5 %, 4 yd, 4 deg; the driver,
/// the table's only club at its speed and spin ratio, is an extrapolation for the other eleven). Without the
/// driver: carry within 4.7 %, apex 3.9 yd, land angle 3.7 deg (the fit before the envelope was held and carry
/// scaled in percent: 3.7 %, 3.0 yd, 4.5 deg; its in-sample errors were 3.6 %, 4.2 yd, 4.2 deg).
#[test]
fn leave_one_club_out_errors() {
    let rows = fit::parse_table(fit::TRACKMAN_CSV).unwrap();
    // The twelve fits side by side (`cv::leave_one_out` runs them one after another, to the same numbers).
    let holdouts = std::thread::scope(|scope| {
        let fits: Vec<_> = (0..rows.len())
            .map(|i| {
                scope.spawn({
                    let rows = &rows;
                    move || cv::hold_out(rows, i, fit::ITERATIONS)
                })
            })
            .collect();
        fits.into_iter().map(|f| f.join().unwrap()).collect()
    });
    let v = cv::CrossValidation::of(holdouts);
    assert_eq!(v.holdouts.len(), 12);
    assert!(v.max_carry_error_pct <= 7.2, "{v:?}");
    assert!(v.max_apex_error_yd <= 3.9, "{v:?}");
    assert!(v.max_land_angle_error_deg <= 6.1, "{v:?}");
    for h in v.holdouts.iter().filter(|h| h.club != "driver") {
        assert!(
            h.carry_error_pct.abs() <= 4.7 && h.apex_error_yd.abs() <= 3.9 && h.land_angle_error_deg.abs() <= 3.7,
            "{h:?}"
        );
    }
}

/// Slower players' drives against TrackMan's own trajectory model: Andrew Rice's chart made with TrackMan
/// ("Optimal Driver Numbers": no wind, flat, normal ground, sea level, premium ball, +5 deg attack, 1900-2200
/// rpm) gives at 85, 90 and 95 mph of club speed 126, 133 and 140 mph of ball speed at 14.6, 14.2 and 13.7 deg,
/// carrying 193, 209 and 225 yd and totalling 242, 256 and 271 yd. The model carries within 5 % across the
/// stated spin range, and on Penner's fairway (firmness 0.5) totals within 5 %.
#[test]
fn slower_drives_agree_with_trackman() {
    let f = Flight::default();
    for (ball_mph, launch, carry, total) in
        [(126.0, 14.6, 193.0, 242.0), (133.0, 14.2, 209.0, 256.0), (140.0, 13.7, 225.0, 271.0)]
    {
        for spin in [1900.0, 2050.0, 2200.0] {
            let t = f.fly_metrics(mph_to_mps(ball_mph), launch, 0.0, spin, 0.0);
            assert!((t.carry_yd / carry - 1.0).abs() <= 0.05, "{ball_mph} mph, {spin} rpm: carry {:.1}", t.carry_yd);
            assert!((t.total_yd / total - 1.0).abs() <= 0.05, "{ball_mph} mph, {spin} rpm: total {:.1}", t.total_yd);
        }
    }
}

/// Bounce and roll: the total is the carry plus the run along the line of travel; a firmer fairway runs further;
/// a tour driver (2686 rpm, landing at about 40 deg) runs 15-40 yd on Penner's fairway (tour totals are 20-25 yd
/// past the 275 yd carry); a pitching wedge (9304 rpm, landing at 51 deg) stops within 3 yd.
#[test]
fn bounce_and_roll() {
    let fly = |firmness: f64, mph: f64, launch: f64, spin: f64| {
        Flight { turf: Turf { firmness }, ..Flight::default() }.fly_metrics(mph_to_mps(mph), launch, 0.0, spin, 0.0)
    };
    let mut last = -1.0;
    for firmness in [0.0, 0.25, 0.5, 0.75, 1.0] {
        let t = fly(firmness, 167.0, 10.9, 2686.0);
        assert!((t.total_m - (t.carry_m + t.roll_m)).abs() < 1e-9);
        assert!(t.roll_m > last, "firmness {firmness}: roll {}", t.roll_m);
        last = t.roll_m;
    }
    let driver = fly(0.5, 167.0, 10.9, 2686.0);
    assert!((15.0..=40.0).contains(&driver.roll_yd), "driver roll {:.1} yd", driver.roll_yd);
    let wedge = fly(0.5, 102.0, 24.2, 9304.0);
    assert!(wedge.roll_yd.abs() <= 3.0, "wedge roll {:.1} yd", wedge.roll_yd);
    // The sampled path runs on past the landing to rest, on the ground.
    let path =
        Flight::default().fly(&golf_physics::flight::LaunchState::from_metrics(70.0, 12.0, 0.0, 2500.0, 0.0), 0.05);
    let last_point = path.points.last().unwrap();
    assert!((last_point[1].hypot(last_point[3]) - path.total_m).abs() < 1e-6 && last_point[2] == 0.0);
    assert!(path.points.iter().all(|p| p[2] >= 0.0));
}

/// Carry against land angle for one ball inside the published envelope (apex left out): held to land angles
/// within 2.5 deg the table's carries cost more than 4 % somewhere; let the land angle go to 4 deg and carry
/// comes within 3.5 %. Measured with `impactd flight-fit --tradeoff`: 2.93 deg with 4.68 %, 3.28 deg with
/// 3.28 % (research/flight-fit.md, "Carry against land angle").
#[test]
fn land_angle_costs_carry_for_one_ball() {
    use golf_physics::flight::tradeoff::largest_errors;
    let rows = fit::parse_table(fit::TRACKMAN_CSV).unwrap();
    let at = |land_deg: f64| {
        let tol = fit::Tolerance {
            carry_yd: 0.0,
            carry_pct: Some(4.0),
            apex_yd: None,
            land_angle_deg: land_deg,
            envelope: Some(fit::ENVELOPE),
        };
        let f = fit::fit_with(&rows, &fit::START, fit::ITERATIONS, &tol, |_| {});
        let (land, carry_pct, ..) = largest_errors(&f.aero, &rows);
        (land, carry_pct)
    };
    let (tight_land, tight_carry) = at(2.5);
    let (loose_land, loose_carry) = at(4.0);
    println!(
        "land 2.5 deg scale: {tight_land:.2} deg, {tight_carry:.2} %; 4 deg: {loose_land:.2} deg, {loose_carry:.2} %"
    );
    assert!(tight_land <= 3.0 && tight_carry > 4.0);
    assert!(loose_carry <= 3.5 && loose_land > 3.0);
}
