//! The daemon and its tools: zenoh in and out, MCAP recording, replay, a synthetic rig, Open Connect to golf
//! simulators and from launch monitors, the Foxglove live view. The only code that touches tokio, zenoh or mcap.

pub mod bridges;
pub mod bus;
pub mod clock;
pub mod config;
pub mod demo;
pub mod inputs;
pub mod live;
pub mod peer_log;
pub mod recording;
pub mod replay;
pub mod sim;
pub mod stats;

pub use config::DaemonConfig;
pub use recording::read_error::ReadError;
// The configuration's parts under their paths before they became `config/`'s files.
pub use config::{
    club as config_club, club_dirs as config_club_dirs, flight as config_flight, pose as config_pose, web as config_web,
};
pub use live::{run, RunOptions, RunSummary};

/// Errors of the daemon layer.
#[derive(Debug, thiserror::Error)]
pub enum DaemonError {
    #[error("{origin}: {}", .source.message())]
    ConfigSyntax {
        /// `config`, or which configuration (the one stored in a recording).
        origin: String,
        #[source]
        source: Box<toml::de::Error>,
    },
    #[error("config field `{field}` {reason}")]
    Config { field: String, reason: String },
    /// A rig's club, soil or models (`field` names which, or the `[rig.clubs]` body) that cannot be set up.
    #[error("config field `{field}` {source}")]
    RigClub {
        field: String,
        #[source]
        source: config::club::RigClubError,
    },
    /// A rig's `input.markers` file that cannot be read or holds no marker set.
    #[error("config field `{field}` {source}")]
    Markers {
        field: String,
        #[source]
        source: inputs::config::MarkerFileError,
    },
    /// A rig's `[rig.conditions]` that no ball flies in.
    #[error("config field `{field}` {source}")]
    Conditions {
        field: String,
        #[source]
        source: config::flight::ConditionsConfigError,
    },
    /// A rig's `[rig.labels]` that no put on `golf/<rig>/session` could carry.
    #[error("config field `{field}` {source}")]
    Labels {
        field: String,
        #[source]
        source: crate::wire::LabelsError,
    },
    #[error("{what}: {source}")]
    Io {
        what: String,
        #[source]
        source: std::io::Error,
    },
    #[error(transparent)]
    Output(#[from] crate::output_file::OutputError),
    #[error("zenoh: {0}")]
    Zenoh(#[source] zenoh::Error),
    #[error("recording {path}: {source}")]
    Mcap {
        path: String,
        #[source]
        source: mcap::McapError,
    },
    /// A file the replay (or a recording's reader) cannot read on.
    #[error(transparent)]
    Read(#[from] ReadError),
    #[error("recording {path}: the writer thread panicked")]
    WriterPanicked { path: String },
    /// Another daemon serves the rig (its liveliness token is there): this one refuses to serve it too.
    #[error(
        "rig {rig} is already served by {by}: refusing to serve it too (every shot would be predicted twice); \
         stop that daemon, or start this one with --take-over to hand the rig over"
    )]
    RigServed { rig: String, by: String },
    /// `--take-over` that could not take the rig over.
    #[error("rig {rig} is served by {by}, and --take-over cannot take it over: {reason}")]
    TakeOver { rig: String, by: String, reason: &'static str },
    #[error("rig name `{0}` must be letters, digits, _ or -")]
    BadRigName(String),
    /// A synthetic rig's options the sim refuses.
    #[error(transparent)]
    SimOptions(#[from] sim::SimOptionError),
    /// A replay's pace that is not a positive number.
    #[error("replay rate must be a positive number, got {0}")]
    ReplayRate(f64),
    /// A synthetic rig's shot that cannot be swung with its club, not even struck at the face centre.
    #[error("rig {rig}: shot {shot} cannot be swung with this club, not even at the face centre: {source}")]
    SimSwing {
        rig: String,
        shot: u64,
        #[source]
        source: crate::impact::ImpactError,
    },
    #[error("a daemon task failed: {0}")]
    Task(#[source] tokio::task::JoinError),
}

impl DaemonError {
    pub(crate) fn zenoh(e: zenoh::Error) -> Self {
        DaemonError::Zenoh(e)
    }
}
