//! The ball where it is: a tracked ball at rest (`mocap/<rig>/ball`) sets the position of the rig's next impact,
//! every impact and launch says which position it used, the recording keeps the ball's samples and replays the
//! same launches; a ball in flight or outside the hitting area changes nothing.

#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]

use crate::common;
use crate::swing;

use std::time::Duration;

use impactd::daemon::replay;
use impactd::daemon::sim::{run_sim, SimOptions};
use impactd::daemon::{DaemonConfig, RunOptions};
use impactd::equipment::ClubSpec;
use impactd::pipeline::Event;
use impactd::wire::{keys, BallSampleMsg, BallSource, ClubheadSampleMsg, LaunchPrediction};
use zenoh::Wait;

const CONFIG: &str = "status_period_s = 0.5\n[[rig]]\nname = \"rig1\"\nclub = \"driver\"\nmodel = \"adjusted\"\n";

fn ball(rig: &str, t_ns: u64, position_m: [f64; 3]) -> BallSampleMsg {
    BallSampleMsg { rig: rig.into(), frame: 0, t_ns, position_m, occluded: false }
}

/// The launches of one synthetic driver swing replayed offline, with `balls` observed before its first sample.
fn launches_with(balls: &[BallSampleMsg]) -> Vec<LaunchPrediction> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("swing.jsonl");
    let mut text = String::new();
    for b in balls {
        text += &serde_json::to_string(b).unwrap();
        text.push('\n');
    }
    for s in swing::samples(1, 720.0, 5) {
        text += &serde_json::to_string(&ClubheadSampleMsg::from_sample("rig1", &s)).unwrap();
        text.push('\n');
    }
    std::fs::write(&path, text).unwrap();
    let input = replay::load(&path).unwrap();
    assert_eq!(input.balls.len(), balls.len(), "ball lines are read beside the samples");
    let (_, setups) = DaemonConfig::parse(CONFIG).unwrap();
    let mut out = Vec::new();
    replay::replay(
        &input,
        setups,
        |_| {},
        |e| {
            if let Event::Launch(l) = e {
                out.push(l.clone());
            }
        },
    );
    out
}

/// A ball 4 mm right of the configured position (world z) is struck 4 mm farther toward the heel or toe: the
/// impact point on the face moves by the ball's displacement along the face (the face is square to the target
/// at impact within a few degrees, so within 0.5 mm), and the launch says the position was tracked.
#[test]
fn a_ball_at_rest_moves_the_impact_by_its_displacement() {
    let fixed = launches_with(&[]);
    assert_eq!(fixed.len(), 1);
    let used = fixed[0].ball.unwrap();
    assert_eq!((used.source, used.position_m), (BallSource::Config, [0.0; 3]));

    let at = [0.0, 0.0, 0.004];
    let tracked = launches_with(&[ball("rig1", 1, at), ball("rig1", 2, at)]);
    assert_eq!(tracked.len(), 1);
    let used = tracked[0].ball.unwrap();
    assert_eq!((used.source, used.position_m), (BallSource::Tracked, at));
    let dh = tracked[0].delivery.impact_h_mm - fixed[0].delivery.impact_h_mm;
    let dv = tracked[0].delivery.impact_v_mm - fixed[0].delivery.impact_v_mm;
    eprintln!("impact moved {dh:.3} mm along the face, {dv:.3} mm up it");
    assert!((dh.abs() - 4.0).abs() < 0.5, "dh {dh} mm");
    assert!(dv.abs() < 0.5, "dv {dv} mm");
    assert_ne!(tracked[0].launch.launch.spin_axis_deg, fixed[0].launch.launch.spin_axis_deg);

    // One observation is no rest; a ball in flight and a ghost 2 m away set nothing.
    let moving = launches_with(&[ball("rig1", 1, at), ball("rig1", 2, [0.05, 0.0, 0.004]), ball("rig1", 3, [2.0; 3])]);
    assert_eq!(moving[0].ball.unwrap().source, BallSource::Config);
    assert_eq!(moving[0].delivery.impact_h_mm, fixed[0].delivery.impact_h_mm);
}

/// Live: ball samples put on `mocap/rig1/ball` before a synthetic swing set its impact's ball; the recording
/// holds them and replays the same launches byte for byte.
#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_tracked_ball_live_is_recorded_and_replayed() {
    let dir = tempfile::tempdir().unwrap();
    let recording = dir.path().join("ball.mcap");
    let options = RunOptions { record: Some(recording.clone()), ..Default::default() };
    let daemon = common::start_daemon(CONFIG, options).await;
    let session = common::client(&daemon.endpoint).await;
    let (launches, _sub) = common::collect::<LaunchPrediction>(&session, &keys::launch("rig1"));
    let publisher = session.declare_publisher(keys::ball("rig1")).wait().unwrap();
    while !publisher.matching_status().await.unwrap().matching() {
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let at = [0.0, 0.0, -0.003];
    for t in 1..=3 {
        publisher.put(serde_json::to_vec(&ball("rig1", t, at)).unwrap()).await.unwrap();
    }
    publisher.put(b"{\"rig\":\"rig1\",\"t_ns\":4,\"position_m\":[NaN]}".to_vec()).await.unwrap();
    let sim = SimOptions {
        rigs: vec!["rig1".into()],
        club: ClubSpec::driver(),
        shots: 2,
        interval_s: 0.6,
        seed: 3,
        ..SimOptions::default()
    };
    run_sim(&session, sim, std::future::pending()).await.unwrap();
    let l = launches.clone();
    assert!(common::wait_until(Duration::from_secs(30), || l.lock().unwrap().len() >= 2).await);
    for l in launches.lock().unwrap().iter() {
        let used = l.ball.unwrap();
        assert_eq!((used.source, used.position_m), (BallSource::Tracked, at), "shot {}", l.shot);
    }
    session.close().await.unwrap();
    daemon.stop().await;

    let recorded = common::recorded(&recording);
    assert_eq!(recorded["/mocap/rig1/ball"].len(), 3, "the three ball samples recorded, the bad one refused");
    let input = replay::load(&recording).unwrap();
    let (_, setups) = DaemonConfig::parse(input.config_toml.as_deref().unwrap()).unwrap();
    let mut produced = Vec::new();
    replay::replay(
        &input,
        setups,
        |_| {},
        |e| {
            if let Event::Launch(l) = e {
                produced.push(serde_json::to_vec(l).unwrap());
            }
        },
    );
    assert_eq!(produced, input.recorded_launches, "replay reproduces the recorded launches");
}
