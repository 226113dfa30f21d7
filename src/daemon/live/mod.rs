//! The live daemon: samples in on zenoh, predictions out on zenoh, everything recorded.
//!
//! One worker thread per rig owns that rig's [`Pipeline`] and publishers, so rigs cannot disturb each other. The
//! zenoh subscriber's callback only routes each payload to its rig's bounded queue (a full queue is counted,
//! never blocks zenoh). A worker parses and validates the sample, runs the pipeline, and publishes the impact and
//! the launch at once; `latency_us` is the time from the callback receiving the revealing frame to the launch
//! being handed to zenoh. Status goes out once per `status_period_s`.
//!
//! Optional edges run on their own tasks, so none can delay a prediction: a rig's Open Connect client and
//! listener ([`crate::daemon::bridges::open_connect`]), the Foxglove live view ([`crate::daemon::bridges::foxglove::live`])
//! and the bay screen ([`crate::daemon::bridges::web`]).
//!
//! Measured launches (`lm/<rig>/launch`, from the Open Connect listener or any publisher) go through the same
//! queue to the same worker, which records them, pairs them with its predictions ([`crate::pairing`])
//! and publishes each pair on `golf/<rig>/comparison` as soon as the later of the two arrives; `latency_us` of a
//! comparison is the time from the callback receiving that message to the comparison being handed to zenoh.

use std::collections::{BTreeMap, HashMap};
use std::future::Future;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{sync_channel, RecvTimeoutError, SyncSender};
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::daemon::bridges::foxglove::live::FoxgloveServer;
use crate::daemon::bridges::open_connect::{self, LaunchMonitorListener, SimulatorClient};
use crate::daemon::bridges::opengolfsim;
use crate::daemon::bridges::web::{WebServer, WebStatusSource};
use crate::daemon::clock::Clock;
use crate::daemon::live::sinks::{RigPublishers, RigSinks};
use crate::daemon::peer_log::PeerLog;
use crate::daemon::recording::writer::{session_metadata, Recorder, RecorderHandle, RecorderSummary};
use crate::daemon::stats::{Budget, LatencyWindow, REJECTED_BYTES_PER_S, REJECTED_KEEP_BYTES, REJECTED_RECORDS_PER_S};
use crate::daemon::{DaemonConfig, DaemonError};
use crate::pairing::Pairer;
use crate::pipeline::{Counts, Event, Pipeline, RigSetup};
use crate::wire::{self, keys, LaunchMonitorStatus, SimulatorStatus};

mod ball;
pub mod claim;
pub mod club_put;
mod clubs;
mod inputs;
mod labels;
mod measured;
mod queue;
mod sample;
mod shot_log;
mod status;
use queue::{Arrival, Incoming, Stamp};
pub mod sinks;
mod truth;

/// Length of each rig's input queue.
pub const RIG_QUEUE: usize = 1 << 14;

/// How to run.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Record every message to this MCAP file.
    pub record: Option<PathBuf>,
    /// Replace an existing recording (otherwise an existing file stops the start).
    pub overwrite: bool,
    /// Serve the Foxglove live view on this `HOST:PORT`.
    pub foxglove: Option<String>,
    /// Serve the bay screen on this `HOST:PORT`.
    pub web: Option<String>,
    /// Take over rigs another daemon serves (it stops) instead of refusing to start ([`claim`]).
    pub take_over: bool,
    /// The clock the rigs' workers stamp and time with (the system's unless a test drives one).
    pub clock: Clock,
}

/// What a run did, per rig.
#[derive(Debug, Clone, Default)]
pub struct RunSummary {
    pub rigs: BTreeMap<String, Counts>,
    pub unknown_rig_samples: u64,
    pub recorder: Option<RecorderSummary>,
    /// Each rig's Open Connect client and listener at the end, for rigs that have them.
    pub simulators: BTreeMap<String, SimulatorStatus>,
    pub launch_monitors: BTreeMap<String, LaunchMonitorStatus>,
    /// Why the daemon stopped when another took its rig over (`--take-over`).
    pub taken_over: Option<String>,
}

/// Runs the daemon on `session` until `shutdown` completes.
pub async fn run(
    config: DaemonConfig,
    setups: Vec<RigSetup>,
    session: &zenoh::Session,
    options: RunOptions,
    shutdown: impl Future<Output = ()>,
) -> Result<RunSummary, DaemonError> {
    // Before anything is created (a recording, a port): another daemon serving one of the rigs stops the start.
    let rig_names: Vec<String> = config.rigs.iter().map(|r| r.name.clone()).collect();
    claim::claim(session, &rig_names, options.take_over).await?;
    let recorder = options
        .record
        .as_deref()
        .map(|p| {
            Recorder::create(p, session_metadata(&config, &options.clock), options.overwrite, options.clock.clone())
        })
        .transpose()?;
    let unknown = Arc::new(AtomicU64::new(0));
    let foxglove = match &options.foxglove {
        Some(address) => {
            let rigs: Vec<&str> = config.rigs.iter().map(|r| r.name.as_str()).collect();
            Some(FoxgloveServer::start(address, &rigs, options.clock.clone()).await?)
        }
        None => None,
    };
    // The screens draw each rig's flights from the lines its worker publishes (`golf/<rig>/flight`).
    let screens = setups.iter().map(|s| s.name.clone()).collect();
    let access = config.web.as_ref().map(|w| w.access()).unwrap_or_default();
    let web = WebServer::start_if(
        options.web.as_deref(),
        &access,
        screens,
        session,
        options.record.as_deref(),
        options.clock.clone(),
    )
    .await?;
    let handle = recorder.as_ref().map_or_else(RecorderHandle::none, |r| r.handle());
    let handle = handle.with_live(foxglove.as_ref().map(FoxgloveServer::tap));
    let mut listeners = Vec::new();
    let status_period = Duration::from_secs_f64(config.status_period_s);
    let mut senders: HashMap<String, (SyncSender<Incoming>, Arc<AtomicU64>)> = HashMap::new();
    let mut workers = Vec::new();
    let mut measured_subscribers = Vec::new();
    let mut input_slots: HashMap<String, InputSlot> = HashMap::new();
    for (setup, rig_config) in setups.into_iter().zip(&config.rigs) {
        let name = setup.name.clone();
        let publishers = RigPublishers::declare(session, &name).await?;
        let (simulator, listener) = open_connect::start_rig(
            &rig_config.name,
            rig_config.simulator.as_ref(),
            rig_config.launch_monitor.as_ref(),
            session,
            &handle,
            &options.clock,
        )
        .await?;
        let simulator =
            simulator.or_else(|| opengolfsim::spawn(&name, rig_config.simulator.as_ref()?, &handle, &options.clock));
        let launch_monitor = listener.as_ref().map(LaunchMonitorListener::status_handle);
        listeners.extend(listener);
        let (tx, rx) = sync_channel::<Incoming>(RIG_QUEUE);
        let queue_dropped = Arc::new(AtomicU64::new(0));
        senders.insert(name.clone(), (tx.clone(), queue_dropped.clone()));
        for (key, kind) in [
            (keys::measured_launch(&name), Arrival::Measured as fn(Vec<u8>) -> Arrival),
            (keys::session(&name), Arrival::Labels),
            (keys::truth(&name), Arrival::Truth),
            (keys::exclude(&name), Arrival::Exclusion),
            (keys::ball(&name), Arrival::Ball),
        ] {
            let route = (tx.clone(), queue_dropped.clone());
            measured_subscribers.push(queue::subscribe(session, key, kind, route, options.clock.clone()).await?);
        }
        let window = rig_config.launch_monitor.as_ref().map(|l| l.pair_window()).unwrap_or_default();
        let mut setup = setup;
        // The prediction's own flight samples its line: published on `golf/<rig>/flight` for the screens,
        // and recorded and drawn in the live view.
        setup.flight_line_step_s = crate::daemon::recording::channels::FLIGHT_LINE_STEP_S;
        let pipeline = Pipeline::new(setup);
        let worker = Worker {
            rig: Arc::from(name.as_str()),
            sinks: RigSinks::new(&pipeline, Some(publishers), handle.clone()),
            pipeline: Some(pipeline),
            queue_dropped,
            latency: LatencyWindow::new(1024),
            log: PeerLog::with_clock(options.clock.clone()),
            started: options.clock.now(),
            budget: Budget::with_clock(REJECTED_RECORDS_PER_S, REJECTED_BYTES_PER_S, options.clock.clone()),
            clock: options.clock.clone(),
            unknown: unknown.clone(),
            simulator,
            launch_monitor,
            live_view: foxglove.as_ref().map(FoxgloveServer::status_source),
            web: web.as_ref().map(WebServer::status_source),
            pairer: Pairer::new(&name, window),
            input: input_slots.entry(name.clone()).or_default().clone(),
            units: config.units,
            held_impact: None,
        };
        workers.push(
            std::thread::Builder::new()
                .name(format!("impactd-{name}"))
                .spawn(move || worker.run(rx, status_period))
                .map_err(|e| DaemonError::Io { what: "starting a rig worker".into(), source: e })?,
        );
        tracing::info!("rig {name}: listening on {}", keys::clubhead(&name));
    }
    let (inputs, input_sources) = inputs::start(&config, &senders, &options.clock)?;
    let club_loader = clubs::start(session, &config, &senders, &options.clock).await?;
    for (rig, source) in input_sources {
        if let Some(slot) = input_slots.get(&rig) {
            if let Ok(mut s) = slot.lock() {
                *s = Some(source);
            }
        }
    }
    let (taken_tx, mut taken_rx) = tokio::sync::mpsc::channel::<String>(1);
    let claims = claim::declare(session, &config.rigs, move |why| {
        let _ = taken_tx.try_send(why);
    })
    .await?;
    let unknown_cb = unknown.clone();
    let clock = options.clock.clone();
    let unknown_log = std::sync::Mutex::new(PeerLog::with_clock(clock.clone()));
    let unknown_budget =
        std::sync::Mutex::new(Budget::with_clock(REJECTED_RECORDS_PER_S, REJECTED_BYTES_PER_S, clock.clone()));
    let unknown_recorder = handle.clone();
    let routes = senders;
    let subscriber = session
        .declare_subscriber(keys::CLUBHEAD_ALL)
        .callback(move |sample| {
            let received = clock.now();
            let key = sample.key_expr().as_str();
            let route = keys::rig_of_clubhead(key).and_then(|rig| routes.get(rig));
            let Some((tx, dropped)) = route else {
                unknown_cb.fetch_add(1, Ordering::Relaxed);
                // Limited by kind, not by key: a peer choosing a new key for every sample gets one line a second.
                if let Ok(mut log) = unknown_log.lock() {
                    log.warn("unknown_rig", || format!("sample on {key} is for no configured rig"));
                }
                // Recorded within the same budget as a rig's rejected payloads.
                let payload = sample.payload().to_bytes();
                let keep = payload.len().min(REJECTED_KEEP_BYTES);
                if unknown_recorder.enabled() && unknown_budget.lock().is_ok_and(|mut b| b.allow(keep)) {
                    let rejected = wire::RejectedInput {
                        reason: format!("no configured rig serves `{key}`"),
                        bytes: payload.len(),
                        payload: String::from_utf8_lossy(&payload[..keep]).into_owned(),
                    };
                    let now = clock.wall_ns();
                    unknown_recorder.send(crate::daemon::recording::record::Record::Message {
                        key: keys::UNKNOWN_RIG_REJECTED.to_string(),
                        message_type: <wire::RejectedInput as wire::Message>::TYPE,
                        log_time_ns: now,
                        publish_time_ns: now,
                        data: serde_json::to_vec(&rejected).unwrap_or_default(),
                    });
                }
                return;
            };
            let arrival = Arrival::Sample {
                payload: sample.payload().to_bytes().into_owned(),
                encoding: sample.encoding().to_string(),
            };
            let incoming = Incoming { at: Stamp { received, log_time_ns: clock.wall_ns() }, arrival };
            if tx.try_send(incoming).is_err() {
                dropped.fetch_add(1, Ordering::Relaxed);
            }
        })
        .await
        .map_err(DaemonError::zenoh)?;
    let taken_over = tokio::select! {
        _ = shutdown => None,
        why = taken_rx.recv() => why,
    };
    tracing::info!("shutting down");
    for input in inputs {
        input.stop();
    }
    subscriber.undeclare().await.map_err(DaemonError::zenoh)?;
    // The loader stops within its poll whatever a put's load is doing (a load given up on runs out on its own
    // thread, which holds none of the rigs' queues).
    club_loader.stop.store(true, Ordering::Relaxed);
    for s in measured_subscribers.into_iter().chain(club_loader.subscribers) {
        s.undeclare().await.map_err(DaemonError::zenoh)?;
    }
    let _ = club_loader.thread.join();
    let mut summary =
        RunSummary { unknown_rig_samples: unknown.load(Ordering::Relaxed), taken_over, ..Default::default() };
    for w in workers {
        if let Ok(end) = w.join() {
            if let Some(task) = end.simulator_task {
                SimulatorClient::finish(task).await;
            }
            if let Some(s) = end.simulator {
                summary.simulators.insert(end.rig.clone(), s);
            }
            if let Some(l) = end.launch_monitor {
                summary.launch_monitors.insert(end.rig.clone(), l);
            }
            summary.rigs.insert(end.rig, end.counts);
        }
    }
    for l in listeners {
        l.stop().await;
    }
    drop(foxglove);
    drop(web);
    drop(handle);
    if let Some(r) = recorder {
        summary.recorder = Some(r.finish()?);
    }
    // Last: a daemon taking the rigs over starts once these are gone, when every port is released and the
    // recording closed.
    drop(claims);
    Ok(summary)
}

struct Worker {
    rig: Arc<str>,
    sinks: RigSinks,
    /// The rig's pipeline; taken out while it runs a sample, so its events can be published as they come.
    pipeline: Option<Pipeline>,
    queue_dropped: Arc<AtomicU64>,
    latency: LatencyWindow,
    /// The rig's peer-driven log lines (bad payloads, labels, exclusions, club changes): one a second per kind.
    log: PeerLog,
    started: Instant,
    /// The recording budget for this rig's rejected payloads.
    budget: Budget,
    /// Samples for unknown rigs, over all of them (shown in every rig's status).
    unknown: Arc<AtomicU64>,
    simulator: Option<SimulatorClient>,
    launch_monitor: Option<Arc<std::sync::Mutex<LaunchMonitorStatus>>>,
    live_view: Option<crate::daemon::bridges::foxglove::live::LiveViewSource>,
    web: Option<WebStatusSource>,
    /// Measured launches waiting for their prediction and predictions waiting for their measurement.
    pairer: Pairer,
    /// The NatNet or QTM client feeding this rig (`[rig.input]`), once started.
    input: InputSlot,
    /// The units of the lines logged per shot.
    units: crate::session::Units,
    /// What the worker stamps records with and measures latency, periods and uptime on.
    clock: Clock,
    /// The shot's impact, published right after its first launch (`on_event`).
    held_impact: Option<wire::ImpactMessage>,
}

/// Where a worker finds its input's counts (filled once the inputs start, after the workers).
type InputSlot = Arc<std::sync::Mutex<Option<crate::daemon::inputs::StatusSource>>>;

/// What a rig's worker leaves behind.
struct WorkerEnd {
    rig: String,
    counts: Counts,
    simulator: Option<SimulatorStatus>,
    simulator_task: Option<tokio::task::JoinHandle<()>>,
    launch_monitor: Option<LaunchMonitorStatus>,
}

impl Worker {
    fn run(mut self, rx: std::sync::mpsc::Receiver<Incoming>, period: Duration) -> WorkerEnd {
        let mut next_status = self.clock.now() + period;
        self.record_club(self.clock.wall_ns(), wire::ClubSource::Config, None);
        loop {
            let wait = next_status.saturating_duration_since(self.clock.now());
            match rx.recv_timeout(wait) {
                Ok(incoming) => self.on_incoming(incoming),
                Err(RecvTimeoutError::Timeout) => self.pairer.expire(self.clock.wall_ns()),
                Err(RecvTimeoutError::Disconnected) => break,
            }
            if self.clock.now() >= next_status {
                self.publish_status();
                self.log.flush();
                next_status += period;
            }
        }
        let status = self.publish_status();
        WorkerEnd {
            rig: self.rig.to_string(),
            counts: self.pipeline.as_ref().map(|p| p.counts.clone()).unwrap_or_default(),
            simulator: status.simulator,
            simulator_task: self.simulator.take().map(SimulatorClient::close),
            launch_monitor: status.launch_monitor,
        }
    }

    fn warn(&mut self, kind: &'static str, message: impl FnOnce() -> String) {
        let rig = &self.rig;
        self.log.warn(kind, || format!("rig {rig}: {}", message()));
    }

    /// A line about a put from any program (labels, an exclusion, a club): one a second per kind.
    fn info(&mut self, kind: &'static str, message: impl FnOnce() -> String) {
        let rig = &self.rig;
        self.log.info(kind, || format!("rig {rig}: {}", message()));
    }

    fn on_incoming(&mut self, incoming: Incoming) {
        let at = incoming.at;
        match incoming.arrival {
            Arrival::Sample { payload, encoding } => self.on_sample(at, payload, &encoding),
            Arrival::DecodedSample(msg) => self.on_decoded_sample(at, &msg),
            Arrival::Measured(payload) => self.on_measured(at, payload),
            Arrival::Labels(payload) => self.on_labels(at, &payload),
            Arrival::Truth(payload) => self.on_truth(at, payload),
            Arrival::Club(switch) => self.on_club(at, *switch),
            Arrival::Exclusion(payload) => self.on_exclusion(at, &payload),
            Arrival::Ball(payload) => self.on_ball(at, payload),
            Arrival::DecodedBall(msg) => self.on_decoded_ball(at, msg),
        }
    }

    /// Publishes and records the impact held for its shot's first launch (or for the shot's end).
    fn release_impact(&mut self) {
        if let Some(m) = self.held_impact.take() {
            self.sinks.impact(&m, self.clock.wall_ns());
        }
    }

    fn on_event(&mut self, rig: &str, event: Event, received: Instant) {
        match event {
            Event::Rejected { frame, reason } => {
                self.warn(reason.key(), || format!("frame {frame} rejected: {reason}"))
            }
            // The impact waits for the shot's first launch: that launch is published first (the latency ends
            // there), the impact right after it, and both are recorded in the order they came.
            Event::Impact(m) => self.held_impact = Some(m),
            Event::Launch(mut l) => {
                // The flight's sampled line (`RigSetup::flight_line_step_s`) is for the recording and the live
                // view, never the wire: taken out before the prediction is published.
                let line = sinks::take_line(&mut l);
                l.latency_us = self.clock.since(received).as_nanos() as f64 / 1e3;
                let data = self.sinks.publish_launch(&l);
                self.release_impact();
                self.sinks.publish_flight(&l, line.as_deref());
                self.sinks.record_launch(&l, data, line, self.clock.wall_ns());
                self.latency.push(l.latency_us);
                if let Some(simulator) = &mut self.simulator {
                    simulator.offer(&l);
                }
                for c in self.pairer.on_prediction(&l) {
                    self.publish_comparison(c, received);
                }
                tracing::info!("{}", shot_log::launch(rig, &l, self.units));
            }
            Event::Failed { shot, frame, reason, .. } => {
                self.release_impact();
                tracing::warn!("rig {rig} shot {shot} (frame {frame}): no prediction: {reason}");
                self.sinks.failed();
            }
            Event::ClubChanged(change) => self.record_club_change(self.clock.wall_ns(), &change),
            Event::Missed(m) => tracing::info!("rig {rig}: {m}"),
            Event::ImpactTiming(t) => tracing::info!("rig {rig} {t}"),
        }
    }
}
