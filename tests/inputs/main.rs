//! Integration tests of the inputs: NatNet, QTM and Vicon against test servers and their vendors' clients, C3D captures, calibration: one test binary, a module per file.

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
