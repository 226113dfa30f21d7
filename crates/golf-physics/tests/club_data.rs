//! TrackMan's club data from the frames (docs/club-data.md): swing direction, swing plane, low point, dynamic
//! lie, closure rate and face to path, through the real pipeline (track, detector, `arc` estimator, club data)
//! on synthetic swings whose exact values the generator gives (`Swing::swing_arc_truth`, the truth state).

#![allow(clippy::unwrap_used)]

use golf_physics::equipment::ClubSpec;
use golf_physics::impact::{Delivery, DeliveryMetrics, Equipment, SwingArc};
use golf_physics::kinematics::Calibration;
use golf_physics::math::Vector3;
use golf_physics::pipeline::{Event, Pipeline, RigSetup};
use golf_physics::rng::Rng;
use golf_physics::swing::{sample, Sampling, Swing, SwingPath, SwingSpec};

/// One shot: the truth and what the pipeline measured.
struct Shot {
    truth: DeliveryMetrics,
    truth_arc: SwingArc,
    measured: DeliveryMetrics,
    measured_arc: SwingArc,
}

/// `n` golfer swings of `club` on `path` (each head turned toe up or down by up to 4 deg about its face normal,
/// so the dynamic lie varies), sampled at 720 Hz with the given noise, each through a fresh pipeline.
fn shots(club: &ClubSpec, path: SwingPath, n: usize, noise_mm: f64, noise_deg: f64, seed: u64) -> Vec<Shot> {
    let eq = Equipment::new(club.clone());
    let mut rng = Rng::new(seed);
    let sampling = Sampling {
        position_noise_m: noise_mm * 1e-3,
        orientation_noise_rad: noise_deg.to_radians(),
        ..Default::default()
    };
    let mut out = Vec::new();
    while out.len() < n {
        let mut spec = SwingSpec::golfer(club, &mut rng);
        spec.face_roll_deg = rng.uniform(-4.0, 4.0);
        if path == SwingPath::DoublePendulum {
            spec.double_pendulum = SwingSpec::random_on(path, club, &mut rng).double_pendulum;
        }
        let swing = Swing::new(&spec, &eq).unwrap();
        let s = sample(&swing, &sampling, &Calibration::default(), 1_000_000_000, 1, &mut rng);
        let mut pipeline = Pipeline::new(RigSetup::new("bay", club.clone()));
        let mut events = Vec::new();
        for x in &s.samples {
            pipeline.on_sample(x, &mut events);
        }
        let measured = events
            .iter()
            .find_map(|e| if let Event::Impact(m) = e { Some(m.delivery) } else { None })
            .expect("every swing is detected and estimated");
        // The launch carries the same club data in its delivery and, for dynamic lie and closure rate, in its
        // `predict`-style output.
        let launch = events.iter().find_map(|e| if let Event::Launch(l) = e { Some(l) } else { None }).unwrap();
        assert_eq!(launch.delivery, measured);
        assert_eq!(launch.launch.dynamic_lie_deg, measured.dynamic_lie_deg);
        assert_eq!(launch.launch.closure_rate_degps, measured.closure_rate_degps);
        let truth = DeliveryMetrics::from_state(&swing.truth, club);
        out.push(Shot {
            truth,
            truth_arc: swing.swing_arc_truth(&Vector3::zeros(), eq.ball.radius_m).unwrap(),
            measured,
            measured_arc: measured.swing_arc.expect("every swing's path fits an arc"),
        });
    }
    out
}

/// RMS and largest absolute error of one metric.
fn errors(shots: &[Shot], f: impl Fn(&Shot) -> f64) -> (f64, f64) {
    let e: Vec<f64> = shots.iter().map(f).collect();
    ((e.iter().map(|x| x * x).sum::<f64>() / e.len() as f64).sqrt(), e.iter().fold(0.0, |m, x| m.max(x.abs())))
}

struct Report {
    direction_deg: (f64, f64),
    plane_deg: (f64, f64),
    lie_deg: (f64, f64),
    low_distance_mm: (f64, f64),
    low_height_mm: (f64, f64),
    closure_degps: (f64, f64),
    face_to_path_deg: (f64, f64),
}

fn report(shots: &[Shot]) -> Report {
    Report {
        direction_deg: errors(shots, |s| s.measured_arc.swing_direction_deg - s.truth_arc.swing_direction_deg),
        plane_deg: errors(shots, |s| s.measured_arc.swing_plane_deg - s.truth_arc.swing_plane_deg),
        lie_deg: errors(shots, |s| s.measured.dynamic_lie_deg - s.truth.dynamic_lie_deg),
        low_distance_mm: errors(shots, |s| s.measured_arc.low_point_distance_mm - s.truth_arc.low_point_distance_mm),
        low_height_mm: errors(shots, |s| s.measured_arc.low_point_height_mm - s.truth_arc.low_point_height_mm),
        closure_degps: errors(shots, |s| s.measured.closure_rate_degps - s.truth.closure_rate_degps),
        face_to_path_deg: errors(shots, |s| s.measured.face_to_path_deg - s.truth.face_to_path_deg),
    }
}

fn print(label: &str, r: &Report) {
    println!(
        "{label}: RMS (max) direction {:.3e} ({:.3e}) deg, plane {:.3e} ({:.3e}) deg, lie {:.3e} ({:.3e}) deg, low \
         point distance {:.3e} ({:.3e}) mm, height {:.3e} ({:.3e}) mm, closure {:.3e} ({:.3e}) deg/s, face to path \
         {:.3e} ({:.3e}) deg",
        r.direction_deg.0,
        r.direction_deg.1,
        r.plane_deg.0,
        r.plane_deg.1,
        r.lie_deg.0,
        r.lie_deg.1,
        r.low_distance_mm.0,
        r.low_distance_mm.1,
        r.low_height_mm.0,
        r.low_height_mm.1,
        r.closure_degps.0,
        r.closure_degps.1,
        r.face_to_path_deg.0,
        r.face_to_path_deg.1
    );
}

/// The targets at 720 Hz with 0.2 mm / 0.1 deg of noise, over 200 golfer swings per club (tour to
/// amateur, both presets, four seeds): swing direction and swing plane RMS <= 0.3 deg, dynamic lie RMS <= 0.2
/// deg, low point RMS <= 5 mm (distance and height). Closure rate RMS <= 40 deg/s (1.3-2.7 % of a golfer's
/// 1500-3000 deg/s; measured 17-20: the derivative of the rotation fit, a cubic over 39 ms, carries the
/// frames' 0.1 deg of noise amplified by the differentiation and the extrapolation to contact) and face to path RMS <= 0.15 deg (face angle and club path each within 0.1 deg, the estimator's
/// targets in tests/physics/kinematics.rs, largely independent).
#[test]
fn club_data_within_the_targets_with_noise() {
    for club in [ClubSpec::driver(), ClubSpec::iron7()] {
        let all: Vec<Shot> = (0..4).flat_map(|seed| shots(&club, SwingPath::Arc, 50, 0.2, 0.1, 100 + seed)).collect();
        let r = report(&all);
        print(&format!("{} arc, 0.2 mm / 0.1 deg", club.name), &r);
        assert!(r.direction_deg.0 <= 0.3, "{} swing direction RMS {}", club.name, r.direction_deg.0);
        assert!(r.plane_deg.0 <= 0.3, "{} swing plane RMS {}", club.name, r.plane_deg.0);
        assert!(r.lie_deg.0 <= 0.2, "{} dynamic lie RMS {}", club.name, r.lie_deg.0);
        assert!(r.low_distance_mm.0 <= 5.0, "{} low point distance RMS {}", club.name, r.low_distance_mm.0);
        assert!(r.low_height_mm.0 <= 5.0, "{} low point height RMS {}", club.name, r.low_height_mm.0);
        assert!(r.closure_degps.0 <= 40.0, "{} closure rate RMS {}", club.name, r.closure_degps.0);
        assert!(r.face_to_path_deg.0 <= 0.15, "{} face to path RMS {}", club.name, r.face_to_path_deg.0);
    }
}

/// On double-pendulum paths (the wrist uncocking: a path no fit reproduces exactly) the plane is still exact
/// (the path is planar) and the low point within the same 5 mm.
#[test]
fn club_data_on_double_pendulum_paths() {
    for club in [ClubSpec::driver(), ClubSpec::iron7()] {
        let all = shots(&club, SwingPath::DoublePendulum, 100, 0.2, 0.1, 7);
        let r = report(&all);
        print(&format!("{} double pendulum, 0.2 mm / 0.1 deg", club.name), &r);
        assert!(r.direction_deg.0 <= 0.3 && r.plane_deg.0 <= 0.3, "{}", club.name);
        assert!(r.lie_deg.0 <= 0.2, "{} dynamic lie RMS {}", club.name, r.lie_deg.0);
        assert!(r.low_distance_mm.0 <= 5.0, "{} low point distance RMS {}", club.name, r.low_distance_mm.0);
        assert!(r.low_height_mm.0 <= 5.0, "{} low point height RMS {}", club.name, r.low_height_mm.0);
    }
}

/// Without noise, on arc swings (the club-data fit's model is exact for them): the plane to rounding, the low
/// point to the arc fit's stopping tolerance, and dynamic lie, closure rate and face to path to the rotation
/// fit's truncation (a cubic rotation vector about the newest frame for the generator's cubic one about impact).
#[test]
fn noise_free_club_data_match_the_truth() {
    for club in [ClubSpec::driver(), ClubSpec::iron7()] {
        let all = shots(&club, SwingPath::Arc, 50, 0.0, 0.0, 3);
        let r = report(&all);
        print(&format!("{} arc, noise free", club.name), &r);
        assert!(r.direction_deg.1 < 1e-6 && r.plane_deg.1 < 1e-6, "{}", club.name);
        assert!(r.low_distance_mm.1 < 1e-3 && r.low_height_mm.1 < 1e-3, "{}", club.name);
        // 1.05e-3 deg for the 7-iron since the tour golfer de-lofts it 9 deg (impact::tour): the truncation grows
        // with the head's attitude away from its static pose; 0.84e-3 before.
        assert!(r.lie_deg.1 < 1.5e-3, "{} dynamic lie max {}", club.name, r.lie_deg.1);
        assert!(r.closure_degps.1 < 1.0, "{} closure rate max {}", club.name, r.closure_degps.1);
        assert!(r.face_to_path_deg.1 < 2e-3, "{} face to path max {}", club.name, r.face_to_path_deg.1);
    }
}

/// The generator's truth against closed forms. A level-radius arc through impact in a plane at `β` to the ground:
/// the club descends at `ψ` from the arc's bottom with `sin AA = -sin ψ sin β`, so the club path is the swing
/// direction plus `atan(tan ψ cos β)` (TrackMan's "path = direction - attack / tan plane" to first order), and
/// the low point lies `ρ sin ψ` along the base line after the face centre and `ρ (1 - cos ψ) sin β` below it.
#[test]
fn truth_matches_the_closed_forms_of_an_inclined_circle() {
    let mut rng = Rng::new(5);
    for club in [ClubSpec::driver(), ClubSpec::iron7()] {
        let eq = Equipment::new(club.clone());
        for _ in 0..50 {
            let mut spec = SwingSpec::golfer(&club, &mut rng);
            spec.radius_curvature_per_s2 = 0.0;
            let swing = Swing::new(&spec, &eq).unwrap();
            let t = swing.swing_arc_truth(&Vector3::zeros(), eq.ball.radius_m).unwrap();
            let m = DeliveryMetrics::from_state(&swing.truth, &club);
            let beta = t.swing_plane_deg.to_radians();
            let psi = (-m.attack_angle_deg.to_radians().sin() / beta.sin()).asin();
            let path = t.swing_direction_deg + (psi.tan() * beta.cos()).atan().to_degrees();
            assert!((m.club_path_deg - path).abs() < 1e-9, "path {} vs {path}", m.club_path_deg);
            let rho = spec.arc_radius_m;
            assert!((t.low_point_distance_mm - rho * psi.sin() * 1e3).abs() < 1e-6, "{}", t.low_point_distance_mm);
            let face_centre_height_mm = (swing.face_centre_at_impact().y + eq.ball.radius_m) * 1e3;
            let drop_mm = rho * (1.0 - psi.cos()) * beta.sin() * 1e3;
            assert!((t.low_point_height_mm - (face_centre_height_mm - drop_mm)).abs() < 1e-6);
            // Hitting down (irons) puts the low point after the ball; hitting up (most drivers) before it.
            assert_eq!(t.low_point_distance_mm > 0.0, m.attack_angle_deg < 0.0);
        }
    }
}

/// Dynamic lie and closure rate from a state alone: a square address shows the static lie; a head turned toe
/// up by `δ` about its face normal shows `asin(sin λ cos δ ... )` (computed here in closed form for a square,
/// loft-only face: the shaft `(0, sin λ, -cos λ)` turned about x by `-δ` rises by `sin(λ - δ)`); an angular
/// velocity along the shaft is all closure rate, one across it none.
#[test]
fn dynamic_lie_and_closure_rate_of_a_state() {
    let club = ClubSpec::iron7();
    let eq = Equipment::new(club.clone());
    let d = Delivery {
        club_speed_mps: 40.0,
        attack_angle_rad: 0.0,
        club_path_rad: 0.0,
        face_angle_rad: 0.0,
        dynamic_loft_rad: club.face.loft_rad,
        impact_h_m: 0.0,
        impact_v_m: 0.0,
        club_angular_velocity_radps: Vector3::zeros(),
    };
    let m = DeliveryMetrics::from_state(&d.to_state(&eq).unwrap(), &club);
    assert!((m.dynamic_lie_deg - club.lie_deg).abs() < 1e-12, "{}", m.dynamic_lie_deg);
    let along = Delivery { club_angular_velocity_radps: 30.0 * club.shaft_axis_up(), ..d };
    let m = DeliveryMetrics::from_state(&along.to_state(&eq).unwrap(), &club);
    // 30 rad/s = 1718.87 deg/s, closing (the face turning left) for a rotation up the shaft.
    assert!((m.closure_rate_degps - 30f64.to_degrees()).abs() < 1e-9, "{}", m.closure_rate_degps);
    let across = Delivery { club_angular_velocity_radps: 30.0 * Vector3::x(), ..d };
    let m = DeliveryMetrics::from_state(&across.to_state(&eq).unwrap(), &club);
    assert!(m.closure_rate_degps.abs() < 1e-9);
    // The same face angle and loft with the toe up by 3 deg: a flatter shaft, by 3 deg on a face without loft
    // (the roll axis is then the x axis); on the iron's 30.5 deg face a little less.
    let flat = ClubSpec { face: golf_physics::face::Face { loft_rad: 0.0, ..club.face }, ..club.clone() };
    let eq_flat = Equipment::new(flat.clone());
    let mut spec = SwingSpec::golfer(&flat, &mut Rng::new(1));
    spec.delivery = Delivery { dynamic_loft_rad: 0.0, ..d };
    spec.face_roll_deg = 3.0;
    let swing = Swing::new(&spec, &eq_flat).unwrap();
    let m = DeliveryMetrics::from_state(&swing.truth, &flat);
    assert!((m.dynamic_lie_deg - (club.lie_deg - 3.0)).abs() < 1e-9, "{}", m.dynamic_lie_deg);
    assert!(m.face_angle_deg.abs() < 1e-12 && m.dynamic_loft_deg.abs() < 1e-12);
}
