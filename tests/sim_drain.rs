//! The synthetic rig's end leaves no zenoh ERROR in the log of the session that received its samples.
//!
//! zenoh 1.10 sends a publisher's undeclaration on its control lane, which can overtake samples still queued on
//! the data lane; when the receiver tears its subscriber down at the same moment, it logs `Received Data for
//! unknown key_expr` for each late sample (seen at the end of `impactd demo`). The rig keeps its publishers for
//! `PUBLISHER_DRAIN_S` after its last put; the receiver here then undeclares and closes at once, as the demo's
//! daemon does, round after round, at the rig's highest rate.
#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]

use std::io::Write;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use impactd::daemon::bus::{free_loopback_port, ZenohArgs};
use impactd::daemon::sim::{run_sim, SimOptions, PUBLISHER_DRAIN_S};
use impactd::wire::keys;

#[derive(Clone, Default)]
struct Log(Arc<Mutex<Vec<u8>>>);

impl Write for Log {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl Log {
    fn unknown_key_lines(&self) -> usize {
        String::from_utf8_lossy(&self.0.lock().unwrap()).lines().filter(|l| l.contains("unknown key_expr")).count()
    }
}

/// One rig run at 10 kHz into a subscriber that is undeclared and closed the moment the rig returns; the samples
/// received.
async fn round(drain_s: f64, seed: u64) -> u64 {
    let endpoint = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
    let daemon = ZenohArgs::loopback(vec![endpoint.clone()], vec![]).open().await.unwrap();
    let rig = ZenohArgs::loopback(vec![], vec![endpoint]).open().await.unwrap();
    let received = Arc::new(AtomicU64::new(0));
    let counter = received.clone();
    let subscriber = daemon
        .declare_subscriber(keys::CLUBHEAD_ALL)
        .callback(move |_| {
            counter.fetch_add(1, Ordering::Relaxed);
        })
        .await
        .unwrap();
    let options = SimOptions {
        shots: 1,
        rate_hz: 10_000.0,
        interval_s: 0.2,
        seed,
        wait_for_subscriber_s: 5.0,
        publisher_drain_s: drain_s,
        ..SimOptions::default()
    };
    let sent = run_sim(&rig, options, std::future::pending()).await.unwrap();
    subscriber.undeclare().await.unwrap();
    daemon.close().await.unwrap();
    rig.close().await.unwrap();
    assert!(sent.samples > 1000, "the rig sent {} samples", sent.samples);
    received.load(Ordering::Relaxed)
}

/// 3,000 puts as fast as they go, the publisher held `hold_s` and dropped, the subscriber undeclared and both
/// sessions closed at once: the mechanism, on zenoh alone.
async fn burst(hold_s: f64) {
    let endpoint = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
    let daemon = ZenohArgs::loopback(vec![endpoint.clone()], vec![]).open().await.unwrap();
    let rig = ZenohArgs::loopback(vec![], vec![endpoint]).open().await.unwrap();
    let subscriber = daemon.declare_subscriber(keys::CLUBHEAD_ALL).callback(|_| {}).await.unwrap();
    let publisher = rig.declare_publisher(keys::clubhead("rig1")).await.unwrap();
    while !publisher.matching_status().await.unwrap().matching() {
        tokio::time::sleep(std::time::Duration::from_millis(5)).await;
    }
    std::thread::spawn(move || {
        use zenoh::Wait;
        for _ in 0..3000 {
            publisher.put(vec![7u8; 300]).wait().unwrap();
        }
        std::thread::sleep(std::time::Duration::from_secs_f64(hold_s));
    })
    .join()
    .unwrap();
    subscriber.undeclare().await.unwrap();
    daemon.close().await.unwrap();
    rig.close().await.unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_rigs_end_leaves_no_unknown_key_expr_error() {
    let log = Log::default();
    let writer = log.clone();
    tracing_subscriber::fmt().with_writer(move || writer.clone()).with_env_filter("warn").with_ansi(false).init();

    for _ in 0..10 {
        burst(0.0).await;
    }
    let dropped_at_once = log.unknown_key_lines();
    for _ in 0..10 {
        burst(PUBLISHER_DRAIN_S).await;
    }
    let held = log.unknown_key_lines() - dropped_at_once;
    for seed in 0..6 {
        round(PUBLISHER_DRAIN_S, seed).await;
    }
    let rig = log.unknown_key_lines() - dropped_at_once - held;
    println!(
        "unknown key_expr lines: {dropped_at_once} after 10 bursts dropped at once, {held} after 10 held \
         {PUBLISHER_DRAIN_S} s, {rig} after 6 runs of the synthetic rig"
    );
    let text = String::from_utf8_lossy(&log.0.lock().unwrap()).into_owned();
    assert_eq!(held, 0, "a publisher held after its burst still left unknown key expressions:\n{text}");
    assert_eq!(rig, 0, "the rig's end made zenoh log unknown key expressions:\n{text}");
}
