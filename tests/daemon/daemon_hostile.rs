//! The live daemon against hostile peers and an unlucky disk, with real zenoh sessions on loopback: one hostile
//! sample and a publisher restart from frame 1 cost the rig no later swing; a flood of 1 MiB payloads grows the
//! recording by at most the budget; a full disk is logged within a second while predictions go on; and
//! `impactd run` with no flags listens on loopback only.

#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use impactd::daemon::bus::{free_loopback_port, ZenohArgs};
use impactd::daemon::sim::{run_sim, SimOptions};
use impactd::daemon::stats::{REJECTED_BYTES_PER_S, REJECTED_KEEP_BYTES};
use impactd::daemon::{DaemonConfig, RunOptions, RunSummary};
use impactd::equipment::ClubSpec;
use impactd::wire::{keys, LaunchPrediction};
use zenoh::Wait;

struct Daemon {
    endpoint: String,
    stop: tokio::sync::oneshot::Sender<()>,
    task: tokio::task::JoinHandle<RunSummary>,
}

async fn start_daemon(record: Option<&Path>) -> Daemon {
    let (config, setups) = DaemonConfig::parse("[[rig]]\nname = \"bay1\"\n").unwrap();
    let endpoint = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
    let session = ZenohArgs::loopback(vec![endpoint.clone()], vec![]).open().await.unwrap();
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let options = RunOptions { record: record.map(Path::to_path_buf), ..Default::default() };
    let task = tokio::spawn(async move {
        let s = impactd::daemon::run(config, setups, &session, options, async {
            let _ = stopped.await;
        })
        .await
        .unwrap();
        session.close().await.unwrap();
        s
    });
    Daemon { endpoint, stop, task }
}

async fn client(endpoint: &str) -> zenoh::Session {
    ZenohArgs::loopback(vec![], vec![endpoint.to_string()]).open().await.unwrap()
}

fn launches(session: &zenoh::Session) -> (Arc<Mutex<Vec<LaunchPrediction>>>, zenoh::pubsub::Subscriber<()>) {
    let out: Arc<Mutex<Vec<LaunchPrediction>>> = Default::default();
    let cb = out.clone();
    let sub = session
        .declare_subscriber(keys::launch("bay1"))
        .callback(move |s| {
            if let Ok(l) = serde_json::from_slice(&s.payload().to_bytes()) {
                cb.lock().unwrap().push(l);
            }
        })
        .wait()
        .unwrap();
    (out, sub)
}

fn sim(shots: u64, seed: u64) -> SimOptions {
    SimOptions {
        rigs: vec!["bay1".into()],
        club: ClubSpec::driver(),
        shots,
        interval_s: 0.5,
        seed,
        ..SimOptions::default()
    }
}

async fn put(p: &zenoh::pubsub::Publisher<'_>, payload: String) {
    p.put(payload.into_bytes()).await.unwrap();
}

/// A hostile sample (frame 2^63, a year ahead), then a publisher restarting from frame 1: the rig predicts its
/// next swing each time, and the status counts the reset.
#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn hostile_sample_and_restart_cost_no_later_swing() {
    let daemon = start_daemon(None).await;
    let rig = client(&daemon.endpoint).await;
    let (got, _s) = launches(&rig);
    run_sim(&rig, sim(1, 1), std::future::pending()).await.unwrap();
    let hostile = rig.declare_publisher(keys::clubhead("bay1")).wait().unwrap();
    let far = 9_223_372_036_854_775_808u64;
    put(&hostile, format!(
        r#"{{"rig":"bay1","frame":{far},"t_ns":{},"position_m":[0,0.3,-0.2],"orientation":{{"x":0,"y":0,"z":0,"w":1}}}}"#,
        impactd::daemon::clock::Clock::system().wall_ns() + 365 * 24 * 3600 * 1_000_000_000
    ))
    .await;
    // The sim numbers frames from 1 and starts its clock afresh: a restarted publisher.
    run_sim(&rig, sim(1, 2), std::future::pending()).await.unwrap();
    run_sim(&rig, sim(1, 3), std::future::pending()).await.unwrap();
    crate::common::wait_until(Duration::from_secs(60), || got.lock().unwrap().len() >= 3).await;
    let _ = daemon.stop.send(());
    let summary = daemon.task.await.unwrap();
    rig.close().await.unwrap();
    let n = got.lock().unwrap().len();
    assert_eq!(n, 3, "every swing predicted: {:?}", summary.rigs["bay1"]);
    assert!(summary.rigs["bay1"].dropped < 1000, "{:?}", summary.rigs["bay1"]);
}

/// 1 MiB payloads as fast as zenoh takes them for 10 s: the recording grows by at most the budget (64 KiB a
/// second, plus the record framing), and every payload is counted.
#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_flood_grows_the_recording_by_at_most_the_budget() {
    let dir = tempfile::tempdir().unwrap();
    let recording = dir.path().join("flood.mcap");
    let daemon = start_daemon(Some(&recording)).await;
    let rig = client(&daemon.endpoint).await;
    let p = rig.declare_publisher(keys::clubhead("bay1")).wait().unwrap();
    let unknown = rig.declare_publisher(keys::clubhead("bay9")).wait().unwrap();
    while !p.matching_status().await.unwrap().matching() {
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let payload = vec![b'x'; 1 << 20];
    let start = Instant::now();
    let flood_s = 10.0;
    let mut sent = 0u64;
    while start.elapsed().as_secs_f64() < flood_s {
        p.put(payload.clone()).await.unwrap();
        unknown.put(payload.clone()).await.unwrap();
        sent += 1;
    }
    tokio::time::sleep(Duration::from_millis(500)).await;
    let _ = daemon.stop.send(());
    let summary = daemon.task.await.unwrap();
    rig.close().await.unwrap();
    let c = &summary.rigs["bay1"];
    assert!(c.rejected.get(impactd::pipeline::Rejection::Oversized) > 0, "{c:?}");
    assert!(summary.unknown_rig_samples > 0);
    let size = std::fs::metadata(&recording).unwrap().len() as f64;
    // Two budgets (the rig's and the unknown rigs'), each per started second, before compression.
    let seconds = flood_s + 1.5;
    let budget = 2.0 * seconds.ceil() * REJECTED_BYTES_PER_S as f64 + 256.0 * 1024.0;
    assert!(size <= budget, "{size} bytes recorded for {sent} MiB sent; budget {budget}");
    const { assert!(REJECTED_KEEP_BYTES < 1 << 20) };
}

/// `impactd run --record /dev/full --overwrite`: the disk-full error is logged (error level, with the OS's
/// reason) within a second of starting, and the daemon goes on predicting.
#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_full_disk_is_logged_at_once_and_predictions_go_on() {
    if !Path::new("/dev/full").exists() {
        panic!("/dev/full is needed for this test");
    }
    let endpoint = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(["run", "--record", "/dev/full", "--overwrite", "-l", &endpoint])
        .env("RUST_LOG", "info,zenoh=warn")
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    let stderr = child.stderr.take().unwrap();
    let lines: Arc<Mutex<Vec<(Duration, String)>>> = Default::default();
    let lines_w = lines.clone();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            lines_w.lock().unwrap().push((started.elapsed(), line));
        }
    });
    let rig = client(&endpoint).await;
    let (got, _s) = launches(&rig);
    let mut sim = sim(2, 7);
    sim.rigs = vec!["rig1".into()];
    let (got_rig1, _s2) = {
        let out: Arc<Mutex<Vec<LaunchPrediction>>> = Default::default();
        let cb = out.clone();
        let sub = rig
            .declare_subscriber(keys::launch("rig1"))
            .callback(move |s| {
                if let Ok(l) = serde_json::from_slice(&s.payload().to_bytes()) {
                    cb.lock().unwrap().push(l);
                }
            })
            .wait()
            .unwrap();
        (out, sub)
    };
    run_sim(&rig, sim, std::future::pending()).await.unwrap();
    crate::common::wait_until(Duration::from_secs(60), || got_rig1.lock().unwrap().len() >= 2).await;
    let _ = std::process::Command::new("kill").args(["-TERM", &child.id().to_string()]).status();
    child.wait().unwrap();
    rig.close().await.unwrap();
    let lines = lines.lock().unwrap().clone();
    let error = lines.iter().find(|(_, l)| l.contains("ERROR") && l.contains("No space left on device"));
    let (at, line) = error.unwrap_or_else(|| panic!("no disk-full error logged: {lines:?}"));
    eprintln!("logged {at:?} after the start: {line}");
    assert_eq!(lines.iter().filter(|(_, l)| l.contains("ERROR") && l.contains("nothing more is recorded")).count(), 1);
    assert_eq!(got_rig1.lock().unwrap().len(), 2, "predictions go on: {lines:?}");
    assert!(got.lock().unwrap().is_empty());
    assert!(lines.iter().any(|(_, l)| l.contains("recording failed") && l.contains("No space left")), "{lines:?}");
}

/// The sockets (inodes) a process has open.
fn socket_inodes(pid: u32) -> Vec<String> {
    std::fs::read_dir(format!("/proc/{pid}/fd"))
        .unwrap()
        .filter_map(|e| std::fs::read_link(e.ok()?.path()).ok())
        .filter_map(|l| l.to_str()?.strip_prefix("socket:[")?.strip_suffix(']').map(str::to_string))
        .collect()
}

/// `impactd run` with no flags: every TCP socket it listens on and every UDP socket it binds is on loopback.
#[test]
fn run_with_no_flags_listens_on_loopback_only() {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_impactd"))
        .arg("run")
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let inodes = socket_inodes(child.id());
    let mut listening = Vec::new();
    for table in ["tcp", "tcp6", "udp", "udp6"] {
        let text = std::fs::read_to_string(format!("/proc/{}/net/{table}", child.id())).unwrap();
        for row in text.lines().skip(1) {
            let f: Vec<&str> = row.split_whitespace().collect();
            let (local, state, inode) = (f[1], f[3], f[9]);
            // TCP: 0A = LISTEN. UDP: every bound socket receives.
            let counts = table.starts_with("udp") || state == "0A";
            if counts && inodes.iter().any(|i| i == inode) {
                listening.push(format!("{table} {local}"));
            }
        }
    }
    let _ = child.kill();
    let _ = child.wait();
    assert!(!listening.is_empty(), "the daemon listens somewhere");
    for l in &listening {
        let addr = l.split_whitespace().nth(1).unwrap().split(':').next().unwrap();
        // 127.0.0.1 as /proc writes it (little-endian hex), or ::1.
        let loopback = addr == "0100007F" || addr == "00000000000000000000000001000000";
        assert!(loopback, "listening outside loopback: {l} (all: {listening:?})");
    }
}

/// The README's example zenoh configuration starts, and its access control works: a peer may put samples
/// (`mocap/**`) but not predictions (`golf/**`), and still receives the router's predictions.
#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn the_example_acl_config_limits_who_may_put() {
    let endpoint = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
    let router_args = ZenohArgs {
        zenoh_config: Some(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/zenoh-acl.json5").into()),
        listen: vec![endpoint.clone()],
        ..ZenohArgs::default()
    };
    let router = router_args.open().await.unwrap();
    let seen: Arc<Mutex<Vec<String>>> = Default::default();
    let seen_cb = seen.clone();
    let _sub = router
        .declare_subscriber("**")
        .callback(move |s| seen_cb.lock().unwrap().push(s.key_expr().to_string()))
        .await
        .unwrap();
    let peer =
        ZenohArgs { mode: Some(impactd::daemon::bus::Mode::Client), connect: vec![endpoint], ..ZenohArgs::default() }
            .open()
            .await
            .unwrap();
    let got: Arc<Mutex<Vec<String>>> = Default::default();
    let got_cb = got.clone();
    let _peer_sub = peer
        .declare_subscriber("golf/**")
        .callback(move |s| got_cb.lock().unwrap().push(s.key_expr().to_string()))
        .await
        .unwrap();
    tokio::time::sleep(Duration::from_millis(500)).await;
    for _ in 0..5 {
        peer.put("mocap/bay1/clubhead", "{}").await.unwrap();
        peer.put("golf/bay1/launch", "spoofed").await.unwrap();
        router.put("golf/bay1/status", "{}").await.unwrap();
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    let seen = seen.lock().unwrap().clone();
    assert!(seen.iter().any(|k| k == "mocap/bay1/clubhead"), "{seen:?}");
    assert!(!seen.iter().any(|k| k == "golf/bay1/launch"), "a spoofed prediction got through: {seen:?}");
    assert!(got.lock().unwrap().iter().any(|k| k == "golf/bay1/status"), "predictions reach subscribers");
    peer.close().await.unwrap();
    router.close().await.unwrap();
}
