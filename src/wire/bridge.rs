//! Health and traffic of the Open Connect bridges: the client that sends predictions to a golf simulator and
//! the listener that takes measured shots from a launch monitor's connector.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The state of the connection to a simulator.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ConnectionState {
    #[default]
    Connecting,
    Connected,
    /// Waiting to retry (with backoff) after a refused or lost connection.
    Disconnected,
}

/// The simulator's player, from its last code-201 reply.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SimulatorPlayer {
    /// "RH" or "LH".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub handed: Option<String>,
    /// The simulator's club code ("DR", "7I", ...).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub club: Option<String>,
}

/// The simulator client of a rig (Open Connect or OpenGolfSim), in
/// [`StatusMessage`](super::StatusMessage)`.simulator`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SimulatorStatus {
    /// `HOST:PORT` of the simulator.
    pub address: String,
    /// The protocol spoken: `open_connect` or `opengolfsim`.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub protocol: String,
    pub state: ConnectionState,
    /// Connections made so far.
    pub connects: u64,
    /// Shots written to the simulator's socket.
    pub sent: u64,
    /// Shots the simulator answered with a 2xx code (Open Connect) or a `result` (OpenGolfSim).
    pub acknowledged: u64,
    /// Shots answered with a failure code, or whose write failed (never sent again: no duplicates).
    pub failed: u64,
    /// Shots not sent: older than `max_shot_age_s` when the connection came back, or the queue was full.
    pub dropped: u64,
    /// Predictions refused before sending (a zero, non-finite or repeated shot: no ghost shots).
    pub refused: u64,
    pub heartbeats: u64,
    /// The last reply, `"<code> <message>"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub last_reply: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub player: Option<SimulatorPlayer>,
}

/// The Open Connect listener of a rig, in [`StatusMessage`](super::StatusMessage)`.launch_monitor`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct LaunchMonitorStatus {
    /// The listening address.
    pub listen: String,
    /// Connectors connected now.
    pub connections: u64,
    /// Shots published as `MeasuredLaunch`.
    pub shots: u64,
    pub heartbeats: u64,
    /// Shots repeated with the same device and shot number (answered 200, published once).
    pub duplicates: u64,
    /// Messages answered with a failure code and connections closed (`evicted_at_cap`, `handshake_timeout`,
    /// `idle_timeout`), by reason.
    pub rejected: BTreeMap<String, u64>,
    /// Rejected messages and their answers not recorded: over the recording budget.
    #[serde(default)]
    pub traffic_not_recorded: u64,
}

/// The Foxglove live view, in [`StatusMessage`](super::StatusMessage)`.live_view`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct LiveViewStatus {
    /// Viewers connected now.
    pub clients: u64,
    /// Client messages refused and connections closed (`oversized`, `unknown_channel`, `evicted_at_cap`,
    /// `handshake_timeout`, `idle_timeout`, ...), by reason.
    pub rejected: BTreeMap<String, u64>,
}

/// Which way an Open Connect message went.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum TrafficDirection {
    Sent,
    Received,
}

/// One Open Connect message as it crossed the socket, recorded (MCAP) beside the zenoh messages.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct OpenConnectTraffic {
    pub rig: String,
    /// Wall-clock time (ns since the Unix epoch).
    pub t_ns: u64,
    /// The other end, `HOST:PORT`.
    pub peer: String,
    pub direction: TrafficDirection,
    /// The message's text as on the socket (at most `MAX_PAYLOAD_BYTES`, invalid UTF-8 replaced).
    pub text: String,
    /// The prediction's shot number, for a shot sent to a simulator.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shot: Option<u64>,
    /// What became of it when it was not simply sent or accepted (dropped, rejected, ...).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}
