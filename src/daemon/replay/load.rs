//! Reading the inputs of a replay: an MCAP recording (samples, recorded predictions, configuration) or a JSONL
//! file of samples.

use std::collections::HashMap;
use std::path::Path;

use crate::daemon::DaemonError;
use crate::wire::{keys, ClubheadSampleMsg, LaunchPrediction};

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
    /// Recorded latency per (rig, shot).
    pub recorded_latency_us: HashMap<(String, u64, String), f64>,
    /// Session labels as recorded (`golf/<rig>/session`): `(i, rig, labels)` label that rig's shots from sample
    /// `i` of `samples` on.
    pub labels: Vec<(usize, String, crate::wire::ShotLabels)>,
    /// A synthetic rig's recorded truths (`sim/<rig>/truth`): `(i, rig, t_impact_ns, payload)`, recorded again by a
    /// replay's recording before sample `i`.
    pub truths: Vec<(usize, String, u64, Vec<u8>)>,
    /// The configuration the recording was made with.
    pub config_toml: Option<String>,
    /// What could not be read (empty: the whole file was read): a replay over a damaged file reproduces
    /// nothing byte for byte.
    pub damage: Vec<String>,
    /// JSONL lines skipped because they are not samples.
    pub skipped_lines: Vec<String>,
}

pub(crate) fn read_file(path: &Path) -> Result<Vec<u8>, DaemonError> {
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
                        input.log_time_ns.push(msg.t_ns);
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
    let scan = crate::daemon::recording::reader::scan(&bytes, crate::daemon::recording::reader::OnDamage::Stop);
    let mut input = ReplayInput { damage: scan.problems(), ..ReplayInput::default() };
    input.config_toml =
        scan.metadata.iter().find(|(n, _)| n == "session").and_then(|(_, m)| m.get("config_toml").cloned());
    for message in &scan.messages {
        let Some(channel) = scan.channels.get(&message.channel_id) else { continue };
        let topic = channel.topic.trim_start_matches('/');
        if keys::rig_of_clubhead(topic).is_some() {
            match serde_json::from_slice::<ClubheadSampleMsg>(&message.data) {
                Ok(msg) => {
                    input.log_time_ns.push(message.log_time);
                    input.samples.push(msg);
                }
                Err(e) => {
                    input.damage.push(format!("a recorded sample at log time {} does not parse: {e}", message.log_time))
                }
            }
        } else if let Some(rig) = keys::rig_of_truth(topic) {
            match serde_json::from_slice::<crate::wire::TruthMessage>(&message.data) {
                Ok(t) => input.truths.push((input.samples.len(), rig.to_string(), t.t_impact_ns, message.data.clone())),
                Err(e) => {
                    input.damage.push(format!("a recorded truth at log time {} does not parse: {e}", message.log_time))
                }
            }
        } else if let Some(rig) = keys::rig_of_session(topic) {
            match crate::wire::ShotLabels::parse(&message.data) {
                Ok(l) => input.labels.push((input.samples.len(), rig.to_string(), l)),
                Err(e) => {
                    input.damage.push(format!("recorded labels at log time {} do not parse: {e}", message.log_time))
                }
            }
        } else if keys::rig_of_launch(topic).is_some() {
            if let Ok(l) = serde_json::from_slice::<LaunchPrediction>(&message.data) {
                input.recorded_latency_us.insert((l.rig.clone(), l.shot, l.model.clone()), l.latency_us);
            }
            input.recorded_launches.push(message.data.clone());
        }
    }
    Ok(input)
}
