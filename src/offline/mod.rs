//! The offline tools: identification against measured launches ([`identify`]), the SVG charts and figures
//! ([`plot`]), synthetic swings with exact truth ([`swing`]) and the accuracy of the stages ([`eval`]).
//!
//! They use the core (impact models, flight, kinematics) and are used by the commands, the synthetic rig and the
//! tests, never by the live path (`daemon/live`, `pipeline`, the models), which stays small enough to audit for
//! latency; `tests/cli/layout.rs` checks that no live-path file names this module. Synthetic swings belong to the
//! physics crate (`golf_physics::swing`, handed on here): they need the physics alone, and its own tests draw
//! them. The rest is a module of impactd rather than a crate of its own: the tools share the core's types with no
//! interface worth versioning apart, and the boundary a crate would enforce is checked by that test.

pub mod coverage;
pub mod eval;
pub mod identify;
pub mod plot;
pub use golf_physics::swing;
