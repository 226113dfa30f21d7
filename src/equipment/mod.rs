//! Equipment (`golf_physics::equipment`: the clubhead, the ball, the shaft, the sole and the soil, with the seed's
//! presets and club files parsed from text), and loading a club or soil file from disk, which the IO-free
//! physics crate leaves to this one.

mod load;

pub use golf_physics::equipment::*;
pub use load::{load_club, load_club_source, sha256_hex, MAX_CLUB_FILE_BYTES};
