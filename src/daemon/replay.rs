//! Offline tools over recordings: `impactd replay`, `impactd info`, `impactd recover`.
//!
//! Replay feeds the recorded clubhead samples, in file order (each rig's arrival order), through the same pure
//! pipeline as the daemon, so it reproduces the recorded predictions byte for byte. `latency_us` is a live
//! measurement: a replay carries the value recorded for the same rig and shot (0 for samples from JSONL).

use std::collections::{BTreeMap, HashMap};
use std::io::BufRead;
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
}

fn mcap_err(path: &Path, e: impl std::fmt::Display) -> DaemonError {
    DaemonError::Mcap { path: path.display().to_string(), reason: e.to_string() }
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
        for (i, line) in bytes.lines().enumerate() {
            let line = line.map_err(|e| DaemonError::Io { what: format!("reading {}", path.display()), source: e })?;
            if line.trim().is_empty() {
                continue;
            }
            let msg: ClubheadSampleMsg = serde_json::from_str(&line)
                .map_err(|e| DaemonError::Input(format!("{} line {}: {e}", path.display(), i + 1)))?;
            input.samples.push(msg);
        }
        return Ok(input);
    }
    let mut input = ReplayInput::default();
    for record in mcap::read::LinearReader::new_with_options(&bytes, mcap::read::Options::IgnoreEndMagic.into())
        .map_err(|e| mcap_err(path, e))?
    {
        if let Ok(mcap::records::Record::Metadata(m)) = record {
            if m.name == "session" {
                input.config_toml = m.metadata.get("config_toml").cloned();
            }
        }
    }
    let stream = mcap::MessageStream::new_with_options(&bytes, mcap::read::Options::IgnoreEndMagic.into())
        .map_err(|e| mcap_err(path, e))?;
    for message in stream {
        let message = match message {
            Ok(m) => m,
            Err(e) => {
                tracing::warn!("{}: stopped reading at a damaged record ({e}); `impactd recover` salvages files cut off by a crash", path.display());
                break;
            }
        };
        let topic = message.channel.topic.trim_start_matches('/');
        if keys::rig_of_clubhead(topic).is_some() {
            let msg: ClubheadSampleMsg = serde_json::from_slice(&message.data).map_err(|e| mcap_err(path, e))?;
            input.samples.push(msg);
        } else if topic.starts_with("golf/") && topic.ends_with("/launch") {
            if let Ok(l) = serde_json::from_slice::<LaunchPrediction>(&message.data) {
                input.recorded_latency_us.insert((l.rig.clone(), l.shot, l.model.clone()), l.latency_us);
            }
            input.recorded_launches.push(message.data.into_owned());
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

/// A description of a recording for `impactd info`.
pub fn info(path: &Path) -> Result<String, DaemonError> {
    let bytes = read_file(path)?;
    if !is_mcap(&bytes) {
        return Err(DaemonError::Input(format!("{} is not an MCAP file", path.display())));
    }
    let mut counts: BTreeMap<String, (String, u64)> = BTreeMap::new();
    let (mut first, mut last) = (u64::MAX, 0u64);
    let mut damaged = None;
    let mut shots: BTreeMap<String, u64> = BTreeMap::new();
    for message in mcap::MessageStream::new_with_options(&bytes, mcap::read::Options::IgnoreEndMagic.into())
        .map_err(|e| mcap_err(path, e))?
    {
        let m = match message {
            Ok(m) => m,
            Err(e) => {
                damaged = Some(e.to_string());
                break;
            }
        };
        first = first.min(m.log_time);
        last = last.max(m.log_time);
        let schema = m.channel.schema.as_ref().map(|s| s.name.clone()).unwrap_or_default();
        let entry = counts.entry(m.channel.topic.clone()).or_insert((schema, 0));
        entry.1 += 1;
        let topic = m.channel.topic.trim_start_matches('/');
        if let Some(rig) = topic.strip_prefix("golf/").and_then(|t| t.strip_suffix("/launch")) {
            *shots.entry(rig.to_string()).or_default() += 1;
        }
    }
    let mut metadata = Vec::new();
    for record in mcap::read::LinearReader::new_with_options(&bytes, mcap::read::Options::IgnoreEndMagic.into())
        .map_err(|e| mcap_err(path, e))?
        .flatten()
    {
        if let mcap::records::Record::Metadata(m) = record {
            let keys: Vec<String> = m
                .metadata
                .iter()
                .filter(|(k, _)| k.as_str() != "config_toml")
                .map(|(k, v)| format!("{k}={v}"))
                .collect();
            metadata.push(format!("  {}: {}", m.name, keys.join(", ")));
        }
    }
    let complete = mcap::read::footer(&bytes).is_ok() && damaged.is_none();
    let total: u64 = counts.values().map(|c| c.1).sum();
    let mut out = format!("file:      {} ({} bytes)\n", path.display(), bytes.len());
    out += &format!(
        "complete:  {}\n",
        if complete { "yes (summary and footer present)" } else { "no: cut off; run `impactd recover`" }
    );
    if let Some(d) = damaged {
        out += &format!("damaged:   {d}\n");
    }
    if total > 0 {
        out += &format!("duration:  {:.3} s\n", (last - first) as f64 * 1e-9);
    }
    out += &format!("messages:  {total}\n");
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
    Ok(out)
}

/// What `recover` salvaged.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Recovered {
    pub messages: u64,
    /// The input was complete: nothing was lost.
    pub complete: bool,
}

/// Copies every readable message and metadata record of `input` into a new, complete MCAP file.
pub fn recover(input: &Path, output: &Path) -> Result<Recovered, DaemonError> {
    let bytes = read_file(input)?;
    if !is_mcap(&bytes) {
        return Err(DaemonError::Input(format!("{} is not an MCAP file", input.display())));
    }
    let file = std::fs::File::create(output)
        .map_err(|e| DaemonError::Io { what: format!("creating {}", output.display()), source: e })?;
    let mut w = mcap::WriteOptions::new()
        .compression(Some(mcap::Compression::Zstd))
        .profile("")
        .create(std::io::BufWriter::new(file))
        .map_err(|e| mcap_err(output, e))?;
    let mut complete = mcap::read::footer(&bytes).is_ok();
    for record in mcap::read::LinearReader::new_with_options(&bytes, mcap::read::Options::IgnoreEndMagic.into())
        .map_err(|e| mcap_err(input, e))?
    {
        match record {
            Ok(mcap::records::Record::Metadata(m)) => w.write_metadata(&m).map_err(|e| mcap_err(output, e))?,
            Ok(_) => {}
            Err(_) => {
                complete = false;
                break;
            }
        }
    }
    let mut channels: HashMap<u16, u16> = HashMap::new();
    let mut schemas: HashMap<u16, u16> = HashMap::new();
    let mut messages = 0;
    for message in mcap::MessageStream::new_with_options(&bytes, mcap::read::Options::IgnoreEndMagic.into())
        .map_err(|e| mcap_err(input, e))?
    {
        let m = match message {
            Ok(m) => m,
            Err(_) => {
                complete = false;
                break;
            }
        };
        let channel_id = match channels.get(&m.channel.id) {
            Some(id) => *id,
            None => {
                let schema_id = match &m.channel.schema {
                    Some(s) => match schemas.get(&s.id) {
                        Some(id) => *id,
                        None => {
                            let id = w.add_schema(&s.name, &s.encoding, &s.data).map_err(|e| mcap_err(output, e))?;
                            schemas.insert(s.id, id);
                            id
                        }
                    },
                    None => 0,
                };
                let id = w
                    .add_channel(schema_id, &m.channel.topic, &m.channel.message_encoding, &m.channel.metadata)
                    .map_err(|e| mcap_err(output, e))?;
                channels.insert(m.channel.id, id);
                id
            }
        };
        w.write_to_known_channel(
            &mcap::records::MessageHeader {
                channel_id,
                sequence: m.sequence,
                log_time: m.log_time,
                publish_time: m.publish_time,
            },
            &m.data,
        )
        .map_err(|e| mcap_err(output, e))?;
        messages += 1;
    }
    w.finish().map_err(|e| mcap_err(output, e))?;
    Ok(Recovered { messages, complete })
}
