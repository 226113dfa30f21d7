//! The configuration a replay runs with: the one given, else the one its recording stored, else the default
//! with a rig per rig name in the samples.

use std::path::Path;

use super::items::ReplaySource;
use crate::daemon::config::RigConfig;
use crate::daemon::{DaemonConfig, DaemonError};
use crate::pipeline::RigSetup;

/// The configuration of a replay: the file at `path`, else the one stored in the recording, else the default
/// with one rig per rig name found in the samples.
pub fn resolve_config(
    input: &impl ReplaySource,
    path: Option<&Path>,
) -> Result<(DaemonConfig, Vec<RigSetup>), DaemonError> {
    let index = input.index();
    match (path, &index.config_toml) {
        (Some(p), _) => DaemonConfig::load(p),
        (None, Some(text)) => DaemonConfig::parse(text).map_err(|e| match e {
            DaemonError::ConfigSyntax { source, .. } => {
                DaemonError::ConfigSyntax { origin: "config: the configuration stored in the recording".into(), source }
            }
            other => other,
        }),
        (None, None) => {
            let mut config = DaemonConfig::default();
            if index.other_rig_samples > 0 {
                return Err(DaemonError::Config {
                    field: "rig".into(),
                    reason: format!(
                        "the samples name more than {} rigs: give the ones to replay in a configuration (-c)",
                        super::items::MAX_INDEXED_RIGS
                    ),
                });
            }
            let names: Vec<String> = index.rigs.keys().cloned().collect();
            if !names.is_empty() {
                let template = config.rigs[0].clone();
                config.rigs = names.into_iter().map(|name| RigConfig { name, ..template.clone() }).collect();
            }
            let s = config.setups()?;
            Ok((config, s))
        }
    }
}
