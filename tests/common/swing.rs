//! A synthetic swing as clubhead samples (the `sim` command's rig), and the launches the pipeline predicts
//! from them: the reference the native inputs are compared with.

#![allow(dead_code)]
#![allow(clippy::unwrap_used)]

use impactd::daemon::sim::{SimOptions, SimRig};
use impactd::daemon::DaemonConfig;
use impactd::kinematics::ClubheadSample;
use impactd::pipeline::{Event, Pipeline};
use impactd::wire::LaunchPrediction;

/// `shots` swings of the default driver at `rate_hz`, frame numbers from 1, capture times from 1 s (small
/// times, as Motive's and QTM's are: exact in f64 seconds).
pub fn samples(shots: u64, rate_hz: f64, seed: u64) -> Vec<ClubheadSample> {
    let options = SimOptions { shots, rate_hz, interval_s: 0.4, seed, ..SimOptions::default() };
    let mut rig = SimRig::new("rig1", &options, 1_000_000_000, seed);
    let mut out = Vec::new();
    while !rig.done() {
        out.push(rig.next_sample().unwrap().0);
    }
    out
}

/// The launches of one rig's pipeline over `samples`, as the daemon configured by `config` would predict them.
pub fn launches(config: &str, samples: &[ClubheadSample]) -> Vec<LaunchPrediction> {
    let (_, setups) = DaemonConfig::parse(config).unwrap();
    let mut pipeline = Pipeline::new(setups.into_iter().next().unwrap());
    let mut out = Vec::new();
    for s in samples {
        pipeline.on_sample_with(s, &mut |e| {
            if let Event::Launch(l) = e {
                out.push(l);
            }
        });
    }
    out
}

/// The largest differences between two runs' launches: ball speed (mph), launch angle and direction (deg),
/// back and side spin (rpm).
pub fn max_differences(a: &[LaunchPrediction], b: &[LaunchPrediction]) -> [f64; 5] {
    let mut d = [0f64; 5];
    for (x, y) in a.iter().zip(b) {
        let (x, y) = (&x.launch.launch, &y.launch.launch);
        let v = [
            x.ball_speed_mph - y.ball_speed_mph,
            x.launch_angle_deg - y.launch_angle_deg,
            x.launch_direction_deg - y.launch_direction_deg,
            x.backspin_rpm - y.backspin_rpm,
            x.sidespin_rpm - y.sidespin_rpm,
        ];
        for (d, v) in d.iter_mut().zip(v) {
            *d = d.max(v.abs());
        }
    }
    d
}

/// Launch numbers without the live-only fields (latency), for exact comparison.
pub fn key(l: &LaunchPrediction) -> (u64, u64, String) {
    let mut l = l.clone();
    l.latency_us = 0.0;
    (l.shot, l.frame, serde_json::to_string(&l.launch).unwrap())
}
