//! Shot -> simulator socket on loopback: a rig's Open Connect client is handed each prediction (as the daemon's
//! worker does, right after publishing it) and a simulator on 127.0.0.1 reads the stream; the time from the hand
//! over to the simulator holding the shot's whole JSON object. Predictions are real: a synthetic rig's swings
//! through the pipeline. Prints p50/p99/max and checks the budget (p99 <= 2 ms, ARCHITECTURE.md section 5).
//! `cargo bench --bench open_connect [-- SHOTS]`.

#![allow(clippy::unwrap_used)]

use std::io::{Read, Write};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use impactd::daemon::bridges::open_connect::splitter::{Frame, Splitter};
use impactd::daemon::bridges::open_connect::{SimulatorClient, SimulatorOptions};
use impactd::daemon::recording::writer::RecorderHandle;
use impactd::daemon::sim::{SimOptions, SimRig};
use impactd::pipeline::{Event, Pipeline, RigSetup};
use impactd::wire::LaunchPrediction;

fn quantile(v: &mut [f64], q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v[((q * v.len() as f64).ceil() as usize).clamp(1, v.len()) - 1]
}

/// `n` predictions of a synthetic rig's swings.
fn predictions(n: u64) -> Vec<LaunchPrediction> {
    let options = SimOptions { shots: n, ..SimOptions::default() };
    let mut rig = SimRig::new("rig1", &options, 1_000_000_000, 7);
    let mut pipeline = Pipeline::new(RigSetup::new("rig1", options.club.clone()));
    let mut out = Vec::new();
    while !rig.done() {
        let (sample, _) = rig.next_sample().unwrap();
        pipeline.on_sample_with(&sample, &mut |e| {
            if let Event::Launch(l) = e {
                out.push(l);
            }
        });
    }
    out
}

fn main() {
    let shots: u64 = std::env::args().skip(1).find_map(|a| a.parse().ok()).unwrap_or(300);
    let launches = predictions(shots.min(50));
    assert!(!launches.is_empty(), "the synthetic rig's swings are predicted");
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let address = listener.local_addr().unwrap().to_string();
    let (arrived_tx, arrived) = mpsc::channel::<Instant>();
    std::thread::spawn(move || {
        let (mut stream, _) = listener.accept().unwrap();
        let mut splitter = Splitter::new(64 * 1024);
        let mut buf = vec![0u8; 8192];
        loop {
            let n = match stream.read(&mut buf) {
                Ok(0) | Err(_) => return,
                Ok(n) => n,
            };
            let now = Instant::now();
            let mut shot = false;
            splitter.push(&buf[..n], &mut |f| {
                if let Frame::Object(o) = f {
                    shot |= !String::from_utf8_lossy(&o).contains("\"IsHeartBeat\":true");
                }
            });
            if shot {
                arrived_tx.send(now).unwrap();
                let _ = stream.write_all(br#"{"Code":200,"Message":"Shot received successfully"}"#);
            }
        }
    });
    let rt = tokio::runtime::Builder::new_multi_thread().worker_threads(2).enable_all().build().unwrap();
    let options = SimulatorOptions {
        rig: "rig1".into(),
        address,
        device_id: "impactd bench".into(),
        max_shot_age: Duration::from_secs(5),
        heartbeat: Duration::from_secs(2),
        backoff_min: Duration::from_millis(10),
        backoff_max: Duration::from_millis(100),
    };
    let mut client = rt.block_on(async { SimulatorClient::spawn(options, RecorderHandle::none(), Default::default()) });
    while client.status().connects == 0 {
        std::thread::sleep(Duration::from_millis(10));
    }
    let mut micros = Vec::new();
    for k in 0..shots {
        let mut l = launches[(k as usize) % launches.len()].clone();
        l.shot = k + 1;
        let t0 = Instant::now();
        client.offer(&l);
        let t1 = arrived.recv_timeout(Duration::from_secs(5)).expect("the shot reaches the simulator");
        micros.push(t1.duration_since(t0).as_secs_f64() * 1e6);
        // Shots are seconds apart in life; 5 ms apart here, so the client is idle between them.
        std::thread::sleep(Duration::from_millis(5));
    }
    let s = client.status();
    let (p50, p99) = (quantile(&mut micros, 0.5), quantile(&mut micros, 0.99));
    let max = micros.iter().cloned().fold(0.0, f64::max);
    println!("prediction handed over -> whole shot read by the simulator (loopback), {shots} shots:");
    println!("  p50 {p50:.0} us   p99 {p99:.0} us   max {max:.0} us   (budget p99 <= 2000 us)");
    println!("  sent {} acknowledged {} failed {} dropped {}", s.sent, s.acknowledged, s.failed, s.dropped);
    assert_eq!(s.sent, shots, "every shot sent once");
    assert!(p99 <= 2000.0, "p99 {p99:.0} us is over the 2 ms budget");
}
