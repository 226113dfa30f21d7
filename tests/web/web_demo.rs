#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]
//! `impactd demo --web` keeps serving the bay screen after the demo's shots, until stopped (issue 32): the binary
//! run as a user runs it, everything on 127.0.0.1 (the demo's zenoh sessions are loopback TCP with multicast
//! scouting off). Seconds after its last shot the process is still up, the page is served, and a WebSocket client
//! (Python's `websockets`, independent of the daemon's tungstenite) gets a snapshot holding the demo's shots;
//! SIGINT (Ctrl-C) then stops it cleanly with the recording written.

use crate::common;

use std::io::{BufRead, BufReader, Read, Write};
use std::time::{Duration, Instant};

const SHOTS: u64 = 2;

/// Reads the rig's snapshot from the page's WebSocket and prints how many shots it holds.
const CLIENT: &str = r#"
import asyncio, json, sys
import websockets

async def main():
    async with websockets.connect(sys.argv[1], max_size=None) as ws:
        while True:
            m = json.loads(await asyncio.wait_for(ws.recv(), 10))
            if m["type"] == "snapshot" and m["rig"] == "rig1":
                print(json.dumps({"shots": [s["shot"] for s in m["shots"]]}))
                return

asyncio.run(main())
"#;

fn get(address: &str, path: &str) -> String {
    let mut s = std::net::TcpStream::connect(address).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    write!(s, "GET {path} HTTP/1.1\r\nHost: {address}\r\nConnection: close\r\n\r\n").unwrap();
    let mut out = String::new();
    let _ = s.read_to_string(&mut out);
    out
}

#[test]
fn the_demos_bay_screen_keeps_serving_after_its_shots_until_stopped() {
    let dir = tempfile::tempdir().unwrap();
    let recording = dir.path().join("demo.mcap");
    let web = format!("127.0.0.1:{}", impactd::daemon::bus::free_loopback_port().unwrap());
    let mut demo = std::process::Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(["demo", "--json", "--shots", &SHOTS.to_string(), "--web", &web, "--record"])
        .arg(&recording)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // The demo prints each launch (JSON) as it is published.
    let mut lines = BufReader::new(demo.stdout.take().unwrap()).lines();
    for _ in 0..SHOTS {
        let line = lines.next().expect("the demo ended before its shots").unwrap();
        assert!(line.contains("\"ball_speed_mph\""), "{line}");
    }
    // Without --web the demo would have ended by now.
    std::thread::sleep(Duration::from_secs(3));
    assert!(demo.try_wait().unwrap().is_none(), "the demo stopped after its shots");
    let page = get(&web, "/");
    assert!(page.starts_with("HTTP/1.1 200") && page.contains("text/html"), "{page}");
    let out = common::python().arg("-c").arg(CLIENT).arg(format!("ws://{web}/ws")).output().unwrap();
    assert!(out.status.success(), "websocket client: {}", String::from_utf8_lossy(&out.stderr));
    let snapshot: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(snapshot["shots"], serde_json::json!((1..=SHOTS).collect::<Vec<_>>()), "{snapshot}");
    assert!(demo.try_wait().unwrap().is_none(), "the demo stopped while a page was open");

    // Ctrl-C stops it: the process ends cleanly and the recording is closed.
    let stopped = std::process::Command::new("kill").args(["-INT", &demo.id().to_string()]).status().unwrap();
    assert!(stopped.success());
    let start = Instant::now();
    let status = loop {
        if let Some(s) = demo.try_wait().unwrap() {
            break s;
        }
        assert!(start.elapsed() < Duration::from_secs(20), "the demo did not stop on SIGINT");
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(status.success(), "{status}");
    assert!(std::fs::metadata(&recording).unwrap().len() > 0);
}
