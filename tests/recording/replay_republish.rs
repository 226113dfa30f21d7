//! `impactd replay --publish-samples`: a recording drives another daemon live. The recorded clubhead samples go
//! out on `mocap/<rig>/clubhead`; a second daemon, in-process on loopback zenoh, predicts from them, and its
//! predictions are the replay's own (the pipeline is deterministic), latency aside.

#![allow(clippy::unwrap_used)]

use crate::common;

use std::path::Path;
use std::time::Duration;

use common::{client, collect, start_daemon, wait_until};
use impactd::daemon::replay::{self, Publish, ReplayOptions};
use impactd::daemon::RunOptions;
use impactd::pipeline::Event;
use impactd::wire::{keys, LaunchPrediction};

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_recording_drives_another_daemon_live() {
    let recording = Path::new(env!("CARGO_MANIFEST_DIR")).join("recordings/driver.mcap");
    let input = replay::load(&recording).unwrap();
    let stored = input.config_toml.clone().expect("the recording stores its configuration");
    let (config, setups) = replay::resolve_config(&input, None).unwrap();
    let rig = config.rigs[0].name.clone();

    // The second daemon serves the recorded rig with the recorded configuration, and records nothing.
    let daemon = start_daemon(&stored, RunOptions::default()).await;
    let watcher = client(&daemon.endpoint).await;
    let (live, _sub) = collect::<LaunchPrediction>(&watcher, &keys::launch(&rig));
    let replayer = client(&daemon.endpoint).await;

    // Ten times real time: the daemon's queue is not what is under test.
    let options = ReplayOptions { rate: Some(10.0), publish: Publish::Samples, ..Default::default() };
    let mut replayed: Vec<LaunchPrediction> = Vec::new();
    let report = replay::run(&input, &config, setups, Some(&replayer), &options, |e, _| {
        if let Event::Launch(l) = e {
            replayed.push(l.clone());
        }
    })
    .await
    .unwrap();
    assert!(report.produced >= 3, "{report:?}");
    let all_in = wait_until(Duration::from_secs(30), || live.lock().unwrap().len() >= report.produced).await;
    replayer.close().await.unwrap();
    watcher.close().await.unwrap();
    let summary = daemon.stop().await;
    let live = live.lock().unwrap().clone();
    assert!(all_in, "the daemon predicted {} of {} shots; {summary:?}", live.len(), report.produced);

    // Same shots, same numbers: only the latency is the live daemon's own.
    assert_eq!(live.len(), replayed.len());
    for (a, b) in live.iter().zip(&replayed) {
        let strip = |l: &LaunchPrediction| {
            let mut v = serde_json::to_value(l).unwrap();
            v.as_object_mut().unwrap().remove("latency_us");
            v
        };
        assert_eq!(strip(a), strip(b), "shot {}", a.shot);
    }
}
