//! What a put on `golf/<rig>/club` may name, and loading it so that no put can stall the loader: a preset, or a
//! club file that resolves (symbolic links followed) under one of the configured club directories (`[clubs]
//! dirs`); the file is a regular one of bounded size (`equipment::load`), and the club is loaded and its models
//! built on a thread of its own that the loader waits for at most [`LOAD_TIMEOUT`], looking at its stop flag
//! meanwhile, so a load stuck in the kernel (a stalled network filesystem) neither holds up the next put nor the
//! daemon's shutdown.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{sync_channel, RecvTimeoutError};
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::daemon::config::RigConfig;
use crate::pipeline::ClubSwitch;

/// How long a put's club may take to load and build before the loader gives up on it.
pub const LOAD_TIMEOUT: Duration = Duration::from_secs(5);

/// Loads given up on that are still running; while this many are, a put is refused rather than start another.
pub const MAX_ABANDONED_LOADS: usize = 4;

/// How often a waiting loader looks at its stop flag.
const POLL: Duration = Duration::from_millis(50);

/// Why a put's club was not loaded.
#[derive(Debug, thiserror::Error)]
pub enum ClubPutError {
    #[error("club file `{spec}` is not under the club directories ({}); a put names a preset or a file there \
             (`[clubs] dirs`)", list(.dirs))]
    OutsideDirs { spec: String, dirs: Vec<PathBuf> },
    #[error("no club file `{spec}` in the club directories ({})", list(.dirs))]
    NotFound { spec: String, dirs: Vec<PathBuf> },
    #[error("{0}")]
    Club(#[source] crate::daemon::config_club::RigClubError),
    #[error("club `{spec}` not loaded within {} s; given up on", LOAD_TIMEOUT.as_secs())]
    TimedOut { spec: String },
    #[error("{running} earlier club loads have not finished; club `{spec}` is not loaded")]
    TooManyRunning { spec: String, running: usize },
    #[error("the club loader is stopping")]
    Stopping,
    #[error("loading club `{spec}` failed (its thread ended without an answer)")]
    Lost { spec: String },
}

fn list(dirs: &[PathBuf]) -> String {
    if dirs.is_empty() {
        return "none: presets only".into();
    }
    dirs.iter().map(|d| d.display().to_string()).collect::<Vec<_>>().join(", ")
}

/// The club a put names, as the loader loads it: a preset name as it is, a club file as the absolute path it
/// resolves to under one of `dirs` (what the recording's `ClubChange` then names, so a replay finds it).
pub fn resolve(spec: &str, dirs: &[PathBuf]) -> Result<String, ClubPutError> {
    if crate::equipment::presets::find(spec).is_some() && !spec.contains(['/', '\\']) && !spec.ends_with(".toml") {
        return Ok(spec.to_string());
    }
    let path = Path::new(spec);
    let candidates: Vec<PathBuf> =
        if path.is_absolute() { vec![path.to_path_buf()] } else { dirs.iter().map(|d| d.join(path)).collect() };
    let mut found_outside = false;
    for candidate in candidates {
        // Resolving a path looks at it (stat), never opens it: a FIFO does not block here.
        let Ok(resolved) = std::fs::canonicalize(&candidate) else { continue };
        if dirs.iter().any(|d| resolved.starts_with(d)) {
            return Ok(resolved.display().to_string());
        }
        found_outside = true;
    }
    let (spec, dirs) = (crate::capped::quote(spec).into_owned(), dirs.to_vec());
    Err(if found_outside || path.is_absolute() {
        ClubPutError::OutsideDirs { spec, dirs }
    } else {
        ClubPutError::NotFound { spec, dirs }
    })
}

/// Loads and builds `spec` (already resolved) for the rig on a thread of its own, waiting for it at most
/// [`LOAD_TIMEOUT`] and only while `stop` is unset. `running` counts the loads still running, given up on or not.
pub fn prepare(
    config: &RigConfig,
    spec: String,
    running: &Arc<AtomicUsize>,
    stop: &AtomicBool,
) -> Result<ClubSwitch, ClubPutError> {
    let already = running.load(Ordering::Relaxed);
    if already >= MAX_ABANDONED_LOADS {
        return Err(ClubPutError::TooManyRunning { spec, running: already });
    }
    let (tx, rx) = sync_channel(1);
    let (config, thread_spec, count) = (config.clone(), spec.clone(), running.clone());
    count.fetch_add(1, Ordering::Relaxed);
    let spawned = std::thread::Builder::new().name("impactd-club-load".into()).spawn(move || {
        let _ = tx.send(config.prepare_club(&thread_spec, "club"));
        count.fetch_sub(1, Ordering::Relaxed);
    });
    if spawned.is_err() {
        running.fetch_sub(1, Ordering::Relaxed);
        return Err(ClubPutError::Lost { spec });
    }
    let deadline = Instant::now() + LOAD_TIMEOUT;
    loop {
        match rx.recv_timeout(POLL) {
            Ok(result) => return result.map_err(ClubPutError::Club),
            Err(RecvTimeoutError::Disconnected) => return Err(ClubPutError::Lost { spec }),
            Err(RecvTimeoutError::Timeout) if stop.load(Ordering::Relaxed) => return Err(ClubPutError::Stopping),
            Err(RecvTimeoutError::Timeout) if Instant::now() >= deadline => {
                return Err(ClubPutError::TimedOut { spec })
            }
            Err(RecvTimeoutError::Timeout) => {}
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// Presets pass as they are; a file resolves to its absolute path under a club directory, a relative name
    /// is looked up in each directory, and a path elsewhere (also through `..` or a symbolic link) is refused.
    #[test]
    fn a_put_names_a_preset_or_a_file_under_the_club_directories() {
        let clubs = tempfile::tempdir().unwrap();
        let other = tempfile::tempdir().unwrap();
        let dirs = vec![std::fs::canonicalize(clubs.path()).unwrap()];
        std::fs::write(clubs.path().join("mine.toml"), "x").unwrap();
        std::fs::write(other.path().join("theirs.toml"), "x").unwrap();
        assert_eq!(resolve("iron7", &dirs).unwrap(), "iron7");
        let mine = dirs[0].join("mine.toml").display().to_string();
        assert_eq!(resolve("mine.toml", &dirs).unwrap(), mine);
        assert_eq!(resolve(&mine, &dirs).unwrap(), mine);
        let theirs = other.path().join("theirs.toml");
        let e = resolve(theirs.to_str().unwrap(), &dirs).unwrap_err();
        assert!(matches!(e, ClubPutError::OutsideDirs { .. }), "{e}");
        let up = format!("../{}/theirs.toml", other.path().file_name().unwrap().to_str().unwrap());
        assert!(matches!(resolve(&up, &dirs), Err(ClubPutError::OutsideDirs { .. })));
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(&theirs, clubs.path().join("link.toml")).unwrap();
            assert!(matches!(resolve("link.toml", &dirs), Err(ClubPutError::OutsideDirs { .. })));
        }
        assert!(matches!(resolve("nothing.toml", &dirs), Err(ClubPutError::NotFound { .. })));
        assert!(matches!(resolve("/proc/self/fd/1", &dirs), Err(ClubPutError::OutsideDirs { .. })));
        let e = resolve("mine.toml", &[]).unwrap_err().to_string();
        assert!(e.contains("presets only"), "{e}");
    }
}
