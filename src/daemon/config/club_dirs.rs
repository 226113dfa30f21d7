//! `[clubs]` of `impactd.toml`: the directories a put on `golf/<rig>/club` may name club files in (presets are
//! always allowed), resolved against the configuration file's directory.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::daemon::DaemonError;

/// `[clubs]`: where a put may name club files. A put names a preset, or a path that resolves (symbolic links
/// followed) under one of `dirs`; a relative path is looked up in each in turn.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClubsConfig {
    /// Directories, relative ones taken from the configuration file's directory. Absent: the configuration
    /// file's directory and `./clubs`; empty: presets only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dirs: Option<Vec<String>>,
}

/// The directories a put may name club files in, absolute: `[clubs] dirs` (relative ones from `config_dir`, the
/// configuration file's directory, else the working directory), by default that directory and `./clubs`. A
/// configured directory that is not one is an error naming it; a default one that does not exist is left out.
pub fn club_dirs(clubs: Option<&ClubsConfig>, config_dir: Option<&Path>) -> Result<Vec<PathBuf>, DaemonError> {
    let cwd = std::env::current_dir()
        .map_err(|e| DaemonError::Io { what: "finding the working directory".into(), source: e })?;
    let base = config_dir.map(Path::to_path_buf).unwrap_or_else(|| cwd.clone());
    let Some(dirs) = clubs.and_then(|c| c.dirs.as_ref()) else {
        let defaults = config_dir.map(Path::to_path_buf).into_iter().chain([cwd.join("clubs")]);
        return Ok(defaults.filter_map(|d| std::fs::canonicalize(d).ok()).filter(|d| d.is_dir()).collect());
    };
    dirs.iter()
        .enumerate()
        .map(|(i, d)| {
            let path = base.join(d);
            match std::fs::canonicalize(&path) {
                Ok(p) if p.is_dir() => Ok(p),
                Ok(_) => Err(invalid(format!("clubs.dirs[{i}]"), format!("`{d}` is not a directory"))),
                Err(e) => Err(invalid(format!("clubs.dirs[{i}]"), format!("`{d}` ({}): {e}", path.display()))),
            }
        })
        .collect()
}

fn invalid(field: String, reason: impl Into<String>) -> DaemonError {
    DaemonError::Config { field, reason: reason.into() }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// By default the configuration file's directory and `./clubs` (those that exist); configured ones relative
    /// to the configuration file, one that is not a directory refused naming it; `[]` for presets only.
    #[test]
    fn club_directories_are_the_configured_ones_else_the_config_files_and_clubs() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("mine")).unwrap();
        let here = std::fs::canonicalize(dir.path()).unwrap();
        let dirs = |text: &str| {
            let clubs: Option<ClubsConfig> = (!text.is_empty()).then(|| toml::from_str(text).unwrap());
            club_dirs(clubs.as_ref(), Some(&here))
        };
        assert_eq!(dirs("").unwrap().first(), Some(&here));
        assert_eq!(dirs("dirs = [\"mine\"]\n").unwrap(), [here.join("mine")]);
        assert!(dirs("dirs = []\n").unwrap().is_empty());
        let e = dirs("dirs = [\"nowhere\"]\n").unwrap_err().to_string();
        assert!(e.contains("clubs.dirs[0]") && e.contains("nowhere"), "{e}");
    }
}
