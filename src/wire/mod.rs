//! Messages on the wire: serde types with units in their field names, their key expressions and encodings
//! (ARCHITECTURE.md section 4). Every key expression is built in [`keys`], with its payload documented beside it. Every
//! message type is a [`MessageType`] (its name, encoding and JSON Schema in `schemas/`, generated from these
//! types by [`schemas`]).
//!
//! The physics' own JSON forms (a delivery and its launch, the impact and launch messages, the club file, labels
//! and ball they carry) are `golf_physics::wire`'s, handed on here; this module adds the daemon's messages.
//! It holds the JSON forms only; it depends on no transport.

mod bay;
mod bridge;
mod flight_line;
pub mod keys;
mod measured;
mod mocap;
mod sample;
mod schema;
mod status;

pub use bay::{club_text, ControlError, DisplaySettings, DisplayUnits, ShotExclusion, MAX_CLUB_BYTES};
pub use bridge::{
    ConnectionState, LaunchMonitorStatus, LiveViewStatus, OpenConnectTraffic, SimulatorPlayer, SimulatorStatus,
    TrafficDirection,
};
pub use flight_line::FlightLine;
pub use golf_physics::wire::*;
pub use measured::{ComparisonMessage, ComparisonStatus, LaunchFields, MeasuredClubData, MeasuredLaunch};
pub use mocap::MocapInputStatus;
pub use sample::{parse_sample, InputError};
pub use schema::{schemas, Message, MessageType};
pub use status::{RejectedInput, StatusMessage, TruthMessage};

/// The first version of every message type; part of the encoding `application/json;impactd.<Type>/<version>`
/// (a type's own version: [`MessageType::version`]).
pub const WIRE_VERSION: u32 = 1;

/// The version of the types that carry the uncertainty of a prediction: `ImpactMessage` and `LaunchPrediction`
/// (`delivery.uncertainty`, `launch.uncertainty`) and `PredictOutput` (`uncertainty`). Fields added, none
/// changed: a reader of version 1 that passes unknown fields by reads them as before.
pub const UNCERTAINTY_WIRE_VERSION: u32 = 2;

/// The version of `LaunchPrediction` and `PredictOutput` that say what an estimate bridged: `impact_timing` (a
/// given impact instant, a gap in the frames before impact, a ball far from the face at address) and the
/// warnings `frame_gap_before_impact` and `ball_far_from_address`. Fields and warning kinds added, none changed.
pub const IMPACT_TIMING_WIRE_VERSION: u32 = 3;

/// Largest accepted payload (bytes): a clubhead sample is about 200.
pub const MAX_PAYLOAD_BYTES: usize = 64 * 1024;
