//! Messages on the wire: serde types with units in their field names, their key expressions and encodings
//! (ARCHITECTURE.md section 4). Every key expression is built in [`keys`], with its payload documented beside it. Every
//! message type is a [`MessageType`] (its name, encoding and JSON Schema in `schemas/`, generated from these
//! types by [`schemas`]).
//!
//! This module holds the JSON forms only; it depends on no transport.

mod ball;
mod bay;
mod bridge;
mod club;
mod delivery;
mod flight;
pub mod keys;
mod labels;
mod measured;
mod messages;
mod mocap;
mod model_name;
mod sample;
mod schema;

pub use ball::{BallSampleMsg, BallSource, BallUsed};
pub use bay::{club_text, ControlError, DisplaySettings, DisplayUnits, ShotExclusion, MAX_CLUB_BYTES};
pub use bridge::{
    ConnectionState, LaunchMonitorStatus, LiveViewStatus, OpenConnectTraffic, SimulatorPlayer, SimulatorStatus,
    TrafficDirection,
};
pub use club::{parse_club_put, ClubChange, ClubPutError, ClubRef, ClubSource, MAX_CLUB_PUT_BYTES};
pub use delivery::{DeliveryInput, Handedness, OutOfBounds, PredictOutput};
pub use flight::{FlightInput, FlightInputError, MAX_BALL_SPIN_RPM};
pub use labels::{LabelsError, ShotLabels, MAX_LABEL_BYTES, MAX_TAGS};
pub use measured::{ComparisonMessage, ComparisonStatus, LaunchFields, MeasuredClubData, MeasuredLaunch};
pub use messages::{
    ClubheadSampleMsg, ImpactMessage, ImpactStateMsg, LaunchPrediction, QuaternionMsg, RejectedInput, StatusMessage,
    TruthMessage,
};
pub use mocap::MocapInputStatus;
pub use sample::{parse_sample, InputError};
pub use schema::{schemas, Message, MessageType};

/// The first version of every message type; part of the encoding `application/json;impactd.<Type>/<version>`
/// (a type's own version: [`MessageType::version`]).
pub const WIRE_VERSION: u32 = 1;

/// The version of the types that carry the uncertainty of a prediction: `ImpactMessage` and `LaunchPrediction`
/// (`delivery.uncertainty`, `launch.uncertainty`) and `PredictOutput` (`uncertainty`). Fields added, none
/// changed: a reader of version 1 that passes unknown fields by reads them as before.
pub const UNCERTAINTY_WIRE_VERSION: u32 = 2;

/// Largest accepted payload (bytes): a clubhead sample is about 200.
pub const MAX_PAYLOAD_BYTES: usize = 64 * 1024;
