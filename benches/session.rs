//! `impactd session`'s work over 10,000 shots (the budget: <= 1 s): parsing 10,000 recorded predictions
//! (JSON, as read from a recording's `golf/<rig>/launch` channel) and summarising them per club, with outliers
//! and gapping. Reading the MCAP file itself is not in it.

#![allow(clippy::unwrap_used)]

use std::collections::BTreeSet;

use criterion::{criterion_group, criterion_main, Criterion};
use impactd::equipment::ClubSpec;
use impactd::impact::{DeliveryMetrics, Equipment, ImpactModel, ImpulseModel, ImpulseVariant};
use impactd::offline::swing::SwingSpec;
use impactd::rng::Rng;
use impactd::session::{summarize, GroupBy};
use impactd::wire::{Handedness, LaunchPrediction, PredictOutput, ShotLabels};

/// 10,000 predictions of ten clubs (labels) and three players, with their flights, as JSON bytes.
fn recorded(n: usize) -> Vec<Vec<u8>> {
    let club = ClubSpec::driver();
    let equipment = Equipment::new(club.clone());
    let model = ImpulseModel::new(ImpulseVariant::Adjusted);
    let flight = impactd::flight::Flight::default();
    let mut rng = Rng::new(7);
    let specs: Vec<SwingSpec> = (0..64).map(|_| SwingSpec::random(&club, &mut rng)).collect();
    let base: Vec<LaunchPrediction> = specs
        .iter()
        .enumerate()
        .map(|(i, spec)| {
            let state = spec.delivery.to_state(&equipment).unwrap();
            let launch = model.predict(&state, &equipment).unwrap();
            let delivery = DeliveryMetrics::from_state(&state, &club);
            let traj = flight.fly(
                &impactd::flight::LaunchState {
                    velocity_mps: launch.ball_velocity_mps,
                    spin_radps: launch.ball_spin_radps,
                },
                0.0,
            );
            LaunchPrediction {
                rig: "bay1".into(),
                shot: i as u64,
                frame: 0,
                t_impact_ns: 0,
                club: club.name.clone(),
                club_file: None,
                model: model.name().into(),
                estimator: "arc".into(),
                delivery,
                launch: PredictOutput::new(&launch, &delivery, Handedness::Right, &equipment),
                frames_used: 8,
                quality: 1.0,
                latency_us: 100.0,
                flight: Some(traj),
                reports: Default::default(),
                labels: ShotLabels::default(),
                ball: None,
                impact_timing: None,
            }
        })
        .collect();
    (0..n)
        .map(|i| {
            let mut p = base[i % base.len()].clone();
            p.shot = i as u64 + 1;
            p.labels = ShotLabels {
                player: Some(["ann", "bob", "cy"][i % 3].into()),
                club: Some(format!("club{}", i % 10)),
                tags: vec!["fitting".into()],
                note: None,
            };
            serde_json::to_vec(&p).unwrap()
        })
        .collect()
}

fn session(c: &mut Criterion) {
    let bytes = recorded(10_000);
    let none = BTreeSet::new();
    c.bench_function("session_10000_shots_parse_and_summarize", |b| {
        b.iter(|| {
            let shots: Vec<LaunchPrediction> = bytes.iter().map(|b| serde_json::from_slice(b).unwrap()).collect();
            std::hint::black_box(summarize(&shots, GroupBy::Club, &none, false))
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = session
}
criterion_main!(benches);
