//! A rig's club during a session: a put on `golf/<rig>/club` (a preset name or a club file's path) is loaded and
//! its models built on a loader thread, off the rig's sample path, then joins the rig's queue as a ready switch;
//! another tracked body coming into view switches to its club (`[rig.clubs]`, in the pipeline). Every change,
//! and the club at start, is recorded on `golf/<rig>/club`; a bad put is logged and changes nothing. A put names
//! a preset or a club file under the club directories, and no put can stall the loader or the shutdown
//! ([`super::club_put`]).

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{sync_channel, Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use super::club_put;
use super::inputs::Route;
use super::queue::{Arrival, Incoming, Stamp};
use super::Worker;
use crate::daemon::clock::Clock;
use crate::daemon::config::RigConfig;
use crate::daemon::peer_log::PeerLog;
use crate::daemon::{DaemonConfig, DaemonError};
use crate::wire::{self, keys, ClubSource};

/// Club puts waiting for the loader; a put beyond them is refused (logged), never blocking zenoh.
const PENDING_PUTS: usize = 64;

/// A put as received.
struct Put {
    rig: String,
    payload: Vec<u8>,
}

/// The subscribers to every rig's `golf/<rig>/club` and the loader thread they feed. Setting `stop` (or
/// undeclaring the subscribers, which closes its queue) ends the loader within [`LOADER_POLL`], whatever a load
/// is doing, and it then lets go of the rigs' queues.
pub(super) struct ClubLoader {
    pub(super) subscribers: Vec<zenoh::pubsub::Subscriber<()>>,
    pub(super) thread: std::thread::JoinHandle<()>,
    pub(super) stop: Arc<AtomicBool>,
}

/// How often the loader, waiting for a put, looks at its stop flag.
const LOADER_POLL: Duration = Duration::from_millis(50);

/// Starts the loader and subscribes each rig's club key.
pub(super) async fn start(
    session: &zenoh::Session,
    config: &DaemonConfig,
    routes: &HashMap<String, Route>,
    clock: &Clock,
) -> Result<ClubLoader, DaemonError> {
    let (tx, rx) = sync_channel::<Put>(PENDING_PUTS);
    let dirs = crate::daemon::config_club_dirs::club_dirs(config.clubs.as_ref(), config.config_dir.as_deref())?;
    tracing::info!(
        "club puts name a preset or a club file under: {}",
        if dirs.is_empty() {
            "no directory (presets only)".to_string()
        } else {
            dirs.iter().map(|d| d.display().to_string()).collect::<Vec<_>>().join(", ")
        }
    );
    let stop = Arc::new(AtomicBool::new(false));
    let loader_stop = stop.clone();
    // The puts' log lines, the subscribers' and the loader's: one a second per kind, floods counted.
    let log = Arc::new(Mutex::new(PeerLog::with_clock(clock.clone())));
    let (loader_log, loader_clock) = (log.clone(), clock.clone());
    let rigs: HashMap<String, (RigConfig, Route)> = config
        .rigs
        .iter()
        .filter_map(|r| routes.get(&r.name).map(|route| (r.name.clone(), (r.clone(), route.clone()))))
        .collect();
    let thread = std::thread::Builder::new()
        .name("impactd-clubs".into())
        .spawn(move || load(rx, rigs, dirs, loader_stop, &loader_log, &loader_clock))
        .map_err(|e| DaemonError::Io { what: "starting the club loader".into(), source: e })?;
    let mut subscribers = Vec::new();
    for rig in &config.rigs {
        let (tx, name, key, log) = (tx.clone(), rig.name.clone(), keys::club(&rig.name), log.clone());
        let subscriber = session
            .declare_subscriber(key.clone())
            .callback(move |sample| {
                let put = Put { rig: name.clone(), payload: sample.payload().to_bytes().into_owned() };
                if tx.try_send(put).is_err() {
                    let mut log = log.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
                    log.warn("club_puts_waiting", || {
                        format!("put on {key} refused: {PENDING_PUTS} club puts are already waiting")
                    });
                }
            })
            .await
            .map_err(DaemonError::zenoh)?;
        subscribers.push(subscriber);
    }
    Ok(ClubLoader { subscribers, thread, stop })
}

/// The loader: each put parsed, resolved under `dirs`, loaded and built for its rig, then queued for the rig's
/// worker; it ends when its queue closes or `stop` is set.
fn load(
    rx: Receiver<Put>,
    rigs: HashMap<String, (RigConfig, Route)>,
    dirs: Vec<PathBuf>,
    stop: Arc<AtomicBool>,
    log: &Mutex<PeerLog>,
    clock: &Clock,
) {
    let log = || log.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    let running = Arc::new(AtomicUsize::new(0));
    loop {
        let put = match rx.recv_timeout(LOADER_POLL) {
            Ok(put) => put,
            Err(RecvTimeoutError::Timeout) if !stop.load(Ordering::Relaxed) => {
                log().flush();
                continue;
            }
            Err(_) => break,
        };
        if stop.load(Ordering::Relaxed) {
            break;
        }
        log().flush();
        let Some((config, (tx, dropped))) = rigs.get(&put.rig) else { continue };
        let key = keys::club(&put.rig);
        let switch = wire::parse_club_put(&put.payload).map_err(|e| e.to_string()).and_then(|spec| {
            let spec = club_put::resolve(&spec, &dirs).map_err(|e| e.to_string())?;
            club_put::prepare(config, spec, &running, &stop).map_err(|e| e.to_string())
        });
        match switch {
            Ok(switch) => {
                let incoming = Incoming::now(clock, Arrival::Club(Box::new(switch)));
                if tx.try_send(incoming).is_err() {
                    dropped.fetch_add(1, Ordering::Relaxed);
                    log().warn("club_queue_full", || format!("put on {key} refused: the rig's queue is full"));
                }
            }
            Err(e) => {
                log().warn("club_refused", || format!("put on {key} refused, the club is unchanged: {e}"));
            }
        }
    }
}

impl Worker {
    /// A put's club, loaded: the rig's club from now on, recorded.
    pub(super) fn on_club(&mut self, at: Stamp, switch: crate::pipeline::ClubSwitch) {
        if let Some(p) = self.pipeline.as_mut() {
            p.switch_club(switch);
        }
        self.record_club(at.log_time_ns, ClubSource::Put, None);
    }

    /// Records (and logs) the rig's club from a pipeline's change (a body's club).
    pub(super) fn record_club_change(&mut self, log_time_ns: u64, change: &wire::ClubChange) {
        self.info("club_change", || {
            format!(
                "club {} ({}, sha256 {}) from {:?}{}",
                change.club.name,
                change.club.file,
                change.club.sha256.get(..12).unwrap_or_default(),
                change.source,
                change.body.as_deref().map(|b| format!(" (body {b})")).unwrap_or_default()
            )
        });
        self.sinks.club_change(log_time_ns, change);
    }

    /// Records (and logs) the rig's club as it is now.
    pub(super) fn record_club(&mut self, log_time_ns: u64, source: ClubSource, body: Option<String>) {
        let Some(p) = self.pipeline.as_ref() else { return };
        let change = p.club_change(source, body);
        self.record_club_change(log_time_ns, &change);
    }
}
