//! The command line's errors: what a command refuses in its own flags, and the daemon's errors (with their
//! sources) where a command calls the daemon. Commands carry them in `anyhow` to `main`, which prints the chain
//! on one line and exits 2.

use impactd::daemon::DaemonError;

/// Errors of the command-line layer.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// `-m/--mode` that names no zenoh mode.
    #[error("--mode must be peer, client or router, got {0}")]
    BadMode(String),
    /// A flag's value out of its range.
    #[error("{option} {reason}")]
    BadOption { option: &'static str, reason: &'static str },
    /// A synthetic rig's flags the sim refuses.
    #[error(transparent)]
    SimOptions(#[from] impactd::daemon::sim::SimOptionError),
    /// What the daemon refused or failed at, with its sources.
    #[error(transparent)]
    Daemon(#[from] DaemonError),
}

/// `--rate` of a replay: a pace, so a positive number when given.
pub fn positive_rate(rate: Option<f64>) -> Result<(), CliError> {
    match rate {
        Some(r) if r.is_nan() || r <= 0.0 => Err(CliError::BadOption { option: "--rate", reason: "must be positive" }),
        _ => Ok(()),
    }
}
