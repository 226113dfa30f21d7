//! Vicon's DataStream protocol (the real-time stream of Nexus, Tracker and Shogun, TCP port 801): pure decoding
//! and encoding, no IO. The socket client is in the daemon's inputs; the test server is in `tests/common`.
//!
//! Everything is little-endian. A packet is a header (`u32` 0x1A2B0001 `Objects`, `u32` byte count of the rest)
//! and a sequence of items, each a `u32` type and a `u32` byte count and its payload ([`framing`]). The SDK's
//! containers: a vector, set or map is a `u32` count and its elements (a map's key then value); a string is a
//! `u32` byte count and the bytes (no NUL); a bool is one byte. The item types and their layouts are in
//! [`enums`] and [`items`].
//!
//! A session: the server opens with a packet holding `ObjectEnums` (the set of item types it can send); the
//! client answers with its own `ObjectEnums` (the types it wants, always including `Contents`), then a
//! `RequestFrame` (`bool` streaming: true is ServerPush, the server sends every frame; false is ClientPull, one
//! frame per request; `RequestNextFrame` asks for the frame after the last one sent). A frame packet opens with
//! `Contents` (a map of each requested type to its object count, and the set of types unchanged since the
//! previous packet, which the server did not resend: they carry over) and holds the static objects
//! (`StreamInfo`: the frame period in ticks of Vicon's 135 MHz clock; `ApplicationInfo`: Z-up or Y-up;
//! `SubjectInfo`, one per subject: its segments with their parents, markers and attachments) and the dynamic
//! ones (`FrameInfo`: the frame id, which the SDK reports plus one; `Timecode`; `LatencyInfo`: named latency
//! samples in seconds; `GlobalSegments`, one per subject: each segment's translation in mm and row-major rotation
//! matrix, a segment absent from the frame being occluded; `LabeledRecons`: labelled markers). A client may send
//! a `Ping` (a `u64` id), which the server sends back. The layouts are those of Vicon's DataStream SDK 1.11 (MIT;
//! `ViconCGStream/*.h`, `ViconCGStreamClient.cpp`), whose own C++ client checks the test server in the tests.
//!
//! Bounded: a packet's size is checked against [`framing::MAX_PACKET_BYTES`] before anything is buffered, every
//! item against the packet, every count against the bytes left before any element is read, and elements are
//! pushed only after their bytes were read; the frame's lists are reused from packet to packet.

pub mod encode;
pub mod enums;
pub mod frame;
pub mod framing;
pub mod items;
pub mod sample;
#[cfg(test)]
mod tests;

pub use frame::{Decoder, DynamicObjects, Frame, PacketSummary, StaticObjects};
pub use items::{LabeledRecon, LatencySample, SegmentDef, SegmentPose, SubjectDef, Timecode, UpAxis};

use super::bytes::Truncated;

/// Vicon's DataStream port.
pub const DEFAULT_PORT: u16 = 801;

/// Ticks per second of Vicon's master clock, in which `StreamInfo` gives the frame period.
pub const CLOCK_HZ: u64 = 135_000_000;

/// Why a packet was not decoded; [`ViconError::reason`] is the key it is counted under.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ViconError {
    #[error(transparent)]
    Truncated(#[from] Truncated),
    #[error("packet tag {0:#010x} is not DataStream's Objects tag 0x1a2b0001")]
    BadTag(u32),
    #[error("packet of {0} bytes is over the {max}-byte limit", max = framing::MAX_PACKET_BYTES)]
    Oversized(u32),
    #[error("the header counts {declared} bytes but the packet holds {actual}")]
    SizeMismatch { declared: usize, actual: usize },
    #[error("item {kind} of {size} bytes does not fit the {left} bytes left in the packet")]
    ItemOverrun { kind: u32, size: u32, left: usize },
    #[error("{what}: {count} elements of at least {min} bytes do not fit the {left} bytes left")]
    BadCount { what: &'static str, count: u32, min: usize, left: usize },
    #[error("{what}: {value} is not a value the protocol defines")]
    BadValue { what: &'static str, value: u32 },
}

impl ViconError {
    /// The counting key.
    pub fn reason(&self) -> &'static str {
        match self {
            ViconError::Truncated(_) | ViconError::SizeMismatch { .. } => "truncated",
            ViconError::BadTag(_) => "unknown_message",
            ViconError::Oversized(_) => "oversized",
            ViconError::ItemOverrun { .. } | ViconError::BadCount { .. } | ViconError::BadValue { .. } => "malformed",
        }
    }
}
