//! Foxglove: the channels and schemas the recording and the live view share ([`server`]), and the live
//! WebSocket server ([`live`]).

pub mod live;
pub mod server;
