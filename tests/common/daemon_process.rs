//! The real `impactd run` binary on loopback for the bay screen's and the inputs' hostile probes: one rig
//! `bay1` (plus what a test adds to its configuration), the bay screen on 127.0.0.1, its log (stderr, at info)
//! in a file the test counts lines in, its resident set read from `/proc/<pid>/status`; and a synthetic rig
//! (`impactd sim`) swinging `bay1` throughout, whose launches are the honest rig's.

#![allow(clippy::unwrap_used, dead_code)]

use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use impactd::daemon::bus::free_loopback_port;
use impactd::wire::{keys, LaunchPrediction, StatusMessage};

use super::common::Collected;

/// Each hostile case's bound on the daemon's resident set.
pub const RSS_LIMIT_KB: u64 = 150 * 1024;
/// The longest log line a peer can make the daemon write: its text cut at 512 bytes (`PEER_LINE_BYTES`), plus
/// the time, level and module.
pub const LONGEST_LINE_BYTES: usize = impactd::daemon::peer_log::PEER_LINE_BYTES + 128;

pub struct DaemonProcess {
    child: Child,
    pub zenoh: String,
    /// The bay screen's `HOST:PORT`.
    pub web: String,
    pub dir: tempfile::TempDir,
    log: PathBuf,
}

impl DaemonProcess {
    /// `impactd run` with rig `bay1` (and `extra` in its configuration) serving `--web` on loopback.
    pub fn start(extra: &str) -> DaemonProcess {
        DaemonProcess::start_with(extra, &[])
    }

    /// [`DaemonProcess::start`] with more arguments to `run`.
    pub fn start_with(extra: &str, args: &[&str]) -> DaemonProcess {
        let dir = tempfile::tempdir().unwrap();
        let config = dir.path().join("impactd.toml");
        std::fs::write(&config, format!("status_period_s = 0.2\n[[rig]]\nname = \"bay1\"\n{extra}")).unwrap();
        let zenoh = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
        let web = format!("127.0.0.1:{}", free_loopback_port().unwrap());
        let log = dir.path().join("impactd.log");
        let child = Command::new(env!("CARGO_BIN_EXE_impactd"))
            .args(["run", "-c"])
            .arg(&config)
            .args(["-l", &zenoh, "--no-multicast-scouting", "--web", &web])
            .args(args)
            .env("RUST_LOG", "info,zenoh=warn")
            .stdout(Stdio::null())
            .stderr(std::fs::File::create(&log).unwrap())
            .spawn()
            .unwrap();
        let d = DaemonProcess { child, zenoh, web, dir, log };
        let start = Instant::now();
        while std::net::TcpStream::connect(&d.web).is_err() {
            assert!(start.elapsed() < Duration::from_secs(20), "the daemon did not start: {}", d.log_text());
            std::thread::sleep(Duration::from_millis(50));
        }
        d
    }

    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    pub fn rss_kb(&self) -> u64 {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.pid())).unwrap_or_default();
        let line = status.lines().find(|l| l.starts_with("VmRSS:")).unwrap_or("VmRSS: 0 kB");
        line.split_whitespace().nth(1).unwrap().parse().unwrap()
    }

    pub fn log_text(&self) -> String {
        String::from_utf8_lossy(&std::fs::read(&self.log).unwrap_or_default()).into_owned()
    }

    /// The log's lines from byte `from` on, and the log's length now.
    pub fn log_since(&self, from: usize) -> (Vec<String>, usize) {
        let bytes = std::fs::read(&self.log).unwrap_or_default();
        let text = String::from_utf8_lossy(&bytes[from.min(bytes.len())..]).into_owned();
        (text.lines().map(String::from).collect(), bytes.len())
    }

    /// Stops the daemon with SIGINT (as Ctrl-C) and waits for it.
    pub fn stop(mut self) -> std::process::ExitStatus {
        self.interrupt()
    }

    /// Stops the daemon, as [`DaemonProcess::stop`], and returns its log's lines from byte `from` on too (the
    /// lines it says as it stops among them).
    pub fn stop_and_log(mut self, from: usize) -> (std::process::ExitStatus, Vec<String>) {
        let status = self.interrupt();
        (status, self.log_since(from).0)
    }

    fn interrupt(&mut self) -> std::process::ExitStatus {
        Command::new("kill").args(["-INT", &self.pid().to_string()]).status().unwrap();
        let start = Instant::now();
        loop {
            if let Some(s) = self.child.try_wait().unwrap() {
                return s;
            }
            if start.elapsed() > Duration::from_secs(20) {
                let _ = self.child.kill();
                panic!("the daemon did not stop on SIGINT");
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

impl Drop for DaemonProcess {
    fn drop(&mut self) {
        if matches!(self.child.try_wait(), Ok(None)) {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

/// Samples the daemon's resident set every 50 ms while `busy` runs; the peak (kB).
pub async fn peak_rss_while<T>(d: &DaemonProcess, busy: tokio::task::JoinHandle<T>) -> (T, u64) {
    let mut peak = d.rss_kb();
    while !busy.is_finished() {
        peak = peak.max(d.rss_kb());
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    let out = busy.await.unwrap();
    (out, peak.max(d.rss_kb()))
}

/// The honest rig: `impactd sim` swinging `bay1`, and the launches and statuses the daemon publishes.
pub struct Rig {
    sim: Child,
    pub session: zenoh::Session,
    pub launches: Collected<LaunchPrediction>,
    pub statuses: Collected<StatusMessage>,
    _subs: Vec<zenoh::pubsub::Subscriber<()>>,
}

impl Rig {
    pub async fn start(d: &DaemonProcess, shots: u64) -> Rig {
        let session = super::common::client(&d.zenoh).await;
        let (launches, s1) = super::common::collect::<LaunchPrediction>(&session, &keys::launch("bay1"));
        let (statuses, s2) = super::common::collect::<StatusMessage>(&session, &keys::status("bay1"));
        super::common::wait_until(Duration::from_secs(10), || !statuses.lock().unwrap().is_empty()).await;
        let sim = Command::new(env!("CARGO_BIN_EXE_impactd"))
            .args(["sim", "--rig", "bay1", "--shots", &shots.to_string(), "--interval", "0.2"])
            .args(["-e", &d.zenoh, "--no-multicast-scouting"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        Rig { sim, session, launches, statuses, _subs: vec![s1, s2] }
    }

    /// Waits for the sim to finish; every shot's latency (us), asserting each shot was predicted.
    pub async fn finish(mut self, shots: usize) -> Vec<f64> {
        let sim = tokio::task::spawn_blocking(move || {
            let s = self.sim.wait().unwrap();
            (s, self)
        });
        let (status, rig) = sim.await.unwrap();
        assert!(status.success(), "sim: {status}");
        let launches = rig.launches.clone();
        super::common::wait_until(Duration::from_secs(10), || launches.lock().unwrap().len() >= shots).await;
        let got: Vec<f64> = rig.launches.lock().unwrap().iter().map(|l| l.latency_us).collect();
        assert_eq!(got.len(), shots, "every honest shot is predicted while the hostile peer runs");
        rig.session.close().await.unwrap();
        got
    }

    pub fn last_status(&self) -> Option<StatusMessage> {
        self.statuses.lock().unwrap().last().cloned()
    }

    /// The bay screen's rejection count of `kind` in the rig's last status.
    pub fn web_rejected(&self, kind: &str) -> u64 {
        let web = self.last_status().and_then(|s| s.web);
        web.and_then(|w| w.rejected.get(kind).copied()).unwrap_or(0)
    }
}

/// One line for `scripts/docs-hostile.sh` (docs/hostile-peers.md): the honest rig's sample-to-launch latencies
/// while the case ran and the daemon's peak RSS; measured and documented, never asserted.
pub fn report_latency(case: &str, latencies_us: &[f64], peak_rss_kb: u64) {
    let mut sorted = latencies_us.to_vec();
    sorted.sort_by(f64::total_cmp);
    let q = |p: f64| sorted[((sorted.len() - 1) as f64 * p).round() as usize];
    let line = serde_json::json!({
        "case": case, "shots": sorted.len(), "p50_us": q(0.5), "p99_us": q(0.99), "max_us": q(1.0),
        "peak_rss_kb": peak_rss_kb,
    });
    eprintln!("\nHOSTILE_PEERS {line}");
}

/// A kind's log lines (those containing `what`, and its summaries) and the count of lines they say were
/// suppressed besides (`(N more KIND since the last)`, `N more KIND since the last (suppressed ...)`): shown +
/// suppressed is every event of the kind, nothing lost.
pub fn lines_and_suppressed(lines: &[String], what: &str, kind: &str) -> (usize, u64) {
    let more = format!(" more {kind} since the last");
    let of_kind: Vec<&String> = lines.iter().filter(|l| l.contains(what) || l.contains(&more)).collect();
    let suppressed = of_kind
        .iter()
        .filter_map(|l| {
            let head = &l[..l.find(&more)?];
            let start = head.rfind(|c: char| !c.is_ascii_digit()).map_or(0, |i| i + 1);
            head[start..].parse::<u64>().ok()
        })
        .sum();
    (of_kind.len(), suppressed)
}

/// Events of a kind the log tells of: its lines that are not summaries, plus what they all say was suppressed.
pub fn events_told(lines: &[String], what: &str, kind: &str) -> u64 {
    let shown = lines.iter().filter(|l| l.contains(what)).count() as u64;
    shown + lines_and_suppressed(lines, what, kind).1
}

/// Asserts no log line is longer than [`LONGEST_LINE_BYTES`].
pub fn assert_lines_bounded(lines: &[String]) {
    let longest = lines.iter().map(String::len).max().unwrap_or(0);
    let example = lines.iter().max_by_key(|l| l.len()).map(|l| &l[..l.len().min(300)]).unwrap_or("");
    assert!(longest <= LONGEST_LINE_BYTES, "a log line of {longest} bytes: {example}");
}
