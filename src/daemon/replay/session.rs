//! A whole replay as `impactd replay` runs it: the configuration, the pace, publishing and recording the
//! predictions, and the comparison with the recorded ones.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use zenoh::Wait;

use super::{replay, ReplayInput, ReplayStats};
use crate::daemon::config::RigConfig;
use crate::daemon::recorder::{Record, Recorder};
use crate::daemon::{wall_ns, DaemonConfig, DaemonError};
use crate::pipeline::{Event, RigSetup};
use crate::wire::{self, keys};

/// How to replay.
#[derive(Debug, Clone, Default)]
pub struct ReplayOptions {
    /// Replay at this multiple of real time (`None`: as fast as possible).
    pub rate: Option<f64>,
    /// Record the replay to this new MCAP file.
    pub output: Option<PathBuf>,
}

/// What a replay did, and whether it reproduced the recorded predictions.
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
}

impl ReplayReport {
    /// Whether every recorded prediction was reproduced byte for byte (true when none was recorded).
    pub fn reproduces_recording(&self) -> bool {
        self.recorded == 0 || (self.reproduced == self.recorded && self.produced == self.recorded)
    }
}

/// The configuration of a replay: the file at `path`, else the one stored in the recording, else the default
/// with one rig per rig name found in the samples.
pub fn resolve_config(input: &ReplayInput, path: Option<&Path>) -> Result<(DaemonConfig, Vec<RigSetup>), DaemonError> {
    match (path, &input.config_toml) {
        (Some(p), _) => DaemonConfig::load(p),
        (None, Some(text)) => DaemonConfig::parse(text).map_err(|e| match e {
            DaemonError::ConfigSyntax(reason) => {
                DaemonError::ConfigSyntax(format!("the configuration stored in the recording: {reason}"))
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

/// Replays `input` through the pipelines of `setups`, publishing the predictions on `session` when given and
/// recording them when asked; `on_event` sees every event (launches with their latency filled in).
pub async fn run(
    input: &ReplayInput,
    config: &DaemonConfig,
    setups: Vec<RigSetup>,
    session: Option<&zenoh::Session>,
    options: &ReplayOptions,
    mut on_event: impl FnMut(&Event, &[u8]),
) -> Result<ReplayReport, DaemonError> {
    if let Some(r) = options.rate {
        if !(r > 0.0) {
            return Err(DaemonError::Input("--rate must be positive".into()));
        }
    }
    let mut publishers = HashMap::new();
    if let Some(s) = session {
        for r in &config.rigs {
            let p = s
                .declare_publisher(keys::launch(&r.name))
                .encoding(wire::encoding("LaunchPrediction"))
                .await
                .map_err(DaemonError::zenoh)?;
            publishers.insert(r.name.clone(), p);
        }
    }
    let recorder = options
        .output
        .as_deref()
        .map(|p| Recorder::create(p, crate::daemon::live::session_metadata(config)))
        .transpose()?;
    let mut produced = Vec::new();
    let start = Instant::now();
    let mut first_t: Option<u64> = None;
    let rate = options.rate;
    let stats = replay(
        input,
        setups,
        |t_ns| {
            if let Some(r) = rate {
                let t0 = *first_t.get_or_insert(t_ns);
                let due = Duration::from_secs_f64((t_ns.saturating_sub(t0)) as f64 * 1e-9 / r);
                if let Some(wait) = due.checked_sub(start.elapsed()) {
                    std::thread::sleep(wait);
                }
            }
        },
        |e| match e {
            Event::Launch(l) => {
                let bytes = serde_json::to_vec(l).unwrap_or_default();
                on_event(e, &bytes);
                if let Some(p) = publishers.get(&l.rig) {
                    let _ = p.put(bytes.clone()).wait();
                }
                if let Some(r) = &recorder {
                    let now = wall_ns();
                    r.send(Record::Message {
                        key: keys::launch(&l.rig),
                        type_name: "LaunchPrediction",
                        log_time_ns: now,
                        publish_time_ns: now,
                        data: bytes.clone(),
                    });
                }
                produced.push(bytes);
            }
            other => on_event(other, &[]),
        },
    );
    if let Some(r) = recorder {
        r.finish()?;
    }
    let reproduced = produced.iter().zip(&input.recorded_launches).filter(|(a, b)| a == b).count();
    Ok(ReplayReport {
        stats,
        elapsed_s: start.elapsed().as_secs_f64(),
        produced: produced.len(),
        recorded: input.recorded_launches.len(),
        reproduced,
    })
}
