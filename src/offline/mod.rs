//! The offline tools: identification against measured launches ([`identify`]), the SVG charts and figures
//! ([`plot`]), synthetic swings with exact truth ([`swing`]) and the accuracy of the stages ([`eval`]).
//!
//! They use the core (impact models, flight, kinematics) and are used by the commands, the synthetic rig and the
//! tests, never by the live path (`daemon/live`, `pipeline`, the models), which stays small enough to audit for
//! latency; `tests/layout.rs` checks that no live-path file names this module. A module of the one crate rather
//! than a workspace crate: the tools share the core's types with no interface worth versioning apart, one crate
//! keeps one build and one `cargo test`, and the boundary a second crate would enforce is checked by that test.

pub mod coverage;
pub mod eval;
pub mod identify;
pub mod plot;
pub mod swing;
