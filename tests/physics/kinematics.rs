//! Impact-state estimation from motion-capture frames: the accuracy targets on synthetic swings with exact truth,
//! and the track's and detector's handling of bad, missing and misleading frames.

#![allow(clippy::unwrap_used)]

use impactd::equipment::ClubSpec;
use impactd::impact::{Equipment, ImpulseModel, ImpulseVariant};
use impactd::kinematics::estimate::estimate;
use impactd::kinematics::track::Accepted;
use impactd::kinematics::*;
use impactd::math::{Isometry3, Translation3Ext, UnitQuaternion, Vector3};
use impactd::offline::eval::{run, EstimatorReport, EvalConfig, EvalReport};
use impactd::offline::swing::{sample, Sampling, Swing, SwingPath, SwingSpec};
use impactd::rng::Rng;

fn eval(club: ClubSpec, shots: usize, noise_mm: f64, noise_deg: f64) -> EvalReport {
    eval_on(SwingPath::Arc, club, shots, noise_mm, noise_deg)
}

fn eval_on(path: SwingPath, club: ClubSpec, shots: usize, noise_mm: f64, noise_deg: f64) -> EvalReport {
    run(
        &EvalConfig {
            club,
            launch_model: std::sync::Arc::new(ImpulseModel::new(ImpulseVariant::Adjusted)),
            rate_hz: 720.0,
            shots,
            noise_mm,
            noise_deg,
            jitter_us: 0.0,
            drop_probability: 0.0,
            seed: 11,
            estimators: vec![EstimatorSpec::linear2(), EstimatorSpec::poly(), EstimatorSpec::arc()],
            path,
        },
        |_| {},
    )
}

/// The extrapolation issue's targets at 720 Hz with 0.2 mm and 0.1 deg of noise: face angle and dynamic loft
/// RMS <= 0.1 deg, impact location RMS <= 1 mm, club speed RMS <= 0.3 %. Every one of 300 shots estimated.
fn assert_meets_the_accuracy_targets(name: &str, est: &EstimatorReport) {
    assert_eq!(est.shots, 300, "{name} {}: {:?}", est.name, est.refused);
    let e = &est.errors;
    assert!(e.face_angle_deg.rms <= 0.1, "{name} {} face {}", est.name, e.face_angle_deg.rms);
    assert!(e.dynamic_loft_deg.rms <= 0.1, "{name} {} loft {}", est.name, e.dynamic_loft_deg.rms);
    assert!(e.impact_h_mm.rms <= 1.0 && e.impact_v_mm.rms <= 1.0, "{name} {} location", est.name);
    assert!(e.club_speed_pct.rms <= 0.3, "{name} {} speed {}", est.name, e.club_speed_pct.rms);
}

#[test]
fn poly_meets_the_accuracy_targets_at_720_hz() {
    for club in [ClubSpec::driver(), ClubSpec::iron7()] {
        let name = club.name.clone();
        let r = eval(club, 300, 0.2, 0.1);
        assert_meets_the_accuracy_targets(&name, &r.estimators[1]);
        let e = &r.estimators[1].errors;
        // Against the seed's two-point method on the same swings: at least twice lower face-angle error and
        // three times lower impact-location error (measured ratios are in the README).
        let lin = &r.estimators[0].errors;
        assert!(lin.face_angle_deg.rms > 2.0 * e.face_angle_deg.rms, "{name} face ratio");
        assert!(lin.impact_h_mm.rms > 3.0 * e.impact_h_mm.rms, "{name} h ratio");
        assert!(lin.impact_v_mm.rms > 4.0 * e.impact_v_mm.rms, "{name} v ratio");
    }
}

/// The arc estimator on the same swings: the accuracy targets, and at least five times lower impact-location
/// error than the seed's two-point method (h and v), and twice lower face-angle error (the five times the issue
/// asks for the face angle is below what the frames' orientation noise allows; README).
#[test]
fn arc_meets_the_targets_and_five_times_lower_location_error() {
    for club in [ClubSpec::driver(), ClubSpec::iron7()] {
        let name = club.name.clone();
        let r = eval(club, 300, 0.2, 0.1);
        assert_meets_the_accuracy_targets(&name, &r.estimators[2]);
        let e = &r.estimators[2].errors;
        let lin = &r.estimators[0].errors;
        assert!(
            lin.impact_h_mm.rms > 5.0 * e.impact_h_mm.rms,
            "{name} h ratio {}",
            lin.impact_h_mm.rms / e.impact_h_mm.rms
        );
        assert!(
            lin.impact_v_mm.rms > 5.0 * e.impact_v_mm.rms,
            "{name} v ratio {}",
            lin.impact_v_mm.rms / e.impact_v_mm.rms
        );
        assert!(lin.face_angle_deg.rms > 2.0 * e.face_angle_deg.rms, "{name} face ratio");
        // Better than poly on the path's geometry, as good on the angles.
        let poly = &r.estimators[1].errors;
        assert!(e.impact_h_mm.rms < poly.impact_h_mm.rms && e.club_path_deg.rms < poly.club_path_deg.rms);
    }
}

/// With the noise off, the poly and arc estimators' errors are below 0.01 deg and 0.05 mm.
#[test]
fn noise_free_errors_are_tiny() {
    for club in [ClubSpec::driver(), ClubSpec::iron7()] {
        let name = club.name.clone();
        let r = eval(club, 100, 0.0, 0.0);
        for est in &r.estimators[1..] {
            for (key, s) in est.errors.entries() {
                if key.ends_with("_deg") && !key.starts_with("launch") {
                    assert!(s.rms < 0.01, "{name} {} {key} {}", est.name, s.rms);
                }
                if key.ends_with("_mm") {
                    assert!(s.rms < 0.05, "{name} {} {key} {}", est.name, s.rms);
                }
            }
        }
    }
}

/// On double-pendulum paths (the wrist uncocking through the window, a path no estimator models exactly) `poly`
/// and the default `arc` (which falls back to `poly`'s path where the arc does not fit) still meet the accuracy
/// targets; `poly` beats the two-point line by at least 3x (h) and 4x (v) in impact location and `arc` by 4.5x
/// and 5x (measured over 1000 swings: `poly` 4.5x and 5.7x, `arc` 5.2x and 6.3x on the driver; README), and
/// `arc` is not worse than `poly` there.
#[test]
fn the_estimators_meet_the_targets_on_double_pendulum_paths() {
    for club in [ClubSpec::driver(), ClubSpec::iron7()] {
        let name = club.name.clone();
        let r = eval_on(SwingPath::DoublePendulum, club, 300, 0.2, 0.1);
        assert_meets_the_accuracy_targets(&name, &r.estimators[1]);
        assert_meets_the_accuracy_targets(&name, &r.estimators[2]);
        let (lin, poly, arc) = (&r.estimators[0].errors, &r.estimators[1].errors, &r.estimators[2].errors);
        let ratio = |e: &impactd::offline::eval::ErrorStats, l: &impactd::offline::eval::ErrorStats| l.rms / e.rms;
        assert!(ratio(&poly.impact_h_mm, &lin.impact_h_mm) > 3.0, "{name} poly h ratio");
        assert!(ratio(&poly.impact_v_mm, &lin.impact_v_mm) > 4.0, "{name} poly v ratio");
        let (h, v) = (ratio(&arc.impact_h_mm, &lin.impact_h_mm), ratio(&arc.impact_v_mm, &lin.impact_v_mm));
        assert!(h > 4.5 && v > 5.0, "{name} arc ratios h {h} v {v}");
        assert!(arc.impact_h_mm.rms <= poly.impact_h_mm.rms && arc.impact_v_mm.rms <= poly.impact_v_mm.rms);
    }
}

/// A double-pendulum swing passes through the truth: the face centre at impact, and its velocity there (a
/// one-sided difference over 1 us) equal to the truth's `v_cg + ω × r`, as the arc's does.
#[test]
fn double_pendulum_swings_pass_through_the_truth() {
    let club = ClubSpec::driver();
    let eq = Equipment::new(club.clone());
    let mut rng = Rng::new(5);
    for _ in 0..20 {
        let spec = SwingSpec::random_on(SwingPath::DoublePendulum, &club, &mut rng);
        let Ok(swing) = Swing::new(&spec, &eq) else { continue };
        let face = |tau: f64| swing.pose(tau) * impactd::math::Point3::from(club.face.center_m);
        assert!((face(0.0).coords - swing.face_centre_at_impact()).norm() < 1e-12);
        let t = &swing.truth;
        let v_truth =
            t.cg_velocity_mps + t.angular_velocity_radps.cross(&(t.world_from_club.rotation * club.face.center_m));
        let h = 1e-6;
        let v = (face(0.0) - face(-h)) / h;
        assert!((v - v_truth).norm() < 1e-3 * v_truth.norm(), "{v} vs {v_truth}");
        // And it is not the arc: 40 ms before impact the two paths are centimetres apart.
        let mut arc_spec = spec;
        arc_spec.double_pendulum = None;
        let arc = Swing::new(&arc_spec, &eq).unwrap();
        let gap = (swing.pose(-0.04).translation.vector - arc.pose(-0.04).translation.vector).norm();
        assert!(gap > 0.005, "{gap}");
    }
}

#[test]
fn the_evaluation_is_deterministic() {
    let a = eval(ClubSpec::driver(), 20, 0.2, 0.1);
    let b = eval(ClubSpec::driver(), 20, 0.2, 0.1);
    assert_eq!(serde_json::to_string(&a).unwrap(), serde_json::to_string(&b).unwrap());
}

fn good_sample(frame: u64, t_ns: u64, x: f64) -> ClubheadSample {
    ClubheadSample {
        frame,
        t_ns,
        position_m: Vector3::new(x, 0.1, 0.0),
        orientation_xyzw: [0.0, 0.0, 0.0, 1.0],
        occluded: false,
    }
}

#[test]
fn the_track_rejects_bad_frames_with_a_reason() {
    let mut track = Track::new(Calibration::default(), TrackLimits::default());
    let dt = 1_388_889;
    assert!(track.push(&good_sample(1, 1_000_000_000, 0.0)).is_ok());
    let t = |k: u64| 1_000_000_000 + k * dt;
    let mut nan = good_sample(2, t(1), 0.0);
    nan.position_m.y = f64::NAN;
    assert_eq!(track.push(&nan), Err(Reject::NonFinite { field: "position_m" }));
    assert!(matches!(track.push(&good_sample(1, t(0), 0.0)), Err(Reject::Duplicate { .. })));
    assert!(matches!(track.push(&good_sample(0, t(0) - 5, 0.0)), Err(Reject::Backwards { .. })));
    // 1 m in one frame is 720 m/s.
    assert!(matches!(track.push(&good_sample(2, t(1), 1.0)), Err(Reject::Jump { .. })));
    // Millimetres where metres are expected.
    let mut mm = good_sample(2, t(1), 0.0);
    mm.position_m = Vector3::new(1200.0, 100.0, -300.0);
    assert!(matches!(track.push(&mm), Err(Reject::OutOfRange { .. })));
    let mut q = good_sample(2, t(1), 0.0);
    q.orientation_xyzw = [0.0, 0.0, 0.0, 2.0];
    assert!(matches!(track.push(&q), Err(Reject::NotUnitQuaternion { .. })));
    assert_eq!(track.counts.rejected, 6);
    // Good frames still go in, and a gap in frame numbers is counted as dropped.
    assert_eq!(track.push(&good_sample(2, t(1), 0.01)), Ok(Accepted::Pose { dropped_before: 0 }));
    let mut occluded = good_sample(3, t(2), 0.0);
    occluded.occluded = true;
    assert_eq!(track.push(&occluded), Ok(Accepted::Occluded));
    assert_eq!(track.push(&good_sample(6, t(5), 0.03)), Ok(Accepted::Pose { dropped_before: 2 }));
    assert_eq!(track.counts.accepted, 3);
    assert_eq!(track.counts.dropped, 2);
    assert_eq!(track.poses().len(), 3);
}

fn detect_all(samples: &[ClubheadSample], club: &ClubSpec, calibration: Calibration) -> Vec<Detection> {
    let mut track = Track::new(calibration, TrackLimits::default());
    let mut det = ImpactDetector::new(DetectorConfig::default());
    let mut out = Vec::new();
    for s in samples {
        if let Ok(Accepted::Pose { .. }) = track.push(s) {
            if let Some(d) = det.on_pose(&track, club, &[EstimatorSpec::linear2(), EstimatorSpec::poly()]) {
                out.extend(d);
            }
        }
    }
    out
}

/// A rig in its own lab frame with markers away from the CG: the calibration recovers the same impact.
#[test]
fn calibration_recovers_the_club_frame() {
    let club = ClubSpec::driver();
    let eq = Equipment::new(club.clone());
    let mut rng = Rng::new(8);
    let swing = Swing::new(&SwingSpec::random(&club, &mut rng), &eq).unwrap();
    let calibration = Calibration {
        world_from_lab: Isometry3::from_parts(
            Vector3::new(2.0, -0.1, 3.5).into_translation(),
            UnitQuaternion::from_euler_angles(0.02, 1.3, -0.01),
        ),
        club_from_body: Isometry3::from_parts(
            Vector3::new(-0.02, 0.03, -0.05).into_translation(),
            UnitQuaternion::from_euler_angles(0.3, -0.2, 0.1),
        ),
    };
    let a = sample(&swing, &Sampling::default(), &Calibration::default(), 5_000_000_000, 1, &mut Rng::new(1));
    let b = sample(&swing, &Sampling::default(), &calibration, 5_000_000_000, 1, &mut Rng::new(1));
    assert!((a.samples[10].position_m - b.samples[10].position_m).norm() > 0.5, "the lab frame differs");
    let da = detect_all(&a.samples, &club, Calibration::default());
    let db = detect_all(&b.samples, &club, calibration);
    let (ea, eb) = (da[1].result.as_ref().unwrap(), db[1].result.as_ref().unwrap());
    assert!((ea.state.cg_velocity_mps - eb.state.cg_velocity_mps).norm() < 1e-6);
    assert!((ea.state.impact_h_m - eb.state.impact_h_m).abs() < 1e-9);
    assert!((ea.t_impact_ns as i64 - eb.t_impact_ns as i64).abs() <= 1);
}

/// Dropped and occluded frames around impact, and timestamp jitter: every shot is still found.
#[test]
fn dropped_occluded_and_jittered_frames() {
    let club = ClubSpec::iron7();
    let eq = Equipment::new(club.clone());
    let mut rng = Rng::new(21);
    let sampling = Sampling {
        position_noise_m: 0.2e-3,
        orientation_noise_rad: 0.1f64.to_radians(),
        jitter_s: 20e-6,
        drop_probability: 0.05,
        occlusion_probability: 0.05,
        ..Sampling::default()
    };
    let mut found = 0;
    for _ in 0..50 {
        let swing = Swing::new(&SwingSpec::random(&club, &mut rng), &eq).unwrap();
        let s = sample(&swing, &sampling, &Calibration::default(), 2_000_000_000, 1, &mut rng);
        let d = detect_all(&s.samples, &club, Calibration::default());
        if let Some(Ok(e)) = d.get(1).map(|d| &d.result) {
            found += 1;
            assert!((e.t_impact_ns as f64 - s.t_impact_ns as f64).abs() < 100_000.0);
        }
    }
    assert_eq!(found, 50);
}

/// The estimators refuse, with a reason, when there are too few pre-impact frames.
#[test]
fn too_few_frames_are_refused() {
    let club = ClubSpec::driver();
    let eq = Equipment::new(club.clone());
    let swing = Swing::new(&SwingSpec::random(&club, &mut Rng::new(4)), &eq).unwrap();
    let s = sample(&swing, &Sampling::default(), &Calibration::default(), 1_000_000_000, 1, &mut Rng::new(2));
    let mut track = Track::new(Calibration::default(), TrackLimits::default());
    let reveal = s.samples.iter().find(|x| x.t_ns > s.t_impact_ns).unwrap().t_ns;
    let pre: Vec<&ClubheadSample> = s.samples.iter().filter(|x| x.t_ns < reveal).collect();
    for x in &pre[pre.len() - 3..] {
        track.push(x).unwrap();
    }
    let poses: Vec<ClubPose> = track.poses().iter().copied().collect();
    let scene =
        Scene { face: &club.face, ball_position_m: Vector3::zeros(), ball_radius_m: 0.0213, max_extrapolation_s: 0.01 };
    assert!(matches!(
        estimate(&EstimatorSpec::poly(), &poses, reveal, &scene),
        Err(EstimateError::TooFewFrames { have: 3, need: 6 })
    ));
    assert!(estimate(&EstimatorSpec::linear2(), &poses, reveal, &scene).is_ok());
    assert!(matches!(
        estimate(&EstimatorSpec::linear2(), &poses[..1], reveal, &scene),
        Err(EstimateError::TooFewFrames { have: 1, need: 2 })
    ));
}

/// Addressing the ball and a slow waggle through it do not fire; only the swing does.
#[test]
fn address_and_waggle_do_not_fire() {
    let club = ClubSpec::driver();
    let eq = Equipment::new(club.clone());
    let swing = Swing::new(&SwingSpec::random(&club, &mut Rng::new(6)), &eq).unwrap();
    let at_ball = swing.truth.world_from_club;
    let period = 1_388_889u64;
    let mut samples = Vec::new();
    let mut frame = 1;
    let mut t = 1_000_000_000u64;
    let mut push = |pose: Isometry3, samples: &mut Vec<ClubheadSample>| {
        samples.push(ClubPose { frame, t_ns: t, world_from_club: pose }.to_sample(&Calibration::default()));
        frame += 1;
        t += period;
    };
    // Far away first (arms the detector), then resting 1 mm behind the ball, then creeping through it at 0.5 m/s.
    let back = |d: f64| {
        let mut p = at_ball;
        p.translation.vector.x -= d;
        p
    };
    push(back(0.5), &mut samples);
    for _ in 0..200 {
        push(back(0.001), &mut samples);
    }
    for k in 0..100 {
        push(back(0.001 - k as f64 * 0.5 / 720.0), &mut samples);
    }
    let d = detect_all(&samples, &club, Calibration::default());
    assert!(
        d.is_empty(),
        "{:?}",
        d.iter().map(|d| (d.reveal_frame, d.result.as_ref().map(|e| e.t_impact_ns))).collect::<Vec<_>>()
    );
}

/// Why the face angle cannot be five times better than `linear2` at 0.1 deg orientation noise: the posterior
/// spread of one rotation-vector component at impact, given every pre-impact frame of the evaluation (60 ms at
/// 720 Hz, 0.1 deg white noise) and the swing generator's own prior on the angular acceleration and its rate
/// (flat on the angle and the rate), is the smallest RMS error any estimator can reach (the Bayes bound of a linear
/// Gaussian model, averaged over the frame clock's phase). `linear2` has `sqrt(8/3)` times the noise from the noise
/// alone (the extrapolation `θ₂ + u (θ₂ − θ₁)`, `u` uniform in [0, 1]).
#[test]
fn the_face_angle_bound_allows_about_three_times_linear2() {
    use impactd::offline::swing::{ANGULAR_ACCEL_SIGMA_RADPS2, ANGULAR_JERK_SIGMA_RADPS3};
    let (rate_hz, before_s, noise_rad) = (720.0, Sampling::default().before_s, 0.1_f64.to_radians());
    let phases = 200;
    let mut variance = 0.0;
    for k in 0..phases {
        let phase = k as f64 / phases as f64;
        let mut info = impactd::math::Matrix4::zeros();
        info[(2, 2)] = ANGULAR_ACCEL_SIGMA_RADPS2.powi(-2);
        info[(3, 3)] = ANGULAR_JERK_SIGMA_RADPS3.powi(-2);
        let first = -(before_s * rate_hz).ceil() as i64;
        for i in first..=0 {
            let tau = (i as f64 + phase) / rate_hz;
            if tau < 0.0 {
                let x = impactd::math::Vector4::new(1.0, tau, tau * tau / 2.0, tau * tau * tau / 6.0);
                info += x * x.transpose() / (noise_rad * noise_rad);
            }
        }
        variance += info.try_inverse().unwrap()[(0, 0)] / phases as f64;
    }
    let bound_deg = variance.sqrt().to_degrees();
    let linear2_deg = (8.0_f64 / 3.0).sqrt() * 0.1;
    assert!((0.058..0.064).contains(&bound_deg), "bound {bound_deg} deg");
    assert!(linear2_deg / bound_deg < 3.0, "at most {}x", linear2_deg / bound_deg);
    // The estimator the daemon uses is within 40 % of the bound (0.076-0.082 deg over 1000 shots).
    let r = eval(ClubSpec::driver(), 300, 0.2, 0.1);
    assert!(r.estimators[2].errors.face_angle_deg.rms < 1.4 * bound_deg);
}
