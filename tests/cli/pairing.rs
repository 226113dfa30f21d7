#![allow(clippy::unwrap_used)]
//! The live pairing of measured launches with predictions (`identify::pairing`), alone: windows, either order
//! of arrival, two models per shot, unpaired counts and the running MAE.

use impactd::equipment::ClubSpec;
use impactd::impact::{Delivery, DeliveryMetrics, Equipment, ImpactModel, ImpulseModel, ImpulseVariant};
use impactd::math::Vector3;
use impactd::pairing::{PairWindow, Pairer};
use impactd::wire::{Handedness, LaunchPrediction, MeasuredLaunch, PredictOutput};

const S: u64 = 1_000_000_000;

fn prediction(shot: u64, t_impact_ns: u64, model: &str) -> LaunchPrediction {
    let equipment = Equipment::new(ClubSpec::driver());
    let delivery = Delivery {
        club_speed_mps: 50.0,
        attack_angle_rad: 0.0,
        club_path_rad: 0.0,
        face_angle_rad: 0.02,
        dynamic_loft_rad: 0.2,
        impact_h_m: 0.0,
        impact_v_m: 0.0,
        club_angular_velocity_radps: Vector3::zeros(),
    };
    let state = delivery.to_state(&equipment).unwrap();
    let launch = ImpulseModel::new(ImpulseVariant::Adjusted).predict(&state, &equipment).unwrap();
    let metrics = DeliveryMetrics::from_state(&state, &equipment.club);
    LaunchPrediction {
        rig: "bay1".into(),
        shot,
        frame: shot * 1000,
        t_impact_ns,
        club: "driver".into(),
        club_file: None,
        model: model.into(),
        estimator: "arc".into(),
        delivery: metrics,
        launch: PredictOutput::new(&launch, &metrics, Handedness::Right, &equipment),
        frames_used: 8,
        quality: 1.0,
        latency_us: 100.0,
        flight: None,
        reports: Default::default(),
        labels: Default::default(),
        ball: None,
        impact_timing: None,
    }
}

fn measured(t_ns: u64, ball_speed_mph: f64) -> MeasuredLaunch {
    MeasuredLaunch {
        rig: "bay1".into(),
        t_ns,
        device: "test".into(),
        ball_speed_mph,
        launch_angle_deg: 10.0,
        launch_direction_deg: 1.0,
        total_spin_rpm: Some(3000.0),
        spin_axis_deg: Some(10.0),
        ..Default::default()
    }
}

#[test]
fn a_measurement_pairs_with_the_latest_shot_in_its_window() {
    let mut p = Pairer::new("bay1", PairWindow::default());
    assert!(p.on_prediction(&prediction(1, 100 * S, "adjusted")).is_empty());
    assert!(p.on_prediction(&prediction(2, 103 * S, "adjusted")).is_empty());
    // 1.5 s after shot 2, 4.5 s after shot 1: shot 2.
    let c = p.on_measured(&measured(104 * S + S / 2, 150.0)).unwrap();
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].shot, 2);
    assert!((c[0].delay_s - 1.5).abs() < 1e-9);
    // residual = predicted - measured; spin from total 3000 rpm at 10 deg: back 3000 cos 10, side 3000 sin 10.
    assert!((c[0].residual.ball_speed_mph - (c[0].predicted.ball_speed_mph - 150.0)).abs() < 1e-9);
    assert!((c[0].measured.backspin_rpm - 3000.0 * 10f64.to_radians().cos()).abs() < 1e-9);
    assert!((c[0].measured.sidespin_rpm - 3000.0 * 10f64.to_radians().sin()).abs() < 1e-9);
    // Shot 1 is still waiting; a measurement 30 ms after it is too early for the window (0.05 s).
    assert!(p.on_measured(&measured(100 * S + 30_000_000, 150.0)).unwrap().is_empty());
    p.expire(200 * S);
    let s = p.status();
    assert_eq!((s.paired, s.unpaired_predictions, s.unpaired_measured, s.measured), (1, 1, 1, 2));
    let mae = &s.mae["adjusted"];
    assert!((mae.ball_speed_mph - c[0].residual.ball_speed_mph.abs()).abs() < 1e-9);
}

#[test]
fn either_side_may_come_first_and_both_models_are_compared() {
    let mut p = Pairer::new("bay1", PairWindow { min_s: 0.05, max_s: 5.0 });
    // The measurement arrives before the prediction (a slow model): it waits.
    assert!(p.on_measured(&measured(10 * S + S / 10, 160.0)).unwrap().is_empty());
    let first = p.on_prediction(&prediction(7, 10 * S, "adjusted"));
    assert_eq!(first.len(), 1);
    // The second model of the same shot is compared with the same measurement.
    let second = p.on_prediction(&prediction(7, 10 * S, "continuous"));
    assert_eq!(second.len(), 1);
    assert_eq!(second[0].measured, first[0].measured);
    let s = p.status();
    assert_eq!(s.paired, 1);
    assert_eq!(s.mae.len(), 2);
    // A second measurement finds no unpaired shot: it waits, then counts as unpaired.
    assert!(p.on_measured(&measured(11 * S, 160.0)).unwrap().is_empty());
    p.expire(20 * S);
    assert_eq!(p.status().unpaired_measured, 1);
    assert_eq!(p.status().unpaired_predictions, 0);
}

#[test]
fn unusable_measurements_are_counted_by_reason() {
    let mut p = Pairer::new("bay1", PairWindow::default());
    let mut no_spin = measured(S, 150.0);
    no_spin.total_spin_rpm = None;
    assert!(p.on_measured(&no_spin).is_err());
    let mut other = measured(S, 150.0);
    other.rig = "bay2".into();
    assert!(p.on_measured(&other).is_err());
    assert!(p.on_measured(&measured(S, f64::NAN)).is_err());
    let s = p.status();
    assert_eq!(s.measured, 3);
    assert_eq!(s.rejected.values().sum::<u64>(), 3);
    assert_eq!(s.rejected["no_spin"], 1);
}
