//! OptiTrack NatNet, live: a NatNet server in this test (127.0.0.1 unicast only) that OptiTrack's own Python
//! client (`natnetsdk`, pinned in scripts/test-requirements.txt) reads as it reads Motive; then the daemon's
//! `[rig.input] natnet` and `impactd bridge natnet`, fed a synthetic swing through that server, against the same
//! swing sent as JSON.

#![allow(clippy::unwrap_used)]

mod common;
#[path = "common/natnet_server.rs"]
mod natnet_server;
#[path = "common/swing.rs"]
mod swing;

use std::time::Duration;

use common::{client, collect, python, start_daemon, wait_until};
use impactd::daemon::bridges::{run_bridge, Source};
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
models, frames = [], []
dd = c._NatNetClient__unpack_data_descriptions
def on_dd(*a):
    r = dd(*a)
    models.append([(rb.sz_name.decode() if isinstance(rb.sz_name, bytes) else rb.sz_name, rb.id_num) for rb in r[1].rigid_body_list])
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
    server=list(c.get_server_version()), models=models, frames=frames)), flush=True)
import os
os._exit(0)   # the SDK's shutdown() waits forever on its unicast data socket, which nothing is sent to
"#;

fn frame_of(s: &ClubheadSample, other_id: i32) -> Frame {
    let p = [s.position_m.x as f32, s.position_m.y as f32, s.position_m.z as f32];
    let q = s.orientation_xyzw.map(|v| v as f32);
    let club = RigidBody { id: 3, position_m: p, orientation_xyzw: q, mean_error_m: 0.0002, tracking_valid: !s.occluded };
    let other = RigidBody { id: other_id, position_m: [0.5, 1.0, -0.25], orientation_xyzw: [0.0, 0.0, 0.0, 1.0], ..club };
    let t_s = s.t_ns as f64 * 1e-9;
    Frame {
        frame_number: s.frame as i32,
        rigid_bodies: vec![other, club],
        timestamp_s: t_s,
        mid_exposure_ticks: (t_s * CLOCK_HZ as f64) as u64,
        data_received_ticks: (t_s * CLOCK_HZ as f64) as u64 + 20_000,
        transmit_ticks: (t_s * CLOCK_HZ as f64) as u64 + 35_000,
        models_changed: false,
    }
}

/// The test server is what OptiTrack's client expects, in NatNet 3.1 and 4.1: the server info, the model
/// (body names and ids) and every frame's bodies (ids, f32 positions and quaternions, tracking flag), frame
/// number, timestamp and mid-exposure stamp decode to what was sent.
#[test]
fn optitracks_python_client_reads_the_test_server() {
    for version in [Version::V3_1, Version::V4_1] {
        let server = NatNetServer::start(version, &[(7, "wand"), (3, "club")]);
        let child = python()
            .args(["-c", CHECK, &server.port.to_string(), "20"])
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let t0 = std::time::Instant::now();
        while server.clients() == 0 && t0.elapsed() < Duration::from_secs(20) {
            std::thread::sleep(Duration::from_millis(20));
        }
        std::thread::sleep(Duration::from_millis(500));
        let samples = swing::samples(1, 720.0, 5);
        let sent: Vec<Frame> = samples[100..120].iter().map(|s| frame_of(s, 7)).collect();
        for f in &sent {
            server.send_frame(f);
            std::thread::sleep(Duration::from_millis(2));
        }
        let out = child.wait_with_output().unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        let line = stdout.lines().find_map(|l| l.strip_prefix("RESULT ")).unwrap_or_else(|| {
            panic!("no result from natnetsdk: {stdout}\n{}", String::from_utf8_lossy(&out.stderr))
        });
        let r: serde_json::Value = serde_json::from_str(line).unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("Traceback"), "natnetsdk failed: {stderr}");
        assert_eq!(r["app"], "Motive");
        assert_eq!(r["natnet"], serde_json::json!([version.major, version.minor, 0, 0]));
        assert_eq!(r["server"], serde_json::json!([3, 1, 0, 0]));
        assert_eq!(r["models"][0], serde_json::json!([["wand", 7], ["club", 3]]), "{version}");
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
    assert!(wait_until(Duration::from_secs(10), || server.model_requests.load(std::sync::atomic::Ordering::Relaxed) > 0).await);
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
    let source = Source::NatNet { host: "127.0.0.1".into(), command_port: server.port, data_port: 0, multicast_group: None };
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
    assert!(wait_until(Duration::from_secs(10), || server.model_requests.load(std::sync::atomic::Ordering::Relaxed) > 0).await);
    tokio::time::sleep(Duration::from_millis(500)).await;
    play(&server, &samples);
    assert!(wait_until(Duration::from_secs(10), || bridged.lock().unwrap().len() >= 3).await, "three bridged launches");
    let _ = stop.send(());
    let bridge_status = bridge.await.unwrap();
    daemon.stop().await;
    let bridged = bridged.lock().unwrap().clone();

    let keys = |v: &[LaunchPrediction]| v.iter().map(swing::key).collect::<Vec<_>>();
    assert_eq!(keys(&input), keys(&f32_json), "daemon input = the f32-rounded JSON swing, exactly");
    assert_eq!(keys(&bridged), keys(&f32_json), "bridge = the f32-rounded JSON swing, exactly");
    let d = swing::max_differences(&input, &json);
    eprintln!("f32 wire vs f64 JSON: ball speed {:.2e} mph, launch {:.2e} deg, direction {:.2e} deg, backspin {:.2e} rpm, sidespin {:.2e} rpm", d[0], d[1], d[2], d[3], d[4]);
    assert!(d[0] < 0.05 && d[1] < 0.05 && d[2] < 0.05 && d[3] < 10.0 && d[4] < 10.0, "{d:?}");

    let s = status.input.unwrap();
    assert_eq!((s.protocol.as_str(), s.body.as_str(), s.body_found, s.connects), ("natnet", "club", true, 1));
    assert_eq!((s.frames, s.published, s.dropped, s.out_of_order), (samples.len() as u64, samples.len() as u64, 0, 0));
    assert!(s.exposure_to_transmit_p99_us.is_some_and(|us| (us - 3500.0).abs() < 1.0), "{s:?}");
    assert_eq!(bridge_status[0].published, samples.len() as u64);
}
