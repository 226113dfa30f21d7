//! Integration tests of the physics through the impactd library where they need more than the physics crate
//! (the offline tools, the predict command's reader): the kinematics against the evaluation and the toy model.
//! The physics crate's own integration tests are in crates/golf-physics/tests. One test binary, a module per
//! file.

#![allow(clippy::unwrap_used)]

mod kinematics;
mod toy_model;
