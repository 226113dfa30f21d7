//! Ball flight: closed forms, symmetry, the landing's accuracy, and the fit to the TrackMan tour averages.

#![allow(clippy::unwrap_used)]

use impactd::flight::{fit, Aero, Conditions, Flight};
use impactd::units::mph_to_mps;

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

/// The fit to the TrackMan tour averages with the coefficients in `Aero::FITTED` (the target): every club
/// within carry 3 yd, apex 2 yd and land angle 2 deg, the largest error 0.97 of its target (README lists them).
#[test]
fn every_club_is_within_the_trackman_targets() {
    let rows = fit::parse_table(fit::TRACKMAN_CSV).unwrap();
    assert_eq!(rows.len(), 12);
    let mut within = 0;
    for r in &rows {
        let (carry, apex, land) = fit::predict(&Aero::FITTED, r);
        let (dc, da, dl) =
            ((carry - r.carry_yd).abs(), (apex - r.max_height_yd).abs(), (land - r.land_angle_deg).abs());
        assert!(
            dc <= 3.0 && da <= 2.0 && dl <= 2.0,
            "{}: carry {carry:.1} ({}), apex {apex:.1} ({}), land {land:.1} ({})",
            r.club,
            r.carry_yd,
            r.max_height_yd,
            r.land_angle_deg
        );
        if dc <= 3.0 && da <= 2.0 && dl <= 2.0 {
            within += 1;
        }
    }
    assert_eq!(within, 12);
    assert!(fit::worst(&Aero::FITTED, &rows) < 0.975);
}

/// The fit is reproducible: from `fit::START`, `impactd flight-fit` (3000 Nelder-Mead iterations per run, then the
/// minimax stage) lands on the coefficients in `Aero::FITTED`.
#[test]
fn the_fit_from_its_start_reproduces_the_shipped_coefficients() {
    let rows = fit::parse_table(fit::TRACKMAN_CSV).unwrap();
    let (mut runs, mut minimax) = (0, 0);
    let result = fit::fit(&rows, &fit::START, 3000, |step| match step {
        fit::Step::Run(..) => runs += 1,
        fit::Step::Minimax(..) => minimax += 1,
    });
    let aero = result.aero;
    let f = Aero::FITTED;
    let pairs = [
        (aero.c_d0, f.c_d0),
        (aero.c_ds, f.c_ds),
        (aero.c_dq, f.c_dq),
        (aero.c_dc, f.c_dc),
        (aero.c_dv, f.c_dv),
        (aero.c_lv, f.c_lv),
        (aero.v_crisis_mps, f.v_crisis_mps),
        (aero.v_width_mps, f.v_width_mps),
        (aero.c_l1, f.c_l1),
        (aero.c_l2, f.c_l2),
        (aero.spin_tau_s, f.spin_tau_s),
    ];
    for (got, shipped) in pairs {
        assert!((got - shipped).abs() <= 1e-6 * shipped.abs(), "{got} vs {shipped}");
    }
    assert!((result.worst - fit::worst(&f, &rows)).abs() < 1e-9 && runs >= 2 && minimax >= 2);
    // The minimax stage lowers the largest error the sum of squares leaves.
    assert!(result.worst < 0.975);
}
