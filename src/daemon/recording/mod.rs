//! The recording: what is recorded (`record`) and its channel messages (`channels`, shared with the Foxglove
//! live view), the MCAP writer the live loop and replay feed, the bounded reader of possibly damaged files
//! and its record parser, `info`, `recover`, the shots and predicted launches a recording holds. C3D captures
//! are in `crate::captures` (handed on here as `c3d`, where they were).

pub use crate::captures::c3d;
pub mod channels;
pub mod damage;
pub mod info;
pub mod launches;
pub mod read_error;
pub mod reader;
pub mod record;
mod records;
pub mod recover;
pub mod shots;
pub mod source;
pub mod stream;
pub mod writer;
