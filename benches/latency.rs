//! Sample -> published prediction latency on loopback: a synthetic rig and a subscriber share one zenoh session,
//! the daemon another, connected over TCP on 127.0.0.1. For every shot, the time from the subscriber seeing the
//! frame that reveals the impact to it receiving the prediction, and the daemon's own `latency_us` (callback to
//! publish). Prints p50/p99/max. `cargo bench --bench latency [-- SHOTS]`.

#![allow(clippy::unwrap_used)]

use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use impactd::daemon::bus::{free_loopback_port, ZenohArgs};
use impactd::daemon::sim::{run_sim, SimOptions};
use impactd::daemon::{DaemonConfig, RunOptions};
use impactd::wire::LaunchPrediction;
use zenoh::Wait;

fn quantile(v: &mut [f64], q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v[((q * v.len() as f64).ceil() as usize).clamp(1, v.len()) - 1]
}

fn main() {
    let shots: u64 = std::env::args().skip(1).find_map(|a| a.parse().ok()).unwrap_or(200);
    let rt = tokio::runtime::Builder::new_multi_thread().enable_all().build().unwrap();
    rt.block_on(async {
        let (config, setups) = DaemonConfig::parse("[[rig]]\nname = \"rig1\"\n").unwrap();
        let endpoint = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
        let daemon_session = ZenohArgs::loopback(vec![endpoint.clone()], vec![]).open().await.unwrap();
        let rig = ZenohArgs::loopback(vec![], vec![endpoint]).open().await.unwrap();
        let frames: Arc<Mutex<HashMap<u64, Instant>>> = Default::default();
        let results: Arc<Mutex<Vec<(f64, f64)>>> = Default::default();
        let f = frames.clone();
        let _frames_sub = rig
            .declare_subscriber("mocap/rig1/clubhead")
            .callback(move |s| {
                let now = Instant::now();
                if let Ok(v) = serde_json::from_slice::<serde_json::Value>(&s.payload().to_bytes()) {
                    if let Some(frame) = v["frame"].as_u64() {
                        f.lock().unwrap().insert(frame, now);
                    }
                }
            })
            .wait()
            .unwrap();
        let (f, r) = (frames.clone(), results.clone());
        let _launch_sub = rig
            .declare_subscriber("golf/rig1/launch")
            .callback(move |s| {
                let now = Instant::now();
                if let Ok(l) = serde_json::from_slice::<LaunchPrediction>(&s.payload().to_bytes()) {
                    if let Some(t) = f.lock().unwrap().get(&l.frame) {
                        r.lock().unwrap().push((now.duration_since(*t).as_secs_f64() * 1e6, l.latency_us));
                    }
                }
            })
            .wait()
            .unwrap();
        let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
        let daemon = tokio::spawn(async move {
            impactd::daemon::run(config, setups, &daemon_session, RunOptions::default(), async {
                let _ = stopped.await;
            })
            .await
            .unwrap();
            daemon_session.close().await.unwrap();
        });
        let options = SimOptions { shots, interval_s: 0.25, ..SimOptions::default() };
        run_sim(&rig, options, std::future::pending()).await.unwrap();
        tokio::time::sleep(Duration::from_millis(300)).await;
        let _ = stop.send(());
        daemon.await.unwrap();
        let results = results.lock().unwrap().clone();
        let mut end_to_end: Vec<f64> = results.iter().map(|r| r.0).collect();
        let mut in_daemon: Vec<f64> = results.iter().map(|r| r.1).collect();
        println!("{} of {shots} shots predicted", results.len());
        for (name, v) in [
            ("revealing frame -> prediction received (loopback)", &mut end_to_end),
            ("in the daemon: callback -> published", &mut in_daemon),
        ] {
            let (p50, p99) = (quantile(v, 0.5), quantile(v, 0.99));
            let max = v.iter().cloned().fold(0.0, f64::max);
            println!("{name}: p50 {p50:.0} us, p99 {p99:.0} us, max {max:.0} us");
        }
        rig.close().await.unwrap();
    });
}
