//! A track that recovers: one hostile sample (a frame number of 2^63, a time a year ahead or at zero) costs at
//! most the swing it lands in, and a publisher that restarts its frame count (or its clock) is followed after a
//! reset. Swings are synthetic with exact truth (`swing::sample`), three per rig, 2 s apart.

#![allow(clippy::unwrap_used, clippy::type_complexity)]

use golf_physics::equipment::ClubSpec;
use golf_physics::impact::Equipment;
use golf_physics::kinematics::{Calibration, ClubheadSample};
use golf_physics::pipeline::{Event, Pipeline, RigSetup};
use golf_physics::rng::Rng;
use golf_physics::swing::{sample, Sampling, Swing, SwingSpec};

const YEAR_NS: u64 = 365 * 24 * 3600 * 1_000_000_000;

/// Three swings' samples, the k-th impact at `t0 + 2 s k`, frames counting from `first_frame`.
fn swings(seed: u64, t0_ns: u64, first_frame: u64) -> Vec<Vec<ClubheadSample>> {
    let club = ClubSpec::driver();
    let eq = Equipment::new(club.clone());
    let mut rng = Rng::new(seed);
    let mut frame = first_frame;
    (0..3)
        .map(|k| {
            let swing = Swing::new(&SwingSpec::random(&club, &mut rng), &eq).unwrap();
            let s = sample(
                &swing,
                &Sampling::default(),
                &Calibration::default(),
                t0_ns + k * 2_000_000_000,
                frame,
                &mut rng,
            );
            frame = s.samples.last().unwrap().frame + 1;
            s.samples
        })
        .collect()
}

fn launches(p: &mut Pipeline, samples: &[ClubheadSample]) -> usize {
    let mut out = Vec::new();
    for s in samples {
        p.on_sample(s, &mut out);
    }
    out.iter().filter(|e| matches!(e, Event::Launch(_))).count()
}

fn pipeline() -> Pipeline {
    Pipeline::new(RigSetup::new("bay1", ClubSpec::driver()))
}

/// Each hostile sample, dropped into the middle of the first swing, costs at most that swing; the next two are
/// predicted.
#[test]
fn one_hostile_sample_costs_at_most_its_swing() {
    let hostile: Vec<(&str, fn(&mut ClubheadSample))> = vec![
        ("frame 2^63", |s| s.frame = 1 << 63),
        ("a year ahead", |s| s.t_ns += YEAR_NS),
        ("time zero", |s| s.t_ns = 0),
        ("frame 2^63 a year ahead", |s| {
            s.frame = 1 << 63;
            s.t_ns += YEAR_NS;
        }),
        ("frame u64::MAX", |s| s.frame = u64::MAX),
    ];
    for (name, spoil) in hostile {
        let sw = swings(1, 10_000_000_000, 1);
        let mut p = pipeline();
        let mid = sw[0].len() / 2;
        let mut bad = sw[0][mid];
        spoil(&mut bad);
        let mut first = sw[0][..mid].to_vec();
        first.push(bad);
        first.extend_from_slice(&sw[0][mid..]);
        let n0 = launches(&mut p, &first);
        let rest = launches(&mut p, &sw[1]) + launches(&mut p, &sw[2]);
        assert_eq!(rest, 2, "{name}: the next swings are predicted (first swing: {n0})");
        // A wild frame number is a new count, not 2^63 dropped frames.
        assert!(p.counts.dropped < 1000, "{name}: dropped {}", p.counts.dropped);
    }
}

/// A publisher that restarts from frame 1 on the same clock, or on a clock restarted at zero, is followed: the
/// swing after the restart is predicted and the restart is counted as a reset.
#[test]
fn a_publisher_restart_is_followed_and_counted() {
    for (name, t_restart_ns) in [("same clock", 20_000_000_000u64), ("clock from zero", 1_000_000_000)] {
        let mut p = pipeline();
        let before = swings(2, 10_000_000_000, 500_000);
        assert_eq!(launches(&mut p, &before[0]), 1, "{name}");
        let after = swings(3, t_restart_ns, 1);
        let n = launches(&mut p, &after[0]) + launches(&mut p, &after[1]);
        assert!(n >= 1, "{name}: {n} swings after the restart predicted");
        assert_eq!(launches(&mut p, &after[2]), 1, "{name}: steady after the restart");
        assert!(p.counts.resets >= 1, "{name}: the restart is counted");
        assert!(p.counts.dropped < 1000, "{name}: dropped {}", p.counts.dropped);
    }
}

/// A frame counter that wraps (u32 rigs) while time goes on is a reset, not dropped frames.
#[test]
fn a_wrapping_frame_counter_is_a_reset() {
    let mut p = pipeline();
    let sw = swings(4, 10_000_000_000, u64::from(u32::MAX) - 100);
    let mut all: Vec<ClubheadSample> = sw.concat();
    for s in &mut all {
        s.frame %= 1 << 32;
    }
    assert_eq!(launches(&mut p, &all), 3);
    assert!(p.counts.resets >= 1);
    assert!(p.counts.dropped < 1000, "dropped {}", p.counts.dropped);
}
