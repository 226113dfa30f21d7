//! Reading the inputs of a replay: an MCAP recording (samples, recorded predictions, configuration) or a JSONL
//! file of samples.

use std::collections::HashMap;
use std::io::BufRead;
use std::path::Path;

use crate::daemon::DaemonError;
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

pub(crate) fn mcap_err(path: &Path, e: impl std::fmt::Display) -> DaemonError {
    DaemonError::Mcap { path: path.display().to_string(), reason: e.to_string() }
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
        for (i, line) in bytes.lines().enumerate() {
            let line = line.map_err(|e| DaemonError::Io { what: format!("reading {}", path.display()), source: e })?;
            if line.trim().is_empty() {
                continue;
            }
            let msg: ClubheadSampleMsg = serde_json::from_str(&line).map_err(|e| DaemonError::BadSampleLine {
                path: path.display().to_string(),
                line: i + 1,
                reason: e.to_string(),
            })?;
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
        } else if keys::rig_of_launch(topic).is_some() {
            if let Ok(l) = serde_json::from_slice::<LaunchPrediction>(&message.data) {
                input.recorded_latency_us.insert((l.rig.clone(), l.shot, l.model.clone()), l.latency_us);
            }
            input.recorded_launches.push(message.data.into_owned());
        }
    }
    Ok(input)
}
