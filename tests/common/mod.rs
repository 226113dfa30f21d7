//! What the bridge tests share: a daemon in-process on loopback zenoh, subscribers that collect, and a
//! recording's messages per topic (read with the `mcap` crate).

#![allow(clippy::unwrap_used)]
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use impactd::daemon::bus::{free_loopback_port, ZenohArgs};
use impactd::daemon::{DaemonConfig, RunOptions, RunSummary};
use zenoh::Wait;

pub struct Daemon {
    pub endpoint: String,
    stop: tokio::sync::oneshot::Sender<()>,
    task: tokio::task::JoinHandle<RunSummary>,
}

pub async fn start_daemon(config: &str, options: RunOptions) -> Daemon {
    let (config, setups) = DaemonConfig::parse(config).unwrap();
    let endpoint = format!("tcp/127.0.0.1:{}", free_loopback_port().unwrap());
    let session = ZenohArgs::loopback(vec![endpoint.clone()], vec![]).open().await.unwrap();
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let task = tokio::spawn(async move {
        let summary = impactd::daemon::run(config, setups, &session, options, async {
            let _ = stopped.await;
        })
        .await
        .unwrap();
        session.close().await.unwrap();
        summary
    });
    Daemon { endpoint, stop, task }
}

impl Daemon {
    pub async fn stop(self) -> RunSummary {
        let _ = self.stop.send(());
        self.task.await.unwrap()
    }
}

pub async fn client(endpoint: &str) -> zenoh::Session {
    ZenohArgs::loopback(vec![], vec![endpoint.to_string()]).open().await.unwrap()
}

pub type Collected<T> = Arc<Mutex<Vec<T>>>;

pub fn collect<T: serde::de::DeserializeOwned + Send + 'static>(
    session: &zenoh::Session,
    key: &str,
) -> (Collected<T>, zenoh::pubsub::Subscriber<()>) {
    let out: Collected<T> = Default::default();
    let out_cb = out.clone();
    let sub = session
        .declare_subscriber(key.to_string())
        .callback(move |s| {
            if let Ok(v) = serde_json::from_slice::<T>(&s.payload().to_bytes()) {
                out_cb.lock().unwrap().push(v);
            }
        })
        .wait()
        .unwrap();
    (out, sub)
}

/// Waits up to `limit` for `done`.
pub async fn wait_until(limit: Duration, mut done: impl FnMut() -> bool) -> bool {
    let start = std::time::Instant::now();
    while !done() {
        if start.elapsed() > limit {
            return false;
        }
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    true
}

/// A connection to a TCP surface of a daemon the tests started: the daemon binds its ports as it starts, and
/// `start_daemon` returns before, so a connect is retried while it is refused (up to 30 s).
pub async fn connect_when_listening(address: &str) -> tokio::net::TcpStream {
    let start = std::time::Instant::now();
    loop {
        match tokio::net::TcpStream::connect(address).await {
            Ok(s) => return s,
            Err(e)
                if e.kind() == std::io::ErrorKind::ConnectionRefused && start.elapsed() < Duration::from_secs(30) =>
            {
                tokio::time::sleep(Duration::from_millis(20)).await
            }
            Err(e) => panic!("connecting to {address}: {e}"),
        }
    }
}

/// What the daemon says it has received, rig by rig: the `samples` of each rig's latest status
/// (`golf/<rig>/status`). A put has left the synthetic rig when it returns, not reached the daemon; under load the
/// last ones are still on their way when the rig ends, and a daemon stopped then never sees them.
pub struct Received {
    latest: Collected<impactd::wire::StatusMessage>,
    _subscriber: zenoh::pubsub::Subscriber<()>,
}

impl Received {
    /// Starts watching the daemon's status on `session` (before the samples are sent).
    pub fn watch(session: &zenoh::Session) -> Self {
        let (latest, _subscriber) = collect(session, "golf/*/status");
        Received { latest, _subscriber }
    }

    /// Waits (up to 60 s) until every rig of `sent` has had at least its count of samples received; false if one
    /// has not by then.
    pub async fn all(&self, sent: &BTreeMap<String, u64>) -> bool {
        wait_until(Duration::from_secs(60), || {
            let statuses = self.latest.lock().unwrap();
            sent.iter().all(|(rig, n)| statuses.iter().rev().find(|s| &s.rig == rig).is_some_and(|s| s.samples >= *n))
        })
        .await
    }
}

/// Every message of a recording, as JSON, by topic.
pub fn recorded(path: &Path) -> BTreeMap<String, Vec<serde_json::Value>> {
    let bytes = std::fs::read(path).unwrap();
    let mut out: BTreeMap<String, Vec<serde_json::Value>> = BTreeMap::new();
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        let v = serde_json::from_slice(&m.data).unwrap_or(serde_json::Value::Null);
        out.entry(m.channel.topic.clone()).or_default().push(v);
    }
    out
}

pub fn quantile(v: &[f64], q: f64) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v[((q * v.len() as f64).ceil() as usize).clamp(1, v.len()) - 1]
}

/// The Python interpreter that has the independent test clients (`scripts/test.sh` prepares them in
/// `target/pyenv` and points `IMPACTD_PYTHON` there). Without it the test fails and says how to set it up.
pub fn python() -> std::process::Command {
    let venv = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/pyenv/bin/python");
    let exe =
        std::env::var_os("IMPACTD_PYTHON").map(std::path::PathBuf::from).or_else(|| venv.exists().then_some(venv));
    let exe = exe.unwrap_or_else(|| {
        panic!("the Python test clients are not set up: run the tests with `bash scripts/test.sh` (it creates target/pyenv)")
    });
    std::process::Command::new(exe)
}

/// Waits for the last status of a rig whose `input` satisfies `done`, and returns that input status.
pub async fn latest_input(
    statuses: &Collected<impactd::wire::StatusMessage>,
    done: impl Fn(&impactd::wire::MocapInputStatus) -> bool,
) -> impactd::wire::MocapInputStatus {
    let ok = wait_until(Duration::from_secs(10), || {
        statuses.lock().unwrap().last().and_then(|s| s.input.as_ref()).is_some_and(&done)
    })
    .await;
    let last = statuses.lock().unwrap().last().and_then(|s| s.input.clone()).unwrap();
    assert!(ok, "status never reached the expected state: {last:?}");
    last
}

/// This process's resident set (KiB), from /proc.
pub fn rss_kib() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let line = status.lines().find_map(|l| l.strip_prefix("VmRSS:"));
    line.and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok()).unwrap_or(0)
}

/// An independent Python client, `python -c SCRIPT PORT FRAMES`, with its output captured: it connects to a test
/// server on loopback, reads `frames` frames and prints `RESULT <json>`.
pub fn spawn_client(script: &str, port: u16, frames: usize) -> std::process::Child {
    python()
        .args(["-c", script, &port.to_string(), &frames.to_string()])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap()
}

/// Polls `ready` every 20 ms for up to 20 s (a client connecting to a test server); whether it became true.
pub fn wait_for(ready: impl Fn() -> bool) -> bool {
    let t0 = std::time::Instant::now();
    while !ready() {
        if t0.elapsed() > Duration::from_secs(20) {
            return false;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    true
}

/// What a [`spawn_client`] client printed after `RESULT `, once it exits; fails with both of its streams when it
/// printed none or raised.
pub fn client_result(child: std::process::Child, client: &str) -> serde_json::Value {
    let out = child.wait_with_output().unwrap();
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    let line = stdout
        .lines()
        .find_map(|l| l.strip_prefix("RESULT "))
        .unwrap_or_else(|| panic!("no result from {client}: {stdout}\n{stderr}"));
    assert!(!stderr.contains("Traceback"), "{client} failed: {stderr}");
    serde_json::from_str(line).unwrap()
}
