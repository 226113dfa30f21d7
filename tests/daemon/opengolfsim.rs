//! The OpenGolfSim client for real: a daemon with a synthetic rig on loopback zenoh sends its predictions to a
//! test server on loopback TCP written from OpenGolfSim's "Developer API" and "Shot Data API" pages (port 3111
//! in the simulator; any free port here): newline-delimited JSON, `device` ready/busy, `shot` with `unit` and
//! the five ball fields, a `result` back per shot in metres. The server reads every message with its own JSON
//! parsing (not impactd's codec), checks each field's name and value against the predictions, and every
//! message both ways is in the recording.

#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]

use crate::common;

use std::sync::{Arc, Mutex};
use std::time::Duration;

use common::{collect, recorded, start_daemon, wait_until};
use impactd::daemon::sim::{run_sim, SimOptions};
use impactd::daemon::RunOptions;
use impactd::equipment::ClubSpec;
use impactd::wire::{ConnectionState, LaunchPrediction};
use serde_json::{json, Value};
use tokio::io::{AsyncBufReadExt, AsyncWriteExt, BufReader};
use tokio::net::TcpListener;

/// Every line the server read, parsed as JSON.
type Lines = Arc<Mutex<Vec<Value>>>;

/// Accepts connections; reads newline-delimited JSON; answers each `shot` with a `result` as the page shows it.
fn start_server(listener: TcpListener) -> Lines {
    let lines: Lines = Arc::default();
    let got = lines.clone();
    tokio::spawn(async move {
        while let Ok((stream, _)) = listener.accept().await {
            let got = got.clone();
            tokio::spawn(async move {
                let (rd, mut wr) = stream.into_split();
                let mut rd = BufReader::new(rd).lines();
                while let Ok(Some(line)) = rd.next_line().await {
                    let v: Value = serde_json::from_str(&line).expect("each line is one JSON object");
                    if v["type"] == "shot" {
                        let result = json!({"type": "result", "data": {
                            "result": {"carry": 200.5, "height": 30.25, "roll": 12.0, "total": 212.5, "lateral": -1.5},
                            "club": {"name": "DR", "id": "DR", "distance": 250},
                            "shot": v["shot"], "sessionId": 7}});
                        let mut bytes = serde_json::to_vec(&result).unwrap();
                        bytes.push(b'\n');
                        wr.write_all(&bytes).await.unwrap();
                    }
                    got.lock().unwrap().push(v);
                }
            });
        }
    });
    lines
}

fn keys(v: &Value) -> Vec<String> {
    let mut k: Vec<String> = v.as_object().unwrap().keys().cloned().collect();
    k.sort();
    k
}

async fn session(unit: Option<&str>) {
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let address = listener.local_addr().unwrap().to_string();
    let lines = start_server(listener);
    let dir = tempfile::tempdir().unwrap();
    let recording = dir.path().join("ogs.mcap");
    let unit_line = unit.map(|u| format!("opengolfsim_unit = \"{u}\"\n")).unwrap_or_default();
    let config = format!(
        "status_period_s = 0.5\n[[rig]]\nname = \"bay1\"\nclub = \"driver\"\n[rig.simulator]\nopengolfsim = \"{address}\"\n{unit_line}"
    );
    let options = RunOptions { record: Some(recording.clone()), ..Default::default() };
    let daemon = start_daemon(&config, options).await;
    let rig = common::client(&daemon.endpoint).await;
    let (launches, _sub) = collect::<LaunchPrediction>(&rig, "golf/bay1/launch");
    let shots = 4u64;
    let sim = SimOptions {
        rigs: vec!["bay1".into()],
        club: ClubSpec::driver(),
        shots,
        interval_s: 0.6,
        seed: 5,
        ..SimOptions::default()
    };
    run_sim(&rig, sim, std::future::pending()).await.unwrap();
    let l = lines.clone();
    wait_until(Duration::from_secs(30), move || {
        l.lock().unwrap().iter().filter(|v| v["type"] == "shot").count() as u64 >= shots
    })
    .await;
    tokio::time::sleep(Duration::from_millis(300)).await;
    let summary = daemon.stop().await;
    rig.close().await.unwrap();
    let l = lines.clone();
    wait_until(Duration::from_secs(30), move || l.lock().unwrap().last().is_some_and(|v| v["status"] == "busy")).await;
    let launches = launches.lock().unwrap().clone();
    assert_eq!(launches.len() as u64, shots, "every swing predicted");
    let lines = lines.lock().unwrap().clone();

    // The device is ready first, busy last, and nothing else is a device message.
    assert_eq!(lines.first().unwrap(), &json!({"type": "device", "status": "ready"}));
    assert_eq!(lines.last().unwrap(), &json!({"type": "device", "status": "busy"}));
    let sent: Vec<&Value> = lines.iter().filter(|v| v["type"] == "shot").collect();
    assert_eq!(sent.len() + 2, lines.len(), "only shots between ready and busy: {lines:?}");
    assert_eq!(sent.len() as u64, shots, "each swing once");
    let metric = unit != Some("imperial");
    for (s, l) in sent.iter().zip(&launches) {
        assert_eq!(keys(s), ["shot", "type", "unit"]);
        assert_eq!(s["unit"], if metric { "metric" } else { "imperial" });
        let b = &s["shot"];
        assert_eq!(keys(b), ["ballSpeed", "horizontalLaunchAngle", "spinAxis", "spinSpeed", "verticalLaunchAngle"]);
        let m = &l.launch.launch;
        // The page's units: ball speed in m/s (metric) or mph (imperial), degrees, rpm; signs TrackMan's.
        let speed = if metric { m.ball_speed_mps } else { m.ball_speed_mph };
        assert_eq!(b["ballSpeed"].as_f64().unwrap(), speed);
        assert_eq!(b["verticalLaunchAngle"].as_f64().unwrap(), m.launch_angle_deg);
        assert_eq!(b["horizontalLaunchAngle"].as_f64().unwrap(), m.launch_direction_deg);
        assert_eq!(b["spinSpeed"].as_f64().unwrap(), m.total_spin_rpm);
        assert_eq!(b["spinAxis"].as_f64().unwrap(), m.spin_axis_deg);
        assert!(m.ball_speed_mph > 100.0 && m.total_spin_rpm > 1000.0, "a drive: {m:?}");
    }
    let s = &summary.simulators["bay1"];
    assert_eq!(s.protocol, "opengolfsim");
    assert_eq!((s.sent, s.acknowledged, s.failed, s.dropped, s.refused, s.heartbeats), (shots, shots, 0, 0, 0, 0));
    assert_eq!((s.connects, s.state), (1, ConnectionState::Connected));
    assert!(s.last_reply.as_deref().unwrap().contains("carry 200.5 m"), "{s:?}");
    // Both ways in the recording: ready, the shots, busy out; the results in.
    let rec = recorded(&recording);
    let traffic = &rec["/golf/bay1/simulator"];
    let count = |dir: &str, text: &str| {
        traffic.iter().filter(|t| t["direction"] == dir && t["text"].as_str().unwrap().contains(text)).count() as u64
    };
    assert_eq!(count("sent", "\"type\":\"shot\""), shots);
    assert_eq!(count("sent", "\"status\":\"ready\""), 1);
    assert_eq!(count("received", "\"type\":\"result\""), shots);
    assert_eq!(count("received", "\"sessionId\":7"), shots);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn opengolfsim_gets_every_field_of_every_shot_in_metric_units() {
    session(None).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn opengolfsim_gets_every_field_of_every_shot_in_imperial_units() {
    session(Some("imperial")).await;
}
