#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]
//! `impactd demo --foxglove` logs no ERROR while a Foxglove client comes and goes (issue 31 saw zenoh's
//! `Received Data for unknown key_expr` there): the binary run as a user runs it, on 127.0.0.1, and an
//! independent client of the Foxglove WebSocket protocol (Python's `websockets`) that connects, subscribes to
//! every channel, reads, unsubscribes and closes; connects again and drops the connection without a close
//! handshake; and connects a third time, reading until the demo ends. The demo must predict every shot, end with
//! exit 0, and its log must hold no ERROR line.
//!
//! The demo also serves the bay screen, so it stays up after its shots until Ctrl-C: the test interrupts it once
//! every shot is predicted and the third visit is reading, however slowly a loaded machine runs the first two.

use crate::common;

const CLIENT: &str = r#"
import asyncio, json, sys, time
import websockets

async def visit(url, seconds, abrupt=False, until_closed=False, reading=None):
    for _ in range(400):
        try:
            ws = await websockets.connect(url, subprotocols=["foxglove.websocket.v1"], max_size=None)
            break
        except OSError:
            await asyncio.sleep(0.05)
    else:
        raise SystemExit(f"no Foxglove server at {url} after 400 tries (did the demo end before this visit?)")
    assert json.loads(await ws.recv())["op"] == "serverInfo"
    channels = [c["id"] for c in json.loads(await ws.recv())["channels"]]
    await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 100 + c, "channelId": c} for c in channels]}))
    n, end = 0, time.monotonic() + seconds
    try:
        while until_closed or time.monotonic() < end:
            await asyncio.wait_for(ws.recv(), 30 if until_closed else max(end - time.monotonic(), 0.01))
            n += 1
            if n == 1 and reading:
                reading()
    except (asyncio.TimeoutError, websockets.ConnectionClosed):
        pass
    if not until_closed:
        await ws.send(json.dumps({"op": "unsubscribe", "subscriptionIds": [100 + c for c in channels]}))
        if abrupt:
            ws.transport.abort()
        else:
            await ws.close()
    return n

async def main(url):
    counts = [await visit(url, 1.0), await visit(url, 1.0, abrupt=True)]
    counts.append(await visit(url, 0, until_closed=True, reading=lambda: print("third visit reading", flush=True)))
    print(json.dumps(counts), flush=True)

asyncio.run(main(sys.argv[1]))
"#;

#[test]
fn a_foxglove_client_coming_and_going_leaves_no_error_in_the_demos_log() {
    use std::io::BufRead;
    let dir = tempfile::tempdir().unwrap();
    let port = || impactd::daemon::bus::free_loopback_port().unwrap();
    let address = format!("127.0.0.1:{}", port());
    let web = format!("127.0.0.1:{}", port());
    let mut demo = std::process::Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(["demo", "--shots", "10", "--json", "--foxglove", &address, "--web", &web, "--record"])
        .arg(dir.path().join("demo.mcap"))
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut client = common::python()
        .arg("-c")
        .arg(CLIENT)
        .arg(format!("ws://{address}"))
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // One JSON line per prediction; the client's line once its third visit reads.
    let (tx, rx) = std::sync::mpsc::channel::<&str>();
    let predictions = std::io::BufReader::new(demo.stdout.take().unwrap());
    let demo_tx = tx.clone();
    std::thread::spawn(move || {
        for _ in predictions.lines().map_while(Result::ok).filter(|l| l.starts_with('{')) {
            let _ = demo_tx.send("prediction");
        }
    });
    let client_lines = std::io::BufReader::new(client.stdout.take().unwrap());
    let client_out = std::thread::spawn(move || {
        let mut last = String::new();
        for line in client_lines.lines().map_while(Result::ok) {
            if line == "third visit reading" {
                let _ = tx.send("third");
            }
            last = line;
        }
        last
    });
    let (mut predicted, mut third) = (0, false);
    while predicted < 10 || !third {
        match rx.recv_timeout(std::time::Duration::from_secs(120)) {
            Ok("prediction") => predicted += 1,
            Ok(_) => third = true,
            Err(e) => {
                let _ = (demo.kill(), client.kill());
                let client = client.wait_with_output().unwrap();
                panic!(
                    "{predicted} predictions, third visit reading: {third} ({e}); client: {}",
                    String::from_utf8_lossy(&client.stderr)
                );
            }
        }
    }
    // Ctrl-C, as a user stops the demo.
    assert!(std::process::Command::new("kill").args(["-INT", &demo.id().to_string()]).status().unwrap().success());
    let out = demo.wait_with_output().unwrap();
    let log = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "the demo failed: {log}");
    assert!(log.contains("10 of 10 shots predicted"), "{log}");
    let errors: Vec<&str> = log.lines().filter(|l| l.contains(" ERROR ")).collect();
    assert!(errors.is_empty(), "the demo logged errors: {errors:#?}");
    let client = client.wait_with_output().unwrap();
    assert!(client.status.success(), "client: {}", String::from_utf8_lossy(&client.stderr));
    // Each visit read messages (the third until the demo closed the connection).
    let counts: Vec<u64> = serde_json::from_str(&client_out.join().unwrap()).unwrap();
    assert!(counts.len() == 3 && counts.iter().all(|&n| n > 0), "{counts:?}");
}
