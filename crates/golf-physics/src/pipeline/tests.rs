//! The pipeline's tests: synthetic swings through it, one body and several.

use super::*;
use crate::rng::Rng;
use crate::swing::{sample, Sampling, Swing, SwingSpec};

#[test]
fn a_swing_gives_one_impact_and_one_launch() {
    let club = ClubSpec::driver();
    let mut p = Pipeline::new(RigSetup::new("bay1", club.clone()));
    let eq = Equipment::new(club.clone());
    let swing = Swing::new(&SwingSpec::random(&club, &mut Rng::new(1)), &eq).unwrap();
    let s = sample(&swing, &Sampling::default(), &Calibration::default(), 1_000_000_000, 1, &mut Rng::new(2));
    let mut out = Vec::new();
    for x in &s.samples {
        p.on_sample(x, &mut out);
    }
    assert_eq!(out.iter().filter(|e| matches!(e, Event::Impact(_))).count(), 1);
    let launch = out.iter().find_map(|e| if let Event::Launch(l) = e { Some(l) } else { None }).unwrap();
    assert_eq!(launch.shot, 1);
    assert_eq!(launch.model, crate::impact::registry::DEFAULT_MODEL);
    assert!(
        (launch.delivery.club_speed_mps - swing.delivery.club_speed_mps).abs() < 1e-3 * swing.delivery.club_speed_mps
    );
    assert_eq!(p.counts.predictions, 1);
}

/// `[rig.clubs]`: the first tracked body takes its club; another body's samples are set aside while the
/// current body was in view within 0.2 s, an unmapped body's refused; then the other body's club takes over
/// and its swing's launch names that club and file.
#[test]
fn another_body_in_view_switches_the_club() {
    let switch = |club: ClubSpec| ClubSwitch {
        club_ref: Some(ClubRef { name: club.name.clone(), file: club.name.clone(), sha256: "00".into() }),
        club,
        models: vec![Arc::new(ImpulseModel::new(ImpulseVariant::Adjusted))],
        calibration: None,
    };
    let mut setup = RigSetup::new("bay1", ClubSpec::driver());
    setup.bodies.insert("a".into(), switch(ClubSpec::driver()));
    setup.bodies.insert("b".into(), switch(ClubSpec::iron7()));
    let mut p = Pipeline::new(setup);
    let swing_of = |club: &ClubSpec, start_ns: u64| {
        let eq = Equipment::new(club.clone());
        let swing = Swing::new(&SwingSpec::random(club, &mut Rng::new(3)), &eq).unwrap();
        sample(&swing, &Sampling::default(), &Calibration::default(), start_ns, 1, &mut Rng::new(4)).samples
    };
    let mut out = Vec::new();
    let driver = swing_of(&ClubSpec::driver(), 1_000_000_000);
    for x in &driver[..10] {
        p.on_body_sample_with(Some("a"), x, &mut |e| out.push(e));
    }
    let changed = |out: &[Event]| -> Vec<String> {
        out.iter()
            .filter_map(|e| if let Event::ClubChanged(c) = e { Some(c.club.name.clone()) } else { None })
            .collect()
    };
    assert_eq!(changed(&out), ["driver"]);
    let mut early = driver[10];
    early.t_ns = driver[9].t_ns + 1_000_000;
    p.on_body_sample_with(Some("b"), &early, &mut |e| out.push(e));
    p.on_body_sample_with(Some("c"), &early, &mut |e| out.push(e));
    assert_eq!((p.counts.rejected.get(Rejection::OtherBody), p.counts.rejected.get(Rejection::UnknownBody)), (1, 1));
    assert_eq!(p.setup.club.name, "driver");
    for x in &swing_of(&ClubSpec::iron7(), driver[9].t_ns + BODY_SWITCH_AFTER_NS + 1_000_000_000) {
        p.on_body_sample_with(Some("b"), x, &mut |e| out.push(e));
    }
    assert_eq!(changed(&out), ["driver", "iron7"]);
    let launches: Vec<&LaunchPrediction> =
        out.iter().filter_map(|e| if let Event::Launch(l) = e { Some(l) } else { None }).collect();
    let failed: Vec<String> = out
        .iter()
        .filter_map(|e| if let Event::Failed { reason, .. } = e { Some(reason.clone()) } else { None })
        .collect();
    assert_eq!(launches.len(), 1, "{failed:?} {:?}", p.counts);
    assert_eq!(launches[0].club, "iron7");
    assert_eq!(launches[0].club_file.as_ref().map(|c| c.file.as_str()), Some("iron7"));
}
