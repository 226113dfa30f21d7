#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]
//! `impactd demo --foxglove` logs no ERROR while a Foxglove client comes and goes (issue 31 saw zenoh's
//! `Received Data for unknown key_expr` there): the binary run as a user runs it, on 127.0.0.1, and an
//! independent client of the Foxglove WebSocket protocol (Python's `websockets`) that connects, subscribes to
//! every channel, reads, unsubscribes and closes; connects again and drops the connection without a close
//! handshake; and connects a third time, reading until the demo ends. The demo must predict every shot, end with
//! exit 0, and its log must hold no ERROR line.

use crate::common;

const CLIENT: &str = r#"
import asyncio, json, sys, time
import websockets

async def visit(url, seconds, abrupt=False, until_closed=False):
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
    counts = [await visit(url, 1.0), await visit(url, 1.0, abrupt=True), await visit(url, 0, until_closed=True)]
    print(json.dumps(counts))

asyncio.run(main(sys.argv[1]))
"#;

#[test]
fn a_foxglove_client_coming_and_going_leaves_no_error_in_the_demos_log() {
    let dir = tempfile::tempdir().unwrap();
    let address = format!("127.0.0.1:{}", impactd::daemon::bus::free_loopback_port().unwrap());
    let demo = std::process::Command::new(env!("CARGO_BIN_EXE_impactd"))
        // Ten shots (about 14 s of paced swings): time for the client to start and make its first two visits
        // on a loaded machine before the third one's.
        .args(["demo", "--shots", "10", "--foxglove", &address, "--record"])
        .arg(dir.path().join("demo.mcap"))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let client = common::python()
        .arg("-c")
        .arg(CLIENT)
        .arg(format!("ws://{address}"))
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let out = demo.wait_with_output().unwrap();
    let log = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "the demo failed: {log}");
    assert!(log.contains("10 of 10 shots predicted"), "{log}");
    let errors: Vec<&str> = log.lines().filter(|l| l.contains(" ERROR ")).collect();
    assert!(errors.is_empty(), "the demo logged errors: {errors:#?}");
    let client = client.wait_with_output().unwrap();
    assert!(client.status.success(), "client: {}", String::from_utf8_lossy(&client.stderr));
    // Each visit read messages (the third until the demo closed the connection).
    let counts: Vec<u64> = serde_json::from_slice(&client.stdout).unwrap();
    assert!(counts.len() == 3 && counts.iter().all(|&n| n > 0), "{counts:?}");
}
