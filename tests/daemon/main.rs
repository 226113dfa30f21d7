//! Integration tests of the daemon on loopback: recording, clubs, comparisons, launch monitors, simulators, watch, hostile peers: one test binary, a module per file.

#![allow(clippy::unwrap_used)]

// What the files share, once for the binary.
#[cfg(feature = "daemon")]
#[path = "../common/mod.rs"]
mod common;
#[cfg(feature = "daemon")]
#[path = "../common/daemon_process.rs"]
mod daemon_process;
#[path = "../common/qtm_server.rs"]
mod qtm_server;

mod club_switch;
mod daemon;
mod daemon_hostile;
mod fitting_session;
mod foxglove_demo_log;
mod foxglove_live;
mod hostile_peers;
mod launch_monitor;
mod live_comparison;
mod log_floods;
mod opengolfsim;
mod simulator;
mod watch;
