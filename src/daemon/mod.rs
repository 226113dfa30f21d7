//! The daemon and its tools: zenoh in and out, MCAP recording, replay, a synthetic rig, Open Connect to golf
//! simulators and from launch monitors, the Foxglove live view. The only code that touches tokio, zenoh or mcap.

pub mod bus;
pub mod config;
pub mod demo;
pub mod foxglove;
pub mod foxglove_live;
pub mod live;
pub mod open_connect;
pub mod recorder;
pub mod replay;
pub mod sim;
pub mod stats;

pub use config::DaemonConfig;
pub use live::{run, RunOptions, RunSummary};

/// Errors of the daemon layer.
#[derive(Debug, thiserror::Error)]
pub enum DaemonError {
    #[error("config: {0}")]
    ConfigSyntax(String),
    #[error("config field `{field}` {reason}")]
    Config { field: String, reason: String },
    #[error("{what}: {source}")]
    Io {
        what: String,
        #[source]
        source: std::io::Error,
    },
    #[error("zenoh: {0}")]
    Zenoh(String),
    #[error("recording {path}: {reason}")]
    Mcap { path: String, reason: String },
    #[error("{0}")]
    Input(String),
}

impl DaemonError {
    pub(crate) fn zenoh(e: impl std::fmt::Display) -> Self {
        DaemonError::Zenoh(e.to_string())
    }
}

/// Nanoseconds since the Unix epoch, now.
pub fn wall_ns() -> u64 {
    std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_nanos() as u64).unwrap_or(0)
}
