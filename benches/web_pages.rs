//! The daemon's sample -> published prediction latency with no bay screen open and with twenty (issue 32: the
//! p99 with 20 pages stays within 10 % of the p99 with none). One daemon serves `--web` on 127.0.0.1; a
//! synthetic rig and a subscriber share one zenoh session, the daemon another, over TCP on loopback (multicast
//! scouting off). The shots are swung in blocks that alternate between no page and twenty pages, so a change
//! in the machine's load falls on both. A page is a WebSocket client on `/ws` that reads every message the
//! daemon sends a browser (hello, snapshots, shots, summaries, status) and answers pings: the daemon's side of
//! twenty screens, without twenty browsers' rendering on the same cores.
//!
//! Per shot: the time from the subscriber seeing the frame that reveals the impact to it receiving the
//! prediction, and the daemon's own `latency_us` (callback -> published).
//! `cargo bench --bench web_pages [-- SHOTS_PER_BLOCK BLOCKS] [-- --json]`

#![allow(clippy::unwrap_used)]

use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use futures_util::StreamExt;
use impactd::daemon::bus::{free_loopback_port, ZenohArgs};
use impactd::daemon::sim::{run_sim, SimOptions};
use impactd::daemon::{DaemonConfig, RunOptions};
use impactd::wire::LaunchPrediction;
use zenoh::Wait;

const PAGES: usize = 20;

/// Per shot: pages open, block, end to end (us), in the daemon (us).
type Results = Arc<Mutex<Vec<(usize, u64, f64, f64)>>>;

fn quantile(v: &[f64], q: f64) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v[((q * v.len() as f64).ceil() as usize).clamp(1, v.len()) - 1]
}

/// A page: reads everything until told to stop; counts the bytes.
async fn page(address: String, bytes: Arc<AtomicU64>, mut stop: tokio::sync::watch::Receiver<bool>) {
    let stream = tokio::net::TcpStream::connect(&address).await.unwrap();
    let (mut ws, _) = tokio_tungstenite::client_async(format!("ws://{address}/ws"), stream).await.unwrap();
    loop {
        tokio::select! {
            m = ws.next() => match m {
                Some(Ok(m)) => { bytes.fetch_add(m.len() as u64, Ordering::Relaxed); }
                _ => break,
            },
            _ = stop.changed() => break,
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let json = args.iter().any(|a| a == "--json");
    let numbers: Vec<u64> = args.iter().filter_map(|a| a.parse().ok()).collect();
    let per_block = numbers.first().copied().unwrap_or(40);
    let blocks = numbers.get(1).copied().unwrap_or(6).max(2);
    let rt = tokio::runtime::Builder::new_multi_thread().enable_all().build().unwrap();
    rt.block_on(async {
        let (config, setups) = DaemonConfig::parse("[[rig]]\nname = \"rig1\"\n").unwrap();
        let endpoint = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
        let web = format!("127.0.0.1:{}", free_loopback_port().unwrap());
        let daemon_session = ZenohArgs::loopback(vec![endpoint.clone()], vec![]).open().await.unwrap();
        let rig = ZenohArgs::loopback(vec![], vec![endpoint]).open().await.unwrap();
        let frames: Arc<Mutex<HashMap<u64, Instant>>> = Default::default();
        // (pages open, block, end to end us, in the daemon us)
        let results: Results = Default::default();
        let block_now = Arc::new(AtomicU64::new(0));
        let open_pages = Arc::new(AtomicU64::new(0));
        let f = frames.clone();
        let _frames_sub = rig
            .declare_subscriber("mocap/rig1/clubhead")
            .callback(move |s| {
                let now = Instant::now();
                if let Ok(v) = serde_json::from_slice::<serde_json::Value>(&s.payload().to_bytes()) {
                    if let Some(frame) = v["frame"].as_u64() {
                        f.lock().unwrap().insert(frame, now);
                    }
                }
            })
            .wait()
            .unwrap();
        let (f, r, pages_now, block_cb) = (frames.clone(), results.clone(), open_pages.clone(), block_now.clone());
        let _launch_sub = rig
            .declare_subscriber("golf/rig1/launch")
            .callback(move |s| {
                let now = Instant::now();
                if let Ok(l) = serde_json::from_slice::<LaunchPrediction>(&s.payload().to_bytes()) {
                    if let Some(t) = f.lock().unwrap().get(&l.frame) {
                        let pages = pages_now.load(Ordering::Relaxed) as usize;
                        let block = block_cb.load(Ordering::Relaxed);
                        r.lock().unwrap().push((pages, block, now.duration_since(*t).as_secs_f64() * 1e6, l.latency_us));
                    }
                }
            })
            .wait()
            .unwrap();
        let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
        let options = RunOptions { web: Some(web.clone()), ..Default::default() };
        let daemon = tokio::spawn(async move {
            impactd::daemon::run(config, setups, &daemon_session, options, async {
                let _ = stopped.await;
            })
            .await
            .unwrap();
            daemon_session.close().await.unwrap();
        });
        tokio::time::sleep(Duration::from_millis(300)).await;
        let bytes = Arc::new(AtomicU64::new(0));
        for block in 0..blocks {
            let pages = if block % 2 == 1 { PAGES } else { 0 };
            let (stop_pages, stop_rx) = tokio::sync::watch::channel(false);
            let tasks: Vec<_> =
                (0..pages).map(|_| tokio::spawn(page(web.clone(), bytes.clone(), stop_rx.clone()))).collect();
            tokio::time::sleep(Duration::from_millis(300)).await;
            // Each block's rig numbers its frames from the start again.
            frames.lock().unwrap().clear();
            open_pages.store(pages as u64, Ordering::Relaxed);
            block_now.store(block, Ordering::Relaxed);
            let options = SimOptions { shots: per_block, interval_s: 0.25, seed: block + 1, wait_for_subscriber_s: 0.0, ..SimOptions::default() };
            run_sim(&rig, options, std::future::pending()).await.unwrap();
            tokio::time::sleep(Duration::from_millis(300)).await;
            let _ = stop_pages.send(true);
            for t in tasks {
                let _ = t.await;
            }
        }
        let _ = stop.send(());
        daemon.await.unwrap();
        let results = results.lock().unwrap().clone();
        let mut rows = Vec::new();
        for pages in [0, PAGES] {
            let e2e: Vec<f64> = results.iter().filter(|r| r.0 == pages).map(|r| r.2).collect();
            let inside: Vec<f64> = results.iter().filter(|r| r.0 == pages).map(|r| r.3).collect();
            if e2e.is_empty() {
                continue;
            }
            let row = serde_json::json!({
                "pages": pages, "shots": e2e.len(),
                "p50_us": quantile(&e2e, 0.5), "p99_us": quantile(&e2e, 0.99), "max_us": quantile(&e2e, 1.0),
                "daemon_p50_us": quantile(&inside, 0.5), "daemon_p99_us": quantile(&inside, 0.99),
            });
            if !json {
                println!(
                    "{pages:>2} pages, {} shots: revealing frame -> prediction received p50 {:.0} us, p99 {:.0} us, max {:.0} us; in the daemon p50 {:.0} us, p99 {:.0} us",
                    e2e.len(), row["p50_us"].as_f64().unwrap(), row["p99_us"].as_f64().unwrap(), row["max_us"].as_f64().unwrap(),
                    row["daemon_p50_us"].as_f64().unwrap(), row["daemon_p99_us"].as_f64().unwrap()
                );
            }
            rows.push(row);
        }
        // The same comparison with no page on either side (the first half of the no-page blocks against the
        // second): how far the p99 moves on this machine with nothing changed.
        let zero = |later: bool| -> Vec<f64> {
            results.iter().filter(|r| r.0 == 0 && (r.1 >= blocks / 2) == later).map(|r| r.2).collect()
        };
        let (early, late) = (zero(false), zero(true));
        let noise = (!early.is_empty() && !late.is_empty()).then(|| quantile(&late, 0.99) / quantile(&early, 0.99));
        let ratio = (rows.len() == 2).then(|| rows[1]["p99_us"].as_f64().unwrap() / rows[0]["p99_us"].as_f64().unwrap());
        let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
        let out = serde_json::json!({
            "date": humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string(),
            "cpus": std::thread::available_parallelism().map(|n| n.get()).unwrap_or(0),
            "loadavg": load.split_whitespace().take(3).collect::<Vec<_>>(),
            "shots_per_block": per_block, "blocks": blocks, "page_bytes": bytes.load(Ordering::Relaxed),
            "rows": rows, "p99_ratio_20_to_0": ratio, "p99_ratio_0_to_0": noise,
        });
        if json {
            println!("{out}");
        } else if let Some(r) = ratio {
            println!("p99 with {PAGES} pages / p99 with none: {r:.3} ({} bytes sent to pages)", bytes.load(Ordering::Relaxed));
        }
        rig.close().await.unwrap();
    });
}
