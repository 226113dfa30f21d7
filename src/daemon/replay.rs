//! Offline tools over recordings: `impactd replay`, `impactd info`, `impactd recover`.
//!
//! Replay feeds the recorded clubhead samples, in file order (each rig's arrival order), through the same pure
//! pipeline as the daemon, so it reproduces the recorded predictions byte for byte. `latency_us` is a live
//! measurement: a replay carries the value recorded for the same rig and shot (0 for samples from JSONL).

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use super::DaemonError;
use crate::pipeline::{Event, Pipeline, RigSetup};
use crate::wire::{keys, ClubheadSampleMsg, LaunchPrediction};

/// The inputs of a replay.
#[derive(Debug, Default)]
pub struct ReplayInput {
    /// Samples in arrival order.
    pub samples: Vec<ClubheadSampleMsg>,
    /// The recorded predictions' bytes, in order.
    pub recorded_launches: Vec<Vec<u8>>,
    /// Recorded latency per (rig, shot).
    pub recorded_latency_us: HashMap<(String, u64, String), f64>,
    /// The configuration the recording was made with.
    pub config_toml: Option<String>,
    /// What could not be read (empty: the whole file was read): a replay over a damaged file reproduces
    /// nothing byte for byte.
    pub damage: Vec<String>,
    /// JSONL lines skipped because they are not samples.
    pub skipped_lines: Vec<String>,
}

fn read_file(path: &Path) -> Result<Vec<u8>, DaemonError> {
    std::fs::read(path).map_err(|e| DaemonError::Io { what: format!("reading {}", path.display()), source: e })
}

/// Whether the bytes start with the MCAP magic.
pub fn is_mcap(bytes: &[u8]) -> bool {
    bytes.starts_with(mcap::MAGIC)
}

/// Reads an MCAP recording or a JSONL file of `ClubheadSample`s.
pub fn load(path: &Path) -> Result<ReplayInput, DaemonError> {
    let bytes = read_file(path)?;
    if !is_mcap(&bytes) {
        let mut input = ReplayInput::default();
        for (i, line) in bytes.split(|b| *b == b'\n').enumerate() {
            let reason = match std::str::from_utf8(line) {
                Err(e) => format!("not UTF-8 ({e})"),
                Ok(text) if text.trim().is_empty() => continue,
                Ok(text) => match serde_json::from_str::<ClubheadSampleMsg>(text) {
                    Ok(msg) => {
                        input.samples.push(msg);
                        continue;
                    }
                    Err(e) => e.to_string(),
                },
            };
            input.skipped_lines.push(format!("{} line {}: {reason}", path.display(), i + 1));
        }
        return Ok(input);
    }
    let scan = super::mcap_read::scan(&bytes, super::mcap_read::OnDamage::Stop);
    let mut input = ReplayInput { damage: scan.problems(), ..ReplayInput::default() };
    input.config_toml = scan.metadata.iter().find(|(n, _)| n == "session").and_then(|(_, m)| m.get("config_toml").cloned());
    for message in &scan.messages {
        let Some(channel) = scan.channels.get(&message.channel_id) else { continue };
        let topic = channel.topic.trim_start_matches('/');
        if keys::rig_of_clubhead(topic).is_some() {
            match serde_json::from_slice::<ClubheadSampleMsg>(&message.data) {
                Ok(msg) => input.samples.push(msg),
                Err(e) => input.damage.push(format!("a recorded sample at log time {} does not parse: {e}", message.log_time)),
            }
        } else if topic.starts_with("golf/") && topic.ends_with("/launch") {
            if let Ok(l) = serde_json::from_slice::<LaunchPrediction>(&message.data) {
                input.recorded_latency_us.insert((l.rig.clone(), l.shot, l.model.clone()), l.latency_us);
            }
            input.recorded_launches.push(message.data.clone());
        }
    }
    Ok(input)
}

/// What a replay did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReplayStats {
    pub samples: u64,
    pub unknown_rig: u64,
    pub predictions: u64,
    pub failed: u64,
}

/// Runs the pipelines over the samples; `on_event` sees every event (launches with their latency filled in).
pub fn replay(
    input: &ReplayInput,
    setups: Vec<RigSetup>,
    mut pace: impl FnMut(u64),
    mut on_event: impl FnMut(&Event),
) -> ReplayStats {
    let mut pipelines: HashMap<String, Pipeline> =
        setups.into_iter().map(|s| (s.name.clone(), Pipeline::new(s))).collect();
    let mut stats = ReplayStats::default();
    let mut events = Vec::with_capacity(8);
    for msg in &input.samples {
        stats.samples += 1;
        let Some(p) = pipelines.get_mut(&msg.rig) else {
            stats.unknown_rig += 1;
            continue;
        };
        pace(msg.t_ns);
        events.clear();
        p.on_sample(&msg.to_sample(), &mut events);
        for e in events.iter_mut() {
            match e {
                Event::Launch(l) => {
                    l.latency_us = input
                        .recorded_latency_us
                        .get(&(l.rig.clone(), l.shot, l.model.clone()))
                        .copied()
                        .unwrap_or(0.0);
                    stats.predictions += 1;
                }
                Event::Failed { .. } => stats.failed += 1,
                _ => {}
            }
            on_event(e);
        }
    }
    stats
}

/// How a replay's predictions compare with the recorded ones.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Verdict {
    /// Nothing was recorded to compare with.
    NothingRecorded,
    /// The whole file was read and every recorded prediction was produced again, byte for byte.
    Identical { predictions: usize },
    /// The whole file was read and the predictions differ.
    Differ { same: usize, recorded: usize, produced: usize },
    /// Part of the file could not be read: no claim of identity is made.
    Damaged { same: usize, recorded: usize, produced: usize },
}

impl Verdict {
    /// Compares `produced` with the recording's predictions, claiming identity only over a file read whole.
    pub fn of(input: &ReplayInput, produced: &[Vec<u8>]) -> Verdict {
        let recorded = input.recorded_launches.len();
        let same = produced.iter().zip(&input.recorded_launches).filter(|(a, b)| a == b).count();
        if !input.damage.is_empty() {
            return Verdict::Damaged { same, recorded, produced: produced.len() };
        }
        if recorded == 0 {
            return Verdict::NothingRecorded;
        }
        if same == recorded && produced.len() == recorded {
            Verdict::Identical { predictions: recorded }
        } else {
            Verdict::Differ { same, recorded, produced: produced.len() }
        }
    }

    /// Replays that reproduce the recording (or had nothing to compare) succeed.
    pub fn success(&self) -> bool {
        matches!(self, Verdict::NothingRecorded | Verdict::Identical { .. })
    }
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Verdict::NothingRecorded => write!(f, "no recorded predictions to compare with"),
            Verdict::Identical { predictions } => {
                write!(f, "{predictions} of {predictions} recorded predictions reproduced byte for byte")
            }
            Verdict::Differ { same, recorded, produced } => {
                write!(f, "{same} of {recorded} recorded predictions reproduced ({produced} produced)")
            }
            Verdict::Damaged { same, recorded, produced } => write!(
                f,
                "the recording is damaged: {produced} predictions over its readable part, {same} equal to the \
                 {recorded} recorded predictions that could be read; not a reproduction"
            ),
        }
    }
}

/// A description of a recording for `impactd info`, and whether it could be read whole.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Info {
    pub text: String,
    /// Finished and undamaged.
    pub intact: bool,
}

/// Describes a recording: channels, counts, duration, shots, metadata, and anything it could not read.
pub fn info(path: &Path) -> Result<Info, DaemonError> {
    let bytes = read_file(path)?;
    if !is_mcap(&bytes) {
        return Err(DaemonError::Input(format!("{} is not an MCAP file", path.display())));
    }
    let scan = super::mcap_read::scan(&bytes, super::mcap_read::OnDamage::Stop);
    let mut counts: BTreeMap<String, (String, u64)> = BTreeMap::new();
    let (mut first, mut last) = (u64::MAX, 0u64);
    let mut shots: BTreeMap<String, u64> = BTreeMap::new();
    for m in &scan.messages {
        first = first.min(m.log_time);
        last = last.max(m.log_time);
        let (topic, schema) = match scan.channels.get(&m.channel_id) {
            Some(c) => (c.topic.clone(), scan.schemas.get(&c.schema_id).map(|s| s.name.clone()).unwrap_or_default()),
            None => (format!("(unknown channel {})", m.channel_id), String::new()),
        };
        if let Some(rig) = topic.trim_start_matches('/').strip_prefix("golf/").and_then(|t| t.strip_suffix("/launch")) {
            *shots.entry(rig.to_string()).or_default() += 1;
        }
        counts.entry(topic).or_insert((schema, 0)).1 += 1;
    }
    let metadata: Vec<String> = scan
        .metadata
        .iter()
        .map(|(name, m)| {
            let keys: Vec<String> =
                m.iter().filter(|(k, _)| k.as_str() != "config_toml").map(|(k, v)| format!("{k}={v}")).collect();
            format!("  {name}: {}", keys.join(", "))
        })
        .collect();
    let total: u64 = counts.values().map(|c| c.1).sum();
    let mut out = format!("file:      {} ({} bytes)\n", path.display(), bytes.len());
    out += &format!(
        "complete:  {}\n",
        if scan.intact() { "yes (summary and footer present)" } else { "no: cut off or damaged; run `impactd recover`" }
    );
    for p in scan.problems() {
        out += &format!("damaged:   {p}\n");
    }
    if total > 0 {
        out += &format!("duration:  {:.3} s\n", (last - first) as f64 * 1e-9);
    }
    out += &format!("messages:  {total}{}\n", if scan.intact() { "" } else { " (readable)" });
    out += "channels:\n";
    for (topic, (schema, n)) in &counts {
        out += &format!("  {topic:<40} {schema:<32} {n:>9}\n");
    }
    out += "shots:\n";
    for (rig, n) in &shots {
        out += &format!("  {rig}: {n} predicted\n");
    }
    if !metadata.is_empty() {
        out += "metadata:\n";
        out += &metadata.join("\n");
        out.push('\n');
    }
    Ok(Info { text: out, intact: scan.intact() })
}

pub use super::salvage::{recover, Recovered};
