//! Bridges between the daemon and other programs: golf simulators and launch monitors over Open Connect, and the
//! Foxglove live view.

pub mod foxglove;
pub mod open_connect;
