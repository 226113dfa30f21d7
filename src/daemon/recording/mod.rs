//! The recording: what is recorded (`record`) and its channel messages (`channels`, shared with the Foxglove
//! live view), the MCAP writer the live loop and replay feed, the bounded reader of possibly damaged files
//! and its record parser, `info`, `recover`, the shots and predicted launches a recording holds; and C3D
//! captures (`c3d`).

pub mod c3d;
pub mod channels;
pub mod damage;
pub mod info;
pub mod launches;
pub mod reader;
pub mod record;
mod records;
pub mod recover;
pub mod shots;
pub mod source;
pub mod stream;
pub mod writer;
