//! Vicon DataStream into the daemon: `[rig.input] vicon` and `impactd bridge vicon`, fed a synthetic swing
//! through the test server (which Vicon's own SDK checks in tests/inputs/vicon.rs), give the launches of the same swing
//! sent as JSON; a marker-fitted club likewise; a server restart mid-session reconnects; the bridge binary's help
//! and SIGINT; two rigs on one server share its connection.

#![allow(clippy::unwrap_used)]

use crate::common;
use crate::scene;
use crate::swing;
use crate::vicon_server;

use std::time::Duration;

use common::{client, collect, latest_input, start_daemon, wait_until};
use impactd::daemon::inputs::{run_bridge_routes, Route, Source};
use impactd::daemon::RunOptions;
use impactd::kinematics::{ClubheadSample, MarkerSet};
use impactd::math::{Isometry3, Point3, Quaternion, UnitQuaternion};
use impactd::mocap::vicon::encode::FrameOut;
use impactd::mocap::vicon::{enums, sample, Decoder, DynamicObjects, LabeledRecon};
use impactd::wire::{ClubheadSampleMsg, LaunchPrediction, StatusMessage};
use vicon_server::ViconServer;

const RIG: &str = "status_period_s = 0.2\n[[rig]]\nname = \"rig1\"\n";

/// A club marker set (body frame, metres) named like the scene's club subject's markers.
const MARKERS: &str = "[markers]\ntoe = [0.035, 0.0, 0.01]\nheel = [-0.035, 0.004, 0.012]\ncrown = [0.0, 0.025, -0.03]\nhosel = [0.012, -0.022, 0.028]\n";

fn input_config(port: u16, extra: &str) -> String {
    format!("{RIG}[rig.input]\nvicon = \"127.0.0.1:{port}\"\nsubject = \"club\"\n{extra}")
}

/// A swing's sample as the scene's labelled club markers (mm), none when the club is occluded.
fn markers_frame(s: &ClubheadSample, set: &MarkerSet) -> DynamicObjects {
    let mut d = scene::frame_of(s);
    d.segments.retain(|p| p.subject_id != scene::CLUB);
    let [x, y, z, w] = s.orientation_xyzw;
    let pose = Isometry3::from_parts(s.position_m.into(), UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)));
    if !s.occluded {
        for (k, name) in scene::CLUB_MARKERS.iter().enumerate() {
            let i = set.labels.iter().position(|l| l == name).unwrap();
            let p = (pose * Point3::from(set.body_m[i])).coords * 1e3;
            d.markers.push(LabeledRecon {
                subject_id: scene::CLUB,
                marker_id: k as u32 + 1,
                radius_mm: 7.0,
                position_mm: [p.x, p.y, p.z],
                covariance: [0.0; 9],
                trajectory_id: k as u32,
            });
        }
    }
    d
}

/// The samples impactd makes of `frames` (through the wire's bytes and its decoder): the JSON the daemon's
/// launches must equal exactly.
fn wire_samples(frames: &[DynamicObjects], fitter: Option<&impactd::kinematics::MarkerFitter>) -> Vec<ClubheadSample> {
    let statics = scene::statics();
    let mut dec = Decoder::new();
    let mut lab = Vec::new();
    frames
        .iter()
        .enumerate()
        .map(|(i, d)| {
            let out = FrameOut {
                statics: &statics,
                resend_statics: i == 0,
                dynamics: d,
                unchanged_dynamics: &[],
                wanted: &enums::CLIENT_WANTS,
            };
            dec.decode(&impactd::mocap::vicon::encode::frame(&out)).unwrap();
            let b = match fitter {
                Some(f) => {
                    let Ok(sample::RouteIds::Markers { marker_ids, .. }) =
                        sample::resolve_markers(&dec.frame, "club", f)
                    else {
                        panic!("the set's markers are the club's")
                    };
                    sample::fitted_sample(&dec.frame, f, scene::CLUB, &marker_ids, &mut lab).unwrap()
                }
                None => sample::segment_sample(&dec.frame, scene::CLUB, 1).unwrap().0,
            };
            ClubheadSample {
                frame: b.frame,
                t_ns: b.t_ns,
                position_m: b.position_m.into(),
                orientation_xyzw: b.orientation_xyzw,
                occluded: b.occluded,
            }
        })
        .collect()
}

fn play(server: &ViconServer, frames: &[DynamicObjects]) {
    for (i, f) in frames.iter().enumerate() {
        server.send_frame(f);
        if i % 4 == 3 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }
}

fn keys(v: &[LaunchPrediction]) -> Vec<(u64, u64, String)> {
    v.iter().map(swing::key).collect()
}

async fn through_daemon(
    config: &str,
    server: &ViconServer,
    frames: &[DynamicObjects],
    shots: usize,
) -> (Vec<LaunchPrediction>, StatusMessage) {
    let daemon = start_daemon(config, RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (launches, _l) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let (statuses, _s) = collect::<StatusMessage>(&session, "golf/rig1/status");
    assert!(wait_until(Duration::from_secs(10), || server.streaming() > 0).await);
    play(server, frames);
    assert!(wait_until(Duration::from_secs(10), || launches.lock().unwrap().len() >= shots).await, "launches");
    tokio::time::sleep(Duration::from_millis(500)).await;
    let input = launches.lock().unwrap().clone();
    let status = statuses.lock().unwrap().last().cloned().unwrap();
    daemon.stop().await;
    (input, status)
}

/// The same swing through the daemon's Vicon input and through the bridge gives exactly the launches of the
/// JSON samples the Vicon wire makes of it (f64 mm, a row-major matrix, the 135 MHz clock), and the launches of
/// the swing's own JSON samples up to that wire; the status counts every frame, states the up axis and rate and
/// records Vicon's latency; the bridge's samples carry it.
#[tokio::test(flavor = "multi_thread")]
async fn vicon_swing_gives_the_launches_of_the_json_swing() {
    let samples = swing::samples(3, 720.0, 13);
    let frames: Vec<DynamicObjects> = samples.iter().map(scene::frame_of).collect();
    let json = swing::launches(RIG, &samples);
    let wire = swing::launches(RIG, &wire_samples(&frames, None));
    assert_eq!(json.len(), 3);

    let server = ViconServer::start(scene::statics());
    let (input, status) = through_daemon(&input_config(server.port, ""), &server, &frames, 3).await;
    drop(server);

    let server = ViconServer::start(scene::statics());
    let daemon = start_daemon(RIG, RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (bridged, _b) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let (published, _p) = collect::<ClubheadSampleMsg>(&session, "mocap/rig1/clubhead");
    let bridge_session = client(&daemon.endpoint).await;
    let source = Source::new("vicon", "127.0.0.1", server.port);
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let bridge = tokio::spawn(async move {
        let routes = vec![(Route { body: "club".into(), ..Route::default() }, "rig1".to_string())];
        run_bridge_routes(&bridge_session, source, routes, Vec::new(), async {
            let _ = stopped.await;
        })
        .await
        .unwrap()
    });
    assert!(wait_until(Duration::from_secs(10), || server.streaming() > 0).await);
    tokio::time::sleep(Duration::from_millis(500)).await;
    play(&server, &frames);
    assert!(wait_until(Duration::from_secs(10), || bridged.lock().unwrap().len() >= 3).await, "three bridged");
    tokio::time::sleep(Duration::from_millis(500)).await;
    let _ = stop.send(());
    let bridge_status = bridge.await.unwrap();
    daemon.stop().await;

    assert_eq!(keys(&input), keys(&wire), "daemon input = the JSON swing through Vicon's wire, exactly");
    assert_eq!(keys(&bridged.lock().unwrap()), keys(&wire), "bridge = the same");
    let d = swing::max_differences(&input, &json);
    eprintln!("Vicon wire vs the swing's JSON: ball speed {:.2e} mph, launch {:.2e} deg, direction {:.2e} deg, backspin {:.2e} rpm, sidespin {:.2e} rpm", d[0], d[1], d[2], d[3], d[4]);
    assert!(d[0] < 0.03 && d[1] < 2e-3 && d[2] < 2e-3 && d[3] < 1.0 && d[4] < 1.0, "{d:?}");
    let s = status.input.unwrap();
    assert_eq!((s.protocol.as_str(), s.body.as_str(), s.body_found, s.connects), ("vicon", "club", true, 1));
    assert_eq!((s.frames, s.published, s.dropped, s.out_of_order), (frames.len() as u64, frames.len() as u64, 0, 0));
    assert_eq!(s.server_version.as_deref(), Some("Vicon DataStream, z-up, 720 Hz"));
    assert_eq!(s.exposure_to_transmit_p99_us, Some(3906.25), "Vicon's own latency, recorded in the status");
    assert_eq!(bridge_status[0].published, frames.len() as u64);
    let published = published.lock().unwrap();
    assert_eq!(published.len(), frames.len());
    assert!(published.iter().all(|m| m.system_latency_us == Some(3906.25)), "the latency beside each sample");
}

/// A club with no segment, its pose fitted to the subject's labelled markers (`markers = "SET.toml"`), gives
/// exactly the launches of the JSON samples the fit makes of the wire, and the swing's own launches up to it.
#[tokio::test(flavor = "multi_thread")]
async fn a_marker_fitted_vicon_club_gives_the_launches_of_the_json_swing() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("club.toml");
    std::fs::write(&path, MARKERS).unwrap();
    let set = MarkerSet::from_toml(MARKERS).unwrap();
    let fitter = impactd::kinematics::MarkerFitter::new(set.clone()).with_reject_m(3e-3);
    let samples = swing::samples(2, 720.0, 21);
    let frames: Vec<DynamicObjects> = samples.iter().map(|s| markers_frame(s, &set)).collect();
    let json = swing::launches(RIG, &samples);
    let wire = swing::launches(RIG, &wire_samples(&frames, Some(&fitter)));

    let server = ViconServer::start(scene::statics());
    let extra = format!("markers = {:?}\n", path.to_str().unwrap());
    let (input, status) = through_daemon(&input_config(server.port, &extra), &server, &frames, 2).await;
    assert_eq!(keys(&input), keys(&wire), "the fitted markers' launches, exactly");
    let d = swing::max_differences(&input, &json);
    eprintln!("Vicon markers fitted vs the swing's JSON: {d:?}");
    assert!(d[0] < 0.03 && d[1] < 2e-3 && d[2] < 2e-3 && d[3] < 1.0 && d[4] < 1.0, "{d:?}");
    let s = status.input.unwrap();
    assert_eq!((s.body_found, s.published), (true, frames.len() as u64));
}

/// The server restarts mid-session (its connections closed, then a new server on the same port): the input
/// connects again with back-off, the status says so, and frames flow again; a subject the server does not have
/// is counted.
#[tokio::test(flavor = "multi_thread")]
async fn a_vicon_server_restart_reconnects() {
    let server = ViconServer::start(scene::statics());
    let port = server.port;
    let daemon = start_daemon(&input_config(port, ""), RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (statuses, _s) = collect::<StatusMessage>(&session, "golf/rig1/status");
    assert!(wait_until(Duration::from_secs(10), || server.streaming() > 0).await);
    for i in 0..10 {
        server.send_frame(&scene::frame(i));
    }
    latest_input(&statuses, |s| s.published == 10 && s.connects == 1).await;
    drop(server);
    latest_input(&statuses, |s| s.state == impactd::wire::ConnectionState::Disconnected).await;
    tokio::time::sleep(Duration::from_millis(200)).await; // the old server's listener closes
    let server = ViconServer::start_on(port, scene::statics());
    assert!(wait_until(Duration::from_secs(15), || server.streaming() > 0).await);
    for i in 10..20 {
        server.send_frame(&scene::frame(i));
    }
    let s = latest_input(&statuses, |s| s.published == 20).await;
    assert_eq!((s.connects, s.state), (2, impactd::wire::ConnectionState::Connected));
    // The subject renamed in the server: counted, not published.
    server.set_statics(scene::statics_named("driver", impactd::mocap::vicon::UpAxis::Y));
    server.send_frame(&scene::frame(20));
    let s = latest_input(&statuses, |s| s.rejected.get("body_not_in_model") == Some(&1)).await;
    assert!(!s.body_found && s.server_version.as_deref() == Some("Vicon DataStream, y-up, 720 Hz"), "{s:?}");
    daemon.stop().await;
}

/// `impactd bridge vicon --help` names its flags, and the bridge exits (0) on SIGINT, printing its counts, while
/// it reads a server (the time it took is printed, not asserted: a hang guard only).
#[tokio::test(flavor = "multi_thread")]
async fn bridge_vicon_helps_and_stops_on_sigint() {
    let exe = env!("CARGO_BIN_EXE_impactd");
    let help = std::process::Command::new(exe).args(["bridge", "vicon", "--help"]).output().unwrap();
    assert!(help.status.success());
    let text = String::from_utf8_lossy(&help.stdout);
    for flag in
        ["--server <HOST[:PORT]>", "--subject <NAME=RIG>", "--segment <NAME>", "--markers <NAME=SET.toml>", "--ball"]
    {
        assert!(text.contains(flag), "{flag} in {text}");
    }
    let server = ViconServer::start(scene::statics());
    let daemon = start_daemon(RIG, RunOptions::default()).await;
    let addr = format!("127.0.0.1:{}", server.port);
    let child = std::process::Command::new(exe)
        .args(["bridge", "vicon", "--server", &addr, "--subject", "club=rig1", "-e", &daemon.endpoint])
        .arg("--no-multicast-scouting")
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    assert!(wait_until(Duration::from_secs(20), || server.streaming() > 0).await);
    for i in 0..50 {
        server.send_frame(&scene::frame(i));
    }
    tokio::time::sleep(Duration::from_millis(300)).await;
    let t0 = std::time::Instant::now();
    assert!(std::process::Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap().success());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    eprintln!("the bridge exited {:?} after SIGINT", t0.elapsed());
    // Frames 3, 10, ... have the club's segment occluded (published occluded).
    assert!(stderr.contains("club -> rig1: 50 frames, 50 published, 7 occluded"), "{stderr}");
    daemon.stop().await;
}

/// Ten subjects at 720 Hz through one bridge (ten rigs): every frame that arrived is published, none is lost
/// between the bridge and a subscriber, and the process's memory stays flat. Two seconds here;
/// `IMPACTD_SOAK_S=60 cargo test --release --test inputs vicon_live::ten_subjects -- --nocapture` is the minute-long
/// check measured by hand (the numbers are in docs/mocap-inputs.md).
#[tokio::test(flavor = "multi_thread")]
async fn ten_subjects_at_720_hz_through_one_bridge_lose_nothing() {
    use impactd::mocap::vicon::{SegmentDef, SegmentPose, StaticObjects, SubjectDef, UpAxis};
    let seconds: f64 = std::env::var("IMPACTD_SOAK_S").ok().and_then(|s| s.parse().ok()).unwrap_or(2.0);
    let subjects = (1..=10u32)
        .map(|s| SubjectDef {
            subject_id: s,
            name: format!("club{s}"),
            segments: vec![SegmentDef { segment_id: 1, parent_id: 0, bounds: [0.0; 6], name: "head".into() }],
            ..SubjectDef::default()
        })
        .collect();
    let statics = StaticObjects { frame_period_ticks: Some(scene::PERIOD_TICKS), up_axis: Some(UpAxis::Z), subjects };
    let server = ViconServer::start(statics);
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
    let source = Source::new("vicon", "127.0.0.1", server.port);
    let routes =
        (1..=10).map(|s| (Route { body: format!("club{s}"), ..Route::default() }, format!("rig{s}"))).collect();
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let bridge = tokio::spawn(async move {
        run_bridge_routes(&bridge_session, source, routes, Vec::new(), async {
            let _ = stopped.await;
        })
        .await
        .unwrap()
    });
    assert!(wait_until(Duration::from_secs(10), || server.streaming() > 0).await);
    tokio::time::sleep(Duration::from_millis(1000)).await;
    let frames = (seconds * 720.0) as u64;
    let (server, rss) = tokio::task::spawn_blocking(move || {
        let period = Duration::from_secs_f64(1.0 / 720.0);
        let start = std::time::Instant::now();
        let mut rss = Vec::new();
        for k in 0..frames {
            let t = k as f64 / 720.0;
            let frame = DynamicObjects {
                frame_id: Some(k as u32),
                latency: vec![impactd::mocap::vicon::LatencySample {
                    name: "Data Collection".into(),
                    latency_s: 0.002,
                }],
                segments: (1..=10)
                    .map(|s| SegmentPose {
                        subject_id: s,
                        segment_id: 1,
                        translation_mm: [f64::from(s) * 100.0, t.sin() * 1000.0, 0.0],
                        rotation: scene::rotation_identity(),
                    })
                    .collect(),
                ..DynamicObjects::default()
            };
            server.send_frame(&frame);
            if k % 720 == 0 {
                rss.push(common::rss_kib());
            }
            let due = start + period * (k as u32 + 1);
            if let Some(wait) = due.checked_duration_since(std::time::Instant::now()) {
                std::thread::sleep(wait);
            }
        }
        rss.push(common::rss_kib());
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
        "{seconds} s, {frames} frames x 10 subjects: published {published}, received {}, RSS (KiB) each second {rss:?}",
        received.load(std::sync::atomic::Ordering::Relaxed)
    );
    assert_eq!(published, want, "{statuses:?}");
    assert_eq!(received.load(std::sync::atomic::Ordering::Relaxed), want, "nothing lost after the bridge");
    assert!(statuses.iter().all(|s| s.rejected.is_empty() && s.dropped == 0 && s.out_of_order == 0), "{statuses:?}");
    let (first, last) = (rss[1.min(rss.len() - 1)], *rss.last().unwrap());
    assert!(last < first + 4096, "RSS grew from {first} to {last} KiB");
}

/// Two rigs served by one Vicon server (`[rig.input] vicon` naming the same address, a subject each) share one
/// connection: the server sees one client, and each rig predicts its own subject's swing exactly as the JSON
/// samples the Vicon wire makes of it.
#[tokio::test(flavor = "multi_thread")]
async fn two_rigs_on_one_vicon_server_share_one_connection_and_both_predict() {
    const CLUB2: u32 = 3;
    let samples = swing::samples(3, 720.0, 17);
    let mut statics = scene::statics();
    let mut second = statics.subjects[0].clone();
    second.subject_id = CLUB2;
    second.name = "club2".into();
    second.segments[0].name = "club2".into();
    statics.subjects.push(second);
    let frames: Vec<DynamicObjects> = samples
        .iter()
        .map(|s| {
            let mut d = scene::frame_of(s);
            let club = d.segments.iter().find(|p| p.subject_id == scene::CLUB).cloned();
            if let Some(mut p) = club {
                p.subject_id = CLUB2;
                d.segments.push(p);
            }
            d
        })
        .collect();
    let wire = swing::launches(RIG, &wire_samples(&frames, None));
    assert_eq!(wire.len(), 3);

    let server = ViconServer::start(statics);
    let port = server.port;
    let rig = |name: &str, subject: &str| {
        format!("[[rig]]\nname = \"{name}\"\n[rig.input]\nvicon = \"127.0.0.1:{port}\"\nsubject = \"{subject}\"\n")
    };
    let config = format!("status_period_s = 0.2\n{}{}", rig("rig1", "club"), rig("rig2", "club2"));
    let daemon = start_daemon(&config, RunOptions::default()).await;
    let session = client(&daemon.endpoint).await;
    let (first, _a) = collect::<LaunchPrediction>(&session, "golf/rig1/launch");
    let (other, _b) = collect::<LaunchPrediction>(&session, "golf/rig2/launch");
    let (statuses, _s) = collect::<StatusMessage>(&session, "golf/rig2/status");
    assert!(wait_until(Duration::from_secs(10), || server.streaming() > 0).await);
    tokio::time::sleep(Duration::from_millis(300)).await;
    assert_eq!((server.clients(), server.streaming()), (1, 1), "one connection serves both rigs");
    play(&server, &frames);
    let both = || first.lock().unwrap().len() >= 3 && other.lock().unwrap().len() >= 3;
    assert!(wait_until(Duration::from_secs(10), both).await, "both rigs predict");
    tokio::time::sleep(Duration::from_millis(500)).await;
    assert_eq!(server.clients(), 1, "still one connection");
    let status = statuses.lock().unwrap().last().cloned().unwrap().input.unwrap();
    daemon.stop().await;
    assert_eq!(keys(&first.lock().unwrap()), keys(&wire), "rig1 = the JSON swing through Vicon's wire");
    assert_eq!(keys(&other.lock().unwrap()), keys(&wire), "rig2 = the same swing on its own subject");
    assert_eq!((status.body.as_str(), status.body_found, status.connects), ("club2", true, 1));
    assert_eq!(status.frames, frames.len() as u64);
}
