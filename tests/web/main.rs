//! Integration tests of the bay screen: the page in Chromium, its WebSocket, its access rules and limits: one test binary, a module per file.

#![allow(clippy::unwrap_used)]

// What the files share, once for the binary.
#[cfg(feature = "daemon")]
#[path = "../common/mod.rs"]
mod common;
#[cfg(feature = "daemon")]
#[path = "../common/daemon_process.rs"]
mod daemon_process;

mod web_cross_site;
mod web_demo;
mod web_hostile;
mod web_page;
mod web_page_cap;
mod web_stalled_page;
