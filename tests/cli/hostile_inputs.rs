//! Property tests: arbitrary JSON and byte strings into the sample parser, the track, `predict`'s path
//! (delivery -> state -> model) and `flight`'s (launch -> trajectory). None may panic or hang.

#![allow(clippy::unwrap_used)]

use proptest::prelude::*;
use serde_json::Value;

use impactd::equipment::ClubSpec;
use impactd::impact::{Equipment, ImpactModel, ImpulseModel, ImpulseVariant};
use impactd::kinematics::{Calibration, ClubheadSample, Track, TrackLimits};
use impactd::wire::{parse_sample, DeliveryInput, FlightInput};

/// Field names the parsers know, so arbitrary objects reach past "unknown field".
const KEYS: [&str; 24] = [
    "rig",
    "frame",
    "t_ns",
    "position_m",
    "orientation",
    "occluded",
    "x",
    "y",
    "z",
    "w",
    "club_speed_mph",
    "attack_angle_deg",
    "club_path_deg",
    "face_angle_deg",
    "dynamic_loft_deg",
    "impact_h_mm",
    "impact_v_mm",
    "club_angular_velocity_radps",
    "ball_speed_mps",
    "launch_angle_deg",
    "backspin_rpm",
    "sidespin_rpm",
    "ball_velocity_mps",
    "ball_spin_radps",
];

fn number() -> impl Strategy<Value = Value> {
    prop_oneof![
        any::<f64>().prop_filter_map("finite", |v| serde_json::Number::from_f64(v).map(Value::Number)),
        any::<i64>().prop_map(|v| Value::Number(v.into())),
        any::<u64>().prop_map(|v| Value::Number(v.into())),
        (-1e3..1e3f64).prop_filter_map("finite", |v| serde_json::Number::from_f64(v).map(Value::Number)),
    ]
}

fn json() -> impl Strategy<Value = Value> {
    let leaf = prop_oneof![
        Just(Value::Null),
        any::<bool>().prop_map(Value::Bool),
        number(),
        "[a-z0-9]{0,6}".prop_map(Value::String),
    ];
    leaf.prop_recursive(4, 48, 8, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..5).prop_map(Value::Array),
            prop::collection::vec((prop::sample::select(KEYS.to_vec()), inner), 0..8)
                .prop_map(|kv| Value::Object(kv.into_iter().map(|(k, v)| (k.to_string(), v)).collect())),
        ]
    })
}

fn predict(text: &[u8]) {
    let Ok(d) = serde_json::from_slice::<DeliveryInput>(text) else { return };
    if d.check_finite().is_err() || d.check_plausible().is_err() {
        return;
    }
    let club = ClubSpec::driver();
    let eq = Equipment::new(club.clone());
    if let Ok(state) = d.to_delivery(club.loft_deg()).to_state(&eq) {
        let _ = ImpulseModel::new(ImpulseVariant::Adjusted).predict(&state, &eq);
    }
}

fn flight(text: &[u8]) {
    let Ok(l) = serde_json::from_slice::<FlightInput>(text) else { return };
    if let Ok(launch) = l.to_launch() {
        let t = impactd::flight::Flight::default().fly(&launch, 0.01);
        assert!(t.points.len() < 100_000);
    }
}

fn sample() -> impl Strategy<Value = ClubheadSample> {
    let real = prop_oneof![any::<f64>(), -2.0..2.0f64];
    (
        any::<u64>(),
        any::<u64>(),
        [real.clone(), real.clone(), real.clone()],
        [real.clone(), real.clone(), real.clone(), real],
        any::<bool>(),
    )
        .prop_map(|(frame, t_ns, p, q, occluded)| ClubheadSample {
            frame,
            t_ns,
            position_m: impactd::math::Vector3::new(p[0], p[1], p[2]),
            orientation_xyzw: q,
            occluded,
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_json_into_every_parser(v in json()) {
        let text = serde_json::to_vec(&v).unwrap();
        let _ = parse_sample("bay1", &text, "application/json");
        predict(&text);
        flight(&text);
    }

    #[test]
    fn arbitrary_bytes_into_every_parser(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        let _ = parse_sample("bay1", &bytes, "application/json");
        predict(&bytes);
        flight(&bytes);
    }

    #[test]
    fn arbitrary_samples_into_the_track(samples in prop::collection::vec(sample(), 0..64)) {
        let mut track = Track::new(Calibration::default(), TrackLimits::default());
        for s in &samples {
            let _ = track.push(s);
        }
        prop_assert!(track.poses().len() <= TrackLimits::default().history);
    }
}

/// An orientation sent as an array is refused with a reason, not read in some order.
#[test]
fn an_orientation_array_is_refused_with_a_reason() {
    let text = br#"{"rig":"bay1","frame":1,"t_ns":1,"position_m":[0,0,0],"orientation":[0,0,0,1]}"#;
    let err = parse_sample("bay1", text, "").unwrap_err().to_string();
    assert!(err.contains("must be an object {x, y, z, w}"), "{err}");
}

/// `predict` refuses an angular velocity of 1e6 rad/s (it answered a 64,717 mph ball) and `flight` a spin of
/// 1e6 rad/s.
#[test]
fn implausible_numbers_are_refused() {
    let d: DeliveryInput =
        serde_json::from_str(r#"{"club_speed_mph":100,"club_angular_velocity_radps":[1e6,0,0]}"#).unwrap();
    assert_eq!(d.check_plausible().unwrap_err().field, "club_angular_velocity_radps");
    let l: FlightInput =
        serde_json::from_str(r#"{"ball_velocity_mps":[60,10,0],"ball_spin_radps":[0,0,1e6]}"#).unwrap();
    assert!(l.to_launch().unwrap_err().to_string().contains("ball_spin_radps"));
}
