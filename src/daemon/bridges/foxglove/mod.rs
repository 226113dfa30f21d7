//! Foxglove: the live WebSocket server ([`live`]), on the channels the recording writes
//! ([`crate::daemon::recording::channels`]).

pub mod live;
