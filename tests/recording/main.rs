//! Integration tests of recordings and replay: damage, size, pause, republish, streaming: one test binary, a module per file.

mod damaged_recordings;
mod large_recordings;
mod replay_pause;
mod replay_republish;
mod replay_streams;
