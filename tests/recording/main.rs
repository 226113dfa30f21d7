//! Integration tests of recordings and replay: damage, size, pause, republish, streaming: one test binary, a module per file.

#![allow(clippy::unwrap_used)]

// What the files share, once for the binary.
#[cfg(feature = "daemon")]
#[path = "../common/c3d_writer.rs"]
mod c3d_writer;
#[cfg(feature = "daemon")]
#[path = "../common/mod.rs"]
mod common;
#[cfg(feature = "daemon")]
#[path = "../common/swing.rs"]
mod swing;

mod capture_markers;
mod captures;
mod damaged_recordings;
mod large_recordings;
mod replay_pause;
mod replay_republish;
mod replay_streams;
