//! The live daemon: samples in on zenoh, predictions out on zenoh, everything recorded.
//!
//! One worker thread per rig owns that rig's [`Pipeline`] and publishers, so rigs cannot disturb each other. The
//! zenoh subscriber's callback only routes each payload to its rig's bounded queue (a full queue is counted,
//! never blocks zenoh). A worker parses and validates the sample, runs the pipeline, and publishes the impact and
//! the launch at once; `latency_us` is the time from the callback receiving the revealing frame to the launch
//! being handed to zenoh. Status goes out once per `status_period_s`.

use std::collections::{BTreeMap, HashMap};
use std::future::Future;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{sync_channel, RecvTimeoutError, SyncSender};
use std::sync::Arc;
use std::time::{Duration, Instant};

use zenoh::Wait;

use super::recorder::{Record, Recorder, RecorderHandle, RecorderSummary};
use super::stats::{LatencyWindow, RateLimiter};
use super::{wall_ns, DaemonConfig, DaemonError};
use crate::pipeline::{Counts, Event, Pipeline, RigSetup};
use crate::wire::{self, keys, StatusMessage};

/// Length of each rig's input queue.
pub const RIG_QUEUE: usize = 1 << 14;

/// How to run.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Record every message to this MCAP file.
    pub record: Option<PathBuf>,
}

/// What a run did, per rig.
#[derive(Debug, Clone, Default)]
pub struct RunSummary {
    pub rigs: BTreeMap<String, Counts>,
    pub unknown_rig_samples: u64,
    pub recorder: Option<RecorderSummary>,
}

struct Incoming {
    received: Instant,
    log_time_ns: u64,
    payload: Vec<u8>,
    encoding: String,
}

/// The `session` metadata of a recording: versions and the configuration.
pub fn session_metadata(config: &DaemonConfig) -> BTreeMap<String, String> {
    let mut m = BTreeMap::new();
    m.insert("impactd_version".into(), env!("CARGO_PKG_VERSION").into());
    m.insert("wire_version".into(), wire::WIRE_VERSION.to_string());
    m.insert("config_toml".into(), toml::to_string(config).unwrap_or_default());
    m.insert("start_ns".into(), wall_ns().to_string());
    m
}

/// Runs the daemon on `session` until `shutdown` completes.
pub async fn run(
    config: DaemonConfig,
    setups: Vec<RigSetup>,
    session: &zenoh::Session,
    options: RunOptions,
    shutdown: impl Future<Output = ()>,
) -> Result<RunSummary, DaemonError> {
    let recorder = options.record.as_deref().map(|p| Recorder::create(p, session_metadata(&config))).transpose()?;
    let handle = recorder.as_ref().map(|r| r.handle()).unwrap_or_else(RecorderHandle::none);
    let status_period = Duration::from_secs_f64(config.status_period_s);
    let mut senders: HashMap<String, (SyncSender<Incoming>, Arc<AtomicU64>)> = HashMap::new();
    let mut workers = Vec::new();
    let mut tokens = Vec::new();
    let mut queryables = Vec::new();
    for (setup, rig_config) in setups.into_iter().zip(&config.rigs) {
        let name = setup.name.clone();
        let impact = session
            .declare_publisher(keys::impact(&name))
            .encoding(wire::encoding("ImpactMessage"))
            .await
            .map_err(DaemonError::zenoh)?;
        let launch = session
            .declare_publisher(keys::launch(&name))
            .encoding(wire::encoding("LaunchPrediction"))
            .await
            .map_err(DaemonError::zenoh)?;
        let status = session
            .declare_publisher(keys::status(&name))
            .encoding(wire::encoding("StatusMessage"))
            .await
            .map_err(DaemonError::zenoh)?;
        tokens.push(session.liveliness().declare_token(keys::alive(&name)).await.map_err(DaemonError::zenoh)?);
        let config_json = serde_json::to_vec(rig_config).unwrap_or_default();
        let config_key = keys::config(&name);
        queryables.push(
            session
                .declare_queryable(config_key.clone())
                .callback(move |query| {
                    if let Err(e) =
                        query.reply(config_key.clone(), config_json.clone()).encoding("application/json").wait()
                    {
                        tracing::warn!("config query: {e}");
                    }
                })
                .await
                .map_err(DaemonError::zenoh)?,
        );
        let setup_ball = (setup.detector.ball_position_m.into(), setup.detector.ball_radius_m);
        let (tx, rx) = sync_channel::<Incoming>(RIG_QUEUE);
        let queue_dropped = Arc::new(AtomicU64::new(0));
        senders.insert(name.clone(), (tx, queue_dropped.clone()));
        let worker = Worker {
            rig: Arc::from(setup.name.as_str()),
            keys: RigKeys::new(&setup.name),
            pipeline: Some(Pipeline::new(setup)),
            impact,
            launch,
            status,
            recorder: handle.clone(),
            queue_dropped,
            latency: LatencyWindow::new(1024),
            limiter: RateLimiter::new(Duration::from_secs(1)),
            started: Instant::now(),
            ball_position_m: setup_ball.0,
            ball_radius_m: setup_ball.1,
        };
        workers.push(
            std::thread::Builder::new()
                .name(format!("impactd-{name}"))
                .spawn(move || worker.run(rx, status_period))
                .map_err(|e| DaemonError::Io { what: "starting a rig worker".into(), source: e })?,
        );
        tracing::info!("rig {name}: listening on {}", keys::clubhead(&name));
    }
    let unknown = Arc::new(AtomicU64::new(0));
    let unknown_cb = unknown.clone();
    let limiter = std::sync::Mutex::new(RateLimiter::new(Duration::from_secs(1)));
    let routes = senders;
    let subscriber = session
        .declare_subscriber(keys::CLUBHEAD_ALL)
        .callback(move |sample| {
            let received = Instant::now();
            let key = sample.key_expr().as_str();
            let route = keys::rig_of_clubhead(key).and_then(|rig| routes.get(rig));
            let Some((tx, dropped)) = route else {
                unknown_cb.fetch_add(1, Ordering::Relaxed);
                if let Some(n) = limiter.lock().ok().and_then(|mut l| l.allow(key)) {
                    tracing::warn!("sample on {key} is for no configured rig ({n} more suppressed)");
                }
                return;
            };
            let incoming = Incoming {
                received,
                log_time_ns: wall_ns(),
                payload: sample.payload().to_bytes().into_owned(),
                encoding: sample.encoding().to_string(),
            };
            if tx.try_send(incoming).is_err() {
                dropped.fetch_add(1, Ordering::Relaxed);
            }
        })
        .await
        .map_err(DaemonError::zenoh)?;
    shutdown.await;
    tracing::info!("shutting down");
    subscriber.undeclare().await.map_err(DaemonError::zenoh)?;
    drop(queryables);
    drop(tokens);
    let mut summary = RunSummary { unknown_rig_samples: unknown.load(Ordering::Relaxed), ..Default::default() };
    for w in workers {
        if let Ok((name, counts)) = w.join() {
            summary.rigs.insert(name, counts);
        }
    }
    drop(handle);
    if let Some(r) = recorder {
        summary.recorder = Some(r.finish()?);
    }
    Ok(summary)
}

/// A rig's key expressions, built once.
struct RigKeys {
    clubhead: String,
    rejected: String,
    impact: String,
    launch: String,
    status: String,
}

impl RigKeys {
    fn new(rig: &str) -> Self {
        RigKeys {
            clubhead: keys::clubhead(rig),
            rejected: format!("{}/rejected", keys::clubhead(rig)),
            impact: keys::impact(rig),
            launch: keys::launch(rig),
            status: keys::status(rig),
        }
    }
}

struct Worker {
    rig: Arc<str>,
    keys: RigKeys,
    /// The rig's pipeline; taken out while it runs a sample, so its events can be published as they come.
    pipeline: Option<Pipeline>,
    impact: zenoh::pubsub::Publisher<'static>,
    launch: zenoh::pubsub::Publisher<'static>,
    status: zenoh::pubsub::Publisher<'static>,
    recorder: RecorderHandle,
    queue_dropped: Arc<AtomicU64>,
    latency: LatencyWindow,
    limiter: RateLimiter,
    started: Instant,
    ball_position_m: [f64; 3],
    ball_radius_m: f64,
}

impl Worker {
    fn p(&self) -> &Pipeline {
        self.pipeline.as_ref().expect("the pipeline is in place between samples")
    }

    fn p_mut(&mut self) -> &mut Pipeline {
        self.pipeline.as_mut().expect("the pipeline is in place between samples")
    }

    fn run(mut self, rx: std::sync::mpsc::Receiver<Incoming>, period: Duration) -> (String, Counts) {
        let mut next_status = Instant::now() + period;
        loop {
            let wait = next_status.saturating_duration_since(Instant::now());
            match rx.recv_timeout(wait) {
                Ok(incoming) => self.on_incoming(incoming),
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => break,
            }
            if Instant::now() >= next_status {
                self.publish_status();
                next_status += period;
            }
        }
        self.publish_status();
        (self.rig.to_string(), self.p().counts.clone())
    }

    fn warn(&mut self, key: &str, message: impl FnOnce() -> String) {
        if let Some(n) = self.limiter.allow(key) {
            let rig = &self.rig;
            if n > 0 {
                tracing::warn!("rig {rig}: {} ({n} more like it suppressed)", message());
            } else {
                tracing::warn!("rig {rig}: {}", message());
            }
        }
    }

    fn record(&self, key: &str, type_name: &'static str, log_time_ns: u64, publish_time_ns: u64, data: Vec<u8>) {
        if self.recorder.enabled() {
            self.recorder.send(Record::Message { key: key.to_string(), type_name, log_time_ns, publish_time_ns, data });
        }
    }

    fn on_incoming(&mut self, incoming: Incoming) {
        let rig = self.rig.clone();
        let msg = match wire::parse_sample(&rig, &incoming.payload, &incoming.encoding) {
            Ok(m) => m,
            Err(e) => {
                *self.p_mut().counts.rejected.entry(e.key().to_string()).or_default() += 1;
                self.p_mut().counts.samples += 1;
                let bytes = incoming.payload.len();
                self.warn(e.key(), || format!("rejected sample: {e}"));
                // Nothing is lost: the raw payload goes to the recording beside the reason.
                let keep = &incoming.payload[..bytes.min(wire::MAX_PAYLOAD_BYTES)];
                let data = serde_json::to_vec(&wire::RejectedInput {
                    reason: e.to_string(),
                    bytes,
                    payload: String::from_utf8_lossy(keep).into_owned(),
                })
                .unwrap_or_default();
                self.record(&self.keys.rejected, "RejectedInput", incoming.log_time_ns, incoming.log_time_ns, data);
                return;
            }
        };
        let sample = msg.to_sample();
        self.record(&self.keys.clubhead, "ClubheadSample", incoming.log_time_ns, msg.t_ns, incoming.payload);
        let mut any_event = false;
        let received = incoming.received;
        let mut pipeline = self.pipeline.take().expect("the pipeline is in place between samples");
        pipeline.on_sample_with(&sample, &mut |event| {
            any_event = true;
            self.on_event(&rig, event, received);
        });
        self.pipeline = Some(pipeline);
        if self.recorder.enabled() && !sample.occluded && !any_event {
            if let Some(q) = crate::kinematics::sample::unit_quaternion(&sample.orientation_xyzw, 0.01) {
                let lab = crate::math::Isometry3::from_parts(sample.position_m.into(), q);
                let world_from_club = self.p().setup.calibration.world_from_club(&lab);
                self.recorder.send(Record::ClubPose {
                    rig: rig.to_string(),
                    t_ns: sample.t_ns,
                    log_time_ns: incoming.log_time_ns,
                    world_from_club,
                });
            }
        }
    }

    fn on_event(&mut self, rig: &str, event: Event, received: Instant) {
        match event {
            Event::Rejected { frame, reason } => {
                self.warn(reason.key(), || format!("frame {frame} rejected: {reason}"))
            }
            Event::Impact(m) => {
                let data = serde_json::to_vec(&m).unwrap_or_default();
                if let Err(e) = self.impact.put(data.clone()).wait() {
                    tracing::error!("rig {rig}: publishing the impact: {e}");
                }
                let now = wall_ns();
                self.record(&self.keys.impact, "ImpactMessage", now, now, data);
                if self.recorder.enabled() {
                    self.recorder.send(Record::ImpactScene {
                        rig: rig.to_string(),
                        t_ns: m.t_impact_ns,
                        log_time_ns: now,
                        ball_position_m: self.ball_position_m,
                        ball_radius_m: self.ball_radius_m,
                        club: m.state,
                    });
                }
            }
            Event::Launch(mut l) => {
                l.latency_us = received.elapsed().as_nanos() as f64 / 1e3;
                let data = serde_json::to_vec(&l).unwrap_or_default();
                if let Err(e) = self.launch.put(data.clone()).wait() {
                    tracing::error!("rig {rig}: publishing the launch: {e}");
                }
                self.latency.push(l.latency_us);
                tracing::info!(
                    "rig {rig} shot {} ({}): {:.1} mph, launch {:.1} deg, direction {:.1} deg, backspin {:.0} rpm, sidespin {:.0} rpm ({:.0} us)",
                    l.shot, l.model, l.launch.launch.ball_speed_mph, l.launch.launch.launch_angle_deg,
                    l.launch.launch.launch_direction_deg, l.launch.launch.backspin_rpm, l.launch.launch.sidespin_rpm, l.latency_us
                );
                let now = wall_ns();
                self.record(&self.keys.launch, "LaunchPrediction", now, now, data);
                self.recorder.send(Record::Flush);
            }
            Event::Failed { shot, frame, reason, .. } => {
                tracing::warn!("rig {rig} shot {shot} (frame {frame}): no prediction: {reason}");
                self.recorder.send(Record::Flush);
            }
        }
    }

    fn publish_status(&mut self) {
        let c = &self.p().counts;
        let mut rejected = c.rejected.clone();
        let queue = self.queue_dropped.load(Ordering::Relaxed);
        if queue > 0 {
            rejected.insert("queue_full".into(), queue);
        }
        let status = StatusMessage {
            rig: self.rig.to_string(),
            t_ns: wall_ns(),
            uptime_s: self.started.elapsed().as_secs_f64(),
            samples: c.samples + queue,
            accepted: c.accepted,
            occluded: c.occluded,
            dropped: c.dropped,
            rejected,
            shots: c.shots,
            predictions: c.predictions,
            failed: c.failed.clone(),
            flagged: c.flagged.clone(),
            latency_p50_us: self.latency.quantile(0.5),
            latency_p99_us: self.latency.quantile(0.99),
            recorder_dropped: self.recorder.dropped(),
        };
        let data = serde_json::to_vec(&status).unwrap_or_default();
        if let Err(e) = self.status.put(data.clone()).wait() {
            tracing::warn!("publishing status: {e}");
        }
        self.record(&self.keys.status, "StatusMessage", status.t_ns, status.t_ns, data);
    }
}
