//! An input's connection-wide counters by kind: why the client ended a session itself (a status's
//! `reconnects`) and why it refused what the server sent (`rejected`). Counted in a [`Tally`] as the pipeline's
//! are; a status carries the wire names ([`Tally::to_wire`]), so its JSON is unchanged.

pub use crate::pipeline::{CounterKind, Tally};

/// Why a client ended a session itself and connected again (a status's `reconnects`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Reconnect {
    /// The server was silent for the input's quiet time.
    Quiet,
    /// The server's frames could not be decoded with the version it announced.
    Undecodable,
}

impl CounterKind for Reconnect {
    fn wire_name(self) -> &'static str {
        match self {
            Reconnect::Quiet => "quiet",
            Reconnect::Undecodable => "undecodable",
        }
    }
}

/// Why a client refused a packet the server sent (a status's `rejected`, beside the bodies' own).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum InputRejection {
    /// A datagram from another host than the server.
    ForeignSender,
    /// A packet over the input's size limit.
    Oversized,
    /// Server info nobody asked for.
    UnsolicitedServerInfo,
    /// A model definition nobody asked for.
    UnsolicitedModelDef,
    /// A server of a protocol version the client does not speak.
    UnknownVersion,
    /// Frames before the server said its version.
    AwaitingServerInfo,
    /// A message of a kind the client does not know.
    UnknownMessage,
    /// Frames before the server said its frame period.
    NoFramePeriod,
    /// What the protocol's decoder refused, under the decoder's own name for it (`NatNetError::reason`).
    Decode(&'static str),
}

impl CounterKind for InputRejection {
    fn wire_name(self) -> &'static str {
        match self {
            InputRejection::ForeignSender => "foreign_sender",
            InputRejection::Oversized => "oversized",
            InputRejection::UnsolicitedServerInfo => "unsolicited_server_info",
            InputRejection::UnsolicitedModelDef => "unsolicited_model_def",
            InputRejection::UnknownVersion => "unknown_version",
            InputRejection::AwaitingServerInfo => "awaiting_server_info",
            InputRejection::UnknownMessage => "unknown_message",
            InputRejection::NoFramePeriod => "no_frame_period",
            InputRejection::Decode(reason) => reason,
        }
    }
}
