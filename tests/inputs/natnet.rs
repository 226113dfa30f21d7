//! OptiTrack NatNet, live: a NatNet server in this test (127.0.0.1 unicast only) that OptiTrack's own Python
//! client (`natnetsdk`, pinned in scripts/test-requirements.txt) reads as it reads Motive; then the daemon's
//! `[rig.input] natnet` and `impactd bridge natnet`, fed a synthetic swing through that server, against the same
//! swing sent as JSON.

#![allow(clippy::unwrap_used)]

use crate::common;
use crate::natnet_server;
use crate::swing;

use std::time::Duration;

use common::{client, client_result, collect, latest_input, rss_kib, spawn_client, start_daemon, wait_for, wait_until};
use impactd::daemon::inputs::natnet::UNDECODABLE_FRAMES;
use impactd::daemon::inputs::{run_bridge, Source};
use impactd::daemon::RunOptions;
use impactd::kinematics::ClubheadSample;
use impactd::mocap::natnet::{Frame, RigidBody, Version};
use impactd::wire::{LaunchPrediction, StatusMessage};
use natnet_server::{NatNetServer, CLOCK_HZ};

const CHECK: &str = r#"
import json, sys, time
from natnetsdk.NatNetClient import NatNetClient
port, want = int(sys.argv[1]), int(sys.argv[2])
c = NatNetClient()
c.set_client_address("127.0.0.1"); c.set_server_address("127.0.0.1"); c.set_use_multicast(False)
c.multicast_address = "255.255.255.255"   # unicast: no group joined
c.command_port = port
c.set_print_level(0)
models, others, frames = [], [], []
dd = c._NatNetClient__unpack_data_descriptions
def on_dd(*a):
    r = dd(*a)
    s = lambda v: v.decode() if isinstance(v, bytes) else v
    d = r[1]
    models.append([(s(rb.sz_name), rb.id_num) for rb in d.rigid_body_list])
    others.append(dict(plates=[s(p.serial_number) for p in d.force_plate_list],
        devices=[s(x.name) for x in d.device_list], cameras=[s(x.name) for x in d.camera_list]))
    return r
c._NatNetClient__unpack_data_descriptions = on_dd
md = c._NatNetClient__unpack_mocap_data
def on_md(*a):
    r = md(*a); m = r[1]
    frames.append(dict(frame=m.prefix_data.frame_number, t=m.suffix_data.timestamp,
        exposure=m.suffix_data.stamp_camera_mid_exposure, changed=m.suffix_data.tracked_models_changed,
        bodies=[dict(id=b.id_num, pos=list(b.pos), rot=list(b.rot), valid=b.tracking_valid)
                for b in m.rigid_body_data.rigid_body_list]))
    return r
c._NatNetClient__unpack_mocap_data = on_md
assert c.run()
time.sleep(0.3)
c.send_request(c.command_socket, c.NAT_REQUEST_MODELDEF, "", (c.server_ip_address, c.command_port))
end = time.time() + 10
while (len(frames) < want or not models) and time.time() < end:
    time.sleep(0.05)
print("RESULT " + json.dumps(dict(app=c.get_application_name(), natnet=list(c.get_nat_net_version_server()),
    server=list(c.get_server_version()), models=models, others=others, frames=frames)), flush=True)
import os
os._exit(0)   # the SDK's shutdown() waits forever on its unicast data socket, which nothing is sent to
"#;

fn frame_of(s: &ClubheadSample, other_id: i32) -> Frame {
    let p = [s.position_m.x as f32, s.position_m.y as f32, s.position_m.z as f32];
    let q = s.orientation_xyzw.map(|v| v as f32);
    let club =
        RigidBody { id: 3, position_m: p, orientation_xyzw: q, mean_error_m: 0.0002, tracking_valid: !s.occluded };
    let other =
        RigidBody { id: other_id, position_m: [0.5, 1.0, -0.25], orientation_xyzw: [0.0, 0.0, 0.0, 1.0], ..club };
    let t_s = s.t_ns as f64 * 1e-9;
    Frame {
        frame_number: s.frame as i32,
        rigid_bodies: vec![other, club],
        labeled_markers: Vec::new(),
        timestamp_s: t_s,
        mid_exposure_ticks: (t_s * CLOCK_HZ as f64) as u64,
        data_received_ticks: (t_s * CLOCK_HZ as f64) as u64 + 20_000,
        transmit_ticks: (t_s * CLOCK_HZ as f64) as u64 + 35_000,
        models_changed: false,
    }
}

/// The test server is what OptiTrack's client expects, in NatNet 3.1, 4.0 and 4.1: the server info, the model
/// (body names and ids, with a force plate, a device and a camera described between the bodies) and every
/// frame's bodies (ids, f32 positions and quaternions, tracking flag), frame number, timestamp and mid-exposure
/// stamp decode to what was sent; impactd's own decoder reads the same model definition to its last body.
#[test]
fn optitracks_python_client_reads_the_test_server() {
    for version in [Version::V3_1, Version::V4_0, Version::V4_1] {
        let model = impactd::mocap::natnet::encode::model_def(version, &[(7, "wand"), (3, "club")]).unwrap();
        let (_, payload) = impactd::mocap::natnet::split(&model).unwrap();
        let ours = impactd::mocap::natnet::decode_model_def(payload, version).unwrap();
        assert!(ours.complete, "{version}: every data set walked");
        let names: Vec<(&str, i32)> = ours.rigid_bodies.iter().map(|b| (b.name.as_str(), b.id)).collect();
        assert_eq!(names, [("wand", 7), ("club", 3)], "{version}");
        let server = NatNetServer::start(version, &[(7, "wand"), (3, "club")]);
        let child = spawn_client(CHECK, server.port, 20);
        wait_for(|| server.clients() > 0);
        std::thread::sleep(Duration::from_millis(500));
        let samples = swing::samples(1, 720.0, 5);
        let sent: Vec<Frame> = samples[100..120].iter().map(|s| frame_of(s, 7)).collect();
        for f in &sent {
            server.send_frame(f);
            std::thread::sleep(Duration::from_millis(2));
        }
        let r = client_result(child, "natnetsdk");
        assert_eq!(r["app"], "Motive");
        assert_eq!(r["natnet"], serde_json::json!([version.major, version.minor, 0, 0]));
        assert_eq!(r["server"], serde_json::json!([3, 1, 0, 0]));
        assert_eq!(r["models"][0], serde_json::json!([["wand", 7], ["club", 3]]), "{version}");
        let others = serde_json::json!({"plates": ["FP-0001"], "devices": ["NI-DAQ"], "cameras": ["Prime 41 #1"]});
        assert_eq!(r["others"][0], others, "{version}: the force plate, device and camera as natnetsdk reads them");
        let frames = r["frames"].as_array().unwrap();
        assert_eq!(frames.len(), sent.len(), "{version}: every frame decoded");
        for (got, f) in frames.iter().zip(&sent) {
            assert_eq!(got["frame"], f.frame_number);
            assert_eq!(got["t"].as_f64().unwrap(), f.timestamp_s);
            assert_eq!(got["exposure"].as_u64().unwrap(), f.mid_exposure_ticks);
            let bodies = got["bodies"].as_array().unwrap();
            assert_eq!(bodies.len(), 2);
            for (b, want) in bodies.iter().zip(&f.rigid_bodies) {
                assert_eq!(b["id"], want.id);
                assert_eq!(b["valid"], want.tracking_valid);
                let pos: Vec<f32> = b["pos"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap() as f32).collect();
                let rot: Vec<f32> = b["rot"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap() as f32).collect();
                assert_eq!(pos, want.position_m);
                assert_eq!(rot, want.orientation_xyzw);
            }
        }
    }
}

const RIG: &str = "status_period_s = 0.2\n[[rig]]\nname = \"rig1\"\n";

fn input_config(port: u16) -> String {
    format!("{RIG}[rig.input]\nnatnet = \"127.0.0.1\"\nbody = \"club\"\nunicast = true\ncommand_port = {port}\ndata_port = 0\n")
}

/// Sends a swing's frames at about 2000 per second.
fn play(server: &NatNetServer, samples: &[ClubheadSample]) {
    for (i, s) in samples.iter().enumerate() {
        server.send_frame(&frame_of(s, 7));
        if i % 4 == 3 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }
}

/// The same swing through the daemon's NatNet input and through the bridge gives the same launches as the
/// swing's own JSON samples, up to the f32 rounding of positions and quaternions on NatNet's wire; and exactly
/// the launches of the JSON samples rounded to f32 (so nothing else differs). The rounding moves the launch by
/// at most the bounds asserted below (measured: printed by the test).
#[tokio::test(flavor = "multi_thread")]
async fn natnet_swing_gives_the_launches_of_the_json_swing() {
    let samples = swing::samples(3, 720.0, 11);
    let json = swing::launches(RIG, &samples);
    let rounded: Vec<ClubheadSample> = samples
        .iter()
        .map(|s| {
            let mut r = *s;
            r.position_m = s.position_m.map(|v| v as f32 as f64);
            r.orientation_xyzw = s.orientation_xyzw.map(|v| v as f32 as f64);
            r
        })
        .collect();
    let f32_json = swing::launches(RIG, &rounded);
    assert_eq!(json.len(), 3, "the reference swing has three shots");

    // The daemon reads the server itself.
    let server = NatNetServer::start(Version::V4_1, &[(7, "wand"), (3, "club")]);
    let daemon = start_daemon(&input_config(server.port), RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (launches, _l) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let (statuses, _s) = collect::<StatusMessage>(&session, "golf/rig1/status");
    assert!(
        wait_until(Duration::from_secs(10), || server.model_requests.load(std::sync::atomic::Ordering::Relaxed) > 0)
            .await
    );
    tokio::time::sleep(Duration::from_millis(200)).await;
    play(&server, &samples);
    assert!(wait_until(Duration::from_secs(10), || launches.lock().unwrap().len() >= 3).await, "three launches");
    tokio::time::sleep(Duration::from_millis(500)).await;
    let input = launches.lock().unwrap().clone();
    let status = statuses.lock().unwrap().last().cloned().unwrap();
    daemon.stop().await;
    drop(server);

    // The bridge publishes the server's frames to a daemon that reads zenoh.
    let server = NatNetServer::start(Version::V3_1, &[(7, "wand"), (3, "club")]);
    let daemon = start_daemon(RIG, RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (bridged, _b) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let source = Source::new("natnet", "127.0.0.1", server.port).with("data_port", 0).with("unicast", true);
    let bridge_session = client(&daemon.endpoint).await;
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let bridge = tokio::spawn(async move {
        let routes = vec![("club".to_string(), "rig1".to_string())];
        run_bridge(&bridge_session, source, routes, async {
            let _ = stopped.await;
        })
        .await
        .unwrap()
    });
    assert!(
        wait_until(Duration::from_secs(10), || server.model_requests.load(std::sync::atomic::Ordering::Relaxed) > 0)
            .await
    );
    tokio::time::sleep(Duration::from_millis(500)).await;
    play(&server, &samples);
    assert!(wait_until(Duration::from_secs(10), || bridged.lock().unwrap().len() >= 3).await, "three bridged launches");
    tokio::time::sleep(Duration::from_millis(500)).await; // the swing's last frames, after its last shot
    let _ = stop.send(());
    let bridge_status = bridge.await.unwrap();
    daemon.stop().await;
    let bridged = bridged.lock().unwrap().clone();

    let keys = |v: &[LaunchPrediction]| v.iter().map(swing::key).collect::<Vec<_>>();
    assert_eq!(keys(&input), keys(&f32_json), "daemon input = the f32-rounded JSON swing, exactly");
    assert_eq!(keys(&bridged), keys(&f32_json), "bridge = the f32-rounded JSON swing, exactly");
    let d = swing::max_differences(&input, &json);
    eprintln!("f32 wire vs f64 JSON: ball speed {:.2e} mph, launch {:.2e} deg, direction {:.2e} deg, backspin {:.2e} rpm, sidespin {:.2e} rpm", d[0], d[1], d[2], d[3], d[4]);
    // Measured: 5.7e-6 mph, 1.1e-6 deg, 1.0e-6 deg, 2.5e-4 rpm, 3.6e-4 rpm.
    assert!(d[0] < 1e-4 && d[1] < 1e-4 && d[2] < 1e-4 && d[3] < 0.01 && d[4] < 0.01, "{d:?}");

    let s = status.input.unwrap();
    assert_eq!((s.protocol.as_str(), s.body.as_str(), s.body_found, s.connects), ("natnet", "club", true, 1));
    assert_eq!((s.frames, s.published, s.dropped, s.out_of_order), (samples.len() as u64, samples.len() as u64, 0, 0));
    assert!(s.exposure_to_transmit_p99_us.is_some_and(|us| (us - 3500.0).abs() < 1.0), "{s:?}");
    assert_eq!(bridge_status[0].published, samples.len() as u64);
}

/// Bad input from a NatNet server is counted by reason and never stops the rig: a server not answering yet
/// (asked again), truncated datagrams, unknown message ids, NaN poses, frame numbers jumping and going back, a
/// body missing from a frame, a renamed body, and a server announcing a NatNet version the decoder does not
/// know. (An oversized datagram cannot reach it: UDP carries at most 65,507 bytes, under NatNet's 65,539.)
#[tokio::test(flavor = "multi_thread")]
async fn bad_natnet_input_is_counted_by_reason() {
    use impactd::mocap::natnet::encode as natnet_encode;
    use impactd::mocap::natnet::ServerInfo;
    let server = NatNetServer::start(Version::V4_1, &[(7, "wand"), (3, "club")]);
    server.state.lock().unwrap().answering = false;
    let daemon = start_daemon(&input_config(server.port), RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (statuses, _s) = collect::<StatusMessage>(&session, "golf/rig1/status");
    let s = latest_input(&statuses, |s| s.last_error.as_deref().is_some_and(|e| e.contains("no answer"))).await;
    assert_eq!(s.connects, 0);
    server.state.lock().unwrap().answering = true;
    latest_input(&statuses, |s| s.connects == 1 && s.body_found).await;

    let samples = swing::samples(1, 720.0, 3);
    let frame = |i: usize| frame_of(&samples[i], 7);
    let bytes = |f: &Frame| natnet_encode::frame(Version::V4_1, f, "club", &[]).unwrap();
    server.send_frame(&frame(10));
    server.send_frame(&frame(14)); // 3 dropped
    server.send_frame(&frame(12)); // out of order
    let mut nan = frame(15);
    nan.rigid_bodies[1].position_m[0] = f32::NAN;
    server.send_frame(&nan); // tracked, NaN: occluded, nan_pose
    let mut untracked = frame(16);
    untracked.rigid_bodies[1].tracking_valid = false;
    server.send_frame(&untracked); // occluded
    let mut zero = frame(17);
    zero.rigid_bodies[1].orientation_xyzw = [0.0; 4];
    server.send_frame(&zero); // bad_rotation
    let mut missing = frame(18);
    missing.rigid_bodies.truncate(1);
    server.send_frame(&missing); // body_missing_from_frame
    let whole = bytes(&frame(19));
    server.send_raw(&whole[..whole.len() / 2]); // truncated
    server.send_raw(&[77, 0, 0, 0]); // unknown_message
    server.send_raw(&[7, 0, 0, 0]); // a frame with no payload: truncated
    server.send_frame(&frame(20));
    let s = latest_input(&statuses, |s| s.published >= 6).await;
    assert_eq!((s.dropped, s.out_of_order, s.occluded), (3 + 2, 1, 3), "{s:?}");
    for (reason, n) in
        [("nan_pose", 1), ("bad_rotation", 1), ("body_missing_from_frame", 1), ("truncated", 2), ("unknown_message", 1)]
    {
        assert_eq!(s.rejected.get(reason), Some(&n), "{reason}: {s:?}");
    }

    // Renamed in Motive: the next frame says the models changed; the client asks again and finds no `club`.
    server.state.lock().unwrap().bodies[1].1 = "club2".into();
    let mut changed = frame(21);
    changed.models_changed = true;
    server.send_frame(&changed);
    latest_input(&statuses, |s| !s.body_found).await;
    server.send_frame(&frame(22));
    latest_input(&statuses, |s| s.rejected.get("body_not_in_model").is_some_and(|&n| n >= 1)).await;
    server.state.lock().unwrap().bodies[1].1 = "club".into();

    // A NatNet 5.0 server info nobody asked for (from the server's own command port): counted, and it changes
    // nothing: the frames after it decode as 4.1.
    let info = |major| ServerInfo {
        app_name: "Motive".into(),
        natnet_version: [major, if major == 4 { 1 } else { 0 }, 0, 0],
        clock_hz: Some(CLOCK_HZ),
        ..ServerInfo::default()
    };
    server.send_raw(&natnet_encode::server_info(&info(5)));
    server.send_frame(&changed);
    latest_input(&statuses, |s| s.body_found).await;
    server.send_frame(&frame(23));
    let s = latest_input(&statuses, |s| s.published >= 8).await;
    assert_eq!(s.rejected.get("unsolicited_server_info"), Some(&1), "{s:?}");
    assert_eq!(s.rejected.get("unknown_version"), None, "{s:?}");

    // A stream none of whose frames decode: after UNDECODABLE_FRAMES of them the client connects again, and the
    // server's answer this time announces NatNet 5.0, which the decoder does not know: counted, its frames
    // refused, and after as many of them the client connects again; the server answers 4.1 and frames flow.
    server.state.lock().unwrap().announced = Some([5, 0]);
    for _ in 0..UNDECODABLE_FRAMES {
        server.send_raw(&[7, 0, 0, 0]);
    }
    let s = latest_input(&statuses, |s| s.rejected.contains_key("unknown_version")).await;
    assert_eq!(s.reconnects.get("undecodable"), Some(&1), "{s:?}");
    assert!(s.last_error.as_deref().is_some_and(|e| e.contains("not supported") || e.contains("5.0")), "{s:?}");
    server.state.lock().unwrap().announced = None;
    for _ in 0..UNDECODABLE_FRAMES {
        server.send_frame(&frame(24));
    }
    let s = latest_input(&statuses, |s| s.reconnects.get("undecodable") == Some(&2) && s.connects >= 3).await;
    assert!(s.rejected.get("unknown_version").is_some_and(|&n| n > UNDECODABLE_FRAMES as u64), "{s:?}");
    server.send_frame(&changed);
    latest_input(&statuses, |s| s.body_found).await;
    server.send_frame(&frame(30));
    let s = latest_input(&statuses, |s| s.published >= 9).await;
    assert_eq!(s.state, impactd::wire::ConnectionState::Connected);
    daemon.stop().await;
}

/// A spoofed server info (another port of the server's address, announcing NatNet 2.9, in the middle of a
/// swing) is counted and changes nothing: the rig predicts every shot of the swing, as the JSON swing gives them.
#[tokio::test(flavor = "multi_thread")]
async fn a_spoofed_server_info_mid_swing_changes_nothing() {
    use impactd::mocap::natnet::encode as natnet_encode;
    use impactd::mocap::natnet::ServerInfo;
    let samples = swing::samples(3, 720.0, 11);
    let rounded: Vec<ClubheadSample> = samples
        .iter()
        .map(|s| {
            let mut r = *s;
            r.position_m = s.position_m.map(|v| v as f32 as f64);
            r.orientation_xyzw = s.orientation_xyzw.map(|v| v as f32 as f64);
            r
        })
        .collect();
    let want = swing::launches(RIG, &rounded);
    let server = NatNetServer::start(Version::V4_1, &[(7, "wand"), (3, "club")]);
    let daemon = start_daemon(&input_config(server.port), RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (launches, _l) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let (statuses, _s) = collect::<StatusMessage>(&session, "golf/rig1/status");
    latest_input(&statuses, |s| s.connects == 1 && s.body_found).await;
    let spoof = natnet_encode::server_info(&ServerInfo {
        app_name: "Motive".into(),
        natnet_version: [2, 9, 0, 0],
        clock_hz: Some(CLOCK_HZ),
        ..ServerInfo::default()
    });
    let half = samples.len() / 2;
    play(&server, &samples[..half]);
    server.send_from_other_port(&spoof);
    server.send_raw(&spoof);
    play(&server, &samples[half..]);
    assert!(wait_until(Duration::from_secs(10), || launches.lock().unwrap().len() >= 3).await, "three launches");
    let s = latest_input(&statuses, |s| s.published == samples.len() as u64).await;
    let got = launches.lock().unwrap().clone();
    daemon.stop().await;
    let keys = |v: &[LaunchPrediction]| v.iter().map(swing::key).collect::<Vec<_>>();
    assert_eq!(keys(&got), keys(&want), "every shot predicted as without the spoof");
    assert_eq!(s.rejected.get("unsolicited_server_info"), Some(&2), "{s:?}");
    assert_eq!((s.connects, s.state), (1, impactd::wire::ConnectionState::Connected), "{s:?}");
    assert!(s.server_version.as_deref().is_some_and(|v| v.contains("NatNet 4.1")), "{s:?}");
}

/// `impactd bridge natnet --help` works, and the bridge exits (0) within a few seconds of SIGINT, printing its
/// counts, while it reads a server.
#[tokio::test(flavor = "multi_thread")]
async fn bridge_binary_helps_and_stops_on_sigint() {
    let exe = env!("CARGO_BIN_EXE_impactd");
    let help = std::process::Command::new(exe).args(["bridge", "natnet", "--help"]).output().unwrap();
    assert!(help.status.success());
    let text = String::from_utf8_lossy(&help.stdout);
    for flag in ["--server", "--body <NAME=RIG>", "--command-port", "--data-port", "--unicast", "--multicast-group"] {
        assert!(text.contains(flag), "{flag} in {text}");
    }
    let help = std::process::Command::new(exe).args(["bridge", "qtm", "--help"]).output().unwrap();
    assert!(help.status.success() && String::from_utf8_lossy(&help.stdout).contains("--port"));

    let server = NatNetServer::start(Version::V4_1, &[(3, "club")]);
    let daemon = start_daemon(RIG, RunOptions::default()).await;
    let port = server.port.to_string();
    let child = std::process::Command::new(exe)
        .args(["bridge", "natnet", "--server", "127.0.0.1", "--command-port", &port, "--data-port", "0", "--unicast"])
        .args(["--body", "club=rig1", "-e", &daemon.endpoint, "--no-multicast-scouting"])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    assert!(
        wait_until(Duration::from_secs(20), || server.model_requests.load(std::sync::atomic::Ordering::Relaxed) > 0)
            .await
    );
    let samples = swing::samples(1, 720.0, 3);
    play(&server, &samples[..50]);
    tokio::time::sleep(Duration::from_millis(300)).await;
    let t0 = std::time::Instant::now();
    assert!(std::process::Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap().success());
    let out = child.wait_with_output().unwrap();
    let took = t0.elapsed();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    eprintln!("the bridge exited {took:?} after SIGINT");
    assert!(stderr.contains("club -> rig1: 50 frames, 50 published"), "{stderr}");
    daemon.stop().await;
}

/// Ten rigid bodies at 360 Hz through one bridge (ten rigs): every frame that arrived is published, none is
/// lost between the bridge and a subscriber, and the process's memory stays flat. Two seconds here;
/// `IMPACTD_SOAK_S=60 cargo test --release --test inputs natnet::ten_bodies -- --nocapture` is the hour-scale check
/// measured by hand (the numbers are in the README).
#[tokio::test(flavor = "multi_thread")]
async fn ten_bodies_at_360_hz_through_one_bridge_lose_nothing() {
    let seconds: f64 = std::env::var("IMPACTD_SOAK_S").ok().and_then(|s| s.parse().ok()).unwrap_or(2.0);
    let names: Vec<String> = (0..10).map(|i| format!("body{i}")).collect();
    let bodies: Vec<(i32, &str)> = names.iter().enumerate().map(|(i, n)| (i as i32 + 1, n.as_str())).collect();
    let server = NatNetServer::start(Version::V4_1, &bodies);
    let endpoint = format!("tcp/127.0.0.1:{}", impactd::daemon::bus::free_loopback_port().unwrap());
    let bridge_session =
        impactd::daemon::bus::ZenohArgs::loopback(vec![endpoint.clone()], vec![]).open().await.unwrap();
    let session = client(&endpoint).await;
    let received = std::sync::Arc::new(std::sync::atomic::AtomicU64::new(0));
    let r = received.clone();
    let _sub = zenoh::Wait::wait(session.declare_subscriber("mocap/*/clubhead").callback(move |_| {
        r.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }))
    .unwrap();
    let source = Source::new("natnet", "127.0.0.1", server.port).with("data_port", 0).with("unicast", true);
    let routes: Vec<(String, String)> = names.iter().enumerate().map(|(i, n)| (n.clone(), format!("rig{i}"))).collect();
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let bridge = tokio::spawn(async move {
        run_bridge(&bridge_session, source, routes, async {
            let _ = stopped.await;
        })
        .await
        .unwrap()
    });
    assert!(
        wait_until(Duration::from_secs(10), || server.model_requests.load(std::sync::atomic::Ordering::Relaxed) > 0)
            .await
    );
    tokio::time::sleep(Duration::from_millis(1000)).await;
    let frames = (seconds * 360.0) as u64;
    let (server, rss) = tokio::task::spawn_blocking(move || {
        let period = Duration::from_secs_f64(1.0 / 360.0);
        let start = std::time::Instant::now();
        let mut rss = Vec::new();
        for k in 0..frames {
            let t = k as f64 / 360.0;
            let frame = Frame {
                frame_number: k as i32 + 1,
                rigid_bodies: (0..10)
                    .map(|i| RigidBody {
                        id: i + 1,
                        position_m: [i as f32 * 0.1, (t.sin() as f32), 0.0],
                        orientation_xyzw: [0.0, 0.0, 0.0, 1.0],
                        mean_error_m: 1e-4,
                        tracking_valid: true,
                    })
                    .collect(),
                timestamp_s: 1.0 + t,
                ..Frame::default()
            };
            server.send_frame(&frame);
            if k % 360 == 0 {
                rss.push(rss_kib());
            }
            let due = start + period * (k as u32 + 1);
            if let Some(wait) = due.checked_duration_since(std::time::Instant::now()) {
                std::thread::sleep(wait);
            }
        }
        rss.push(rss_kib());
        (server, rss)
    })
    .await
    .unwrap();
    let want = frames * 10;
    assert!(wait_until(Duration::from_secs(10), || received.load(std::sync::atomic::Ordering::Relaxed) >= want).await);
    tokio::time::sleep(Duration::from_millis(300)).await;
    let _ = stop.send(());
    let statuses = bridge.await.unwrap();
    drop(server);
    let published: u64 = statuses.iter().map(|s| s.published).sum();
    eprintln!(
        "{seconds} s, {frames} frames x 10 bodies: published {published}, received {}, RSS (KiB) each second {rss:?}",
        received.load(std::sync::atomic::Ordering::Relaxed)
    );
    assert_eq!(published, want, "{statuses:?}");
    assert_eq!(received.load(std::sync::atomic::Ordering::Relaxed), want, "nothing lost after the bridge");
    assert!(statuses.iter().all(|s| s.rejected.is_empty() && s.dropped == 0 && s.out_of_order == 0), "{statuses:?}");
    // Flat: after the first second, the resident set grows by less than 4 MiB (allocator noise).
    let (first, last) = (rss[1.min(rss.len() - 1)], *rss.last().unwrap());
    assert!(last < first + 4096, "RSS grew from {first} to {last} KiB");
}

/// A rig's `ball_body` (and the bridge's `--ball`): a body whose origin is the ball's centre, 4 mm right of the
/// configured ball, sets the shot's ball position; the launch says it was tracked, at the body's f32 position.
#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_ball_body_sets_the_shots_ball() {
    use impactd::wire::{BallSampleMsg, BallSource};
    let ball_at = [0.0f32, 0.0, 0.004];
    let frames = |samples: &[ClubheadSample]| -> Vec<Frame> {
        samples
            .iter()
            .map(|s| {
                let mut f = frame_of(s, 9);
                f.rigid_bodies[0].position_m = ball_at;
                f
            })
            .collect()
    };
    let samples = swing::samples(1, 720.0, 11);
    let server = NatNetServer::start(Version::V4_1, &[(9, "ball"), (3, "club")]);
    let config = input_config(server.port) + "ball_body = \"ball\"\n";
    let daemon = start_daemon(&config, RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (launches, _l) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    assert!(
        wait_until(Duration::from_secs(10), || server.model_requests.load(std::sync::atomic::Ordering::Relaxed) > 0)
            .await
    );
    tokio::time::sleep(Duration::from_millis(200)).await;
    for f in frames(&samples) {
        server.send_frame(&f);
    }
    assert!(wait_until(Duration::from_secs(10), || !launches.lock().unwrap().is_empty()).await, "a launch");
    let used = launches.lock().unwrap()[0].ball.unwrap();
    daemon.stop().await;
    assert_eq!(used.source, BallSource::Tracked);
    assert_eq!(used.position_m, ball_at.map(f64::from), "the ball body's position, as sent");
    drop(server);

    // The bridge publishes the same body on mocap/rig1/ball.
    let server = NatNetServer::start(Version::V4_1, &[(9, "ball"), (3, "club")]);
    let daemon = start_daemon(RIG, RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (balls, _b) = collect::<BallSampleMsg>(&session, "mocap/rig1/ball");
    let source = Source::new("natnet", "127.0.0.1", server.port).with("data_port", 0).with("unicast", true);
    let bridge_session = client(&daemon.endpoint).await;
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let bridge = tokio::spawn(async move {
        let routes = vec![("club".to_string(), "rig1".to_string())];
        let balls = vec![("ball".to_string(), "rig1".to_string())];
        impactd::daemon::inputs::run_bridge_with_balls(&bridge_session, source, routes, balls, async {
            let _ = stopped.await;
        })
        .await
        .unwrap()
    });
    assert!(
        wait_until(Duration::from_secs(10), || server.model_requests.load(std::sync::atomic::Ordering::Relaxed) > 0)
            .await
    );
    tokio::time::sleep(Duration::from_millis(500)).await;
    let sent = frames(&samples[..50]);
    for f in &sent {
        server.send_frame(f);
    }
    assert!(wait_until(Duration::from_secs(10), || balls.lock().unwrap().len() >= sent.len()).await);
    let _ = stop.send(());
    let statuses = bridge.await.unwrap();
    daemon.stop().await;
    let got = balls.lock().unwrap().clone();
    assert!(got.iter().all(|b| b.position_m == ball_at.map(f64::from) && !b.occluded), "{:?}", got.first());
    assert_eq!(statuses.len(), 2, "the club's route and the ball's");
}
