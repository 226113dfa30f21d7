//! What a replay reads, an item at a time in the input's order, and what it knows of the input before it starts
//! (its [`ReplayIndex`]): a replay holds one item and the index, never the input, so its memory does not grow
//! with the file. A file is read twice: once for the index (the rigs and their first capture time, the recorded
//! predictions' hashes and latencies, the stored configuration, the damage), then item by item as it replays.

use std::collections::{BTreeMap, HashMap};

use sha2::{Digest, Sha256};

use crate::daemon::DaemonError;
use crate::wire::{BallSampleMsg, ClubChange, ClubheadSampleMsg, ShotLabels};

/// One thing a replay reads.
#[derive(Debug, Clone)]
pub enum Item {
    /// A clubhead sample and when it was received (the recording's log time; a JSONL sample's `t_ns`; none for
    /// a capture, whose samples are stamped as they are replayed).
    Sample { msg: ClubheadSampleMsg, log_time_ns: Option<u64> },
    /// A tracked ball's sample and its bytes (`mocap/<rig>/ball`, or a ball line of a JSONL file).
    Ball { ball: BallSampleMsg, payload: Vec<u8> },
    /// Session labels as recorded (`golf/<rig>/session`).
    Labels { rig: String, labels: ShotLabels },
    /// A club switched by a put (`golf/<rig>/club`, recorded as a `ClubChange` from a put).
    ClubPut { rig: String, change: ClubChange },
    /// A synthetic rig's recorded truth (`sim/<rig>/truth`) and its bytes.
    Truth { rig: String, t_impact_ns: u64, payload: Vec<u8> },
    /// A recorded sample that does not parse (damage the index pass, which reads samples by their topic and
    /// times only, does not see): why.
    Unreadable(String),
}

/// A rig's samples in the input.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RigSpan {
    pub samples: u64,
    /// The earliest capture time among them (ns).
    pub first_t_ns: u64,
}

/// The most rig names an index keeps apart; the samples of any more are counted in `other_rig_samples`.
pub const MAX_INDEXED_RIGS: usize = 1024;

/// Skipped lines whose reason is kept.
pub const KEPT_SKIPPED_LINES: usize = 100;

/// What a replay knows of its input before it starts.
#[derive(Debug, Clone, Default)]
pub struct ReplayIndex {
    /// Each rig's samples.
    pub rigs: BTreeMap<String, RigSpan>,
    /// Samples of rigs beyond [`MAX_INDEXED_RIGS`] names.
    pub other_rig_samples: u64,
    /// The log time of the first sample, in the input's order.
    pub first_log_time_ns: Option<u64>,
    /// The SHA-256 of each recorded prediction's bytes (under the current model names), in order.
    pub recorded_launches: Vec<[u8; 32]>,
    /// Per recorded prediction, whether it was made before predictions carried their uncertainty
    /// (`LaunchPrediction` version 1): it is compared with the replay's without it.
    pub recorded_before_uncertainty: Vec<bool>,
    /// Per recorded prediction, whether it was made before predictions said what the estimate bridged
    /// (`LaunchPrediction` version 2 and before: no `impact_timing`, no warnings `frame_gap_before_impact` or
    /// `ball_far_from_address`): it is compared with the replay's without them.
    pub recorded_before_impact_timing: Vec<bool>,
    /// Former model names the recorded predictions carried, each with the name it is compared under
    /// (`impact::registry::FORMER_NAMES`): `(former, current)`, each pair once.
    pub renamed_models: Vec<(String, String)>,
    /// Recorded latency per (rig, shot, model).
    pub recorded_latency_us: HashMap<(String, u64, String), f64>,
    /// The configuration the recording was made with.
    pub config_toml: Option<String>,
    /// What could not be read (empty: the whole file was read).
    pub damage: Vec<String>,
    /// JSONL lines skipped because they are not samples (the first [`KEPT_SKIPPED_LINES`] of them).
    pub skipped_lines: Vec<String>,
    /// JSONL lines skipped, all of them.
    pub skipped: usize,
}

impl ReplayIndex {
    /// Samples of every rig.
    pub fn samples(&self) -> u64 {
        self.rigs.values().map(|r| r.samples).sum::<u64>() + self.other_rig_samples
    }

    /// Counts a sample of `rig` captured at `t_ns` and received at `log_time_ns`.
    pub fn add_sample(&mut self, rig: &str, t_ns: u64, log_time_ns: Option<u64>) {
        if self.samples() == 0 {
            self.first_log_time_ns = log_time_ns;
        }
        let room = self.rigs.len() < MAX_INDEXED_RIGS;
        match self.rigs.get_mut(rig) {
            Some(span) => {
                span.samples += 1;
                span.first_t_ns = span.first_t_ns.min(t_ns);
            }
            None if room => {
                self.rigs.insert(rig.to_string(), RigSpan { samples: 1, first_t_ns: t_ns });
            }
            None => self.other_rig_samples += 1,
        }
    }

    /// Notes a recorded prediction's bytes (already under the current model name) and its latency.
    pub fn add_launch(&mut self, data: &[u8], key: Option<((String, u64, String), f64)>) {
        self.recorded_launches.push(digest(data));
        self.recorded_before_uncertainty.push(!contains(data, b"\"uncertainty\":"));
        self.recorded_before_impact_timing.push(!contains(data, b"\"impact_timing\":"));
        if let Some((key, latency_us)) = key {
            self.recorded_latency_us.insert(key, latency_us);
        }
    }

    /// Recorded predictions made before predictions carried their uncertainty.
    pub fn before_uncertainty(&self) -> usize {
        self.recorded_before_uncertainty.iter().filter(|b| **b).count()
    }

    /// Whether the replay's prediction `l`, published as `bytes`, is the recorded prediction at `index`: byte for
    /// byte, or, where that was recorded before predictions carried their uncertainty, byte for byte without it.
    /// A recording without `impact_timing` (made before version 3, or with nothing to say) is compared with the
    /// replay's prediction without it and without the warnings it explains.
    pub fn reproduces(&self, index: usize, l: &crate::wire::LaunchPrediction, bytes: &[u8]) -> bool {
        let Some(recorded) = self.recorded_launches.get(index) else { return false };
        if *recorded == digest(bytes) {
            return true;
        }
        let before_uncertainty = self.recorded_before_uncertainty.get(index).copied().unwrap_or(false);
        let before_timing = self.recorded_before_impact_timing.get(index).copied().unwrap_or(false);
        if !(before_uncertainty || before_timing) {
            return false;
        }
        let mut without = l.clone();
        if before_uncertainty {
            without.delivery.uncertainty = None;
            without.launch.uncertainty = None;
        }
        if before_timing {
            use crate::impact::LaunchWarning;
            without.impact_timing = None;
            without
                .launch
                .warnings
                .retain(|w| !matches!(w, LaunchWarning::FrameGapBeforeImpact | LaunchWarning::BallFarFromAddress));
        }
        serde_json::to_vec(&without).is_ok_and(|b| *recorded == digest(&b))
    }

    /// Notes a JSONL line skipped for `reason` (`where_` names the file and line).
    pub fn skip_line(&mut self, where_: String, reason: &str) {
        self.skipped += 1;
        if self.skipped_lines.len() < KEPT_SKIPPED_LINES {
            self.skipped_lines.push(format!("{where_}: {reason}"));
        }
    }

    /// The latency recorded for the same rig, shot and model (a live measurement a replay cannot make), else 0.
    pub fn recorded_latency(&self, l: &crate::wire::LaunchPrediction) -> f64 {
        self.recorded_latency_us.get(&(l.rig.clone(), l.shot, l.model.clone())).copied().unwrap_or(0.0)
    }
}

/// The SHA-256 of a prediction's bytes: what a replay compares, rather than keeping every recorded prediction.
pub fn digest(bytes: &[u8]) -> [u8; 32] {
    Sha256::digest(bytes).into()
}

/// The items of a replay, in order.
pub type Items<'a> = Box<dyn Iterator<Item = Result<Item, DaemonError>> + Send + 'a>;

/// An input a replay reads: its index, and its items from the start (again at each call: `--loop`).
pub trait ReplaySource {
    fn index(&self) -> std::borrow::Cow<'_, ReplayIndex>;
    fn items(&self) -> Result<Items<'_>, DaemonError>;
}

/// Whether `needle` occurs in `data` (a recorded message's bytes, searched as written).
pub(super) fn contains(data: &[u8], needle: &[u8]) -> bool {
    data.windows(needle.len()).any(|w| w == needle)
}
