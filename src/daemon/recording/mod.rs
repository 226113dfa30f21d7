//! The recording: the MCAP writer the live loop and replay feed, the bounded reader of possibly damaged files
//! and its record parser, `info`, `recover`, and the shots and predicted launches a recording holds.

pub mod info;
pub mod launches;
pub mod reader;
pub mod record;
mod records;
pub mod recover;
pub mod shots;
pub mod writer;
