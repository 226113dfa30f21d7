//! `impactd watch` for real: the binary joins a daemon on loopback zenoh while a synthetic rig swings, and
//! prints one line per shot. Each line's numbers are the prediction's; its delay from the prediction's
//! publication (loopback, from the test's own subscriber to the line read from the child's stdout) is measured
//! and printed, never asserted.

#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]

use crate::common;

use std::collections::HashMap;
use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

use common::{quantile, start_daemon};
use impactd::daemon::sim::{run_sim, SimOptions};
use impactd::daemon::RunOptions;
use impactd::equipment::ClubSpec;
use impactd::wire::LaunchPrediction;
use zenoh::Wait;

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn each_shot_is_shown_once_with_its_launch_numbers() {
    let config = "[[rig]]\nname = \"bay1\"\nclub = \"driver\"\n";
    let daemon = start_daemon(config, RunOptions::default()).await;
    let shots = 12u64;
    let mut child = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(["watch", "bay1", "--units", "metric", "--count", &shots.to_string(), "-e", &daemon.endpoint])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Lines as they arrive, stamped on arrival.
    let (tx, rx) = mpsc::channel::<(Instant, String)>();
    let stdout = child.stdout.take().unwrap();
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            let _ = tx.send((Instant::now(), line));
        }
    });
    let (ready_tx, ready_rx) = mpsc::channel::<()>();
    let stderr = child.stderr.take().unwrap();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            if line.starts_with("watching golf/bay1/launch") {
                let _ = ready_tx.send(());
            }
        }
    });
    ready_rx.recv_timeout(Duration::from_secs(20)).expect("watch subscribes");
    // The test's own subscriber stamps each launch as it is published (in-process loopback: microseconds).
    let rig = common::client(&daemon.endpoint).await;
    let published: Arc<Mutex<HashMap<u64, (Instant, LaunchPrediction)>>> = Arc::default();
    let p = published.clone();
    let _sub = rig
        .declare_subscriber("golf/bay1/launch")
        .callback(move |s| {
            let now = Instant::now();
            let l: LaunchPrediction = serde_json::from_slice(&s.payload().to_bytes()).unwrap();
            p.lock().unwrap().entry(l.shot).or_insert((now, l));
        })
        .wait()
        .unwrap();
    tokio::time::sleep(Duration::from_millis(500)).await;
    let sim = SimOptions {
        rigs: vec!["bay1".into()],
        club: ClubSpec::driver(),
        shots,
        interval_s: 0.3,
        seed: 3,
        ..SimOptions::default()
    };
    run_sim(&rig, sim, std::future::pending()).await.unwrap();
    let status = tokio::task::spawn_blocking(move || wait_at_most_30_s(child)).await.unwrap();
    assert!(status.success(), "watch exits 0 after --count shots");
    // The reader ends at the child's end of output.
    let lines: Vec<(Instant, String)> = tokio::task::spawn_blocking(move || rx.iter().collect()).await.unwrap();
    let published = published.lock().unwrap().clone();
    assert_eq!(published.len() as u64, shots);
    let rows: Vec<&(Instant, String)> = lines.iter().filter(|(_, l)| l.starts_with("bay1#")).collect();
    assert_eq!(rows.len() as u64, shots, "one line per shot: {lines:?}");
    assert!(lines[1].1.contains("m/s") && !lines[1].1.contains("mph"), "metric units: {}", lines[1].1);
    let mut delays_ms = Vec::new();
    for (at, line) in rows {
        let fields: Vec<&str> = line.split_whitespace().collect();
        let shot: u64 = fields[0].trim_start_matches("bay1#").parse().unwrap();
        let (published_at, l) = &published[&shot];
        // Club speed and ball speed in m/s, spin in rpm, carry in m, as the prediction has them.
        // A metric with an uncertainty shows its one sigma beside it: `62.4±0.1`.
        let cells: Vec<(f64, Option<f64>)> = fields[2..]
            .iter()
            .map(|f| match f.split_once('±') {
                Some((v, s)) => (v.parse().unwrap(), Some(s.parse().unwrap())),
                None => (f.parse().unwrap(), None),
            })
            .collect();
        let numbers: Vec<f64> = cells.iter().map(|c| c.0).collect();
        assert_eq!(numbers.len(), 17, "{line}");
        let (d, u) = (l.delivery.uncertainty.unwrap(), l.launch.uncertainty.unwrap());
        assert!((cells[0].1.unwrap() - d.club_speed_mph * 0.44704).abs() <= 0.051, "club speed's sigma: {line}");
        assert!((cells[10].1.unwrap() - u.total_spin_rpm).abs() <= 0.51, "spin's sigma: {line}");
        assert_eq!(cells.iter().filter(|c| c.1.is_some()).count(), 11, "every metric with a sigma shows it: {line}");
        assert!((numbers[0] - l.delivery.club_speed_mps).abs() <= 0.051, "{line}");
        assert!((numbers[6] - l.launch.launch.ball_speed_mps).abs() <= 0.051, "{line}");
        assert!((numbers[10] - l.launch.launch.total_spin_rpm).abs() <= 0.51, "{line}");
        assert!((numbers[12] - l.flight.as_ref().unwrap().carry_m).abs() <= 0.051, "{line}");
        delays_ms.push(at.saturating_duration_since(*published_at).as_secs_f64() * 1e3);
    }
    let (p50, max) = (quantile(&delays_ms, 0.5), delays_ms.iter().cloned().fold(0.0, f64::max));
    eprintln!("watch: {shots} shots, publication to line p50 {p50:.2} ms, max {max:.2} ms");
    // The delay is measured, not asserted (a wall-clock bound cannot hold on a shared machine).
    assert_eq!(delays_ms.len() as u64, shots);
    rig.close().await.unwrap();
    daemon.stop().await;
}

/// Waits up to 30 s for the child, killing it after.
fn wait_at_most_30_s(mut child: std::process::Child) -> std::process::ExitStatus {
    let start = Instant::now();
    loop {
        if let Some(s) = child.try_wait().unwrap() {
            return s;
        }
        if start.elapsed() > Duration::from_secs(30) {
            let _ = child.kill();
            return child.wait().unwrap();
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}
