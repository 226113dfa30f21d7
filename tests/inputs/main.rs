//! Integration tests of the inputs: NatNet, QTM and Vicon against test servers and their vendors' clients, C3D captures, calibration: one test binary, a module per file.

#![allow(clippy::unwrap_used)]

// What the files share, once for the binary.
#[cfg(feature = "daemon")]
#[path = "../common/c3d_writer.rs"]
mod c3d_writer;
#[cfg(feature = "daemon")]
#[path = "../common/mod.rs"]
mod common;
#[path = "../common/natnet_server.rs"]
mod natnet_server;
#[cfg(feature = "daemon")]
#[path = "../common/probe_daemon.rs"]
mod probe_daemon;
#[path = "../common/qtm_server.rs"]
mod qtm_server;
#[path = "../common/vicon_scene.rs"]
mod scene;
#[cfg(feature = "daemon")]
#[path = "../common/swing.rs"]
mod swing;
#[path = "../common/vicon_server.rs"]
mod vicon_server;

mod ball_position;
mod c3d_files;
mod c3d_hostile;
mod c3d_large;
mod c3d_round_trip;
mod calibration;
mod hostile_rigs;
mod mocap_fuzz;
mod natnet;
mod natnet_clubs;
mod natnet_markers;
mod qtm;
mod toy_input;
mod vicon;
mod vicon_fuzz;
mod vicon_live;
