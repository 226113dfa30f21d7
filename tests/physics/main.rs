//! Integration tests of the physics through the impactd library: the models, the flight, the ground, the kinematics, the presets: one test binary, a module per file.

#![allow(clippy::unwrap_used)]

mod club_data;
mod club_presets;
mod continuous;
mod flight;
mod ground;
mod ground_teed;
mod impulse_golden;
mod impulse_physics;
mod kinematics;
mod maw_arakawa;
mod shaft;
mod tour_deliveries;
mod toy_model;
mod track_recovery;
