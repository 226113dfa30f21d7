//! The bay screens' feed: zenoh subscribers on the rigs' predictions, their flight lines, comparisons, status,
//! labels, exclusions and display settings hand each payload to one task (a bounded queue: the callbacks never block zenoh and
//! never parse), which updates the rigs' [`RigState`] and broadcasts the page messages.
//!
//! The screens read the bus like any other program, so whatever the daemon publishes and whatever anyone puts
//! (a control from a page, a script, another screen) shows on every page the same way.

use std::collections::{BTreeMap, VecDeque};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use tokio::sync::{broadcast, mpsc};

use super::limits::{FEED_QUEUE, PAGE_LAG};
use super::state::RigState;
use crate::daemon::clock::Clock;
use crate::daemon::DaemonError;
use crate::wire::{keys, DisplaySettings, FlightLine, LaunchPrediction, ShotExclusion, ShotLabels};

/// What a bus payload is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Launch,
    Flight,
    Comparison,
    Status,
    Labels,
    Exclusion,
    Display,
}

type KeyOf = fn(&str) -> String;

/// How long after a prediction arrives the screens take it up (the page's budget is 100 ms).
pub const LAUNCH_DEFER: std::time::Duration = std::time::Duration::from_millis(10);

const KINDS: [(Kind, KeyOf); 7] = [
    (Kind::Launch, keys::launch),
    (Kind::Flight, keys::flight),
    (Kind::Comparison, keys::comparison),
    (Kind::Status, keys::status),
    (Kind::Labels, keys::session),
    (Kind::Exclusion, keys::exclude),
    (Kind::Display, keys::display),
];

struct Update {
    kind: Kind,
    rig: String,
    received: std::time::Instant,
    received_ns: u64,
    payload: Vec<u8>,
}

/// The rigs' screens, shared by the feed, the pages and the CSV download.
pub struct Bay {
    pub rigs: Vec<String>,
    pub states: Mutex<BTreeMap<String, RigState>>,
    /// Page messages (JSON texts) for every page.
    pub out: broadcast::Sender<Arc<str>>,
    /// The recording's file name, for the CSV's `TMD Filename` column (empty without a recording).
    pub recording_name: String,
    /// Bus payloads that did not parse, and payloads dropped at a full queue.
    pub refused: AtomicU64,
    pub dropped: AtomicU64,
    /// Set when the screen stops: every open page is closed (and reconnects to the next daemon).
    pub closing: tokio::sync::watch::Sender<bool>,
    /// The daemon's clock: what arrives, and a page's start, are stamped on it.
    pub clock: Clock,
}

impl Bay {
    /// The screens of `rigs`, stamping on `clock`.
    pub fn new(rigs: Vec<String>, recording_name: String, clock: Clock) -> Arc<Self> {
        let states = rigs.iter().map(|r| (r.clone(), RigState::new(r))).collect();
        let (out, _) = broadcast::channel(PAGE_LAG);
        Arc::new(Bay {
            rigs,
            states: Mutex::new(states),
            out,
            recording_name,
            refused: AtomicU64::new(0),
            dropped: AtomicU64::new(0),
            closing: tokio::sync::watch::Sender::new(false),
            clock,
        })
    }

    /// Every rig's snapshot, in the configuration's order.
    pub fn snapshots(&self) -> Vec<String> {
        let Ok(mut states) = self.states.lock() else { return Vec::new() };
        self.rigs.iter().filter_map(|r| states.get_mut(r).map(RigState::snapshot)).collect()
    }

    fn apply(&self, u: Update) {
        let Ok(mut states) = self.states.lock() else { return };
        let Some(state) = states.get_mut(&u.rig) else { return };
        let json = |p: &[u8]| serde_json::from_slice::<serde_json::Value>(p).ok();
        let texts: Vec<String> = match u.kind {
            Kind::Launch => match serde_json::from_slice::<LaunchPrediction>(&u.payload) {
                Ok(p) => state.on_launch(p, u.received_ns).into_iter().chain([state.summary_json()]).collect(),
                Err(_) => return self.refuse(),
            },
            Kind::Flight => match FlightLine::parse(&u.payload) {
                Ok(line) => state.on_flight(&line).into_iter().collect(),
                Err(_) => return self.refuse(),
            },
            Kind::Comparison => match json(&u.payload) {
                Some(c) => vec![state.on_comparison(c)],
                None => return self.refuse(),
            },
            Kind::Status => match json(&u.payload) {
                Some(s) => vec![state.on_status(s)],
                None => return self.refuse(),
            },
            Kind::Labels => match ShotLabels::parse(&u.payload) {
                Ok(l) => {
                    state.labels = l;
                    vec![state.labels_json()]
                }
                Err(_) => return self.refuse(),
            },
            Kind::Exclusion => match ShotExclusion::parse(&u.payload) {
                Ok(x) => vec![state.on_exclusion(x.shot, x.excluded), state.summary_json()],
                Err(_) => return self.refuse(),
            },
            Kind::Display => match DisplaySettings::parse(&u.payload) {
                Ok(d) => {
                    state.units = d.units;
                    vec![state.units_json()]
                }
                Err(_) => return self.refuse(),
            },
        };
        drop(states);
        for t in texts {
            // No page open is not an error.
            let _ = self.out.send(Arc::from(t));
        }
    }

    fn refuse(&self) {
        self.refused.fetch_add(1, Ordering::Relaxed);
    }
}

/// The feed's subscribers and task; dropping it stops them.
pub struct Feed {
    _subscribers: Vec<zenoh::pubsub::Subscriber<()>>,
    task: tokio::task::JoinHandle<()>,
}

impl Drop for Feed {
    fn drop(&mut self) {
        self.task.abort();
    }
}

impl Feed {
    /// Subscribes to every rig's keys on `session` and starts applying what comes to `bay`.
    pub async fn start(session: &zenoh::Session, bay: Arc<Bay>) -> Result<Self, DaemonError> {
        let (tx, mut rx) = mpsc::channel::<Update>(FEED_QUEUE);
        let mut subscribers = Vec::new();
        for rig in &bay.rigs {
            for (kind, key_of) in KINDS {
                let (tx, key, rig, bay) = (tx.clone(), key_of(rig), rig.clone(), bay.clone());
                let subscriber = session
                    .declare_subscriber(key)
                    .callback(move |sample| {
                        let update = Update {
                            kind,
                            rig: rig.clone(),
                            received: bay.clock.now(),
                            received_ns: bay.clock.wall_ns(),
                            payload: sample.payload().to_bytes().into_owned(),
                        };
                        if tx.try_send(update).is_err() {
                            bay.dropped.fetch_add(1, Ordering::Relaxed);
                        }
                    })
                    .await
                    .map_err(DaemonError::zenoh)?;
                subscribers.push(subscriber);
            }
        }
        let task = tokio::spawn(async move {
            // What came while a launch waited, other than flight lines, in the order it came.
            let mut backlog: VecDeque<Update> = VecDeque::new();
            loop {
                let u = match backlog.pop_front() {
                    Some(u) => u,
                    None => match rx.recv().await {
                        Some(u) => u,
                        None => break,
                    },
                };
                // The screens' work on a shot (the session's numbers, a message to every page) waits until zenoh
                // has delivered the prediction to every other subscriber, so on a loaded machine it never
                // competes with that delivery. The shot's flight line, put right after it, is taken first when
                // it has come by then, so the shot goes to the pages with its line.
                if u.kind == Kind::Launch {
                    tokio::time::sleep_until((u.received + LAUNCH_DEFER).into()).await;
                    while backlog.len() < FEED_QUEUE {
                        match rx.try_recv() {
                            Ok(next) if next.kind == Kind::Flight => bay.apply(next),
                            Ok(next) => backlog.push_back(next),
                            Err(_) => break,
                        }
                    }
                }
                bay.apply(u);
            }
        });
        Ok(Feed { _subscribers: subscribers, task })
    }
}
