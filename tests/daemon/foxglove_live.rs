//! The Foxglove live view for real: `impactd demo` with `--foxglove` on loopback, and an independent client of
//! the Foxglove WebSocket protocol (Python's `websockets`, installed by `scripts/test.sh`) that negotiates
//! `foxglove.websocket.v1`, reads the server info and the advertised channels, subscribes to all of them and
//! decodes the binary message frames (opcode 1, subscription id, time, JSON) until every channel of the demo's
//! rig has spoken.

#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]

use crate::common;

use impactd::daemon::bus::free_loopback_port;
use impactd::daemon::demo::{demo, DemoOptions};
use impactd::daemon::sim::SimOptions;
use impactd::daemon::DaemonConfig;
use impactd::equipment::ClubSpec;

const CLIENT: &str = r#"
import asyncio, json, struct, sys, time
import websockets

async def main(url, want, timeout_s):
    deadline = time.monotonic() + timeout_s
    while True:
        try:
            ws = await websockets.connect(url, subprotocols=["foxglove.websocket.v1"], max_size=None)
            break
        except OSError:
            if time.monotonic() > deadline:
                raise
            await asyncio.sleep(0.05)
    async with ws:
        assert ws.subprotocol == "foxglove.websocket.v1", ws.subprotocol
        info = json.loads(await ws.recv())
        assert info["op"] == "serverInfo", info
        adv = json.loads(await ws.recv())
        assert adv["op"] == "advertise", adv
        topics = {c["id"]: c["topic"] for c in adv["channels"]}
        for c in adv["channels"]:
            assert c["encoding"] == "json" and c["schemaEncoding"] == "jsonschema" and json.loads(c["schema"]), c
        await ws.send(json.dumps({"op": "subscribe",
                                  "subscriptions": [{"id": 100 + cid, "channelId": cid} for cid in topics]}))
        counts = {t: 0 for t in topics.values()}
        first = {}
        while not all(counts.get(t, 0) > 0 for t in want):
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                break
            try:
                msg = await asyncio.wait_for(ws.recv(), remaining)
            except (asyncio.TimeoutError, websockets.ConnectionClosed):
                break
            if isinstance(msg, bytes):
                op, sub, t_ns = struct.unpack_from("<BIQ", msg)
                assert op == 1 and t_ns > 0
                topic = topics[sub - 100]
                counts[topic] += 1
                first.setdefault(topic, json.loads(msg[13:]))
        flight = first.get("/foxglove/rig1/ball_flight", {"entities": [{"lines": [{"points": []}]}]})
        print(json.dumps({"counts": counts,
                          "flight_points": len(flight["entities"][0]["lines"][0]["points"]),
                          "launch_speed_mph": first.get("/golf/rig1/launch", {}).get("launch", {}).get("ball_speed_mph")}))

asyncio.run(main(sys.argv[1], sys.argv[2].split(","), float(sys.argv[3])))
"#;

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_foxglove_client_receives_every_channel_during_a_demo() {
    let address = format!("127.0.0.1:{}", free_loopback_port().unwrap());
    let want = [
        "/mocap/rig1/clubhead",
        "/golf/rig1/impact",
        "/golf/rig1/launch",
        "/golf/rig1/status",
        "/foxglove/rig1/club_pose",
        "/foxglove/rig1/impact_scene",
        "/foxglove/rig1/ball_flight",
    ];
    let client = common::python()
        .arg("-c")
        .arg(CLIENT)
        .arg(format!("ws://{address}"))
        .arg(want.join(","))
        .arg("25")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("python3");
    let sim = SimOptions { club: ClubSpec::driver(), shots: 3, interval_s: 2.0, ..SimOptions::default() };
    let options = DemoOptions {
        config: DaemonConfig::default(),
        sim,
        record: None,
        overwrite: false,
        json: true,
        foxglove: Some(address),
        web: None,
    };
    let summary = demo(options, std::future::pending()).await.unwrap();
    assert_eq!(summary.rigs["rig1"].predictions, 3);
    let out = tokio::task::spawn_blocking(move || client.wait_with_output()).await.unwrap().unwrap();
    assert!(out.status.success(), "the Python Foxglove client: {}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    eprintln!("{report}");
    for topic in want {
        assert!(report["counts"][topic].as_u64().unwrap_or(0) > 0, "no message on {topic}: {report}");
    }
    // The flight line is sampled every 50 ms of a driver's 5-7 s flight.
    assert!(report["flight_points"].as_u64().unwrap() > 50, "{report}");
    assert!(report["launch_speed_mph"].as_f64().unwrap() > 100.0, "{report}");
}
