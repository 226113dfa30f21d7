#![allow(clippy::unwrap_used)]
#![cfg(all(feature = "daemon", target_os = "linux"))]
//! Log floods a peer could drive (issue 48, defect 3), against the real `impactd run` binary on loopback with a
//! synthetic rig swinging throughout: 10,000 controls from a bay screen page (and 200 page connections), a
//! flood of club puts the loader cannot keep up with, and a QTM server alternating its body list (20,000 bodies
//! a packet) then naming a body with 1 MiB. Each kind of line is logged at most about once a second, its
//! suppressed lines counted in the next line of the kind or a summary once the flood stops (so the log tells
//! of every event: shown + suppressed); no line is longer than 512 bytes of text plus its prefix; a peer's
//! newline cannot start a line. The daemon's RSS stays under 150 MB and every honest shot is predicted; the
//! honest rig's latency is printed for docs/hostile-peers.md, never asserted.

use crate::common;
use crate::daemon_process;
use crate::qtm_server;

use std::time::{Duration, Instant};

use daemon_process::{assert_lines_bounded, events_told, lines_and_suppressed, peak_rss_while, report_latency};
use daemon_process::{DaemonProcess, Rig, RSS_LIMIT_KB};
use futures_util::{SinkExt, StreamExt};
use impactd::mocap::qtm::encode as qtm_encode;
use qtm_server::QtmServer;
use tokio_tungstenite::tungstenite::Message;

/// Whether `lines` of a kind came at most about one a second over `seconds` (its summaries included).
fn assert_rate(kind: &str, lines: usize, seconds: f64) {
    assert!((lines as f64) <= seconds + 4.0, "{kind}: {lines} lines in {seconds:.1} s");
}

async fn page(web: &str) -> tokio_tungstenite::WebSocketStream<tokio::net::TcpStream> {
    let stream = tokio::net::TcpStream::connect(web).await.unwrap();
    tokio_tungstenite::client_async(format!("ws://{web}/ws"), stream).await.unwrap().0
}

#[tokio::test(flavor = "multi_thread")]
async fn ten_thousand_page_controls_and_200_page_connections_log_a_line_a_second_per_kind() {
    let d = DaemonProcess::start("");
    let rig = Rig::start(&d, 20).await;
    let web = d.web.clone();
    let log_from = d.log_text().len();
    let t0 = Instant::now();
    let flood = tokio::spawn(async move {
        let started = Instant::now();
        // Reads what the daemon sends meanwhile, as a page does.
        let (mut tx, mut rx) = page(&web).await.split();
        let reader = tokio::spawn(async move { while let Some(Ok(_)) = rx.next().await {} });
        for i in 0..10_000u64 {
            let control = match i % 5 {
                0 | 1 => format!(r#"{{"op":"exclude","rig":"bay1","shot":{},"excluded":{}}}"#, i % 40, i % 2 == 0),
                2 | 3 => format!(r#"{{"op":"labels","rig":"bay1","player":"p{}","tags":["t"]}}"#, i % 7),
                _ => r#"{"op":"units","rig":"bay1","units":"metric"}"#.to_string(),
            };
            tx.send(Message::text(control)).await.unwrap();
        }
        for _ in 0..200 {
            drop(page(&web).await);
        }
        drop(page(&web).await);
        // The first page stays until the daemon has taken every control it sent.
        (started.elapsed().as_secs_f64(), tx, reader)
    });
    let ((seconds, mut tx, reader), peak) = peak_rss_while(&d, flood).await;
    // The worker takes the 8,000 puts in turn; its summaries follow within a second of the last.
    let told = |what: &str, kind: &str| events_told(&d.log_since(log_from).0, what, kind);
    let all = common::wait_until(Duration::from_secs(20), || {
        told("the session", "exclusion") == 4000 && told("shots labelled", "labels") == 4000
    })
    .await;
    let elapsed = t0.elapsed().as_secs_f64();
    let _ = tx.close().await;
    reader.abort();
    // The first page's leaving, and the summaries of the suppressed page lines, follow within about a second
    // (longer on a loaded machine).
    common::wait_until(Duration::from_secs(20), || {
        told("page connected: ", "page_connected") == 202 && told("page left: ", "page_left") == 202
    })
    .await;
    let (lines, _) = d.log_since(log_from);
    eprintln!("10,000 controls and 200 pages in {seconds:.1} s: {} log lines", lines.len());
    assert!(
        all,
        "the log tells of {} exclusions and {} labels of 4000 each: {lines:#?}",
        events_told(&lines, "the session", "exclusion"),
        events_told(&lines, "shots labelled", "labels")
    );
    for (kind, what, n) in [
        ("exclusion", "the session", 4000),
        ("labels", "shots labelled", 4000),
        ("page_connected", "page connected: ", 202),
        ("page_left", "page left: ", 202),
    ] {
        let (kind_lines, _) = lines_and_suppressed(&lines, what, kind);
        assert_rate(kind, kind_lines, elapsed);
        assert_eq!(events_told(&lines, what, kind), n, "{kind}: the log does not tell of them all");
    }
    assert!(lines.len() < 200, "{} lines for 10,000 controls and 200 pages", lines.len());
    assert_lines_bounded(&lines);
    let latencies = rig.finish(20).await;
    report_latency("page_controls_flood", &latencies, peak);
    assert!(peak < RSS_LIMIT_KB, "peak RSS {peak} kB");
    assert!(d.stop().success());
}

#[tokio::test(flavor = "multi_thread")]
async fn a_flood_of_club_puts_logs_a_line_a_second_per_kind() {
    let d = DaemonProcess::start("");
    let rig = Rig::start(&d, 20).await;
    let putter = common::client(&d.zenoh).await;
    let log_from = d.log_text().len();
    let flood = tokio::spawn(async move {
        let started = Instant::now();
        for i in 0..3000 {
            let club = if i % 2 == 0 { "iron7" } else { "driver" };
            putter.put("golf/bay1/club", club).await.unwrap();
        }
        let seconds = started.elapsed().as_secs_f64();
        putter.close().await.unwrap();
        seconds
    });
    let (seconds, peak) = peak_rss_while(&d, flood).await;
    tokio::time::sleep(Duration::from_millis(2000)).await;
    let latencies = rig.finish(20).await;
    // The last lines owed are said when the loader ends.
    let (stopped, lines) = d.stop_and_log(log_from);
    assert!(stopped.success());
    let (waiting_lines, _) = lines_and_suppressed(&lines, "already waiting", "club_puts_waiting");
    let refused = events_told(&lines, "already waiting", "club_puts_waiting");
    let switched = events_told(&lines, "from Put", "club_change");
    eprintln!("3,000 club puts in {seconds:.1} s: {refused} refused, {switched} switches, {} log lines", lines.len());
    assert!(refused > 0, "no put was refused: the flood did not outrun the loader");
    assert!(refused + switched <= 3000, "{refused} + {switched}");
    assert_rate("club_puts_waiting", waiting_lines, seconds + 3.0);
    let (change_lines, _) = lines_and_suppressed(&lines, "from Put", "club_change");
    assert_rate("club_change", change_lines, seconds + 3.0);
    assert_lines_bounded(&lines);
    report_latency("club_put_flood", &latencies, peak);
    assert!(peak < RSS_LIMIT_KB, "peak RSS {peak} kB");
}

/// A 6D parameters document naming `names` (what QTM's `GetParameters 6D` answers, without the rest).
fn bodies_xml(names: &[String]) -> Vec<u8> {
    let mut x = String::from("<QTM_Parameters_Ver_1.25><The_6D>");
    x += &format!("<Bodies>{}</Bodies>", names.len());
    for n in names {
        x += &format!("<Body><Name>{n}</Name></Body>");
    }
    x += "</The_6D></QTM_Parameters_Ver_1.25>";
    qtm_encode::xml(&x)
}

#[tokio::test(flavor = "multi_thread")]
async fn a_qtm_server_alternating_its_body_list_logs_a_line_a_second_and_cuts_names() {
    let server = QtmServer::start(&["club"]);
    let d =
        DaemonProcess::start(&format!("[rig.input]\nqtm = \"127.0.0.1\"\nbody = \"club\"\nport = {}\n", server.port));
    let rig = Rig::start(&d, 20).await;
    assert!(common::wait_for(|| server.streaming() == 1), "the daemon did not stream from QTM");
    let log_from = d.log_text().len();
    let flood = tokio::task::spawn_blocking(move || {
        let others: Vec<String> = (0..20_000).map(|i| format!("body{i:05}")).collect();
        let with_club: Vec<String> = std::iter::once("club".to_string()).chain(others.iter().cloned()).collect();
        let (without, with) = (bodies_xml(&others), bodies_xml(&with_club));
        let started = Instant::now();
        let mut missing = 0u64;
        while started.elapsed() < Duration::from_secs(3) {
            server.send_raw(&with);
            server.send_raw(&without);
            missing += 1;
        }
        // A body named with a megabyte (and a newline that would start a forged line).
        let huge = format!("club\nFORGED {}", "x".repeat(1_000_000));
        server.send_raw(&bodies_xml(&[huge]));
        (server, missing + 1, started.elapsed().as_secs_f64())
    });
    let ((server, missing, seconds), peak) = peak_rss_while(&d, flood).await;
    let what = "is not among QTM's bodies";
    let told = |lines: &[String]| events_told(lines, what, "body_not_in_model");
    let all = common::wait_until(Duration::from_secs(20), || told(&d.log_since(log_from).0) == missing).await;
    let (lines, _) = d.log_since(log_from);
    let bytes: usize = lines.iter().map(|l| l.len() + 1).sum();
    eprintln!("{missing} body lists without the body in {seconds:.1} s: {} log lines, {bytes} bytes", lines.len());
    assert!(all, "the log tells of {} of {missing} lists without the body", told(&lines));
    let (kind_lines, _) = lines_and_suppressed(&lines, what, "body_not_in_model");
    assert_rate("body_not_in_model", kind_lines, seconds + 3.0);
    assert!(bytes < 64 * 1024, "{bytes} bytes of log");
    assert_lines_bounded(&lines);
    assert!(lines.iter().all(|l| !l.starts_with("FORGED")), "a body name started a line of its own");
    assert!(lines.iter().any(|l| l.contains("more (20000 in all)")), "the list is not summarised with its count");
    drop(server);
    let latencies = rig.finish(20).await;
    report_latency("qtm_body_list_flood", &latencies, peak);
    assert!(peak < RSS_LIMIT_KB, "peak RSS {peak} kB");
    assert!(d.stop().success());
}
