//! The health of a native motion-capture input (OptiTrack NatNet, Qualisys QTM): in a rig's
//! [`StatusMessage`](super::StatusMessage)`.input` when the daemon reads the server itself, and on
//! `mocap/<rig>/input` from `impactd bridge`.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::ConnectionState;

/// One tracked body of a NatNet or QTM server feeding one rig.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MocapInputStatus {
    pub rig: String,
    /// `natnet` or `qtm`.
    pub protocol: String,
    /// The server's address (`HOST:PORT`).
    pub server: String,
    /// The rigid body (NatNet) or 6DOF body (QTM) name that feeds the rig.
    pub body: String,
    pub state: ConnectionState,
    /// Sessions with the server so far (a second one means it restarted or the measurement stopped).
    pub connects: u64,
    /// Times the client ended a session itself and connected again, by reason: `quiet` (nothing from the server
    /// for 3 s), `undecodable` (NatNet: a run of frames none of which decoded, as after a version announced by
    /// someone else).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub reconnects: BTreeMap<String, u64>,
    /// The server's name and version, and the protocol version it speaks.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub server_version: Option<String>,
    /// Whether the server's model names the body now.
    pub body_found: bool,
    /// Frames of the body received (tracked or not).
    pub frames: u64,
    /// Frames in which the body was not tracked (published with `occluded: true`).
    pub occluded: u64,
    /// Frames missing from the server's numbering.
    pub dropped: u64,
    /// Frames numbered at or before one already published (not published).
    pub out_of_order: u64,
    /// Times the numbering went far back (a server restart): the count starts again.
    pub restarts: u64,
    /// Samples handed on (to the rig's pipeline, or to zenoh by a bridge).
    pub published: u64,
    /// Datagrams or packets not used, and frames of the body not usable, by reason.
    pub rejected: BTreeMap<String, u64>,
    /// NatNet: the server's own time from the cameras' mid-exposure to transmitting the frame (p99 over the
    /// last 1024 frames, us); the capture-to-transmit part of the latency, on the server's clock.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exposure_to_transmit_p99_us: Option<f64>,
    /// The last problem, in words.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub last_error: Option<String>,
}
