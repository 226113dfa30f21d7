//! The message types by name: each Rust message type implements [`Message`], naming its [`MessageType`], which
//! gives the encoding on zenoh and the JSON Schema in `schemas/` and in recordings. A type's name is never typed
//! as a string, so a misspelt one cannot give an empty schema.

use schemars::JsonSchema;
use serde::Serialize;

use super::*;

/// Every message type on the wire, in the order of [`schemas`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MessageType {
    ClubheadSample,
    ImpactMessage,
    LaunchPrediction,
    StatusMessage,
    TruthMessage,
    RejectedInput,
    DeliveryInput,
    PredictOutput,
    FlightInput,
    Trajectory,
    MeasuredLaunch,
    ComparisonMessage,
    OpenConnectTraffic,
    MocapInputStatus,
    ShotLabels,
    ClubChange,
    BallSample,
    ShotExclusion,
    DisplaySettings,
    FlightLine,
}

/// A Rust type sent on the wire, with its [`MessageType`].
pub trait Message: Serialize + JsonSchema {
    const TYPE: MessageType;
}

macro_rules! messages {
    ($($variant:ident => $ty:ty),* $(,)?) => {
        impl MessageType {
            /// Every message type.
            pub const ALL: &'static [MessageType] = &[$(MessageType::$variant),*];

            /// The type's name: `LaunchPrediction`.
            pub fn name(self) -> &'static str {
                match self {
                    $(MessageType::$variant => stringify!($variant),)*
                }
            }

            /// The type's JSON Schema, as written to `schemas/<Type>.json`.
            pub fn schema(self) -> String {
                match self {
                    $(MessageType::$variant => schema_of::<$ty>(),)*
                }
            }
        }
        $(impl Message for $ty {
            const TYPE: MessageType = MessageType::$variant;
        })*
    };
}

messages! {
    ClubheadSample => ClubheadSampleMsg,
    ImpactMessage => ImpactMessage,
    LaunchPrediction => LaunchPrediction,
    StatusMessage => StatusMessage,
    TruthMessage => TruthMessage,
    RejectedInput => RejectedInput,
    DeliveryInput => DeliveryInput,
    PredictOutput => PredictOutput,
    FlightInput => FlightInput,
    Trajectory => crate::flight::Trajectory,
    MeasuredLaunch => MeasuredLaunch,
    ComparisonMessage => ComparisonMessage,
    OpenConnectTraffic => OpenConnectTraffic,
    MocapInputStatus => MocapInputStatus,
    ShotLabels => ShotLabels,
    ClubChange => ClubChange,
    BallSample => BallSampleMsg,
    ShotExclusion => ShotExclusion,
    DisplaySettings => DisplaySettings,
    FlightLine => super::FlightLine,
}

impl MessageType {
    /// The type's version: [`WIRE_VERSION`], [`UNCERTAINTY_WIRE_VERSION`] for the impact (which carries a
    /// prediction's uncertainty), [`IMPACT_TIMING_WIRE_VERSION`] for the launch types.
    pub fn version(self) -> u32 {
        match self {
            MessageType::ImpactMessage => UNCERTAINTY_WIRE_VERSION,
            MessageType::LaunchPrediction | MessageType::PredictOutput => IMPACT_TIMING_WIRE_VERSION,
            _ => WIRE_VERSION,
        }
    }

    /// The encoding on zenoh: `application/json;impactd.LaunchPrediction/3`.
    pub fn encoding(self) -> String {
        format!("application/json;impactd.{}/{}", self.name(), self.version())
    }

    /// The schema name in recordings: `impactd.LaunchPrediction`.
    pub fn schema_name(self) -> String {
        format!("impactd.{}", self.name())
    }
}

fn schema_of<T: JsonSchema>() -> String {
    let mut s = serde_json::to_string_pretty(&schemars::schema_for!(T)).unwrap_or_default();
    s.push('\n');
    s
}

/// Every message type with its JSON Schema, as written to `schemas/<Type>.json`.
pub fn schemas() -> Vec<(&'static str, String)> {
    MessageType::ALL.iter().map(|t| (t.name(), t.schema())).collect()
}
