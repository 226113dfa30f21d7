//! Bad parameters are `InvalidParameter`, a contact that does not end is `NotConverged` naming the registry's
//! model.

use super::HertzModel;
use crate::equipment::ClubSpec;
use crate::impact::{Delivery, Equipment, ImpactError, ImpactModel, ImpactState};
use crate::math::Vector3;

/// A 7-iron at 40 m/s, centred (the seed's Table 3.1 club).
fn strike() -> (Equipment, ImpactState) {
    let eq = Equipment::new(ClubSpec::iron7());
    let delivery = Delivery {
        club_speed_mps: 40.0,
        attack_angle_rad: (-4.3f64).to_radians(),
        club_path_rad: 0.0,
        face_angle_rad: 0.0,
        dynamic_loft_rad: 25f64.to_radians(),
        impact_h_m: 0.0,
        impact_v_m: 0.0,
        club_angular_velocity_radps: Vector3::zeros(),
    };
    let state = delivery.to_state(&eq).unwrap();
    (eq, state)
}

#[test]
fn a_bad_step_or_contact_limit_is_an_invalid_parameter() {
    let (eq, state) = strike();
    for model in [HertzModel::maw(), HertzModel::arakawa()] {
        for bad in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
            for (field, m) in [
                ("step_s", HertzModel { step_s: bad, ..model }),
                ("max_contact_s", HertzModel { max_contact_s: bad, ..model }),
            ] {
                match m.simulate(&state, &eq, 0) {
                    Err(ImpactError::InvalidParameter { field: f, .. }) => assert_eq!(f, field),
                    other => panic!("{} {field} = {bad}: {other:?}", model.name()),
                }
            }
        }
    }
}

/// The contact lasts about 450 µs (crates/golf-physics/tests/maw_arakawa.rs); a 50 µs limit is an error naming `maw` or `arakawa`, the
/// registry's names.
#[test]
fn a_contact_past_the_limit_names_the_registry_model() {
    let (eq, state) = strike();
    for model in [HertzModel::maw(), HertzModel::arakawa()] {
        let short = HertzModel { max_contact_s: 50e-6, ..model };
        match short.simulate(&state, &eq, 0) {
            Err(ImpactError::NotConverged { model: name, reason }) => {
                assert_eq!(name, model.name());
                assert!(reason.contains("still in contact"), "{reason}");
            }
            other => panic!("{}: {other:?}", model.name()),
        }
        assert!(model.simulate(&state, &eq, 0).is_ok());
    }
}
