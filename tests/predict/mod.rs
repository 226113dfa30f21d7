//! What the tests that run `impactd predict` on delivery lines share: the binary's answers, a JSON value per line.

#![allow(clippy::unwrap_used)]
#![allow(dead_code)]

use std::io::Write;
use std::process::{Command, Stdio};

/// `impactd ARGS` with `input` on its standard input; asserts success; one JSON value per line of its output.
pub fn answers(args: &[&str], input: &str) -> Vec<serde_json::Value> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child.stdin.take().unwrap().write_all(input.as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect()
}
