//! The real `impactd run` binary on loopback for probes: its configuration in a directory of its own, its log
//! kept in a file to read back, its resident set from /proc, signals through `kill`; a synthetic rig (`impactd
//! sim`) swinging at it; and the line `scripts/docs-hostile.sh` reads for docs/hostile-peers.md.

#![allow(clippy::unwrap_used)]
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

use impactd::daemon::bus::free_loopback_port;
use impactd::wire::{keys, LaunchPrediction, StatusMessage};

pub const RSS_LIMIT_KB: u64 = 150 * 1024;

/// One line for `scripts/docs-hostile.sh`: the honest rig's sample-to-launch latencies (the daemon's own
/// `latency_us`) and the daemon's peak RSS while a case ran. Measured and documented, never asserted.
pub fn report_latency(case: &str, latencies_us: &[f64], peak_rss_kb: u64) {
    let mut sorted = latencies_us.to_vec();
    sorted.sort_by(f64::total_cmp);
    if sorted.is_empty() {
        return;
    }
    let q = |p: f64| sorted[((sorted.len() - 1) as f64 * p).round() as usize];
    let line = serde_json::json!({
        "case": case, "shots": sorted.len(), "p50_us": q(0.5), "p99_us": q(0.99), "max_us": q(1.0),
        "peak_rss_kb": peak_rss_kb,
    });
    eprintln!("\nHOSTILE_PEERS {line}");
}

pub struct DaemonProcess {
    pub child: Child,
    /// The zenoh endpoint it listens on.
    pub zenoh: String,
    pub dir: PathBuf,
    log: PathBuf,
}

impl DaemonProcess {
    /// `impactd run -c DIR/impactd.toml` listening on a free loopback port, connecting to `connect` too, with
    /// `extra` arguments; its stdout a pipe nobody reads (as under a supervisor), its log in `DIR/<name>.log`.
    pub fn start(dir: &Path, name: &str, config: &str, connect: &[&str], extra: &[&str]) -> DaemonProcess {
        std::fs::create_dir_all(dir).unwrap();
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, config).unwrap();
        let zenoh = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
        let log = dir.join(format!("{name}.log"));
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_impactd"));
        cmd.args(["run", "-c"]).arg(&path).args(["-l", &zenoh, "--no-multicast-scouting"]);
        for c in connect {
            cmd.args(["-e", c]);
        }
        let child = cmd
            .args(extra)
            .env("RUST_LOG", "info,zenoh=warn")
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(std::fs::File::create(&log).unwrap())
            .spawn()
            .unwrap();
        DaemonProcess { child, zenoh, dir: dir.to_path_buf(), log }
    }

    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    pub fn rss_kb(&self) -> u64 {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.pid())).unwrap_or_default();
        let line = status.lines().find(|l| l.starts_with("VmRSS:"));
        line.and_then(|l| l.split_whitespace().nth(1)?.parse().ok()).unwrap_or(0)
    }

    /// Everything it has logged so far.
    pub fn log(&self) -> String {
        std::fs::read_to_string(&self.log).unwrap_or_default()
    }

    pub fn signal(&self, signal: &str) {
        Command::new("kill").args([&format!("-{signal}"), &self.pid().to_string()]).status().unwrap();
    }

    /// Its exit status, waiting at most `guard` (a hang guard, not a timing assertion): `None` when it is still
    /// running then.
    pub fn wait(&mut self, guard: Duration) -> Option<ExitStatus> {
        let start = Instant::now();
        loop {
            if let Some(s) = self.child.try_wait().unwrap() {
                return Some(s);
            }
            if start.elapsed() > guard {
                return None;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// SIGTERM, then its exit status; killed, and the test failed, when it hangs.
    pub fn stop(mut self) -> ExitStatus {
        self.signal("TERM");
        let asked = Instant::now();
        match self.wait(Duration::from_secs(30)) {
            Some(s) => {
                // Measured, not asserted.
                eprintln!("the daemon stopped {:?} after SIGTERM", asked.elapsed());
                s
            }
            None => {
                let _ = self.child.kill();
                panic!("the daemon did not stop on SIGTERM; its log:\n{}", self.log());
            }
        }
    }
}

impl Drop for DaemonProcess {
    fn drop(&mut self) {
        if self.child.try_wait().ok().flatten().is_none() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

/// A synthetic rig publishing to a daemon, and what it hears back.
pub struct SimRig {
    sim: Option<Child>,
    pub session: zenoh::Session,
    pub launches: super::common::Collected<LaunchPrediction>,
    pub statuses: super::common::Collected<StatusMessage>,
    _subs: Vec<zenoh::pubsub::Subscriber<()>>,
}

impl SimRig {
    /// A listener on `rig`'s launches and status through `endpoints`, before any shot.
    pub async fn listen(endpoints: &[&str], rig: &str) -> SimRig {
        let args = impactd::daemon::bus::ZenohArgs::loopback(vec![], endpoints.iter().map(|e| e.to_string()).collect());
        let session = args.open().await.unwrap();
        let (launches, s1) = super::common::collect::<LaunchPrediction>(&session, &keys::launch(rig));
        let (statuses, s2) = super::common::collect::<StatusMessage>(&session, &keys::status(rig));
        SimRig { sim: None, session, launches, statuses, _subs: vec![s1, s2] }
    }

    /// Waits (up to 20 s: a hang guard) for the rig's status, so the daemon serves it.
    pub async fn wait_served(&self) {
        let statuses = self.statuses.clone();
        let served = super::common::wait_until(Duration::from_secs(20), || !statuses.lock().unwrap().is_empty()).await;
        assert!(served, "the daemon never published the rig's status");
    }

    /// `impactd sim` swinging `shots` shots at the rig through `endpoint`.
    pub fn swing(&mut self, endpoint: &str, rig: &str, shots: u64) {
        if let Some(mut old) = self.sim.take() {
            let _ = old.wait();
        }
        let sim = Command::new(env!("CARGO_BIN_EXE_impactd"))
            .args(["sim", "--rig", rig, "--shots", &shots.to_string(), "--interval", "0.2"])
            .args(["-e", endpoint, "--no-multicast-scouting"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        self.sim = Some(sim);
    }

    /// Whether the sim is still swinging.
    pub fn swinging(&mut self) -> bool {
        self.sim.as_mut().is_some_and(|s| s.try_wait().unwrap().is_none())
    }

    /// Waits for the sim to end and for `shots` predictions in all; every prediction's latency (us).
    pub async fn finish(&mut self, shots: usize) -> Vec<f64> {
        while self.swinging() {
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
        if let Some(mut sim) = self.sim.take() {
            let status = sim.wait().unwrap();
            assert!(status.success(), "sim: {status}");
        }
        let launches = self.launches.clone();
        super::common::wait_until(Duration::from_secs(10), || launches.lock().unwrap().len() >= shots).await;
        // A moment for a doubled prediction, were there one, to arrive too.
        tokio::time::sleep(Duration::from_millis(300)).await;
        self.launches.lock().unwrap().iter().map(|l| l.latency_us).collect()
    }

    pub fn last_status(&self) -> Option<StatusMessage> {
        self.statuses.lock().unwrap().last().cloned()
    }
}
