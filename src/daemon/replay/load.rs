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
    /// JSONL lines skipped because they are not samples (the first [`KEPT_SKIPPED_LINES`] of them).
    pub skipped_lines: Vec<String>,
    /// JSONL lines skipped, all of them.
    pub skipped: usize,
}

impl ReplayInput {
    /// Recorded predictions made before predictions carried their uncertainty (`LaunchPrediction` version 1).
    pub fn recorded_before_uncertainty(&self) -> usize {
        self.recorded_launches.iter().filter(|b| before_uncertainty(b)).count()
    }

    /// The bytes a produced prediction is compared by with the recorded one at `index`: as published, or, where
    /// that was recorded before predictions carried their uncertainty, as published without it (the rest byte for
    /// byte as before).
    pub fn comparable(&self, index: usize, l: &LaunchPrediction, bytes: Vec<u8>) -> Vec<u8> {
        if !self.recorded_launches.get(index).is_some_and(|b| before_uncertainty(b)) {
            return bytes;
        }
        let mut without = l.clone();
        without.delivery.uncertainty = None;
        without.launch.uncertainty = None;
        serde_json::to_vec(&without).unwrap_or(bytes)
    }
}

/// Whether recorded prediction bytes carry no uncertainty (made before version 2 of `LaunchPrediction`).
fn before_uncertainty(data: &[u8]) -> bool {
    !contains(data, b"\"uncertainty\":")
}

/// Skipped lines whose reason is kept.
pub const KEPT_SKIPPED_LINES: usize = 100;

pub use crate::daemon::recording::source::is_mcap;

/// Reads an MCAP recording or a JSONL file of `ClubheadSample`s. A JSONL file is read a line at a time, each
/// at most [`crate::jsonl::MAX_LINE_BYTES`], so `/dev/zero` or a huge file that is not JSONL is an error, not a
/// whole-file read.
pub fn load(path: &Path) -> Result<ReplayInput, DaemonError> {
    use std::io::{BufRead, Read};
    let io = |e| DaemonError::Io { what: format!("reading {}", path.display()), source: e };
    let mut file = std::io::BufReader::new(std::fs::File::open(path).map_err(io)?);
    if !is_mcap(file.fill_buf().map_err(io)?) {
        let mut input = ReplayInput::default();
        let mut line = Vec::new();
        for n in 1.. {
            match crate::jsonl::read_line(&mut file, &mut line, crate::jsonl::MAX_LINE_BYTES) {
                Ok(true) => {}
                Ok(false) => break,
                Err(e) => {
                    return Err(DaemonError::BadSampleLine { path: path.display().to_string(), line: n, source: e })
                }
            }
            let reason = match std::str::from_utf8(&line) {
                Err(e) => format!("not UTF-8 ({e})"),
                Ok(text) if text.trim().is_empty() => continue,
                Ok(text) => match serde_json::from_str::<ClubheadSampleMsg>(text) {
                    Ok(msg) => {
                        input.log_time_ns.push(msg.t_ns);
                        input.samples.push(msg);
                        continue;
                    }
                    Err(e) => match crate::wire::BallSampleMsg::parse(text.as_bytes()) {
                        // A ball line (`impactd import --ball-marker`): taken before the next sample.
                        Ok(ball) => {
                            input.balls.push((input.samples.len(), ball, text.as_bytes().to_vec()));
                            continue;
                        }
                        Err(_) => crate::capped::quote(&e.to_string()).into_owned(),
                    },
                },
            };
            input.skipped += 1;
            if input.skipped_lines.len() < KEPT_SKIPPED_LINES {
                input.skipped_lines.push(format!("{} line {n}: {reason}", path.display()));
            }
        }
        return Ok(input);
    }
    // A regular file is read a record at a time; a pipe that starts with the magic is read into memory (capped).
    use crate::daemon::recording::source::{Opened, MAX_STREAMED_RECORDING_BYTES};
    let opened = if file.get_ref().metadata().map_err(io)?.is_file() {
        drop(file);
        Opened::open(path)?
    } else {
        let mut bytes = Vec::new();
        file.take(MAX_STREAMED_RECORDING_BYTES + 1).read_to_end(&mut bytes).map_err(io)?;
        if bytes.len() as u64 > MAX_STREAMED_RECORDING_BYTES {
            return Err(DaemonError::StreamTooLarge {
                path: path.display().to_string(),
                limit_bytes: MAX_STREAMED_RECORDING_BYTES,
            });
        }
        Opened::Bytes(bytes)
    };
    let mut input = ReplayInput::default();
    let mut damage = Vec::new();
    let on_damage = crate::daemon::recording::reader::OnDamage::Stop;
    let scan = crate::daemon::recording::stream::read_opened(opened, path, on_damage, |_, channel, message| {
        let Some(channel) = channel else { return };
        let topic = channel.topic.trim_start_matches('/');
        if keys::rig_of_clubhead(topic).is_some() {
            match serde_json::from_slice::<ClubheadSampleMsg>(&message.data) {
                Ok(msg) => {
                    input.log_time_ns.push(message.log_time);
                    input.samples.push(msg);
                }
                Err(e) => {
                    damage.push(format!("a recorded sample at log time {} does not parse: {e}", message.log_time))
                }
            }
        } else if keys::rig_of_ball(topic).is_some() {
            match crate::wire::BallSampleMsg::parse(&message.data) {
                Ok(b) => input.balls.push((input.samples.len(), b, message.data)),
                Err(e) => {
                    damage.push(format!("a recorded ball sample at log time {} does not parse: {e}", message.log_time))
                }
            }
        } else if let Some(rig) = keys::rig_of_truth(topic) {
            match serde_json::from_slice::<crate::wire::TruthMessage>(&message.data) {
                Ok(t) => input.truths.push((input.samples.len(), rig.to_string(), t.t_impact_ns, message.data)),
                Err(e) => damage.push(format!("a recorded truth at log time {} does not parse: {e}", message.log_time)),
            }
        } else if let Some(rig) = keys::rig_of_session(topic) {
            match crate::wire::ShotLabels::parse(&message.data) {
                Ok(l) => input.labels.push((input.samples.len(), rig.to_string(), l)),
                Err(e) => damage.push(format!("recorded labels at log time {} do not parse: {e}", message.log_time)),
            }
        } else if let Some(rig) = keys::rig_of_club(topic) {
            match serde_json::from_slice::<crate::wire::ClubChange>(&message.data) {
                Ok(c) if c.source == crate::wire::ClubSource::Put => {
                    input.club_puts.push((input.samples.len(), rig.to_string(), c))
                }
                Ok(_) => {}
                Err(e) => input
                    .damage
                    .push(format!("a recorded club change at log time {} does not parse: {e}", message.log_time)),
            }
        } else if keys::rig_of_launch(topic).is_some() {
            let mut data = message.data;
            if let Ok(l) = serde_json::from_slice::<LaunchPrediction>(&data) {
                if let Some(renamed) = under_current_name(&data, &l.model) {
                    data = renamed.0;
                    if !input.renamed_models.contains(&renamed.1) {
                        input.renamed_models.push(renamed.1);
                    }
                }
                input.recorded_latency_us.insert((l.rig.clone(), l.shot, l.model.clone()), l.latency_us);
            }
            input.recorded_launches.push(data);
        }
    })?;
    input.damage = scan.problems();
    input.damage.extend(damage);
    input.config_toml =
        scan.metadata.iter().find(|(n, _)| n == "session").and_then(|(_, m)| m.get("config_toml").cloned());
    Ok(input)
}

/// A recorded prediction published under a former name of its model (`model`, as read, is the current name), as
/// it is published today: the same bytes with the name replaced, and `(former, current)`. `None` when it carries
/// the current name. The bytes are compared as they were written, so the name is replaced in them, not
/// re-serialized.
fn under_current_name(data: &[u8], model: &str) -> Option<(Vec<u8>, (String, String))> {
    let current = format!("\"model\":\"{model}\"");
    if contains(data, current.as_bytes()) {
        return None;
    }
    crate::impact::registry::FORMER_NAMES.iter().filter(|(_, c)| *c == model).find_map(|(former, _)| {
        let field = format!("\"model\":\"{former}\"");
        let at = data.windows(field.len()).position(|w| w == field.as_bytes())?;
        let mut out = Vec::with_capacity(data.len());
        out.extend_from_slice(&data[..at]);
        out.extend_from_slice(current.as_bytes());
        out.extend_from_slice(&data[at + field.len()..]);
        Some((out, (former.to_string(), model.to_string())))
    })
}

fn contains(data: &[u8], needle: &[u8]) -> bool {
    data.windows(needle.len()).any(|w| w == needle)
}
