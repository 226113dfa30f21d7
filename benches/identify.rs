//! The two-layer fit's parts on a small dataset (issue 34: `impactd fit --model continuous` on 550 shots with
//! its 5-fold cross-validation in a minute on 2 cores; docs/identify.md times the whole command): the local
//! stage alone (Levenberg-Marquardt on the reweighted residuals, from Table 3.5's 7-iron) and a whole small fit
//! with its cross-validation, on 60 synthetic 7-iron shots.

#![allow(clippy::unwrap_used)]

use criterion::{criterion_group, criterion_main, Criterion};
use impactd::equipment::{ClubSpec, LoadedClub, ModelSections};
use impactd::impact::Equipment;
use impactd::offline::identify::dataset::resolve;
use impactd::offline::identify::fit::{fit_local, run, FitOptions, LocalMethod};
use impactd::offline::identify::synth::{generate, DeliveryRanges, LmNoise, SynthSpec};
use impactd::offline::identify::{FitModel, ParamSpace, Shot};

fn shots(n: usize) -> (ParamSpace, LoadedClub, Vec<Shot>) {
    // research/identify-results.md's truth.
    let truth = [8.5e9, 7.0e-3, 0.42, 45.0, 9.0e-3, 2.2e-3, 0.65];
    let space = ParamSpace::new(FitModel::parse("continuous").unwrap(), &[]).unwrap();
    let club = LoadedClub { club: ClubSpec::iron7(), sections: ModelSections::default() };
    let spec = SynthSpec {
        club: space.club_with(&club, &truth),
        model: "continuous".into(),
        shots: n,
        noise: LmNoise::default(),
        ranges: DeliveryRanges::for_club(&club.club),
        seed: 17,
    };
    let shots = resolve(&generate(&spec).unwrap(), &Equipment::new(club.club.clone())).unwrap();
    (space, club, shots)
}

fn identify(c: &mut Criterion) {
    let (space, club, shots) = shots(60);
    let ball = Default::default();
    let start = space.to_unit(&space.get(&club));
    let mut group = c.benchmark_group("identify");
    group.sample_size(10);
    group.bench_function("two_layer_local_lm_60_shots", |b| {
        let options = FitOptions { local: Some(LocalMethod::LevenbergMarquardt), ..Default::default() };
        b.iter(|| fit_local(&space, &club, &ball, &shots, &options, &start, &mut |_| {}))
    });
    group.bench_function("two_layer_fit_3_folds_60_shots", |b| {
        let options = FitOptions { folds: 3, generations: 10, global_shots: Some(30), ..Default::default() };
        b.iter(|| run(&space, &club, &ball, &shots, &options, &mut |_, _| {}).unwrap())
    });
    group.finish();
}

criterion_group!(benches, identify);
criterion_main!(benches);
