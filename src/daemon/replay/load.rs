//! A replay's input held in memory: an MCAP recording (samples, recorded predictions, configuration) or a JSONL
//! file of samples, read whole.

use std::borrow::Cow;
use std::collections::HashMap;
use std::path::Path;

use super::file::ReplayFile;
use super::items::{Item, Items, ReplayIndex, ReplaySource};
use crate::daemon::DaemonError;
use crate::wire::ClubheadSampleMsg;

/// The inputs of a replay.
#[derive(Debug, Default)]
pub struct ReplayInput {
    /// Samples in arrival order.
    pub samples: Vec<ClubheadSampleMsg>,
    /// When each sample was received (ns since the Unix epoch: the recording's log time; a JSONL sample's
    /// `t_ns`), so a replay's recording keeps the session's timing.
    pub log_time_ns: Vec<u64>,
    /// The recorded predictions' bytes, in order.
    pub recorded_launches: Vec<Vec<u8>>,
    /// Former model names the recorded predictions carried, each with the name it is compared under
    /// (`impact::registry::FORMER_NAMES`): `(former, current)`, each pair once.
    pub renamed_models: Vec<(String, String)>,
    /// Recorded latency per (rig, shot).
    pub recorded_latency_us: HashMap<(String, u64, String), f64>,
    /// Session labels as recorded (`golf/<rig>/session`): `(i, rig, labels)` label that rig's shots from sample
    /// `i` of `samples` on.
    pub labels: Vec<(usize, String, crate::wire::ShotLabels)>,
    /// A tracked ball's samples (`mocap/<rig>/ball`, or ball lines in a JSONL file): `(i, payload)` are taken
    /// before sample `i` of `samples`, in order.
    pub balls: Vec<(usize, crate::wire::BallSampleMsg, Vec<u8>)>,
    /// A synthetic rig's recorded truths (`sim/<rig>/truth`): `(i, rig, t_impact_ns, payload)`, recorded again by a
    /// replay's recording before sample `i`.
    pub truths: Vec<(usize, String, u64, Vec<u8>)>,
    /// Clubs switched by a put (`golf/<rig>/club`, recorded as a `ClubChange` from a put): `(i, rig, change)`
    /// switch that rig's club before sample `i` (a replay loads the same preset or file and checks its hash).
    pub club_puts: Vec<(usize, String, crate::wire::ClubChange)>,
    /// The configuration the recording was made with.
    pub config_toml: Option<String>,
    /// What could not be read (empty: the whole file was read): a replay over a damaged file reproduces
    /// nothing byte for byte.
    pub damage: Vec<String>,
    /// JSONL lines skipped because they are not samples (the first [`super::items::KEPT_SKIPPED_LINES`] of them).
    pub skipped_lines: Vec<String>,
    /// JSONL lines skipped, all of them.
    pub skipped: usize,
}

pub use crate::daemon::recording::source::is_mcap;

/// Reads an MCAP recording or a JSONL file of `ClubheadSample`s into memory (what tests and tools that look at
/// every sample use; `impactd replay` streams the file instead, [`super::ReplayFile`]). It reads the file as a
/// replay does, so the two agree on every message.
pub fn load(path: &Path) -> Result<ReplayInput, DaemonError> {
    let mut recorded_launches = Vec::new();
    let file = ReplayFile::open_with(path, false, |data| recorded_launches.push(data.to_vec()))?;
    let index = file.index().into_owned();
    let mut input = ReplayInput {
        recorded_launches,
        renamed_models: index.renamed_models,
        recorded_latency_us: index.recorded_latency_us,
        config_toml: index.config_toml,
        damage: index.damage,
        skipped_lines: index.skipped_lines,
        skipped: index.skipped,
        ..ReplayInput::default()
    };
    for item in file.items()? {
        let at = input.samples.len();
        match item? {
            Item::Sample { msg, log_time_ns } => {
                input.log_time_ns.push(log_time_ns.unwrap_or(msg.t_ns));
                input.samples.push(msg);
            }
            Item::Ball { ball, payload } => input.balls.push((at, ball, payload)),
            Item::Labels { rig, labels } => input.labels.push((at, rig, labels)),
            Item::ClubPut { rig, change } => input.club_puts.push((at, rig, change)),
            Item::Truth { rig, t_impact_ns, payload } => input.truths.push((at, rig, t_impact_ns, payload)),
            Item::Unreadable(why) => input.damage.push(why),
        }
    }
    Ok(input)
}

impl ReplaySource for ReplayInput {
    fn index(&self) -> Cow<'_, ReplayIndex> {
        let mut index = ReplayIndex {
            renamed_models: self.renamed_models.clone(),
            recorded_latency_us: self.recorded_latency_us.clone(),
            config_toml: self.config_toml.clone(),
            damage: self.damage.clone(),
            skipped_lines: self.skipped_lines.clone(),
            skipped: self.skipped,
            ..ReplayIndex::default()
        };
        for b in &self.recorded_launches {
            index.add_launch(b, None);
        }
        for (i, msg) in self.samples.iter().enumerate() {
            index.add_sample(&msg.rig, msg.t_ns, self.log_time_ns.get(i).copied());
        }
        Cow::Owned(index)
    }

    /// The samples in order, each after the balls, labels, club puts and truths recorded before it, and the
    /// truths after the last one.
    fn items(&self) -> Result<Items<'_>, DaemonError> {
        let mut balls = self.balls.iter().peekable();
        let mut labels = self.labels.iter().peekable();
        let mut puts = self.club_puts.iter().peekable();
        let mut truths = self.truths.iter().peekable();
        let mut queue = std::collections::VecDeque::new();
        let mut i = 0;
        Ok(Box::new(std::iter::from_fn(move || loop {
            if let Some(item) = queue.pop_front() {
                return Some(Ok(item));
            }
            if i > self.samples.len() {
                return None;
            }
            while let Some((_, ball, payload)) = balls.next_if(|(at, ..)| *at <= i) {
                queue.push_back(Item::Ball { ball: ball.clone(), payload: payload.clone() });
            }
            while let Some((_, rig, l)) = labels.next_if(|(at, ..)| *at <= i) {
                queue.push_back(Item::Labels { rig: rig.clone(), labels: l.clone() });
            }
            while let Some((_, rig, change)) = puts.next_if(|(at, ..)| *at <= i) {
                queue.push_back(Item::ClubPut { rig: rig.clone(), change: change.clone() });
            }
            while let Some((_, rig, t_impact_ns, payload)) = truths.next_if(|(at, ..)| *at <= i) {
                queue.push_back(Item::Truth { rig: rig.clone(), t_impact_ns: *t_impact_ns, payload: payload.clone() });
            }
            if let Some(msg) = self.samples.get(i) {
                queue.push_back(Item::Sample { msg: msg.clone(), log_time_ns: self.log_time_ns.get(i).copied() });
            }
            i += 1;
        })))
    }
}
