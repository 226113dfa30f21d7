//! A whole replay as `impactd replay` runs it: the configuration, the pace, publishing and recording the
//! predictions, and the comparison with the recorded ones.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use super::items::{Item, ReplaySource};
use super::ReplayStats;
use crate::daemon::clock::Clock;
use crate::daemon::live::sinks::{self, RigPublishers, RigSinks, StatusInputs};
use crate::daemon::recording::writer::session_metadata;
use crate::daemon::recording::writer::{Recorder, RecorderHandle};
use crate::daemon::stats::LatencyWindow;
use crate::daemon::{DaemonConfig, DaemonError};
use crate::pipeline::{Event, Pipeline, RigSetup};

/// How to replay.
#[derive(Debug, Clone, Default)]
pub struct ReplayOptions {
    /// Replay at this multiple of real time (`None`: as fast as possible).
    pub rate: Option<f64>,
    /// Record the replay to this MCAP file.
    pub output: Option<PathBuf>,
    /// Replace `output` if it exists (otherwise an existing file stops the replay).
    pub overwrite: bool,
    /// With a `session`: what the replay puts on zenoh.
    pub publish: Publish,
    /// A switch that pauses the replay before its next sample (`impactd replay --pause`).
    pub pause: Option<std::sync::Arc<super::PauseControl>>,
    /// The samples replayed (default: all).
    pub select: Selection,
    /// The clock that stamps what the input carries no log time for (the system's unless a test drives one).
    pub clock: Clock,
}

/// The samples a replay takes: of these rigs (none named: all), captured within `[from_ns, to_ns)`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Selection {
    pub rigs: Vec<String>,
    pub from_ns: u64,
    pub to_ns: Option<u64>,
}

impl Selection {
    /// Whether the sample is replayed.
    pub fn keeps(&self, msg: &crate::wire::ClubheadSampleMsg) -> bool {
        (self.rigs.is_empty() || self.rigs.contains(&msg.rig))
            && msg.t_ns >= self.from_ns
            && self.to_ns.is_none_or(|to| msg.t_ns < to)
    }
}

/// What a replay with a zenoh session publishes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Publish {
    /// Impacts, launches and status on the daemon's keys, as the daemon would (`--publish`).
    #[default]
    Predictions,
    /// Each clubhead sample on `mocap/<rig>/clubhead`, paced like the replay, so a recording drives another
    /// daemon live (`--publish-samples`).
    Samples,
    /// Both.
    Both,
}

/// What a replay did, and whether it reproduced the recorded predictions. `elapsed_s` leaves out time paused.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReplayReport {
    pub stats: ReplayStats,
    pub elapsed_s: f64,
    /// Predictions made.
    pub produced: usize,
    /// Predictions in the recording.
    pub recorded: usize,
    /// Predictions identical, byte for byte, to the recorded one at the same place.
    pub reproduced: usize,
    /// Part of the recording could not be read: nothing is claimed reproduced.
    pub damaged: bool,
    /// What the replay found it could not read (beside the index's `damage`).
    pub damage: Vec<String>,
}

impl ReplayReport {
    /// Whether every recorded prediction was reproduced byte for byte (true when none was recorded).
    pub fn reproduces_recording(&self) -> bool {
        !self.damaged && (self.recorded == 0 || (self.reproduced == self.recorded && self.produced == self.recorded))
    }
}

/// One rig of a replay: its pipeline, its sinks and what its status reports.
struct ReplayRig {
    pipeline: Pipeline,
    sinks: RigSinks,
    latency: LatencyWindow,
    first_t_ns: Option<u64>,
    next_status_ns: u64,
    /// The capture and receive time of its last sample.
    last: Option<(u64, u64)>,
}

/// A recorded put's club, loaded again from the same preset or file: switched and recorded when its SHA-256 is
/// the recorded one; otherwise the rig keeps its club, says so, and the replay reproduces nothing after it.
fn replay_club_put(
    rig: &mut ReplayRig,
    config: &crate::daemon::config::RigConfig,
    change: &crate::wire::ClubChange,
    log_time_ns: u64,
) {
    match config.prepare_club(&change.club.file, "club") {
        Ok(switch) if switch.club_ref.as_ref() == Some(&change.club) => {
            rig.pipeline.switch_club(switch);
            let now = rig.pipeline.club_change(crate::wire::ClubSource::Put, None);
            rig.sinks.club_change(log_time_ns, &now);
        }
        Ok(switch) => tracing::warn!(
            "rig {}: the recorded club {} is not the file there now (sha256 {}, recorded {}); the club is unchanged",
            change.rig,
            change.club.file,
            switch.club_ref.map(|c| c.sha256).unwrap_or_default(),
            change.club.sha256
        ),
        Err(e) => tracing::warn!("rig {}: the recorded club cannot be loaded: {e}", change.rig),
    }
}

impl ReplayRig {
    /// `t_ns` on the rig's clock (for the uptime), stamped `log_time_ns` (the recording's receive time).
    fn publish_status(&self, t_ns: u64, log_time_ns: u64) {
        let inputs = StatusInputs {
            counts: &self.pipeline.counts,
            queue_dropped: 0,
            latency: &self.latency,
            uptime_s: t_ns.saturating_sub(self.first_t_ns.unwrap_or(t_ns)) as f64 * 1e-9,
            t_ns: log_time_ns,
            unknown_rig_samples: 0,
            rejected_not_recorded: 0,
            recorder_error: self.sinks.recorder().error(),
        };
        let status = sinks::status_message(&self.pipeline.setup.name, inputs, self.sinks.recorder().dropped());
        self.sinks.status(&status);
    }
}

/// Replays `input` through the pipelines of `setups` as the daemon would run them: every rig writes through the
/// daemon's sinks ([`RigSinks`]), so with a `session` the replay publishes impacts, launches and status on the
/// daemon's keys, and with `options.output` it records what `impactd run` records (samples, impacts, launches,
/// status, Foxglove poses and scenes) as it goes. Status goes out once per `status_period_s` of capture time and
/// once at the end. `on_event` sees every event (launches with their latency filled in, and their bytes). The
/// input is read an item at a time: what the replay holds does not grow with it.
pub async fn run(
    input: &impl ReplaySource,
    config: &DaemonConfig,
    setups: Vec<RigSetup>,
    session: Option<&zenoh::Session>,
    options: &ReplayOptions,
    mut on_event: impl FnMut(&Event, &[u8]),
) -> Result<ReplayReport, DaemonError> {
    if let Some(r) = options.rate {
        if r.is_nan() || r <= 0.0 {
            return Err(DaemonError::ReplayRate(r));
        }
    }
    let index = input.index();
    let items = input.items()?;
    let recorder = options
        .output
        .as_deref()
        .map(|p| {
            Recorder::create_waiting(
                p,
                session_metadata(config, &options.clock),
                options.overwrite,
                options.clock.clone(),
            )
        })
        .transpose()?;
    let handle = recorder.as_ref().map(|r| r.handle()).unwrap_or_else(RecorderHandle::none);
    let mut rigs: BTreeMap<String, ReplayRig> = BTreeMap::new();
    for mut setup in setups {
        let publishers = match session {
            Some(s) if options.publish != Publish::Samples => Some(RigPublishers::declare(s, &setup.name).await?),
            _ => None,
        };
        // As the daemon: the prediction's own flight samples the line it publishes and records.
        if publishers.is_some() || handle.enabled() {
            setup.flight_line_step_s = crate::daemon::recording::channels::FLIGHT_LINE_STEP_S;
        }
        let pipeline = Pipeline::new(setup);
        let name = pipeline.setup.name.clone();
        let sinks = RigSinks::new(&pipeline, publishers, handle.clone());
        let first = index.first_log_time_ns.unwrap_or_else(|| options.clock.wall_ns());
        sinks.club_change(first, &pipeline.club_change(crate::wire::ClubSource::Config, None));
        rigs.insert(
            name,
            ReplayRig {
                pipeline,
                sinks,
                latency: LatencyWindow::new(1024),
                first_t_ns: None,
                next_status_ns: 0,
                last: None,
            },
        );
    }
    let mut sample_publishers = BTreeMap::new();
    if let (Some(s), Publish::Samples | Publish::Both) = (session, options.publish) {
        for name in rigs.keys() {
            let publisher = s
                .declare_publisher(crate::wire::keys::clubhead(name))
                .encoding(crate::wire::MessageType::ClubheadSample.encoding())
                .await
                .map_err(DaemonError::zenoh)?;
            // Give a daemon that serves the rig a moment to be found, so the first shot is not put into the void.
            let deadline = Instant::now() + Duration::from_secs(3);
            while Instant::now() < deadline
                && !publisher.matching_status().await.map_err(DaemonError::zenoh)?.matching()
            {
                tokio::time::sleep(Duration::from_millis(20)).await;
            }
            sample_publishers.insert(name.clone(), publisher);
        }
    }
    let period_ns = (config.status_period_s * 1e9) as u64;
    let (start, mut first_t, mut paused) = (Instant::now(), None, Duration::ZERO);
    let (mut stats, mut events) = (ReplayStats::default(), Vec::with_capacity(8));
    let (mut produced, mut reproduced) = (0usize, 0usize);
    let mut pending = Pending::default();
    let mut last_log_time_ns = None;
    let mut damage = Vec::new();
    for item in items {
        let (msg, log_time_ns) = match item? {
            Item::Sample { msg, log_time_ns } => (msg, log_time_ns),
            Item::Unreadable(why) => {
                damage.push(why);
                continue;
            }
            side => {
                pending.push(side);
                if pending.len() > MAX_PENDING {
                    // A run of records with no sample between them: taken now, rather than held.
                    pending.apply(&mut rigs, config, last_log_time_ns, &options.clock);
                }
                continue;
            }
        };
        // What was recorded before this sample is taken at its receive time, as the session took it.
        pending.apply(&mut rigs, config, log_time_ns, &options.clock);
        last_log_time_ns = log_time_ns;
        if !options.select.keeps(&msg) {
            stats.left_out += 1;
            continue;
        }
        stats.samples += 1;
        let Some(rig) = rigs.get_mut(&msg.rig) else {
            stats.unknown_rig += 1;
            continue;
        };
        if let Some(p) = &options.pause {
            paused += p.checkpoint(msg.t_ns).await;
        }
        if let Some(r) = options.rate {
            let t0 = *first_t.get_or_insert(msg.t_ns);
            // A pace too slow for a `Duration` waits for ever rather than panics (the command refuses one).
            let due =
                Duration::try_from_secs_f64(msg.t_ns.saturating_sub(t0) as f64 * 1e-9 / r).unwrap_or(Duration::MAX);
            // Time spent paused does not count: the pace resumes where it stopped.
            if let Some(wait) = due.checked_sub(start.elapsed().saturating_sub(paused)) {
                std::thread::sleep(wait);
            }
        }
        if let Some(publisher) = sample_publishers.get(&msg.rig) {
            publisher.put(serde_json::to_vec(&msg).unwrap_or_default()).await.map_err(DaemonError::zenoh)?;
        }
        // The recording's own receive time: a replay's recording has the session's timing, not the replay's.
        let log_time_ns = log_time_ns.unwrap_or_else(|| options.clock.wall_ns());
        let sample = msg.to_sample();
        if handle.enabled() {
            rig.sinks.sample(log_time_ns, msg.t_ns, serde_json::to_vec(&msg).unwrap_or_default());
        }
        events.clear();
        rig.pipeline.on_body_sample_with(msg.body.as_deref(), &sample, &mut |e| events.push(e));
        for e in events.iter_mut() {
            match e {
                Event::Launch(l) => {
                    l.latency_us = index.recorded_latency(l);
                    stats.predictions += 1;
                    rig.latency.push(l.latency_us);
                    let line = sinks::take_line(l);
                    let bytes = rig.sinks.launch_with_line(l, line, log_time_ns);
                    if index.reproduces(produced, l, &bytes) {
                        reproduced += 1;
                    }
                    on_event(e, &bytes);
                    produced += 1;
                }
                Event::Impact(m) => {
                    rig.sinks.impact(m, log_time_ns);
                    on_event(e, &[]);
                }
                Event::Failed { .. } => {
                    stats.failed += 1;
                    rig.sinks.failed();
                    on_event(e, &[]);
                }
                Event::Rejected { .. } | Event::ImpactTiming(_) => on_event(e, &[]),
                Event::Missed(_) => {
                    stats.missed += 1;
                    on_event(e, &[]);
                }
                Event::ClubChanged(change) => {
                    rig.sinks.club_change(log_time_ns, change);
                    on_event(e, &[]);
                }
            }
        }
        if handle.enabled() && events.is_empty() && !sample.occluded {
            if let Some(world_from_club) = sinks::world_from_club(&rig.pipeline, &sample) {
                rig.sinks.club_pose(sample.t_ns, log_time_ns, world_from_club);
            }
        }
        let t0 = *rig.first_t_ns.get_or_insert(msg.t_ns);
        if rig.next_status_ns == 0 {
            rig.next_status_ns = t0.saturating_add(period_ns);
        }
        if msg.t_ns >= rig.next_status_ns {
            rig.publish_status(msg.t_ns, log_time_ns);
            rig.next_status_ns = rig.next_status_ns.saturating_add(period_ns);
        }
        rig.last = Some((msg.t_ns, log_time_ns));
    }
    // Truths recorded after the last sample (balls, labels and club puts after it change nothing).
    for (name, t_impact_ns, payload) in pending.truths.drain(..) {
        if let Some(rig) = rigs.get(&name) {
            rig.sinks.truth(last_log_time_ns.unwrap_or_else(|| options.clock.wall_ns()), t_impact_ns, payload);
        }
    }
    // The input ended: each rig's swing in progress, and the step waiting for the frames after its impact.
    for rig in rigs.values_mut() {
        events.clear();
        rig.pipeline.finish(&mut |e| events.push(e));
        for e in &events {
            if let Event::Missed(_) = e {
                stats.missed += 1;
            }
            on_event(e, &[]);
        }
    }
    for rig in rigs.values() {
        let (t_ns, log_time_ns) = rig.last.unwrap_or_else(|| (0, options.clock.wall_ns()));
        rig.publish_status(t_ns, log_time_ns);
    }
    // The writer finishes once every sink's handle is gone.
    drop(rigs);
    drop(handle);
    if let Some(r) = recorder {
        r.finish()?;
    }
    Ok(ReplayReport {
        stats,
        elapsed_s: start.elapsed().saturating_sub(paused).as_secs_f64(),
        produced,
        recorded: index.recorded_launches.len(),
        reproduced,
        damaged: !index.damage.is_empty() || !damage.is_empty(),
        damage,
    })
}

/// Records a replay read between two samples but has not taken yet: each kind in the order it was read.
#[derive(Default)]
struct Pending {
    balls: Vec<(crate::wire::BallSampleMsg, Vec<u8>)>,
    labels: Vec<(String, crate::wire::ShotLabels)>,
    club_puts: Vec<(String, crate::wire::ClubChange)>,
    truths: Vec<(String, u64, Vec<u8>)>,
}

/// The most records held between two samples before they are taken.
const MAX_PENDING: usize = 4096;

impl Pending {
    fn len(&self) -> usize {
        self.balls.len() + self.labels.len() + self.club_puts.len() + self.truths.len()
    }

    fn push(&mut self, item: Item) {
        match item {
            Item::Ball { ball, payload } => self.balls.push((ball, payload)),
            Item::Labels { rig, labels } => self.labels.push((rig, labels)),
            Item::ClubPut { rig, change } => self.club_puts.push((rig, change)),
            Item::Truth { rig, t_impact_ns, payload } => self.truths.push((rig, t_impact_ns, payload)),
            Item::Sample { .. } | Item::Unreadable(_) => {}
        }
    }

    /// Takes what is pending, stamped `log_time_ns` (now on `clock`, when none): the balls, then the labels, the club puts
    /// and the truths.
    fn apply(
        &mut self,
        rigs: &mut BTreeMap<String, ReplayRig>,
        config: &DaemonConfig,
        log_time_ns: Option<u64>,
        clock: &Clock,
    ) {
        let at = || log_time_ns.unwrap_or_else(|| clock.wall_ns());
        for (ball, payload) in self.balls.drain(..) {
            if let Some(rig) = rigs.get_mut(&ball.rig) {
                rig.sinks.ball(at(), ball.t_ns, payload);
                let _ = rig.pipeline.on_ball((!ball.occluded).then_some(ball.position_m));
            }
        }
        for (name, l) in self.labels.drain(..) {
            if let Some(rig) = rigs.get_mut(&name) {
                rig.sinks.labels(at(), &l);
                rig.pipeline.set_labels(l);
            }
        }
        for (name, change) in self.club_puts.drain(..) {
            if let (Some(rig), Some(rig_config)) = (rigs.get_mut(&name), config.rigs.iter().find(|r| r.name == name)) {
                replay_club_put(rig, rig_config, &change, at());
            }
        }
        for (name, t_impact_ns, payload) in self.truths.drain(..) {
            if let Some(rig) = rigs.get(&name) {
                rig.sinks.truth(at(), t_impact_ns, payload);
            }
        }
    }
}
