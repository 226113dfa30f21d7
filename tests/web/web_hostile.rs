#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]
//! The bay screen's port against clients that misbehave (issue 33's rules for every network surface): a daemon
//! in-process on loopback zenoh (multicast scouting off) serving `--web` on 127.0.0.1, and raw TCP and
//! WebSocket clients on loopback. Oversized request heads, other methods, unknown paths, malformed or unknown
//! controls and oversized WebSocket messages are refused and counted by kind in the rig's status (`web`); at the
//! connection cap the longest-idle connection is closed for a newcomer, who is served; the page's files come
//! with their content types; and a well-formed control from a page is the put a program would make.

use crate::common;

use std::time::Duration;

use common::start_daemon;
use futures_util::{SinkExt, StreamExt};
use impactd::daemon::bridges::web::limits::{MAX_CLIENT_MESSAGE_BYTES, WEB_LIMITS};
use impactd::daemon::RunOptions;
use impactd::wire::StatusMessage;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::Message;
use zenoh::Wait;

async fn request(address: &str, head: &str) -> String {
    let mut s = common::connect_when_listening(address).await;
    s.write_all(head.as_bytes()).await.unwrap();
    let mut out = Vec::new();
    tokio::time::timeout(Duration::from_secs(5), s.read_to_end(&mut out)).await.unwrap().unwrap();
    String::from_utf8_lossy(&out).into_owned()
}

fn get(address: &str, path: &str) -> String {
    format!("GET {path} HTTP/1.1\r\nHost: {address}\r\n\r\n")
}

async fn page(address: &str) -> tokio_tungstenite::WebSocketStream<TcpStream> {
    let stream = common::connect_when_listening(address).await;
    tokio_tungstenite::client_async(format!("ws://{address}/ws"), stream).await.unwrap().0
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn the_bay_screen_refuses_and_counts_what_it_cannot_use_and_serves_the_next_client() {
    let web = format!("127.0.0.1:{}", impactd::daemon::bus::free_loopback_port().unwrap());
    let config = "status_period_s = 0.2\n[[rig]]\nname = \"bay1\"\n";
    let daemon = start_daemon(config, RunOptions { web: Some(web.clone()), ..Default::default() }).await;
    let observer = common::client(&daemon.endpoint).await;
    let (statuses, _s1) = common::collect::<StatusMessage>(&observer, "golf/bay1/status");
    let puts: common::Collected<(String, String)> = Default::default();
    let sink = puts.clone();
    let _s2 = observer
        .declare_subscriber("golf/bay1/**")
        .callback(move |s| {
            let payload = String::from_utf8_lossy(&s.payload().to_bytes()).into_owned();
            sink.lock().unwrap().push((s.key_expr().to_string(), payload));
        })
        .wait()
        .unwrap();

    // The page's files, with their content types and without caching.
    for (path, kind) in [("/", "text/html"), ("/style.css", "text/css"), ("/app.js", "text/javascript")] {
        let r = request(&web, &get(&web, path)).await;
        assert!(r.starts_with("HTTP/1.1 200 OK\r\n"), "{path}: {r:.80}");
        assert!(r.contains(&format!("Content-Type: {kind}")), "{path}: {r:.300}");
        assert!(r.contains("Cache-Control: no-store"));
    }
    // Refused, each with its status and counted by kind.
    assert!(request(&web, &get(&web, "/secret")).await.starts_with("HTTP/1.1 404"));
    assert!(request(&web, &format!("POST / HTTP/1.1\r\nHost: {web}\r\n\r\n")).await.starts_with("HTTP/1.1 405"));
    let huge = format!("GET / HTTP/1.1\r\nHost: {web}\r\nX-Filler: {}\r\n\r\n", "x".repeat(9000));
    assert!(request(&web, &huge).await.starts_with("HTTP/1.1 431"));

    // A page: a malformed control, a control for another rig and an oversized message are refused; the last
    // closes the page. A good control is the put a program would make.
    let mut p = page(&web).await;
    let hello: serde_json::Value = match p.next().await.unwrap().unwrap() {
        Message::Text(t) => serde_json::from_str(t.as_str()).unwrap(),
        m => panic!("{m:?}"),
    };
    assert_eq!(hello["rigs"], serde_json::json!(["bay1"]));
    p.send(Message::text("{\"op\":\"reboot\"}")).await.unwrap();
    p.send(Message::text(r#"{"op":"club","rig":"bay9","club":"iron7"}"#)).await.unwrap();
    p.send(Message::text(r#"{"op":"club","rig":"bay1","club":"iron7"}"#)).await.unwrap();
    assert!(
        common::wait_until(Duration::from_secs(30), || {
            puts.lock().unwrap().iter().any(|(k, v)| k == "golf/bay1/club" && v == "iron7")
        })
        .await
    );
    p.send(Message::text("x".repeat(MAX_CLIENT_MESSAGE_BYTES + 1))).await.unwrap();
    let closed = tokio::time::timeout(Duration::from_secs(5), async {
        loop {
            match p.next().await {
                None | Some(Err(_)) | Some(Ok(Message::Close(_))) => return,
                Some(Ok(_)) => {}
            }
        }
    })
    .await;
    assert!(closed.is_ok(), "an oversized message did not close the page");

    // At the cap: idle connections that never send a request fill it; an honest request is still answered.
    let mut idle = Vec::new();
    for _ in 0..WEB_LIMITS.max_connections {
        idle.push(TcpStream::connect(&web).await.unwrap());
    }
    tokio::time::sleep(Duration::from_millis(100)).await;
    assert!(request(&web, &get(&web, "/")).await.starts_with("HTTP/1.1 200 OK"));

    let want = ["not_found", "method", "oversized", "malformed", "unknown_rig", "evicted_at_cap"];
    let counted = common::wait_until(Duration::from_secs(30), || {
        let s = statuses.lock().unwrap();
        s.last()
            .and_then(|s| s.web.as_ref())
            .is_some_and(|w| want.iter().all(|k| w.rejected.get(*k).is_some_and(|n| *n >= 1)))
    })
    .await;
    let last = statuses.lock().unwrap().last().and_then(|s| s.web.clone());
    assert!(counted, "rejections not all counted: {last:?}");
    drop(idle);
    daemon.stop().await;
}
