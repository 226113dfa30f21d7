//! Integration tests of the offline commands and the tree itself: identification, pairing, the CLI, exit codes, schemas, docs, layout: one test binary, a module per file.

#![allow(clippy::unwrap_used)]

// What the files share, once for the binary.
#[cfg(feature = "daemon")]
#[path = "../common/c3d_writer.rs"]
mod c3d_writer;
#[cfg(feature = "daemon")]
#[path = "../common/mod.rs"]
mod common;
#[cfg(feature = "daemon")]
#[path = "../common/static_trials.rs"]
mod static_trials;

#[cfg(feature = "daemon")]
mod calibrate_club;
#[cfg(feature = "daemon")]
mod calibrate_lab;
#[cfg(feature = "daemon")]
mod calibrate_static;
mod camera_monitors;
#[cfg(feature = "daemon")]
mod capture_grip;
mod capture_guards;
mod cli;
mod doc_links;
mod examples_realistic;
mod exit_codes;
mod ground_cli;
mod hostile_inputs;
mod identify;
mod identify_cli;
mod identify_local;
mod layout;
mod map_picture;
mod pairing;
mod registry_docs;
mod schemas;
mod trackman_report;
