#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]
//! A screen that stops reading does not make the daemon hold what it is sent, and a long session does not make
//! the screens grow (issue 32: "a page left open for a day does not grow without bound"): a daemon in-process on
//! loopback zenoh (multicast scouting off) serving `--web` on 127.0.0.1; one page that completes its WebSocket
//! handshake and never reads again, one that reads everything; then 1500 launches put on `golf/<rig>/launch`
//! (the bus the screens read, as the daemon's worker publishes them). The stalled page is closed once its socket
//! stays full for the daemon's 5 s write limit (the rig's status counts one connection less), the reading page
//! sees the last shot, and a page that joins afterwards is sent the last 1000 shots only (its bound).

use crate::common;

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;

use common::start_daemon;
use futures_util::StreamExt;
use impactd::daemon::RunOptions;
use impactd::wire::{LaunchPrediction, StatusMessage};
use tokio::net::TcpStream;

const SHOTS: u64 = 1500;

/// A page's websocket; the daemon's web server may still be binding when the daemon task has just started.
async fn page(address: &str) -> tokio_tungstenite::WebSocketStream<TcpStream> {
    let stream = common::connect_when_listening(address).await;
    tokio_tungstenite::client_async(format!("ws://{address}/ws"), stream).await.unwrap().0
}

fn open_pages(statuses: &common::Collected<StatusMessage>) -> Option<u64> {
    statuses.lock().unwrap().last().and_then(|s| s.web.as_ref().map(|w| w.clients))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_stalled_page_is_let_go_and_a_long_session_stays_within_the_screens_bounds() {
    let web = format!("127.0.0.1:{}", impactd::daemon::bus::free_loopback_port().unwrap());
    let config = "status_period_s = 0.2\n[[rig]]\nname = \"rig1\"\n";
    let daemon = start_daemon(config, RunOptions { web: Some(web.clone()), ..Default::default() }).await;
    let bus = common::client(&daemon.endpoint).await;
    let (statuses, _s) = common::collect::<StatusMessage>(&bus, "golf/rig1/status");

    // Held open, never read.
    let _stalled = page(&web).await;
    // Reads everything; notes the highest shot number it has been sent (in a shot or a snapshot).
    let highest = Arc::new(AtomicU64::new(0));
    let seen = highest.clone();
    let mut reader = page(&web).await;
    let reading = tokio::spawn(async move {
        while let Some(Ok(m)) = reader.next().await {
            let Ok(v) = serde_json::from_str::<serde_json::Value>(m.to_text().unwrap_or("")) else { continue };
            let shots = match v["type"].as_str() {
                Some("shot") => vec![v["shot"].as_u64().unwrap_or(0)],
                Some("snapshot") => {
                    v["shots"].as_array().into_iter().flatten().filter_map(|s| s["shot"].as_u64()).collect()
                }
                _ => continue,
            };
            seen.fetch_max(shots.into_iter().max().unwrap_or(0), Ordering::Relaxed);
        }
    });
    assert!(common::wait_until(Duration::from_secs(10), || open_pages(&statuses) == Some(2)).await, "two pages open");

    let template: LaunchPrediction = serde_json::from_str(include_str!("../data/web-launch.json")).unwrap();
    for shot in 1..=SHOTS {
        let mut p = template.clone();
        p.shot = shot;
        // Blocking, not dropping, when the bus's queue is full: the test is about the screen's bounds, and a
        // burst of puts on a loaded machine would otherwise lose a few launches on the way.
        bus.put("golf/rig1/launch", serde_json::to_vec(&p).unwrap())
            .congestion_control(zenoh::qos::CongestionControl::Block)
            .await
            .unwrap();
        // Its flight line, as the daemon puts it right after the launch.
        bus.put("golf/rig1/flight", serde_json::to_vec(&line(shot)).unwrap())
            .congestion_control(zenoh::qos::CongestionControl::Block)
            .await
            .unwrap();
        if shot % 100 == 0 {
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
    }
    // The reading page keeps up (or is sent a fresh snapshot when it falls behind) and sees the last shot.
    assert!(
        common::wait_until(Duration::from_secs(60), || highest.load(Ordering::Relaxed) == SHOTS).await,
        "the reading page saw shot {} of {SHOTS}",
        highest.load(Ordering::Relaxed)
    );
    // The stalled page is let go: its socket stayed full past the 5 s write limit.
    assert!(
        common::wait_until(Duration::from_secs(30), || open_pages(&statuses) == Some(1)).await,
        "the stalled page is still held: {:?} pages open",
        open_pages(&statuses)
    );
    // A page joining now is sent the last 1000 shots, not the 1500 of the session.
    let mut late = page(&web).await;
    let snapshot = loop {
        let m = tokio::time::timeout(Duration::from_secs(10), late.next()).await.unwrap().unwrap().unwrap();
        let v: serde_json::Value = serde_json::from_str(m.to_text().unwrap()).unwrap();
        if v["type"] == "snapshot" {
            break v;
        }
    };
    let shots: Vec<u64> = snapshot["shots"].as_array().unwrap().iter().map(|s| s["shot"].as_u64().unwrap()).collect();
    assert_eq!(shots.len(), 1000);
    assert_eq!((shots[0], shots[999]), (SHOTS - 999, SHOTS));
    let flights = snapshot["flights"].as_array().unwrap();
    assert_eq!(flights.len(), 12);
    // The lines drawn are the ones put, to the centimetre.
    let last = flights.last().unwrap();
    assert_eq!(last["shot"], serde_json::json!(SHOTS));
    assert_eq!(last["line"], serde_json::json!([[0.0, 0.0, 0.0], [12.35, 3.0, -0.5]]));
    // The per-club numbers still count every kept shot (the daemon keeps 5000).
    assert_eq!(snapshot["summary"]["by"]["club"][0]["shots"], serde_json::json!(SHOTS));
    reading.abort();
    daemon.stop().await;
}

/// A flight line of the daemon's form for `shot`.
fn line(shot: u64) -> impactd::wire::FlightLine {
    impactd::wire::FlightLine {
        rig: "rig1".into(),
        shot,
        model: "adjusted".into(),
        t_impact_ns: 0,
        step_s: 0.05,
        points: vec![[0.0; 4], [0.05, 12.3456, 3.0012, -0.4987]],
    }
}
