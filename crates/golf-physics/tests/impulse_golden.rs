//! The exact cases of `tests/data/im-golden.jsonl` (copied from the project's reference data): every launch
//! number of every preset case matches to 1e-6 relative, angles to 1e-5 deg and spins to 0.01 rpm.

#![allow(clippy::unwrap_used)]

use golf_physics::equipment::ClubSpec;
use golf_physics::impact::{DeliveryMetrics, Equipment, ImpactModel, ImpulseModel, ImpulseVariant};
use golf_physics::wire::{DeliveryInput, Handedness, PredictOutput};

#[derive(serde::Deserialize)]
struct Case {
    club: String,
    model: String,
    delivery: DeliveryInput,
    expected: std::collections::BTreeMap<String, f64>,
}

fn predict(case: &Case) -> PredictOutput {
    let club = ClubSpec::preset(&case.club).unwrap();
    let eq = Equipment::new(club.clone());
    let delivery = case.delivery.to_delivery(club.loft_deg());
    let state = delivery.to_state(&eq).unwrap();
    let model = ImpulseModel::new(ImpulseVariant::parse(&case.model).unwrap());
    let launch = model.predict(&state, &eq).unwrap();
    PredictOutput::new(&launch, &DeliveryMetrics::from_state(&state, &club), Handedness::Right, &eq)
}

#[test]
fn golden_cases_match() {
    let text = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data/im-golden.jsonl"));
    let mut failures = Vec::new();
    let mut n = 0;
    for (i, line) in text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty()) {
        let case: Case = serde_json::from_str(line).unwrap();
        let got = serde_json::to_value(predict(&case)).unwrap();
        for (key, want) in &case.expected {
            let have = got[key].as_f64().unwrap();
            let tol = if key.ends_with("_deg") {
                1e-5
            } else if key.ends_with("_rpm") {
                0.01
            } else {
                1e-6 * want.abs()
            };
            n += 1;
            if (have - want).abs() > tol {
                failures.push(format!(
                    "line {} {}/{} {key}: got {have:.6}, want {want:.6}",
                    i + 1,
                    case.club,
                    case.model
                ));
            }
        }
    }
    assert!(n >= 70, "only {n} numbers checked");
    assert!(failures.is_empty(), "{} mismatches:\n{}", failures.len(), failures.join("\n"));
}
