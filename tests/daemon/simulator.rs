//! The Open Connect client for real: a daemon with a synthetic rig on loopback zenoh sends its predictions to
//! test simulators on loopback TCP that follow GSPro's Open Connect v1 page (glued `200` + `201` replies, no
//! answer to heartbeats), answer 501 to everything, close the connection after each shot, start late, or stall.
//! Every shot arrives once with the predicted numbers, none twice, stale ones are dropped and counted, and a
//! stalled simulator leaves the daemon's latency where it was.

#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]

use crate::common;

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use common::{collect, quantile, recorded, start_daemon, wait_until};
use impactd::daemon::bridges::open_connect::codec::ShotMessage;
use impactd::daemon::bridges::open_connect::splitter::{Frame, Splitter};
use impactd::daemon::sim::{run_sim, SimOptions};
use impactd::daemon::RunOptions;
use impactd::equipment::ClubSpec;
use impactd::wire::{ConnectionState, LaunchPrediction};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};

#[derive(Clone, Copy, PartialEq)]
enum Behaviour {
    /// GSPro's page: 200 and 201 glued in one write per shot, heartbeats unanswered.
    Spec,
    /// 501 to every message, heartbeats too (as OpenShotGolf answers heartbeats).
    Fails501,
    /// Reads one shot, answers 200, closes.
    ClosesAfterEachShot,
    /// Reads nothing for this long after accepting, then behaves as `Spec`.
    Stalls(Duration),
}

#[derive(Clone, Default)]
struct Received {
    shots: Arc<Mutex<Vec<ShotMessage>>>,
    /// The same shots as the JSON objects read, for the field names.
    raw: Arc<Mutex<Vec<serde_json::Value>>>,
    heartbeats: Arc<AtomicU64>,
    connections: Arc<AtomicU64>,
}

const GLUED_REPLY: &[u8] = br#"{"Code":200,"Message":"Shot received successfully"}{"Code":201,"Message":"GSPro Player Information","Player":{"Handed":"RH","Club":"DR"}}"#;

async fn serve(mut stream: TcpStream, behaviour: Behaviour, got: Received) {
    got.connections.fetch_add(1, Ordering::SeqCst);
    if let Behaviour::Stalls(d) = behaviour {
        tokio::time::sleep(d).await;
    }
    let mut splitter = Splitter::new(64 * 1024);
    let mut buf = vec![0u8; 4096];
    loop {
        let n = match stream.read(&mut buf).await {
            Ok(0) | Err(_) => return,
            Ok(n) => n,
        };
        let mut frames = Vec::new();
        splitter.push(&buf[..n], &mut |f| frames.push(f));
        for f in frames {
            let Frame::Object(o) = f else { panic!("the client sent {f:?}") };
            let m: ShotMessage = serde_json::from_slice(&o).expect("the client sends Open Connect messages");
            if behaviour == Behaviour::Fails501 {
                let _ = stream.write_all(br#"{"Code":501,"Message":"failure occurred"}"#).await;
            }
            if m.is_heartbeat() {
                got.heartbeats.fetch_add(1, Ordering::SeqCst);
                continue;
            }
            got.shots.lock().unwrap().push(m);
            got.raw.lock().unwrap().push(serde_json::from_slice(&o).unwrap());
            match behaviour {
                Behaviour::Spec | Behaviour::Stalls(_) => {
                    let _ = stream.write_all(GLUED_REPLY).await;
                }
                Behaviour::ClosesAfterEachShot => {
                    let _ = stream.write_all(br#"{"Code":200,"Message":"ok"}"#).await;
                    return;
                }
                Behaviour::Fails501 => {}
            }
        }
    }
}

fn start_simulator(listener: TcpListener, behaviour: Behaviour) -> Received {
    let got = Received::default();
    let g = got.clone();
    tokio::spawn(async move {
        while let Ok((stream, _)) = listener.accept().await {
            tokio::spawn(serve(stream, behaviour, g.clone()));
        }
    });
    got
}

fn config(rigs: &[(&str, Option<&str>)], max_age_s: f64) -> String {
    let mut c = String::from("status_period_s = 0.5\n");
    for (name, sim) in rigs {
        c.push_str(&format!("[[rig]]\nname = \"{name}\"\nclub = \"driver\"\n"));
        if let Some(a) = sim {
            c.push_str(&format!(
                "[rig.simulator]\nopen_connect = \"{a}\"\nmax_shot_age_s = {max_age_s}\nheartbeat_s = 0.3\n"
            ));
        }
    }
    c
}

fn sim(rig: &str, shots: u64, interval_s: f64, seed: u64) -> SimOptions {
    SimOptions { rigs: vec![rig.into()], club: ClubSpec::driver(), shots, interval_s, seed, ..SimOptions::default() }
}

/// Every shot received is a prediction, number for number, and none is received twice.
fn assert_each_once(shots: &[ShotMessage], launches: &[LaunchPrediction]) {
    let mut numbers: Vec<u64> = shots.iter().map(|s| s.shot_number).collect();
    numbers.dedup();
    assert_eq!(numbers.len(), shots.len(), "a shot number repeats: {numbers:?}");
    let mut matched = std::collections::BTreeSet::new();
    for s in shots {
        let b = s.ball_data.as_ref().expect("a shot carries ball data");
        let l = launches
            .iter()
            .find(|l| l.launch.launch.ball_speed_mph == b.speed_mph)
            .unwrap_or_else(|| panic!("shot {} at {} mph is no prediction", s.shot_number, b.speed_mph));
        assert!(matched.insert(l.shot), "prediction {} arrived twice", l.shot);
        let m = &l.launch.launch;
        // The specification's fields and signs are TrackMan's: the numbers pass unchanged (JSON round trip).
        assert_eq!((b.vla_deg, b.hla_deg), (m.launch_angle_deg, m.launch_direction_deg));
        assert_eq!((b.back_spin_rpm, b.side_spin_rpm), (Some(m.backspin_rpm), Some(m.sidespin_rpm)));
        assert_eq!((b.total_spin_rpm, b.spin_axis_deg), (Some(m.total_spin_rpm), Some(m.spin_axis_deg)));
        assert_eq!(b.carry_yd, l.flight.as_ref().map(|f| f.carry_yd));
        // Every ClubData field of the specification, from the delivery (TrackMan's definitions; the face
        // impact in mm, toe + and up +). Face to path has no field of its own: it is FaceToTarget - Path.
        let c = s.club_data.as_ref().unwrap();
        let d = &l.delivery;
        assert!(s.shot_data_options.contains_club_data);
        assert_eq!((c.speed_mph, c.speed_at_impact_mph), (Some(d.club_speed_mph), Some(d.club_speed_mph)));
        assert_eq!(c.angle_of_attack_deg, Some(d.attack_angle_deg));
        assert_eq!((c.path_deg, c.face_to_target_deg), (Some(d.club_path_deg), Some(d.face_angle_deg)));
        assert!((c.face_to_target_deg.unwrap() - c.path_deg.unwrap() - d.face_to_path_deg).abs() < 1e-9);
        assert_eq!((c.loft_deg, c.lie_deg), (Some(d.dynamic_loft_deg), Some(d.dynamic_lie_deg)));
        assert_eq!(
            (c.horizontal_face_impact_mm, c.vertical_face_impact_mm),
            (Some(d.impact_h_mm), Some(d.impact_v_mm))
        );
        assert_eq!(c.closure_rate, Some(d.closure_rate_degps));
        assert!(d.club_speed_mph > 80.0 && d.dynamic_loft_deg > 5.0 && d.dynamic_lie_deg > 30.0, "a drive: {d:?}");
        assert!(b.speed_mph > 50.0 && s.api_version == "1" && s.units == "Yards");
    }
}

/// Runs a rig `bay1` sending to `address` for `shots` shots, then waits for `settled`.
async fn run(
    address: &str,
    shots: u64,
    max_age_s: f64,
    record: Option<&std::path::Path>,
    settled: impl FnMut() -> bool,
) -> (Vec<LaunchPrediction>, impactd::daemon::RunSummary) {
    let options = RunOptions { record: record.map(|p| p.to_path_buf()), ..Default::default() };
    let daemon = start_daemon(&config(&[("bay1", Some(address))], max_age_s), options).await;
    let rig = common::client(&daemon.endpoint).await;
    let (launches, _sub) = collect::<LaunchPrediction>(&rig, "golf/bay1/launch");
    run_sim(&rig, sim("bay1", shots, 0.6, 11), std::future::pending()).await.unwrap();
    wait_until(Duration::from_secs(60), || launches.lock().unwrap().len() as u64 >= shots).await;
    wait_until(Duration::from_secs(30), settled).await;
    tokio::time::sleep(Duration::from_millis(300)).await;
    let summary = daemon.stop().await;
    rig.close().await.unwrap();
    let launches = launches.lock().unwrap().clone();
    assert_eq!(launches.len() as u64, shots, "every swing predicted");
    (launches, summary)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_simulator_following_the_specification_gets_every_shot_once() {
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let address = listener.local_addr().unwrap().to_string();
    let got = start_simulator(listener, Behaviour::Spec);
    let dir = tempfile::tempdir().unwrap();
    let recording = dir.path().join("s.mcap");
    let shots = 4;
    let g = got.clone();
    let (launches, summary) =
        run(&address, shots, 5.0, Some(&recording), move || g.shots.lock().unwrap().len() as u64 >= shots).await;
    let received = got.shots.lock().unwrap().clone();
    assert_eq!(received.len() as u64, shots);
    assert_each_once(&received, &launches);
    // On the wire, every field of the specification's ClubData and BallData is there by its name.
    for raw in got.raw.lock().unwrap().iter() {
        let names = |o: &serde_json::Value| o.as_object().unwrap().keys().cloned().collect::<Vec<_>>();
        let club = [
            "Speed",
            "AngleOfAttack",
            "FaceToTarget",
            "Lie",
            "Loft",
            "Path",
            "SpeedAtImpact",
            "VerticalFaceImpact",
            "HorizontalFaceImpact",
            "ClosureRate",
        ];
        assert_eq!(names(&raw["ClubData"]).len(), club.len(), "{raw}");
        assert!(club.iter().all(|k| raw["ClubData"][k].is_number()), "{raw}");
        let ball = ["Speed", "SpinAxis", "TotalSpin", "BackSpin", "SideSpin", "HLA", "VLA", "CarryDistance"];
        assert!(ball.iter().all(|k| raw["BallData"][k].is_number()), "{raw}");
    }
    let s = &summary.simulators["bay1"];
    assert_eq!((s.sent, s.acknowledged, s.failed, s.dropped, s.refused), (shots, shots, 0, 0, 0), "{s:?}");
    assert_eq!((s.connects, s.state), (1, ConnectionState::Connected));
    let player = s.player.as_ref().expect("the 201 reply's player is kept");
    assert_eq!((player.handed.as_deref(), player.club.as_deref()), (Some("RH"), Some("DR")));
    assert!(got.heartbeats.load(Ordering::SeqCst) >= 1, "heartbeats while idle");
    // Everything sent and received is in the recording: each shot, each heartbeat, each glued reply apart.
    let rec = recorded(&recording);
    let traffic = &rec["/golf/bay1/simulator"];
    let count = |dir: &str, text: &str| {
        traffic.iter().filter(|t| t["direction"] == dir && t["text"].as_str().unwrap().contains(text)).count() as u64
    };
    assert_eq!(count("sent", "\"BallData\""), shots);
    assert_eq!(count("received", "\"Code\":200"), shots);
    assert_eq!(count("received", "\"Code\":201"), shots);
    let statuses = &rec["/golf/bay1/status"];
    assert!(statuses.iter().any(|st| st["simulator"]["acknowledged"] == shots), "status counts the acknowledged");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_simulator_answering_501_sees_each_shot_once_and_the_failures_are_counted() {
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let address = listener.local_addr().unwrap().to_string();
    let got = start_simulator(listener, Behaviour::Fails501);
    let shots = 3;
    let g = got.clone();
    let (launches, summary) =
        run(&address, shots, 5.0, None, move || g.shots.lock().unwrap().len() as u64 >= shots).await;
    tokio::time::sleep(Duration::from_millis(300)).await;
    let received = got.shots.lock().unwrap().clone();
    assert_eq!(received.len() as u64, shots, "a failure is never sent again");
    assert_each_once(&received, &launches);
    let s = &summary.simulators["bay1"];
    assert_eq!((s.sent, s.acknowledged, s.failed), (shots, 0, shots), "{s:?}");
    assert_eq!(s.last_reply.as_deref(), Some("501 failure occurred"));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_simulator_that_closes_the_connection_gets_every_shot_once() {
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let address = listener.local_addr().unwrap().to_string();
    let got = start_simulator(listener, Behaviour::ClosesAfterEachShot);
    let shots = 4;
    let g = got.clone();
    let (launches, summary) =
        run(&address, shots, 5.0, None, move || g.shots.lock().unwrap().len() as u64 >= shots).await;
    let received = got.shots.lock().unwrap().clone();
    assert_eq!(received.len() as u64, shots);
    assert_each_once(&received, &launches);
    // On the wire, every field of the specification's ClubData and BallData is there by its name.
    for raw in got.raw.lock().unwrap().iter() {
        let names = |o: &serde_json::Value| o.as_object().unwrap().keys().cloned().collect::<Vec<_>>();
        let club = [
            "Speed",
            "AngleOfAttack",
            "FaceToTarget",
            "Lie",
            "Loft",
            "Path",
            "SpeedAtImpact",
            "VerticalFaceImpact",
            "HorizontalFaceImpact",
            "ClosureRate",
        ];
        assert_eq!(names(&raw["ClubData"]).len(), club.len(), "{raw}");
        assert!(club.iter().all(|k| raw["ClubData"][k].is_number()), "{raw}");
        let ball = ["Speed", "SpinAxis", "TotalSpin", "BackSpin", "SideSpin", "HLA", "VLA", "CarryDistance"];
        assert!(ball.iter().all(|k| raw["BallData"][k].is_number()), "{raw}");
    }
    let s = &summary.simulators["bay1"];
    assert_eq!((s.sent, s.acknowledged, s.failed, s.dropped), (shots, shots, 0, 0), "{s:?}");
    assert!(s.connects >= shots, "reconnected after each close: {} connections", s.connects);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_simulator_that_starts_late_gets_the_fresh_shots_and_the_stale_ones_are_dropped() {
    let port = impactd::daemon::bus::free_loopback_port().unwrap();
    let address = format!("127.0.0.1:{port}");
    let got = Received::default();
    let (g, a) = (got.clone(), address.clone());
    // Shots every 0.6 s from about 0.6 s; the simulator appears at 2.5 s; shots older than 1 s by then are dropped.
    tokio::spawn(async move {
        tokio::time::sleep(Duration::from_millis(2500)).await;
        let listener = TcpListener::bind(&a).await.unwrap();
        let got = start_simulator(listener, Behaviour::Spec);
        loop {
            tokio::time::sleep(Duration::from_millis(20)).await;
            *g.shots.lock().unwrap() = got.shots.lock().unwrap().clone();
        }
    });
    let shots = 6;
    let g = got.clone();
    let (launches, summary) = run(&address, shots, 1.0, None, move || g.shots.lock().unwrap().len() >= 2).await;
    let received = got.shots.lock().unwrap().clone();
    let s = &summary.simulators["bay1"];
    assert_each_once(&received, &launches);
    assert_eq!(received.len() as u64, s.sent, "{s:?}");
    assert_eq!(s.sent + s.dropped, shots, "each shot sent or dropped: {s:?}");
    assert!(s.dropped >= 1 && s.sent >= 2, "{s:?}");
    assert_eq!(s.acknowledged, s.sent);
}

/// Two rigs swing at once; one sends to a simulator that reads nothing for 10 s. The daemon's own latency
/// (callback -> published) of that rig stays where the other rig's is.
#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_stalled_simulator_does_not_move_the_latency() {
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let address = listener.local_addr().unwrap().to_string();
    let got = start_simulator(listener, Behaviour::Stalls(Duration::from_secs(10)));
    let daemon = start_daemon(&config(&[("bay1", Some(&address)), ("bay2", None)], 30.0), RunOptions::default()).await;
    let rig = common::client(&daemon.endpoint).await;
    let (launches, _sub) = collect::<LaunchPrediction>(&rig, "golf/*/launch");
    let shots = 12;
    let (a, b) = tokio::join!(
        run_sim(&rig, sim("bay1", shots, 0.7, 21), std::future::pending()),
        run_sim(&rig, sim("bay2", shots, 0.7, 21), std::future::pending()),
    );
    a.unwrap();
    b.unwrap();
    wait_until(Duration::from_secs(60), || launches.lock().unwrap().len() as u64 >= 2 * shots).await;
    let stalled_at_end = got.shots.lock().unwrap().len();
    let g = got.clone();
    wait_until(Duration::from_secs(30), move || g.shots.lock().unwrap().len() as u64 >= shots).await;
    let summary = daemon.stop().await;
    rig.close().await.unwrap();
    let launches = launches.lock().unwrap().clone();
    let latency = |rig: &str| -> Vec<f64> { launches.iter().filter(|l| l.rig == rig).map(|l| l.latency_us).collect() };
    let (stalled, free) = (latency("bay1"), latency("bay2"));
    assert_eq!((stalled.len() as u64, free.len() as u64), (shots, shots));
    let (p50s, p99s, p50f, p99f) =
        (quantile(&stalled, 0.5), quantile(&stalled, 0.99), quantile(&free, 0.5), quantile(&free, 0.99));
    eprintln!("latency with the simulator stalled: p50 {p50s:.0} us p99 {p99s:.0} us; without: p50 {p50f:.0} us p99 {p99f:.0} us");
    // The percentiles are printed, not asserted (benches/latency.rs times the live path): the stalled
    // simulator must not hold the rig back, which the counts show: every shot of both rigs was predicted
    // while the simulator was still stalled.
    assert!(stalled_at_end < shots as usize, "the simulator was still stalled when the rig finished");
    let s = &summary.simulators["bay1"];
    assert_eq!(got.shots.lock().unwrap().len() as u64, shots, "after the stall every shot arrives: {s:?}");
    assert_eq!((s.sent, s.dropped), (shots, 0), "{s:?}");
}
