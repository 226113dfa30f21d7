//! Integration tests of the offline commands and the tree itself: identification, pairing, the CLI, exit codes, schemas, docs, layout: one test binary, a module per file.

#![allow(clippy::unwrap_used)]

mod camera_monitors;
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
