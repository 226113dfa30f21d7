//! A whole replay as `impactd replay` runs it: the configuration, the pace, publishing and recording the
//! predictions, and the comparison with the recorded ones.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::{recorded_latency, ReplayInput, ReplayStats};
use crate::daemon::config::RigConfig;
use crate::daemon::live::sinks::{self, RigPublishers, RigSinks, StatusInputs};
use crate::daemon::recording::writer::session_metadata;
use crate::daemon::recording::writer::{Recorder, RecorderHandle};
use crate::daemon::stats::LatencyWindow;
use crate::daemon::{wall_ns, DaemonConfig, DaemonError};
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
}

impl ReplayReport {
    /// Whether every recorded prediction was reproduced byte for byte (true when none was recorded).
    pub fn reproduces_recording(&self) -> bool {
        !self.damaged && (self.recorded == 0 || (self.reproduced == self.recorded && self.produced == self.recorded))
    }
}

/// The configuration of a replay: the file at `path`, else the one stored in the recording, else the default
/// with one rig per rig name found in the samples.
pub fn resolve_config(input: &ReplayInput, path: Option<&Path>) -> Result<(DaemonConfig, Vec<RigSetup>), DaemonError> {
    match (path, &input.config_toml) {
        (Some(p), _) => DaemonConfig::load(p),
        (None, Some(text)) => DaemonConfig::parse(text).map_err(|e| match e {
            DaemonError::ConfigSyntax { source, .. } => {
                DaemonError::ConfigSyntax { origin: "config: the configuration stored in the recording".into(), source }
            }
            other => other,
        }),
        (None, None) => {
            let mut config = DaemonConfig::default();
            let mut names: Vec<String> = input.samples.iter().map(|s| s.rig.clone()).collect();
            names.sort();
            names.dedup();
            if !names.is_empty() {
                let template = config.rigs[0].clone();
                config.rigs = names.into_iter().map(|name| RigConfig { name, ..template.clone() }).collect();
            }
            let s = config.setups()?;
            Ok((config, s))
        }
    }
}

/// One rig of a replay: its pipeline, its sinks and what its status reports.
struct ReplayRig {
    pipeline: Pipeline,
    sinks: RigSinks,
    latency: LatencyWindow,
    first_t_ns: Option<u64>,
    next_status_ns: u64,
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
/// status, Foxglove poses and scenes). Status goes out once per `status_period_s` of capture time and once at the
/// end. `on_event` sees every event (launches with their latency filled in, and their bytes).
pub async fn run(
    input: &ReplayInput,
    config: &DaemonConfig,
    setups: Vec<RigSetup>,
    session: Option<&zenoh::Session>,
    options: &ReplayOptions,
    mut on_event: impl FnMut(&Event, &[u8]),
) -> Result<ReplayReport, DaemonError> {
    if let Some(r) = options.rate {
        if r.is_nan() || r <= 0.0 {
            return Err(DaemonError::BadOption { option: "--rate", reason: "must be positive" });
        }
    }
    let recorder = options
        .output
        .as_deref()
        .map(|p| Recorder::create(p, session_metadata(config), options.overwrite))
        .transpose()?;
    let handle = recorder.as_ref().map(|r| r.handle()).unwrap_or_else(RecorderHandle::none);
    let mut rigs: BTreeMap<String, ReplayRig> = BTreeMap::new();
    for setup in setups {
        let pipeline = Pipeline::new(setup);
        let name = pipeline.setup.name.clone();
        let publishers = match session {
            Some(s) if options.publish != Publish::Samples => Some(RigPublishers::declare(s, &name).await?),
            _ => None,
        };
        let sinks = RigSinks::new(&pipeline, publishers, handle.clone());
        let first = input.log_time_ns.first().copied().unwrap_or_else(wall_ns);
        sinks.club_change(first, &pipeline.club_change(crate::wire::ClubSource::Config, None));
        rigs.insert(
            name,
            ReplayRig { pipeline, sinks, latency: LatencyWindow::new(1024), first_t_ns: None, next_status_ns: 0 },
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
    let (mut stats, mut produced, mut events) = (ReplayStats::default(), Vec::new(), Vec::with_capacity(8));
    let mut labels = input.labels.iter().peekable();
    let mut truths = input.truths.iter().peekable();
    let mut club_puts = input.club_puts.iter().peekable();
    let mut balls = input.balls.iter().peekable();
    for (i, msg) in input.samples.iter().enumerate() {
        while let Some((_, ball, payload)) = balls.next_if(|(at, ..)| *at <= i) {
            if let Some(rig) = rigs.get_mut(&ball.rig) {
                rig.sinks.ball(input.log_time_ns.get(i).copied().unwrap_or_else(wall_ns), ball.t_ns, payload.clone());
                let _ = rig.pipeline.on_ball((!ball.occluded).then_some(ball.position_m));
            }
        }
        while let Some((_, name, l)) = labels.next_if(|(at, _, _)| *at <= i) {
            if let Some(rig) = rigs.get_mut(name) {
                rig.sinks.labels(input.log_time_ns.get(i).copied().unwrap_or_else(wall_ns), l);
                rig.pipeline.set_labels(l.clone());
            }
        }
        while let Some((_, name, change)) = club_puts.next_if(|(at, ..)| *at <= i) {
            if let (Some(rig), Some(rig_config)) = (rigs.get_mut(name), config.rigs.iter().find(|r| &r.name == name)) {
                let log_time_ns = input.log_time_ns.get(i).copied().unwrap_or_else(wall_ns);
                replay_club_put(rig, rig_config, change, log_time_ns);
            }
        }
        while let Some((_, name, t_impact_ns, payload)) = truths.next_if(|(at, ..)| *at <= i) {
            if let Some(rig) = rigs.get(name) {
                let log_time_ns = input.log_time_ns.get(i).copied().unwrap_or_else(wall_ns);
                rig.sinks.truth(log_time_ns, *t_impact_ns, payload.clone());
            }
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
            publisher.put(serde_json::to_vec(msg).unwrap_or_default()).await.map_err(DaemonError::zenoh)?;
        }
        // The recording's own receive time: a replay's recording has the session's timing, not the replay's.
        let log_time_ns = input.log_time_ns.get(i).copied().unwrap_or_else(wall_ns);
        let sample = msg.to_sample();
        if handle.enabled() {
            rig.sinks.sample(log_time_ns, msg.t_ns, serde_json::to_vec(msg).unwrap_or_default());
        }
        events.clear();
        rig.pipeline.on_body_sample_with(msg.body.as_deref(), &sample, &mut |e| events.push(e));
        for e in events.iter_mut() {
            match e {
                Event::Launch(l) => {
                    l.latency_us = recorded_latency(input, l);
                    stats.predictions += 1;
                    rig.latency.push(l.latency_us);
                    let bytes = rig.sinks.launch(l, log_time_ns);
                    let compared = input.comparable(produced.len(), l, bytes.clone());
                    on_event(e, &bytes);
                    produced.push(compared);
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
                Event::Rejected { .. } => on_event(e, &[]),
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
    }
    // Truths recorded after the last sample.
    for (_, name, t_impact_ns, payload) in truths {
        if let Some(rig) = rigs.get(name) {
            rig.sinks.truth(input.log_time_ns.last().copied().unwrap_or_else(wall_ns), *t_impact_ns, payload.clone());
        }
    }
    for rig in rigs.values() {
        let last = input.samples.iter().enumerate().rev().find(|(_, m)| m.rig == rig.pipeline.setup.name);
        let (t_ns, log_time_ns) =
            last.map_or((0, wall_ns()), |(i, m)| (m.t_ns, input.log_time_ns.get(i).copied().unwrap_or_else(wall_ns)));
        rig.publish_status(t_ns, log_time_ns);
    }
    // The writer finishes once every sink's handle is gone.
    drop(rigs);
    drop(handle);
    if let Some(r) = recorder {
        r.finish()?;
    }
    let reproduced = produced.iter().zip(&input.recorded_launches).filter(|(a, b)| a == b).count();
    Ok(ReplayReport {
        stats,
        elapsed_s: start.elapsed().saturating_sub(paused).as_secs_f64(),
        produced: produced.len(),
        recorded: input.recorded_launches.len(),
        reproduced,
        damaged: !input.damage.is_empty(),
    })
}
