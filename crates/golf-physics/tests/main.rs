//! Integration tests of the physics crate alone (no daemon, no transport): the models, the flight, the ground,
//! the shaft, the presets and the pure pipeline: one test binary, a module per file.

#![allow(clippy::unwrap_used)]

mod club_data;
mod club_presets;
mod continuous;
mod flight;
mod ground;
mod ground_teed;
mod impulse_golden;
mod impulse_physics;
mod maw_arakawa;
mod shaft;
mod tour_deliveries;
mod track_recovery;

use golf_physics::equipment::{presets, EquipmentError, LoadedClub};

/// A preset club by name with its model sections: what `impactd::equipment::load_club` gives for a preset's name
/// (these tests read no club file from disk).
fn load_club(name: &str) -> Result<LoadedClub, EquipmentError> {
    presets::find(name).ok_or_else(|| EquipmentError::UnknownPreset(name.to_string()))?.load()
}
