//! Qualisys QTM, live: a QTM real-time server in this test (TCP on 127.0.0.1) that Qualisys' own Python SDK
//! (`qtm-rt`, pinned in scripts/test-requirements.txt) reads as it reads QTM; then the daemon's `[rig.input]
//! qtm` and `impactd bridge qtm`, fed a synthetic swing through that server, against the same swing sent as
//! JSON; then bad input, counted by reason.

#![allow(clippy::unwrap_used)]

use crate::common;
use crate::qtm_server;
use crate::swing;

use std::sync::atomic::Ordering;
use std::time::Duration;

use common::{client, client_result, collect, latest_input, spawn_client, start_daemon, wait_for, wait_until};
use impactd::daemon::inputs::{run_bridge, Source};
use impactd::daemon::RunOptions;
use impactd::kinematics::ClubheadSample;
use impactd::math::Quaternion;
use impactd::math::UnitQuaternion;
use impactd::mocap::qtm::{Body6d, Frame6d};
use impactd::mocap::{qtm::encode as qtm_encode, track};
use impactd::wire::{LaunchPrediction, StatusMessage};
use qtm_server::QtmServer;

const CHECK: &str = r#"
import asyncio, json, sys
import xml.etree.ElementTree as ET
import qtm_rt
async def main(port, want):
    c = await qtm_rt.connect("127.0.0.1", port=port, version="1.25", timeout=5)
    assert c is not None, "no connection"
    xml = await c.get_parameters(parameters=["6d"])
    names = [b.find("Name").text for b in ET.fromstring(xml).find("The_6D").findall("Body")]
    frames = []
    def on_packet(p):
        h, bodies = p.get_6d()
        frames.append(dict(frame=p.framenumber, t=p.timestamp, count=h.body_count,
                           bodies=[dict(pos=list(pos), rot=list(rot.matrix)) for pos, rot in bodies]))
    await c.stream_frames(components=["6d"], on_packet=on_packet)
    for _ in range(200):
        if len(frames) >= want: break
        await asyncio.sleep(0.05)
    print("RESULT " + json.dumps(dict(names=names, frames=frames)), flush=True)
    c.disconnect()
asyncio.run(main(int(sys.argv[1]), int(sys.argv[2])))
"#;

/// A swing's sample as a 6D body: mm, and the orientation as QTM's column-major rotation matrix.
fn body_of(s: &ClubheadSample) -> Body6d {
    let [x, y, z, w] = s.orientation_xyzw;
    let m = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)).to_rotation_matrix();
    let mut rotation = [0f32; 9];
    for (r, v) in rotation.iter_mut().zip(m.matrix().as_slice()) {
        *r = *v as f32;
    }
    let p = s.position_m * 1e3;
    Body6d { position_mm: [p.x as f32, p.y as f32, p.z as f32], rotation, residual_mm: None }
}

fn frame_of(s: &ClubheadSample) -> Frame6d {
    let other = Body6d {
        position_mm: [500.0, 1000.0, -250.0],
        rotation: [1., 0., 0., 0., 1., 0., 0., 0., 1.],
        residual_mm: None,
    };
    Frame6d {
        timestamp_us: (s.t_ns / 1000) as i64,
        frame_number: s.frame as u32,
        bodies: vec![other, body_of(s)],
        drop_rate_2d: 0,
        out_of_sync_rate_2d: 0,
        markers_mm: Vec::new(),
    }
}

/// The test server is what Qualisys' SDK expects: the handshake and version, the 6D parameters XML (body names
/// in order) and every 6D frame (frame number, timestamp, f32 positions and column-major matrices).
#[test]
fn qualisys_python_sdk_reads_the_test_server() {
    let server = QtmServer::start(&["wand", "club & co"]);
    let child = spawn_client(CHECK, server.port, 20);
    wait_for(|| server.streaming() > 0);
    let samples = swing::samples(1, 720.0, 5);
    let sent: Vec<Frame6d> = samples[100..120].iter().map(frame_of).collect();
    for f in &sent {
        server.send_frame(f);
        std::thread::sleep(Duration::from_millis(2));
    }
    let r = client_result(child, "qtm-rt");
    assert_eq!(r["names"], serde_json::json!(["wand", "club & co"]));
    let frames = r["frames"].as_array().unwrap();
    assert_eq!(frames.len(), sent.len());
    for (got, f) in frames.iter().zip(&sent) {
        assert_eq!(got["frame"], f.frame_number);
        assert_eq!(got["t"], f.timestamp_us);
        assert_eq!(got["count"], 2);
        for (b, want) in got["bodies"].as_array().unwrap().iter().zip(&f.bodies) {
            let pos: Vec<f32> = b["pos"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap() as f32).collect();
            let rot: Vec<f32> = b["rot"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap() as f32).collect();
            assert_eq!(pos, want.position_mm);
            assert_eq!(rot, want.rotation);
        }
    }
}

const RIG: &str = "status_period_s = 0.2\n[[rig]]\nname = \"rig1\"\n";

fn input_config(port: u16) -> String {
    format!("{RIG}[rig.input]\nqtm = \"127.0.0.1\"\nbody = \"club\"\nport = {port}\n")
}

fn play(server: &QtmServer, samples: &[ClubheadSample]) {
    for (i, s) in samples.iter().enumerate() {
        server.send_frame(&frame_of(s));
        if i % 4 == 3 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }
}

/// The same swing through the daemon's QTM input and through the bridge gives the same launches as the swing's
/// JSON samples, up to QTM's wire (f32 mm, an f32 rotation matrix, microsecond timestamps), and exactly the
/// launches of the JSON samples taken through that wire's rounding.
#[tokio::test(flavor = "multi_thread")]
async fn qtm_swing_gives_the_launches_of_the_json_swing() {
    let samples = swing::samples(3, 720.0, 13);
    let json = swing::launches(RIG, &samples);
    let wire: Vec<ClubheadSample> = samples
        .iter()
        .map(|s| {
            let f = frame_of(s);
            let b = track::qtm_sample(&f.bodies[1], &f).0;
            ClubheadSample {
                frame: b.frame,
                t_ns: b.t_ns,
                position_m: b.position_m.into(),
                orientation_xyzw: b.orientation_xyzw,
                occluded: b.occluded,
            }
        })
        .collect();
    let wire_json = swing::launches(RIG, &wire);
    assert_eq!(json.len(), 3);

    let server = QtmServer::start(&["wand", "club"]);
    let daemon = start_daemon(&input_config(server.port), RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (launches, _l) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let (statuses, _s) = collect::<StatusMessage>(&session, "golf/rig1/status");
    assert!(wait_until(Duration::from_secs(10), || server.streaming() > 0).await);
    play(&server, &samples);
    assert!(wait_until(Duration::from_secs(10), || launches.lock().unwrap().len() >= 3).await, "three launches");
    tokio::time::sleep(Duration::from_millis(500)).await;
    let input = launches.lock().unwrap().clone();
    let status = statuses.lock().unwrap().last().cloned().unwrap();
    daemon.stop().await;
    drop(server);

    let server = QtmServer::start(&["wand", "club"]);
    let daemon = start_daemon(RIG, RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (bridged, _b) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let bridge_session = client(&daemon.endpoint).await;
    let source = Source::new("qtm", "127.0.0.1", server.port);
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let bridge = tokio::spawn(async move {
        let routes = vec![("club".to_string(), "rig1".to_string())];
        run_bridge(&bridge_session, source, routes, async {
            let _ = stopped.await;
        })
        .await
        .unwrap()
    });
    assert!(wait_until(Duration::from_secs(10), || server.streaming() > 0).await);
    tokio::time::sleep(Duration::from_millis(500)).await;
    play(&server, &samples);
    assert!(wait_until(Duration::from_secs(10), || bridged.lock().unwrap().len() >= 3).await, "three bridged");
    tokio::time::sleep(Duration::from_millis(500)).await; // the swing's last frames, after its last shot
    let _ = stop.send(());
    let bridge_status = bridge.await.unwrap();
    daemon.stop().await;
    let bridged = bridged.lock().unwrap().clone();

    let keys = |v: &[LaunchPrediction]| v.iter().map(swing::key).collect::<Vec<_>>();
    assert_eq!(keys(&input), keys(&wire_json), "daemon input = the JSON swing through QTM's rounding, exactly");
    assert_eq!(keys(&bridged), keys(&wire_json), "bridge = the same");
    let d = swing::max_differences(&input, &json);
    eprintln!("QTM wire vs f64 JSON: ball speed {:.2e} mph, launch {:.2e} deg, direction {:.2e} deg, backspin {:.2e} rpm, sidespin {:.2e} rpm", d[0], d[1], d[2], d[3], d[4]);
    // Measured: 8.9e-3 mph, 2.2e-4 deg, 2.7e-4 deg, 0.26 rpm, 0.16 rpm (the microsecond timestamps dominate).
    assert!(d[0] < 0.03 && d[1] < 2e-3 && d[2] < 2e-3 && d[3] < 1.0 && d[4] < 1.0, "{d:?}");
    let s = status.input.unwrap();
    assert_eq!((s.protocol.as_str(), s.body_found, s.connects, s.dropped, s.out_of_order), ("qtm", true, 1, 0, 0));
    assert_eq!((s.frames, s.published), (samples.len() as u64, samples.len() as u64));
    assert_eq!(bridge_status[0].published, samples.len() as u64);
}

/// A QTM that goes silent after the handshake (streaming asked for, then nothing, not even an answer to
/// `QTMVersion`) does not stay "connected": after 3 s the client ends the session, counts it
/// (`reconnects.quiet`) and connects again; once QTM speaks again the rig predicts its swing.
#[tokio::test(flavor = "multi_thread")]
async fn a_qtm_silent_after_the_handshake_is_connected_to_again() {
    let server = QtmServer::start(&["wand", "club"]);
    let daemon = start_daemon(&input_config(server.port), RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (launches, _l) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let (statuses, _s) = collect::<StatusMessage>(&session, "golf/rig1/status");
    latest_input(&statuses, |s| s.connects == 1 && s.state == impactd::wire::ConnectionState::Connected).await;
    server.mute.store(true, Ordering::Relaxed);
    let s = latest_input(&statuses, |s| s.reconnects.get("quiet") == Some(&1)).await;
    assert_ne!(s.state, impactd::wire::ConnectionState::Connected, "{s:?}");
    assert!(s.last_error.as_deref().is_some_and(|e| e.contains("sent nothing for 3 s")), "{s:?}");
    server.mute.store(false, Ordering::Relaxed);
    latest_input(&statuses, |s| s.connects >= 2 && s.state == impactd::wire::ConnectionState::Connected).await;
    assert!(wait_until(Duration::from_secs(10), || server.streaming() > 0).await);
    let samples = swing::samples(1, 720.0, 5);
    play(&server, &samples);
    assert!(wait_until(Duration::from_secs(10), || !launches.lock().unwrap().is_empty()).await, "a launch");
    daemon.stop().await;
}

/// Bad input from QTM is counted by reason and never stops the rig: a server not there yet (retried), a
/// refused protocol version, NaN and non-rotation poses, frame numbers jumping and going back, unknown packet
/// types, data without 6D, a truncated 6D component, a renamed body, a stopped measurement and an oversized
/// packet (both: connect again).
#[tokio::test(flavor = "multi_thread")]
async fn bad_qtm_input_is_counted_by_reason() {
    let port = {
        let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        l.local_addr().unwrap().port()
    };
    let daemon = start_daemon(&input_config(port), RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (statuses, _s) = collect::<StatusMessage>(&session, "golf/rig1/status");
    let s = latest_input(&statuses, |s| s.last_error.as_deref().is_some_and(|e| e.contains("no QTM real-time server")))
        .await;
    assert_eq!(s.connects, 0);

    let server = QtmServer::start_on(port, &["wand", "club"]);
    server.refuse_version.store(true, Ordering::Relaxed);
    latest_input(&statuses, |s| s.rejected.get("unknown_version").is_some_and(|&n| n >= 1)).await;
    server.refuse_version.store(false, Ordering::Relaxed);
    assert!(wait_until(Duration::from_secs(15), || server.streaming() > 0).await);

    let samples = swing::samples(1, 720.0, 3);
    let frame = |i: usize| frame_of(&samples[i]);
    server.send_frame(&frame(10));
    server.send_frame(&frame(14)); // 3 dropped
    server.send_frame(&frame(12)); // out of order
    let mut nan = frame(15);
    nan.bodies[1].position_mm = [f32::NAN; 3];
    server.send_frame(&nan); // occluded
    let mut skew = frame(16);
    skew.bodies[1].rotation = [2.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    server.send_frame(&skew); // bad rotation
    let mut inf = frame(17);
    inf.bodies[1].rotation[0] = f32::INFINITY;
    server.send_frame(&inf); // nan pose
    let mut short = frame(18);
    short.bodies.truncate(1);
    server.send_frame(&short); // the body's index is past the frame's bodies
    server.send_raw(&qtm_encode::event(16)); // an event that changes nothing
    let mut unknown = qtm_encode::command("x");
    unknown[4] = 42;
    server.send_raw(&unknown); // unknown packet type
    let mut no6d = qtm_encode::data(&frame(19));
    no6d[8 + 8 + 4 + 4 + 4] = 1; // the component is 3D now
    server.send_raw(&no6d);
    let mut cut = qtm_encode::data(&frame(20));
    cut[8 + 16 + 8..8 + 16 + 12].copy_from_slice(&5u32.to_le_bytes()); // five bodies claimed, two sent
    server.send_raw(&cut);
    server.send_frame(&frame(21));
    let s = latest_input(&statuses, |s| s.published >= 6).await;
    assert_eq!((s.dropped, s.out_of_order, s.occluded), (6, 1, 3), "{s:?}");
    for (reason, n) in [
        ("bad_rotation", 1),
        ("nan_pose", 1),
        ("body_missing_from_frame", 1),
        ("unknown_message", 1),
        ("no_6d", 1),
        ("truncated", 1),
    ] {
        assert_eq!(s.rejected.get(reason), Some(&n), "{reason}: {s:?}");
    }

    // Renamed: QTM tells of new camera settings, the client asks for the parameters again.
    server.bodies.lock().unwrap()[1] = "club2".into();
    server.send_raw(&qtm_encode::event(11));
    latest_input(&statuses, |s| !s.body_found).await;
    server.send_frame(&frame(22));
    latest_input(&statuses, |s| s.rejected.get("body_not_in_model") == Some(&1)).await;
    server.bodies.lock().unwrap()[1] = "club".into();

    // The measurement stops: connect again.
    server.send_raw(&qtm_encode::event(4));
    latest_input(&statuses, |s| s.connects == 2 && s.body_found).await;
    // An oversized packet: the stream is out of step, connect again.
    assert!(wait_until(Duration::from_secs(10), || server.streaming() > 0).await);
    let mut huge = qtm_encode::command("x");
    huge[..4].copy_from_slice(&(4u32 << 20).to_le_bytes());
    server.send_raw(&huge);
    latest_input(&statuses, |s| s.connects == 3 && s.rejected.get("oversized") == Some(&1)).await;
    assert!(wait_until(Duration::from_secs(10), || server.streaming() > 0).await);
    server.send_frame(&frame(30));
    let s = latest_input(&statuses, |s| s.published >= 7).await;
    assert_eq!(s.state, impactd::wire::ConnectionState::Connected);
    assert_eq!(server.stream_requests.load(Ordering::Relaxed), 3, "one StreamFrames per session");
    daemon.stop().await;
}

/// A club marker set (body frame, metres) whose labels QTM streams as 3D markers, with a wand's marker
/// between them.
const MARKERS: &str = "[markers]\nCH1 = [0.035, 0.0, 0.01]\nCH2 = [-0.035, 0.004, 0.012]\nTOE = [0.0, 0.025, -0.03]\nHEEL = [0.012, -0.022, 0.028]\n";
const LABELS: [&str; 5] = ["CH1", "wand tip", "CH2", "TOE", "HEEL"];

/// A swing's sample as QTM's labelled 3D markers of [`MARKERS`] (mm, f32; NaN when the body is occluded).
fn markers_frame(s: &ClubheadSample, set: &impactd::kinematics::MarkerSet) -> Frame6d {
    let [x, y, z, w] = s.orientation_xyzw;
    let q = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z));
    let pose = impactd::math::Isometry3::from_parts(s.position_m.into(), q);
    // In QTM's label order; the wand's marker is not the club's.
    let markers: Vec<[f32; 3]> = LABELS
        .iter()
        .map(|label| match set.labels.iter().position(|l| l == label) {
            Some(k) if !s.occluded => {
                let p = (pose * impactd::math::Point3::from(set.body_m[k])).coords * 1e3;
                [p.x as f32, p.y as f32, p.z as f32]
            }
            Some(_) => [f32::NAN; 3],
            None => [500.0, 1000.0, -250.0],
        })
        .collect();
    Frame6d {
        timestamp_us: (s.t_ns / 1000) as i64,
        frame_number: s.frame as u32,
        bodies: Vec::new(),
        drop_rate_2d: 0,
        out_of_sync_rate_2d: 0,
        markers_mm: markers,
    }
}

const CHECK_3D: &str = r#"
import asyncio, json, sys
import xml.etree.ElementTree as ET
import qtm_rt
async def main(port, want):
    c = await qtm_rt.connect("127.0.0.1", port=port, version="1.25", timeout=5)
    xml = await c.get_parameters(parameters=["3d"])
    labels = [l.find("Name").text for l in ET.fromstring(xml).find("The_3D").findall("Label")]
    frames = []
    def on_packet(p):
        h, markers = p.get_3d_markers()
        frames.append(dict(frame=p.framenumber, count=h.marker_count, markers=[[m.x, m.y, m.z] for m in markers]))
    await c.stream_frames(components=["3d"], on_packet=on_packet)
    for _ in range(200):
        if len(frames) >= want: break
        await asyncio.sleep(0.05)
    print("RESULT " + json.dumps(dict(labels=labels, frames=frames)), flush=True)
    c.disconnect()
asyncio.run(main(int(sys.argv[1]), int(sys.argv[2])))
"#;

/// QTM's 3D: the test server's labels XML and 3D components are what Qualisys' SDK reads (labels in order,
/// every marker's f32 millimetres).
#[test]
fn qualisys_python_sdk_reads_the_3d_markers() {
    let set = impactd::kinematics::MarkerSet::from_toml(MARKERS).unwrap();
    let server = QtmServer::start(&[]);
    *server.labels.lock().unwrap() = LABELS.iter().map(|l| l.to_string()).collect();
    let child = spawn_client(CHECK_3D, server.port, 20);
    wait_for(|| server.streaming() > 0);
    let samples = swing::samples(1, 720.0, 5);
    let sent: Vec<Frame6d> = samples[100..120].iter().map(|s| markers_frame(s, &set)).collect();
    for f in &sent {
        server.send_frame(f);
        std::thread::sleep(Duration::from_millis(2));
    }
    let r = client_result(child, "qtm-rt");
    assert_eq!(r["labels"], serde_json::json!(LABELS));
    let frames = r["frames"].as_array().unwrap();
    assert_eq!(frames.len(), sent.len());
    for (got, f) in frames.iter().zip(&sent) {
        assert_eq!(got["frame"], f.frame_number);
        assert_eq!(got["count"], LABELS.len());
        let markers: Vec<[f32; 3]> = got["markers"]
            .as_array()
            .unwrap()
            .iter()
            .map(|m| {
                let v: Vec<f32> = m.as_array().unwrap().iter().map(|x| x.as_f64().unwrap() as f32).collect();
                [v[0], v[1], v[2]]
            })
            .collect();
        assert_eq!(markers, f.markers_mm);
    }
}

/// `[rig.input] qtm` with `markers = SET.toml`: no rigid body in QTM, the club's marker set fitted to its
/// labelled 3D markers each frame gives the launches of the same swing sent as JSON poses, within the f32
/// millimetres of QTM's wire (the fit of exact markers is exact to rounding).
#[tokio::test(flavor = "multi_thread")]
async fn a_marker_set_is_fitted_live_to_qtms_3d_markers() {
    let set = impactd::kinematics::MarkerSet::from_toml(MARKERS).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let set_path = dir.path().join("club.toml");
    std::fs::write(&set_path, MARKERS).unwrap();
    let samples = swing::samples(2, 720.0, 13);
    let json = swing::launches(RIG, &samples);
    assert_eq!(json.len(), 2);
    let server = QtmServer::start(&[]);
    *server.labels.lock().unwrap() = LABELS.iter().map(|l| l.to_string()).collect();
    let config = format!(
        "{RIG}[rig.input]\nqtm = \"127.0.0.1\"\nbody = \"club markers\"\nport = {}\nmarkers = {:?}\n",
        server.port,
        set_path.to_str().unwrap()
    );
    let daemon = start_daemon(&config, RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (launches, _l) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let (statuses, _s) = collect::<StatusMessage>(&session, "golf/rig1/status");
    assert!(wait_until(Duration::from_secs(10), || server.streaming() > 0).await, "the daemon streams 3D");
    for (i, s) in samples.iter().enumerate() {
        server.send_frame(&markers_frame(s, &set));
        if i % 4 == 3 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }
    let two = wait_until(Duration::from_secs(10), || launches.lock().unwrap().len() >= 2).await;
    assert!(two, "two launches; status {:?}", statuses.lock().unwrap().last());
    let got = launches.lock().unwrap().clone();
    daemon.stop().await;
    let d = swing::max_differences(&got, &json);
    eprintln!("fitted 3D markers vs JSON poses: ball speed {:.2e} mph, launch {:.2e} deg, direction {:.2e} deg, backspin {:.2e} rpm, sidespin {:.2e} rpm", d[0], d[1], d[2], d[3], d[4]);
    assert!(d[0] < 0.05 && d[1] < 0.05 && d[2] < 0.05 && d[3] < 5.0 && d[4] < 5.0, "{d:?}");
}
