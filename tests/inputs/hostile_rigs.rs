//! The probes of a rig's own inputs against the real `impactd run` binary on loopback, a synthetic rig swinging
//! at it throughout (the honest rig, whose latency docs/hostile-peers.md gives beside each case): club puts that
//! would block an unchecked loader (a FIFO, a pipe, a device), a NatNet server info spoofed from another port and
//! a NatNet stream that decodes nothing, a QTM that goes silent after its handshake, and a second daemon on the
//! same rig. Each asserts counts, exit codes, log lines and memory, never a time; a hang guard of tens of seconds
//! only detects a hang.

#![allow(clippy::unwrap_used)]
#![cfg(all(feature = "daemon", target_os = "linux"))]

use crate::common;
use crate::natnet_server;
use crate::probe_daemon;
use crate::qtm_server;
use crate::swing;

use std::path::Path;
use std::process::Command;
use std::sync::atomic::Ordering;
use std::time::Duration;

use impactd::kinematics::ClubheadSample;
use impactd::wire::{keys, ConnectionState, LaunchPrediction, MocapInputStatus, StatusMessage};
use probe_daemon::{report_latency, DaemonProcess, SimRig, RSS_LIMIT_KB};
use zenoh::Wait;

const SHOTS: u64 = 10;

/// The daemon's peak resident set while `busy` holds, sampled every 50 ms.
async fn peak_rss(d: &DaemonProcess, mut busy: impl FnMut() -> bool) -> u64 {
    let mut peak = d.rss_kb();
    while busy() {
        peak = peak.max(d.rss_kb());
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    peak.max(d.rss_kb())
}

/// Waits (a hang guard) for the last status of `rig` whose input satisfies `done`.
async fn input_status(
    statuses: &common::Collected<StatusMessage>,
    done: impl Fn(&MocapInputStatus) -> bool,
) -> MocapInputStatus {
    common::latest_input(statuses, done).await
}

/// Club puts that would block a loader that opened whatever it was named: a FIFO in the club directory, the
/// daemon's own stdout (a pipe), a device, and a club file outside the club directories; then a good one. Each
/// bad one is refused saying why, the good one switches the club, every shot is predicted, and SIGTERM ends the
/// daemon with its recording closed (summary and all), which replays byte for byte.
#[tokio::test(flavor = "multi_thread")]
async fn club_puts_that_would_block_are_refused_and_shutdown_closes_the_recording() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = tempfile::tempdir().unwrap();
    let clubs = dir.path().join("clubs");
    std::fs::create_dir_all(&clubs).unwrap();
    let fifo = clubs.join("stall.toml");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    // The rig swings a driver: the good put is a driver of its own (another file, another hash).
    let driver = std::fs::read_to_string(root.join("clubs/presets/driver.toml")).unwrap();
    let mine = driver.replace("name = \"driver\"", "name = \"my driver\"");
    assert_ne!(mine, driver);
    std::fs::write(clubs.join("my-driver.toml"), mine).unwrap();
    let recording = dir.path().join("session.mcap");
    let config = "status_period_s = 0.2\n[clubs]\ndirs = [\"clubs\"]\n[[rig]]\nname = \"bay1\"\n";
    let d = DaemonProcess::start(dir.path(), "daemon", config, &[], &["--record", recording.to_str().unwrap()]);
    let mut rig = SimRig::listen(&[&d.zenoh], "bay1").await;
    rig.wait_served().await;
    let club = rig.session.declare_publisher(keys::club("bay1")).await.unwrap();
    let matched = || club.matching_status().wait().is_ok_and(|m| m.matching());
    assert!(common::wait_until(Duration::from_secs(20), matched).await);
    let shots = 3 * SHOTS;
    rig.swing(&d.zenoh, "bay1", shots);
    let outside = root.join("clubs/presets/driver.toml");
    for put in ["stall.toml", fifo.to_str().unwrap(), "/proc/self/fd/1", "/dev/zero", outside.to_str().unwrap()] {
        club.put(put).await.unwrap();
        // The refusals are logged at most once a second (docs/limits.md): one each, to read back.
        tokio::time::sleep(Duration::from_millis(1200)).await;
    }
    club.put("my-driver.toml").await.unwrap();
    let statuses = rig.statuses.clone();
    let switched =
        move || statuses.lock().unwrap().last().and_then(|s| s.club.clone()).is_some_and(|c| c.name == "my driver");
    let peak = peak_rss(&d, || !switched()).await;
    assert!(switched(), "the good put switched the club");
    let latencies = rig.finish(shots as usize).await;
    let peak = peak.max(d.rss_kb());
    let log = d.log();
    assert_eq!(latencies.len() as u64, shots, "every shot predicted:\n{log}");
    let refused = |says: &str| log.lines().filter(|l| l.contains("refused") && l.contains(says)).count();
    assert_eq!(refused("is a FIFO, not a regular file"), 2, "{log}");
    assert_eq!(refused("is not under the club directories"), 3, "{log}");
    assert!(!log.contains("not loaded within"), "no put needed the timeout:\n{log}");
    report_latency("club_puts", &latencies, peak);
    assert!(peak < RSS_LIMIT_KB, "peak RSS {peak} kB");

    let status = d.stop();
    assert!(status.success(), "{status}");
    let bytes = std::fs::read(&recording).unwrap();
    let summary = mcap::Summary::read(&bytes).unwrap();
    assert!(summary.is_some_and(|s| s.stats.is_some_and(|st| st.message_count > 0)), "the recording has its summary");
    let changes = common::recorded(&recording).remove("/golf/bay1/club").unwrap_or_default();
    let sources: Vec<(&str, &str)> =
        changes.iter().map(|c| (c["source"].as_str().unwrap(), c["club"]["name"].as_str().unwrap())).collect();
    assert_eq!(sources, [("config", "driver"), ("put", "my driver")], "{changes:?}");
    let replay = Command::new(env!("CARGO_BIN_EXE_impactd")).arg("replay").arg(&recording).output().unwrap();
    let err = String::from_utf8_lossy(&replay.stderr);
    assert!(err.contains(&format!("{shots} of {shots} recorded predictions reproduced byte for byte")), "{err}");
}

/// A NatNet frame of `s` with its frame number and time moved on by `shift` frames and seconds.
fn natnet_frame(s: &ClubheadSample, shift: (i32, f64)) -> impactd::mocap::natnet::Frame {
    use impactd::mocap::natnet::{Frame, RigidBody};
    let p = [s.position_m.x as f32, s.position_m.y as f32, s.position_m.z as f32];
    let club = RigidBody {
        id: 3,
        position_m: p,
        orientation_xyzw: s.orientation_xyzw.map(|v| v as f32),
        mean_error_m: 0.0002,
        tracking_valid: !s.occluded,
    };
    let t_s = s.t_ns as f64 * 1e-9 + shift.1;
    let ticks = (t_s * natnet_server::CLOCK_HZ as f64) as u64;
    Frame {
        frame_number: s.frame as i32 + shift.0,
        rigid_bodies: vec![club],
        labeled_markers: Vec::new(),
        timestamp_s: t_s,
        mid_exposure_ticks: ticks,
        data_received_ticks: ticks + 20_000,
        transmit_ticks: ticks + 35_000,
        models_changed: false,
    }
}

fn play_natnet(server: &natnet_server::NatNetServer, samples: &[ClubheadSample], shift: (i32, f64)) {
    for (i, s) in samples.iter().enumerate() {
        server.send_frame(&natnet_frame(s, shift));
        if i % 4 == 3 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }
}

/// A NatNet server info announcing 2.9 from another port of the server's address, mid-swing (one datagram left
/// the rig dead: every later frame `unknown_version`, status "connected"): counted, and the NatNet rig predicts
/// every shot. Then a stream that decodes nothing: after UNDECODABLE_FRAMES frames the client connects again,
/// says so and counts it, and the next swing is predicted. The honest zenoh rig predicts throughout.
#[tokio::test(flavor = "multi_thread")]
async fn natnet_spoofed_version_and_undecodable_stream_leave_every_rig_predicting() {
    use impactd::daemon::inputs::natnet::UNDECODABLE_FRAMES;
    use impactd::mocap::natnet::encode as natnet_encode;
    use impactd::mocap::natnet::{ServerInfo, Version};
    let server = natnet_server::NatNetServer::start(Version::V4_1, &[(3, "club")]);
    let dir = tempfile::tempdir().unwrap();
    let config = format!(
        "status_period_s = 0.2\n[[rig]]\nname = \"bay1\"\n[[rig]]\nname = \"nat\"\n[rig.input]\nnatnet = \
         \"127.0.0.1\"\nbody = \"club\"\nunicast = true\ncommand_port = {}\ndata_port = 0\n",
        server.port
    );
    let d = DaemonProcess::start(dir.path(), "daemon", &config, &[], &[]);
    let mut rig = SimRig::listen(&[&d.zenoh], "bay1").await;
    let (nat_launches, _l) = common::collect::<LaunchPrediction>(&rig.session, &keys::launch("nat"));
    let (nat_statuses, _s) = common::collect::<StatusMessage>(&rig.session, &keys::status("nat"));
    rig.wait_served().await;
    input_status(&nat_statuses, |s| s.connects == 1 && s.body_found).await;
    rig.swing(&d.zenoh, "bay1", SHOTS);
    let spoof = natnet_encode::server_info(&ServerInfo {
        app_name: "Motive".into(),
        natnet_version: [2, 9, 0, 0],
        clock_hz: Some(natnet_server::CLOCK_HZ),
        ..ServerInfo::default()
    });
    let first = swing::samples(3, 720.0, 21);
    let second = swing::samples(2, 720.0, 22);
    let (last_frame, last_s) = (first.last().unwrap().frame as i32, first.last().unwrap().t_ns as f64 * 1e-9);
    let half = first.len() / 2;
    play_natnet(&server, &first[..half], (0, 0.0));
    server.send_from_other_port(&spoof);
    play_natnet(&server, &first[half..], (0, 0.0));
    let n = nat_launches.clone();
    assert!(common::wait_until(Duration::from_secs(20), || n.lock().unwrap().len() >= 3).await, "three launches");
    let s = input_status(&nat_statuses, |s| s.published == first.len() as u64).await;
    assert_eq!(s.rejected.get("unsolicited_server_info"), Some(&1), "{s:?}");
    assert_eq!((s.connects, s.state), (1, ConnectionState::Connected), "{s:?}");

    for _ in 0..UNDECODABLE_FRAMES {
        server.send_raw(&[7, 0, 0, 0]);
    }
    let s = input_status(&nat_statuses, |s| s.reconnects.get("undecodable") == Some(&1) && s.connects == 2).await;
    assert!(s.last_error.is_some(), "{s:?}");
    play_natnet(&server, &second, (last_frame + 1000, last_s + 2.0));
    let n = nat_launches.clone();
    assert!(common::wait_until(Duration::from_secs(20), || n.lock().unwrap().len() >= 5).await, "five launches");
    let peak = peak_rss(&d, || false).await;
    let latencies = rig.finish(SHOTS as usize).await;
    assert_eq!(latencies.len() as u64, SHOTS, "every honest shot predicted");
    assert_eq!(nat_launches.lock().unwrap().len(), 5, "every NatNet shot predicted once");
    let log = d.log();
    assert!(log.contains("did not decode") && log.contains("connecting again"), "{log}");
    report_latency("natnet_version", &latencies, peak);
    assert!(peak < RSS_LIMIT_KB, "peak RSS {peak} kB");
    assert!(d.stop().success());
}

/// A QTM 6D frame of `s` (its one body).
fn qtm_frame(s: &ClubheadSample) -> impactd::mocap::qtm::Frame6d {
    use impactd::math::{Quaternion, UnitQuaternion};
    let [x, y, z, w] = s.orientation_xyzw;
    let m = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)).to_rotation_matrix();
    let mut rotation = [0f32; 9];
    for (r, v) in rotation.iter_mut().zip(m.matrix().as_slice()) {
        *r = *v as f32;
    }
    let p = s.position_m * 1e3;
    let body =
        impactd::mocap::qtm::Body6d { position_mm: [p.x as f32, p.y as f32, p.z as f32], rotation, residual_mm: None };
    impactd::mocap::qtm::Frame6d {
        timestamp_us: (s.t_ns / 1000) as i64,
        frame_number: s.frame as u32,
        bodies: vec![body],
        drop_rate_2d: 0,
        out_of_sync_rate_2d: 0,
        markers_mm: Vec::new(),
    }
}

/// A QTM that goes silent after its handshake (it asked for frames, then nothing, not even an answer to
/// `QTMVersion`): after 3 s the connection is ended and counted (`reconnects.quiet`), the status stops saying
/// "connected", and once QTM speaks again its rig predicts. The honest rig predicts throughout.
#[tokio::test(flavor = "multi_thread")]
async fn a_silent_qtm_is_connected_to_again_and_every_rig_predicts() {
    let server = qtm_server::QtmServer::start(&["club"]);
    let dir = tempfile::tempdir().unwrap();
    let config = format!(
        "status_period_s = 0.2\n[[rig]]\nname = \"bay1\"\n[[rig]]\nname = \"q\"\n[rig.input]\nqtm = \
         \"127.0.0.1\"\nbody = \"club\"\nport = {}\n",
        server.port
    );
    let d = DaemonProcess::start(dir.path(), "daemon", &config, &[], &[]);
    let mut rig = SimRig::listen(&[&d.zenoh], "bay1").await;
    let (q_launches, _l) = common::collect::<LaunchPrediction>(&rig.session, &keys::launch("q"));
    let (q_statuses, _s) = common::collect::<StatusMessage>(&rig.session, &keys::status("q"));
    rig.wait_served().await;
    input_status(&q_statuses, |s| s.connects == 1 && s.state == ConnectionState::Connected).await;
    rig.swing(&d.zenoh, "bay1", SHOTS);
    server.mute.store(true, Ordering::Relaxed);
    let s = input_status(&q_statuses, |s| s.reconnects.get("quiet") == Some(&1)).await;
    assert_ne!(s.state, ConnectionState::Connected, "{s:?}");
    server.mute.store(false, Ordering::Relaxed);
    input_status(&q_statuses, |s| s.connects == 2 && s.state == ConnectionState::Connected).await;
    for s in swing::samples(2, 720.0, 23) {
        server.send_frame(&qtm_frame(&s));
        if s.frame % 4 == 3 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }
    let n = q_launches.clone();
    assert!(common::wait_until(Duration::from_secs(20), || n.lock().unwrap().len() >= 2).await, "QTM's two shots");
    let peak = peak_rss(&d, || false).await;
    let latencies = rig.finish(SHOTS as usize).await;
    assert_eq!(latencies.len() as u64, SHOTS, "every honest shot predicted");
    assert!(d.log().contains("QTM sent nothing for 3 s"), "{}", d.log());
    report_latency("qtm_silent", &latencies, peak);
    assert!(peak < RSS_LIMIT_KB, "peak RSS {peak} kB");
    assert!(d.stop().success());
}

/// Two daemons on one rig: the second refuses (exit 4, saying who serves the rig) and the first says it refused
/// one; the shots are predicted once each. `--take-over` hands the rig over: the first stops (exit 0, its
/// recording closed) and says why, the second serves the rig and predicts the next shots, once each.
#[tokio::test(flavor = "multi_thread")]
async fn a_second_daemon_on_a_rig_refuses_unless_it_takes_over() {
    let dir = tempfile::tempdir().unwrap();
    let config = "status_period_s = 0.2\n[[rig]]\nname = \"bay1\"\n";
    let recording = dir.path().join("first.mcap");
    let first = DaemonProcess::start(dir.path(), "first", config, &[], &["--record", recording.to_str().unwrap()]);
    let mut rig = SimRig::listen(&[&first.zenoh], "bay1").await;
    rig.wait_served().await;
    rig.swing(&first.zenoh, "bay1", SHOTS);
    let mut second = DaemonProcess::start(dir.path(), "second", config, &[&first.zenoh], &[]);
    let code = second.wait(Duration::from_secs(30)).and_then(|s| s.code());
    assert_eq!(code, Some(4), "the second daemon refuses: {}", second.log());
    let said = second.log();
    assert!(
        said.contains("rig bay1 is already served by impactd") && said.contains(&first.pid().to_string()),
        "{said}"
    );
    let peak = peak_rss(&first, || false).await;
    let latencies = rig.finish(SHOTS as usize).await;
    let shots: Vec<u64> = rig.launches.lock().unwrap().iter().map(|l| l.shot).collect();
    assert_eq!(shots, (1..=SHOTS).collect::<Vec<_>>(), "each shot predicted once");
    assert!(first.log().contains("asked to serve it too and was refused"), "{}", first.log());
    report_latency("second_daemon", &latencies, peak);
    assert!(peak < RSS_LIMIT_KB, "peak RSS {peak} kB");

    let mut first = first;
    let third = DaemonProcess::start(dir.path(), "third", config, &[&first.zenoh], &["--take-over"]);
    let status = first.wait(Duration::from_secs(30));
    assert!(status.is_some_and(|s| s.success()), "the first daemon stops, handing over: {}", first.log());
    assert!(first.log().contains("takes it over (--take-over); this daemon stops"), "{}", first.log());
    assert!(mcap::Summary::read(&std::fs::read(&recording).unwrap()).unwrap().is_some(), "its recording is closed");
    let mut next = SimRig::listen(&[&third.zenoh], "bay1").await;
    let t = third.log();
    let said = || third.log().contains("rig bay1: taken over from impactd");
    assert!(common::wait_until(Duration::from_secs(30), said).await, "{t}");
    next.wait_served().await;
    next.swing(&third.zenoh, "bay1", 3);
    next.finish(3).await;
    let shots: Vec<u64> = next.launches.lock().unwrap().iter().map(|l| l.shot).collect();
    assert_eq!(shots, [1, 2, 3], "the new daemon predicts each shot once");
    assert!(third.stop().success());
}
