//! Bridges between the daemon and other programs: golf simulators (Open Connect, OpenGolfSim's developer API)
//! and launch monitors over Open Connect, the Foxglove live view and the bay screen (web page). The
//! motion-capture servers the daemon reads are its inputs (`daemon::inputs`).

pub mod foxglove;
pub mod open_connect;
pub mod opengolfsim;
pub mod peer_rejection;
pub mod peers;
pub mod web;
