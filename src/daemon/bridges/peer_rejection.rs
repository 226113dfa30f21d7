//! Why a TCP surface (an Open Connect listener, the Foxglove live view, the bay screen) refused a connection,
//! cut one or rejected a message: the kinds of a status's `rejected` counts, counted in a [`Tally`] as the
//! pipeline's are; a status carries the wire names ([`Tally::to_wire`]), so its JSON is unchanged.

pub use crate::pipeline::{CounterKind, Tally};

/// A kind of refusal, cut or rejection on a surface's connections.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum PeerRejection {
    /// Closed for a newcomer at the cap.
    EvictedAtCap,
    /// Said nothing useful within the handshake timeout.
    HandshakeTimeout,
    /// Quiet for the idle timeout.
    IdleTimeout,
    /// Refused at the cap, every connection there live (the bay screen).
    RefusedAtCap,
    /// A message over the surface's size limit.
    Oversized,
    /// A WebSocket protocol error.
    Protocol,
    /// A WebSocket handshake that failed.
    Handshake,
    /// A message that is not what the surface reads (not JSON, not a control, not an operation).
    Malformed,
    /// Bytes outside any JSON object (Open Connect).
    NotJson,
    /// A shot from another device than the connection's (Open Connect).
    DeviceId,
    /// A shot whose numbers cannot be a launch (Open Connect).
    Invalid,
    /// A shot that could not be published (Open Connect).
    Publish,
    /// A control without the screen's token (the bay screen).
    Unauthorized,
    /// A control for a rig not served here (the bay screen).
    UnknownRig,
    /// A control with a value it cannot take (the bay screen).
    InvalidControl,
    /// A control that could not be put on zenoh (the bay screen).
    PutFailed,
    /// A request that is not HTTP (the bay screen).
    BadRequest,
    /// An HTTP method other than GET (the bay screen).
    Method,
    /// A path the screen does not serve.
    NotFound,
    /// A request that names no Host.
    NoHost,
    /// A request for another host than the screen's.
    WrongHost,
    /// A request from another origin.
    CrossOrigin,
    /// A wrong token.
    BadToken,
    /// An operation the live view does not support (Foxglove).
    UnknownOp,
    /// A subscription to a channel never advertised (Foxglove).
    UnknownChannel,
    /// A bus payload the screen refused to read (over its limit, or not its message).
    BusPayloadRefused,
    /// Bus messages dropped because the screen's queue was full.
    BusQueueFull,
}

impl CounterKind for PeerRejection {
    fn wire_name(self) -> &'static str {
        match self {
            PeerRejection::EvictedAtCap => "evicted_at_cap",
            PeerRejection::HandshakeTimeout => "handshake_timeout",
            PeerRejection::IdleTimeout => "idle_timeout",
            PeerRejection::RefusedAtCap => "refused_at_cap",
            PeerRejection::Oversized => "oversized",
            PeerRejection::Protocol => "protocol",
            PeerRejection::Handshake => "handshake",
            PeerRejection::Malformed => "malformed",
            PeerRejection::NotJson => "not_json",
            PeerRejection::DeviceId => "device_id",
            PeerRejection::Invalid => "invalid",
            PeerRejection::Publish => "publish",
            PeerRejection::Unauthorized => "unauthorized",
            PeerRejection::UnknownRig => "unknown_rig",
            PeerRejection::InvalidControl => "invalid_control",
            PeerRejection::PutFailed => "put_failed",
            PeerRejection::BadRequest => "bad_request",
            PeerRejection::Method => "method",
            PeerRejection::NotFound => "not_found",
            PeerRejection::NoHost => "no_host",
            PeerRejection::WrongHost => "wrong_host",
            PeerRejection::CrossOrigin => "cross_origin",
            PeerRejection::BadToken => "bad_token",
            PeerRejection::UnknownOp => "unknown_op",
            PeerRejection::UnknownChannel => "unknown_channel",
            PeerRejection::BusPayloadRefused => "bus_payload_refused",
            PeerRejection::BusQueueFull => "bus_queue_full",
        }
    }
}
