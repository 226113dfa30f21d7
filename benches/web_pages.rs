//! The daemon's sample -> published prediction latency with no bay screen open and with twenty (issue 32: the
//! p99 with 20 pages stays within 10 % of the p99 with none), and the rig worker's CPU time per sample in each.
//!
//! One daemon serves `--web` on 127.0.0.1; a synthetic rig and a subscriber share one zenoh session, the daemon
//! another, over TCP on loopback (multicast scouting off). The shots are swung in short blocks, many of them,
//! ordered A B B A A B B A ... (A: no page, B: twenty pages), so a change in the machine's load falls on both
//! arms and a steady drift cancels. A page is a WebSocket client on `/ws` that reads every message the daemon
//! sends a browser (hello, snapshots, shots, summaries, status) and answers pings: the daemon's side of twenty
//! screens, without twenty browsers' rendering on the same cores.
//!
//! Per shot: the time from the subscriber seeing the frame that reveals the impact to it receiving the
//! prediction, and the daemon's own `latency_us` (callback -> published). Per block: the rig worker thread's CPU
//! time (`/proc/self/task/TID/schedstat`, nanoseconds on the CPU), which another program's load on the machine
//! does not change, divided by the samples the block swung.
//!
//! Each ratio (20 pages / none) comes with a 95 % interval from a block bootstrap: the blocks of each arm are
//! drawn again with replacement and the statistic recomputed 2000 times. The same comparison of the no-page
//! blocks against each other (alternate A blocks) shows how far the numbers move with nothing changed.
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
use serde_json::{json, Value};
use zenoh::Wait;

const PAGES: usize = 20;
const RESAMPLES: usize = 2000;
/// The rig worker thread's name (`impactd-<rig>`, see `daemon::live`).
const WORKER: &str = "impactd-rig1";

/// One block of shots.
#[derive(Debug, Default, Clone)]
struct Block {
    pages: usize,
    /// Per shot: revealing frame seen -> prediction received (us), and the daemon's own `latency_us`.
    e2e_us: Vec<f64>,
    daemon_us: Vec<f64>,
    worker_cpu_ns: u64,
    samples: u64,
}

impl Block {
    fn cpu_ns_per_sample(&self) -> f64 {
        self.worker_cpu_ns as f64 / self.samples.max(1) as f64
    }
}

fn quantile(v: &[f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v[((q * v.len() as f64).ceil() as usize).clamp(1, v.len()) - 1]
}

fn median(v: &[f64]) -> f64 {
    quantile(v, 0.5)
}

/// A statistic of a set of blocks (e.g. the p99 of all their shots together).
type Stat = fn(&[&Block]) -> f64;

fn e2e_p99(b: &[&Block]) -> f64 {
    quantile(&b.iter().flat_map(|b| b.e2e_us.iter().copied()).collect::<Vec<_>>(), 0.99)
}

fn e2e_p50(b: &[&Block]) -> f64 {
    median(&b.iter().flat_map(|b| b.e2e_us.iter().copied()).collect::<Vec<_>>())
}

fn daemon_p50(b: &[&Block]) -> f64 {
    median(&b.iter().flat_map(|b| b.daemon_us.iter().copied()).collect::<Vec<_>>())
}

fn daemon_p99(b: &[&Block]) -> f64 {
    quantile(&b.iter().flat_map(|b| b.daemon_us.iter().copied()).collect::<Vec<_>>(), 0.99)
}

fn block_p99_median(b: &[&Block]) -> f64 {
    median(&b.iter().map(|b| quantile(&b.e2e_us, 0.99)).collect::<Vec<_>>())
}

fn cpu_per_sample(b: &[&Block]) -> f64 {
    let (ns, n) = b.iter().fold((0u64, 0u64), |(ns, n), b| (ns + b.worker_cpu_ns, n + b.samples));
    ns as f64 / n.max(1) as f64
}

/// `stat(b) / stat(a)` and its 95 % block-bootstrap interval: `{ratio, ci95: [lo, hi], a, b}`.
fn ratio(a: &[&Block], b: &[&Block], stat: Stat, rng: &mut fastrand::Rng) -> Value {
    let draw = |arm: &[&Block], rng: &mut fastrand::Rng| -> f64 {
        let pick: Vec<&Block> = (0..arm.len()).map(|_| arm[rng.usize(..arm.len())]).collect();
        stat(&pick)
    };
    let ratios: Vec<f64> = (0..RESAMPLES).map(|_| draw(b, rng) / draw(a, rng)).collect();
    let (sa, sb) = (stat(a), stat(b));
    json!({ "ratio": sb / sa, "ci95": [quantile(&ratios, 0.025), quantile(&ratios, 0.975)], "a": sa, "b": sb })
}

/// The CPU time a thread of this process named `name` has spent (ns), from `/proc/self/task/*/schedstat`.
fn thread_cpu_ns(name: &str) -> Option<u64> {
    for task in std::fs::read_dir("/proc/self/task").ok()?.flatten() {
        let comm = std::fs::read_to_string(task.path().join("comm")).unwrap_or_default();
        if comm.trim_end() == name {
            let s = std::fs::read_to_string(task.path().join("schedstat")).ok()?;
            return s.split_whitespace().next()?.parse().ok();
        }
    }
    None
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

/// A B B A A B B A ...: no page in blocks 0, 3, 4, 7, 8, ... (`only`: every block with that many pages).
fn pages_in(block: usize, only: Option<usize>) -> usize {
    if let Some(n) = only {
        n
    } else if matches!(block % 4, 1 | 2) {
        PAGES
    } else {
        0
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let json_out = args.iter().any(|a| a == "--json");
    // `--pages N`: every block with N pages (one arm per run, as under callgrind: scripts/web-pages-callgrind.sh).
    let only: Option<usize> =
        args.iter().position(|a| a == "--pages").and_then(|i| args.get(i + 1)).map(|n| n.parse().unwrap());
    let numbers: Vec<usize> = args
        .iter()
        .enumerate()
        .filter(|(i, _)| *i == 0 || args[i - 1] != "--pages")
        .filter_map(|(_, a)| a.parse().ok())
        .collect();
    let per_block = numbers.first().copied().unwrap_or(25) as u64;
    let blocks = numbers.get(1).copied().unwrap_or(16);
    let blocks = if only.is_some() { blocks.max(1) } else { blocks.max(8) / 4 * 4 };
    let rt = tokio::runtime::Builder::new_multi_thread().enable_all().build().unwrap();
    let (results, bytes) = rt.block_on(swing(per_block, blocks, only));
    let a: Vec<&Block> = results.iter().filter(|b| b.pages == 0).collect();
    let b: Vec<&Block> = results.iter().filter(|b| b.pages == PAGES).collect();
    // Alternate no-page blocks against each other: nothing differs but the time they ran.
    let (a1, a2): (Vec<&Block>, Vec<&Block>) = {
        let (x, y): (Vec<_>, Vec<_>) = a.iter().enumerate().partition(|(i, _)| i % 2 == 0);
        (x.into_iter().map(|(_, b)| *b).collect(), y.into_iter().map(|(_, b)| *b).collect())
    };
    let mut rng = fastrand::Rng::with_seed(32);
    let row = |arm: &[&Block], pages: usize| {
        let e2e: Vec<f64> = arm.iter().flat_map(|b| b.e2e_us.iter().copied()).collect();
        let inside: Vec<f64> = arm.iter().flat_map(|b| b.daemon_us.iter().copied()).collect();
        json!({
            "pages": pages, "blocks": arm.len(), "shots": e2e.len(),
            "p50_us": median(&e2e), "p99_us": quantile(&e2e, 0.99), "max_us": quantile(&e2e, 1.0),
            "daemon_p50_us": median(&inside), "daemon_p99_us": quantile(&inside, 0.99),
            "block_p99_median_us": block_p99_median(arm),
            "worker_cpu_ns_per_sample": cpu_per_sample(arm),
            "worker_cpu_ns_per_sample_blocks": arm.iter().map(|b| b.cpu_ns_per_sample()).collect::<Vec<_>>(),
            "samples": arm.iter().map(|b| b.samples).sum::<u64>(),
        })
    };
    let rows: Vec<Value> =
        [(&a, 0), (&b, PAGES)].iter().filter(|(arm, _)| !arm.is_empty()).map(|(arm, n)| row(arm, *n)).collect();
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let mut out = json!({
        "date": humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string(),
        "cpus": std::thread::available_parallelism().map(|n| n.get()).unwrap_or(0),
        "loadavg": load.split_whitespace().take(3).collect::<Vec<_>>(),
        "shots_per_block": per_block, "blocks": blocks, "page_bytes": bytes, "resamples": RESAMPLES,
        "rows": rows,
    });
    let both = !a.is_empty() && !b.is_empty() && !a2.is_empty();
    let comparisons: [(&str, &[&Block], &[&Block], Stat); 9] = [
        ("e2e_p99", &a, &b, e2e_p99),
        ("e2e_p50", &a, &b, e2e_p50),
        ("daemon_p99", &a, &b, daemon_p99),
        ("daemon_p50", &a, &b, daemon_p50),
        ("block_p99_median", &a, &b, block_p99_median),
        ("worker_cpu", &a, &b, cpu_per_sample),
        ("noise_e2e_p99", &a1, &a2, e2e_p99),
        ("noise_e2e_p50", &a1, &a2, e2e_p50),
        ("noise_worker_cpu", &a1, &a2, cpu_per_sample),
    ];
    for (key, x, y, stat) in comparisons.into_iter().filter(|_| both) {
        out[key] = ratio(x, y, stat, &mut rng);
    }
    if json_out {
        println!("{out}");
        return;
    }
    for r in out["rows"].as_array().unwrap() {
        println!(
            "{:>2} pages, {} shots: revealing frame -> prediction p50 {:.0} us, p99 {:.0} us; in the daemon p99 {:.0} us; worker CPU {:.0} ns/sample",
            r["pages"], r["shots"], r["p50_us"].as_f64().unwrap(), r["p99_us"].as_f64().unwrap(),
            r["daemon_p99_us"].as_f64().unwrap(), r["worker_cpu_ns_per_sample"].as_f64().unwrap()
        );
    }
    for key in [
        "e2e_p99",
        "e2e_p50",
        "daemon_p99",
        "daemon_p50",
        "block_p99_median",
        "worker_cpu",
        "noise_e2e_p99",
        "noise_e2e_p50",
        "noise_worker_cpu",
    ] {
        let r = &out[key];
        if r.is_null() {
            continue;
        }
        println!(
            "{key}: {:.3} (95 % interval {:.3} .. {:.3})",
            r["ratio"].as_f64().unwrap(),
            r["ci95"][0].as_f64().unwrap(),
            r["ci95"][1].as_f64().unwrap()
        );
    }
}

/// Runs the daemon and swings `blocks` blocks of `per_block` shots; returns the blocks and the bytes the pages read.
async fn swing(per_block: u64, blocks: usize, only: Option<usize>) -> (Vec<Block>, u64) {
    let (config, setups) = DaemonConfig::parse("[[rig]]\nname = \"rig1\"\n").unwrap();
    let endpoint = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
    let web = format!("127.0.0.1:{}", free_loopback_port().unwrap());
    let daemon_session = ZenohArgs::loopback(vec![endpoint.clone()], vec![]).open().await.unwrap();
    let rig = ZenohArgs::loopback(vec![], vec![endpoint]).open().await.unwrap();
    let frames: Arc<Mutex<HashMap<u64, Instant>>> = Default::default();
    let results: Arc<Mutex<Vec<Block>>> = Default::default();
    let f = frames.clone();
    let _frames_sub = rig
        .declare_subscriber("mocap/rig1/clubhead")
        .callback(move |s| {
            let now = Instant::now();
            if let Ok(v) = serde_json::from_slice::<Value>(&s.payload().to_bytes()) {
                if let Some(frame) = v["frame"].as_u64() {
                    f.lock().unwrap().insert(frame, now);
                }
            }
        })
        .wait()
        .unwrap();
    let (f, r) = (frames.clone(), results.clone());
    let _launch_sub = rig
        .declare_subscriber("golf/rig1/launch")
        .callback(move |s| {
            let now = Instant::now();
            if let Ok(l) = serde_json::from_slice::<LaunchPrediction>(&s.payload().to_bytes()) {
                if let Some(t) = f.lock().unwrap().get(&l.frame) {
                    if let Some(block) = r.lock().unwrap().last_mut() {
                        block.e2e_us.push(now.duration_since(*t).as_secs_f64() * 1e6);
                        block.daemon_us.push(l.latency_us);
                    }
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
        let pages = pages_in(block, only);
        let (stop_pages, stop_rx) = tokio::sync::watch::channel(false);
        let tasks: Vec<_> =
            (0..pages).map(|_| tokio::spawn(page(web.clone(), bytes.clone(), stop_rx.clone()))).collect();
        tokio::time::sleep(Duration::from_millis(300)).await;
        // Each block's rig numbers its frames from the start again.
        frames.lock().unwrap().clear();
        results.lock().unwrap().push(Block { pages, ..Default::default() });
        let cpu_before = thread_cpu_ns(WORKER).unwrap();
        let options = SimOptions {
            shots: per_block,
            interval_s: 0.2,
            seed: block as u64 + 1,
            wait_for_subscriber_s: 0.0,
            ..SimOptions::default()
        };
        let sim = run_sim(&rig, options, std::future::pending()).await.unwrap();
        tokio::time::sleep(Duration::from_millis(300)).await;
        let cpu = thread_cpu_ns(WORKER).unwrap() - cpu_before;
        if let Some(b) = results.lock().unwrap().last_mut() {
            b.worker_cpu_ns = cpu;
            b.samples = sim.samples;
        }
        let _ = stop_pages.send(true);
        for t in tasks {
            let _ = t.await;
        }
    }
    let _ = stop.send(());
    daemon.await.unwrap();
    rig.close().await.unwrap();
    let results = results.lock().unwrap().clone();
    (results, bytes.load(Ordering::Relaxed))
}
