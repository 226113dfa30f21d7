//! Recordings and captures on disk.

pub mod c3d;
