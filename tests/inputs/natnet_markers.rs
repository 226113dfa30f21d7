//! OptiTrack NatNet labelled markers, live: a club tracked as a marker set (Motive's asset "Club" with markers
//! CH1, CH2, TOE, HEEL and one more the set file does not use), no rigid body for it in Motive. The test
//! server's marker set descriptions, asset descriptions and labelled markers are checked with OptiTrack's own
//! Python client (`natnetsdk`); then the daemon's `[rig.input] natnet` with `markers = SET.toml` fits the set
//! to the streamed markers each frame and gives the launches of the same swing sent as JSON poses.

#![allow(clippy::unwrap_used)]

use crate::common;
use crate::natnet_server;
use crate::swing;

use std::time::Duration;

use common::{client, client_result, collect, latest_input, spawn_client, start_daemon, wait_for, wait_until};
use impactd::daemon::RunOptions;
use impactd::kinematics::{ClubheadSample, MarkerSet};
use impactd::math::{Isometry3, Quaternion, UnitQuaternion};
use impactd::mocap::natnet::markers::{LabeledMarker, OCCLUDED, POINT_CLOUD_SOLVED};
use impactd::mocap::natnet::{self, Frame, RigidBody, Version};
use impactd::wire::{LaunchPrediction, StatusMessage};
use natnet_server::{NatNetServer, CLOCK_HZ};

/// The club's marker set (body frame, metres), as `impactd calibrate body` writes one.
const MARKERS: &str = "[markers]\nCH1 = [0.035, 0.0, 0.01]\nCH2 = [-0.035, 0.004, 0.012]\nTOE = [0.0, 0.025, -0.03]\nHEEL = [0.012, -0.022, 0.028]\n";
/// Motive's marker set "Club", in Motive's order (labelled markers are numbered by it, from 1); SHAFT is a
/// marker on the shaft the set file leaves out.
const MOTIVE_MARKERS: [&str; 5] = ["HEEL", "CH1", "SHAFT", "TOE", "CH2"];
const CLUB_ID: i32 = 5;
const WAND_ID: i32 = 7;

/// What happens to the club's markers in frame `k` (besides the swing's own occlusions).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Trouble {
    None,
    /// CH2 flagged occluded by Motive (its stale position sent 3 cm off): 3 valid markers remain.
    Occluded,
    /// TOE a ghost 2 cm off: rejected by its residual, the pose from the other 3.
    Ghost,
}

fn trouble(k: usize) -> Trouble {
    match k % 7 {
        3 => Trouble::Occluded,
        5 => Trouble::Ghost,
        _ => Trouble::None,
    }
}

/// A swing's sample `k` as Motive's frame: the wand's rigid body, the club's labelled markers (model id
/// `CLUB_ID`, index in `MOTIVE_MARKERS`), a wand marker and an unlabelled one; the club's marker set positions.
fn frame_of(k: usize, s: &ClubheadSample, set: &MarkerSet) -> (Frame, Vec<[f32; 3]>) {
    let [x, y, z, w] = s.orientation_xyzw;
    let pose = Isometry3::from_parts(s.position_m.into(), UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)));
    let at = |label: &str| match set.labels.iter().position(|l| l == label) {
        Some(i) => pose * impactd::math::Point3::from(set.body_m[i]),
        None => pose * impactd::math::Point3::new(-0.01, 0.12, 0.0), // SHAFT, 12 cm up the shaft
    };
    let mut labeled = Vec::new();
    let mut positions = Vec::new();
    for (i, name) in MOTIVE_MARKERS.iter().enumerate() {
        let mut p = at(name);
        let mut params = POINT_CLOUD_SOLVED;
        if s.occluded {
            params = OCCLUDED;
        } else if *name == "CH2" && trouble(k) == Trouble::Occluded {
            params = OCCLUDED;
            p.x += 0.03;
        } else if *name == "TOE" && trouble(k) == Trouble::Ghost {
            p.y += 0.02;
        }
        let position_m = [p.x as f32, p.y as f32, p.z as f32];
        positions.push(position_m);
        let id = LabeledMarker::pack_id(CLUB_ID, i as i32 + 1);
        labeled.push(LabeledMarker { id, position_m, size_m: 0.014, params, residual_m: 2e-4 });
    }
    let wand = [0.5f32, 1.0, -0.25];
    labeled.push(LabeledMarker {
        id: LabeledMarker::pack_id(WAND_ID, 1),
        position_m: wand,
        size_m: 0.012,
        params: POINT_CLOUD_SOLVED,
        residual_m: 1e-4,
    });
    let unlabeled = [0.1f32, 0.02, 0.3];
    labeled.push(LabeledMarker {
        id: 4242,
        position_m: unlabeled,
        size_m: 0.01,
        params: 0x10 | 0x02,
        residual_m: 3e-4,
    });
    let wand_body = RigidBody {
        id: WAND_ID,
        position_m: wand,
        orientation_xyzw: [0.0, 0.0, 0.0, 1.0],
        mean_error_m: 1e-4,
        tracking_valid: true,
    };
    let t_s = s.t_ns as f64 * 1e-9;
    let frame = Frame {
        frame_number: s.frame as i32,
        rigid_bodies: vec![wand_body],
        labeled_markers: labeled,
        timestamp_s: t_s,
        mid_exposure_ticks: (t_s * CLOCK_HZ as f64) as u64,
        data_received_ticks: (t_s * CLOCK_HZ as f64) as u64 + 20_000,
        transmit_ticks: (t_s * CLOCK_HZ as f64) as u64 + 35_000,
        models_changed: false,
    };
    (frame, positions)
}

fn server(version: Version) -> NatNetServer {
    let server = NatNetServer::start(version, &[(WAND_ID, "wand")]);
    let names = MOTIVE_MARKERS.iter().map(|m| m.to_string()).collect();
    server.state.lock().unwrap().marker_assets = vec![(CLUB_ID, "Club".into(), names)];
    server
}

const CHECK: &str = r#"
import json, sys, time
from natnetsdk.NatNetClient import NatNetClient
port, want = int(sys.argv[1]), int(sys.argv[2])
c = NatNetClient()
c.set_client_address("127.0.0.1"); c.set_server_address("127.0.0.1"); c.set_use_multicast(False)
c.multicast_address = "255.255.255.255"   # unicast: no group joined
c.command_port = port
c.set_print_level(0)
s = lambda v: v.decode() if isinstance(v, bytes) else v
sets, ids, frames = [], [], []
dd = c._NatNetClient__unpack_data_descriptions
def on_dd(*a):
    r = dd(*a); d = r[1]
    sets.append([(s(m.marker_set_name), [s(n) for n in m.marker_names_list]) for m in d.marker_set_list])
    ids.append([(s(b.sz_name), b.id_num) for b in d.rigid_body_list] + [(s(x.name), x.assetID) for x in d.asset_list])
    return r
c._NatNetClient__unpack_data_descriptions = on_dd
md = c._NatNetClient__unpack_mocap_data
def on_md(*a):
    r = md(*a); m = r[1]
    frames.append(dict(frame=m.prefix_data.frame_number,
        sets=[(s(x.model_name), [list(p) for p in x.marker_pos_list]) for x in m.marker_set_data.marker_data_list],
        labeled=[dict(id=x.id_num, pos=list(x.pos), size=x.size, param=x.param, residual_mm=x.residual)
                 for x in m.labeled_marker_data.labeled_marker_list]))
    return r
c._NatNetClient__unpack_mocap_data = on_md
assert c.run()
time.sleep(0.3)
c.send_request(c.command_socket, c.NAT_REQUEST_MODELDEF, "", (c.server_ip_address, c.command_port))
end = time.time() + 10
while (len(frames) < want or not sets) and time.time() < end:
    time.sleep(0.05)
print("RESULT " + json.dumps(dict(sets=sets, ids=ids, frames=frames)), flush=True)
import os
os._exit(0)   # the SDK's shutdown() waits forever on its unicast data socket, which nothing is sent to
"#;

/// The test server's marker set and asset descriptions and its labelled markers are what OptiTrack's client
/// reads, in NatNet 3.1, 4.0 and 4.1: the set's name and marker names in order, the asset's id (a Trained
/// Markerset asset in 4.1; before 4.1 a model of that name), every labelled marker's packed id, f32 position,
/// size, params (occluded flag included) and residual (natnetsdk reports it in mm), and the marker set's
/// positions; impactd's own decoder reads the same.
#[test]
fn optitracks_python_client_reads_labelled_markers_and_marker_sets() {
    let set = MarkerSet::from_toml(MARKERS).unwrap();
    let samples = swing::samples(1, 720.0, 5);
    for version in [Version::V3_1, Version::V4_0, Version::V4_1] {
        let server = server(version);
        let child = spawn_client(CHECK, server.port, 20);
        wait_for(|| server.clients() > 0);
        std::thread::sleep(Duration::from_millis(500));
        let sent: Vec<(Frame, Vec<[f32; 3]>)> =
            samples[100..120].iter().enumerate().map(|(k, s)| frame_of(k, s, &set)).collect();
        for (f, positions) in &sent {
            server.send_marker_frame(f, "Club", positions);
            std::thread::sleep(Duration::from_millis(2));
        }
        let r = client_result(child, "natnetsdk");
        let sets = &r["sets"][0];
        assert_eq!(sets[0], serde_json::json!(["wand", ["m1", "m2", "m3"]]), "{version}");
        assert_eq!(sets[1], serde_json::json!(["Club", MOTIVE_MARKERS]), "{version}: the club's marker set");
        let ids = r["ids"][0].as_array().unwrap();
        assert!(ids.contains(&serde_json::json!(["Club", CLUB_ID])), "{version}: the club's id: {ids:?}");
        let frames = r["frames"].as_array().unwrap();
        assert_eq!(frames.len(), sent.len(), "{version}: every frame decoded");
        let mut ours = Frame::default();
        for (got, (f, positions)) in frames.iter().zip(&sent) {
            assert_eq!(got["frame"], f.frame_number);
            let labeled = got["labeled"].as_array().unwrap();
            assert_eq!(labeled.len(), f.labeled_markers.len(), "{version}");
            for (g, m) in labeled.iter().zip(&f.labeled_markers) {
                assert_eq!(g["id"], m.id);
                let pos: Vec<f32> = g["pos"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap() as f32).collect();
                assert_eq!(pos, m.position_m);
                assert_eq!(g["size"].as_f64().unwrap() as f32, m.size_m);
                assert_eq!(g["param"], m.params);
                assert!((g["residual_mm"].as_f64().unwrap() - f64::from(m.residual_m) * 1e3).abs() < 1e-6);
            }
            let club = &got["sets"][0];
            assert_eq!(club[0], "Club");
            let p: Vec<[f32; 3]> = club[1]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| {
                    let v: Vec<f32> = v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap() as f32).collect();
                    [v[0], v[1], v[2]]
                })
                .collect();
            assert_eq!(&p, positions);
            // impactd's decoder: the same labelled markers.
            let bytes = impactd::mocap::natnet::encode::frame(version, f, "Club", positions).unwrap();
            assert_eq!(natnet::decode(&bytes, version, &mut ours), Ok(natnet::Message::Frame));
            assert_eq!(ours.labeled_markers, f.labeled_markers);
        }
    }
}

/// `[rig.input] natnet` with `markers = SET.toml` and `body = "Club"` (Motive's asset, no rigid body): the set
/// fitted to the labelled markers each frame gives the launches of the same swing sent as JSON poses, within
/// the f32 metres of NatNet's wire, though every seventh frame has a marker flagged occluded (sent 3 cm off:
/// ignored, not fitted) and every seventh a ghost 2 cm off (rejected by its residual, not averaged in).
#[tokio::test(flavor = "multi_thread")]
async fn a_marker_set_is_fitted_live_to_motives_labelled_markers() {
    let set = MarkerSet::from_toml(MARKERS).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let set_path = dir.path().join("club.toml");
    std::fs::write(&set_path, MARKERS).unwrap();
    let rig = "status_period_s = 0.2\n[[rig]]\nname = \"rig1\"\n";
    let samples = swing::samples(2, 720.0, 13);
    let json = swing::launches(rig, &samples);
    assert_eq!(json.len(), 2);
    let server = server(Version::V4_1);
    let config = format!(
        "{rig}[rig.input]\nnatnet = \"127.0.0.1\"\nbody = \"Club\"\nunicast = true\ncommand_port = {}\ndata_port = 0\nmarkers = {:?}\n",
        server.port,
        set_path.to_str().unwrap()
    );
    let daemon = start_daemon(&config, RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (launches, _l) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let (statuses, _s) = collect::<StatusMessage>(&session, "golf/rig1/status");
    let asked = || server.model_requests.load(std::sync::atomic::Ordering::Relaxed) > 0;
    assert!(wait_until(Duration::from_secs(10), asked).await, "the daemon asks for the model");
    tokio::time::sleep(Duration::from_millis(300)).await;
    let (mut ghosts, mut flagged) = (0, 0);
    for (k, s) in samples.iter().enumerate() {
        let (frame, positions) = frame_of(k, s, &set);
        if !s.occluded {
            match trouble(k) {
                Trouble::Ghost => ghosts += 1,
                Trouble::Occluded => flagged += 1,
                Trouble::None => {}
            }
        }
        server.send_marker_frame(&frame, "Club", &positions);
        if k % 4 == 3 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }
    let two = wait_until(Duration::from_secs(10), || launches.lock().unwrap().len() >= 2).await;
    assert!(two, "two launches; status {:?}", statuses.lock().unwrap().last());
    let occluded = samples.iter().filter(|s| s.occluded).count() as u64;
    let frames = samples.len() as u64;
    let input = latest_input(&statuses, |i| i.frames == frames).await;
    let got = launches.lock().unwrap().clone();
    daemon.stop().await;
    assert!(input.body_found, "Motive's asset `Club` maps the set: {input:?}");
    assert_eq!(input.occluded, occluded, "only the swing's own occlusions: a flagged or ghost marker leaves 3");
    assert!(!input.rejected.contains_key("markers_not_in_model"), "{input:?}");
    assert!(ghosts > 50 && flagged > 50, "{ghosts} ghosts, {flagged} flagged markers");
    let d = swing::max_differences(&got, &json);
    eprintln!("fitted labelled markers vs JSON poses: ball speed {:.2e} mph, launch {:.2e} deg, direction {:.2e} deg, backspin {:.2e} rpm, sidespin {:.2e} rpm", d[0], d[1], d[2], d[3], d[4]);
    // Measured: 2.5e-5 mph, 6.8e-6 deg, 7.5e-6 deg, 2.5e-3 rpm, 2.1e-3 rpm (the f32 metres and the fit's
    // rounding); a 2 cm ghost averaged into one frame in seven would move the pose by millimetres.
    assert!(d[0] < 1e-3 && d[1] < 1e-3 && d[2] < 1e-3 && d[3] < 0.1 && d[4] < 0.1, "{d:?}");
}

/// `impactd bridge natnet --body Club=rig1 --markers Club=SET.toml`: the bridge fits the set the same way and
/// publishes the samples on zenoh (with the fit's residual), to a daemon that reads zenoh: the same launches.
#[tokio::test(flavor = "multi_thread")]
async fn the_bridge_fits_the_marker_set_too() {
    let set = MarkerSet::from_toml(MARKERS).unwrap();
    let rig = "status_period_s = 0.2\n[[rig]]\nname = \"rig1\"\n";
    let samples = swing::samples(2, 720.0, 13);
    let json = swing::launches(rig, &samples);
    let server = server(Version::V3_1);
    let daemon = start_daemon(rig, RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (launches, _l) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let (published, _p) = collect::<impactd::wire::ClubheadSampleMsg>(&session, "mocap/rig1/clubhead");
    let source = impactd::daemon::inputs::Source::new("natnet", "127.0.0.1", server.port)
        .with("data_port", 0)
        .with("unicast", true);
    let fitter = impactd::kinematics::MarkerFitter::new(set.clone()).with_reject_m(3e-3);
    let bridge_session = client(&daemon.endpoint).await;
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let bridge = tokio::spawn(async move {
        let routes = vec![("Club".to_string(), "rig1".to_string())];
        impactd::daemon::inputs::run_bridge_fitted(&bridge_session, source, routes, vec![Some(fitter)], vec![], async {
            let _ = stopped.await;
        })
        .await
        .unwrap()
    });
    let asked = || server.model_requests.load(std::sync::atomic::Ordering::Relaxed) > 0;
    assert!(wait_until(Duration::from_secs(10), asked).await, "the bridge asks for the model");
    tokio::time::sleep(Duration::from_millis(500)).await;
    for (k, s) in samples.iter().enumerate() {
        let (frame, positions) = frame_of(k, s, &set);
        server.send_marker_frame(&frame, "Club", &positions);
        if k % 4 == 3 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }
    assert!(wait_until(Duration::from_secs(10), || launches.lock().unwrap().len() >= 2).await, "two launches");
    tokio::time::sleep(Duration::from_millis(500)).await;
    let _ = stop.send(());
    let status = bridge.await.unwrap();
    daemon.stop().await;
    assert!(status[0].body_found, "NatNet 3.1: the asset's id from the model of its name: {:?}", status[0]);
    let published = published.lock().unwrap().clone();
    let fitted = published.iter().filter(|s| !s.occluded).collect::<Vec<_>>();
    assert!(!fitted.is_empty() && fitted.iter().all(|s| s.fit_residual_m.is_some_and(|r| r < 1e-6)));
    assert!(published.iter().filter(|s| s.occluded).all(|s| s.fit_residual_m.is_none()));
    let got = launches.lock().unwrap().clone();
    let d = swing::max_differences(&got, &json);
    assert_eq!(got.len(), json.len());
    assert!(d[0] < 1e-3 && d[1] < 1e-3 && d[2] < 1e-3 && d[3] < 0.1 && d[4] < 0.1, "{d:?}");
}
