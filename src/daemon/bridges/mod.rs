//! Bridges between the daemon and other programs: golf simulators (Open Connect, OpenGolfSim's developer API)
//! and launch monitors over Open Connect, the Foxglove live view, the bay screen (web page), and motion-capture
//! servers (OptiTrack NatNet, Qualisys QTM) read natively.

pub mod foxglove;
pub mod mocap;
pub mod open_connect;
pub mod opengolfsim;
pub mod peers;
pub mod web;
