//! `impactd replay --pause` / `--start-paused` driven through stdin (not a terminal: lines `pause`, `resume`,
//! `toggle`), through the real binary on a shipped recording.

#![allow(clippy::unwrap_used)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

fn recording(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("recordings").join(name)
}

fn replay(args: &[&str]) -> std::process::Child {
    Command::new(env!("CARGO_BIN_EXE_impactd"))
        .arg("replay")
        .arg(recording("driver.mcap"))
        .args(args)
        .env("RUST_LOG", "warn")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// A replay started paused sends nothing until told to resume (unpaused, this recording replays in
/// milliseconds), then reproduces the whole recording (its 3 shots).
#[test]
fn start_paused_waits_for_resume() {
    let mut child = replay(&["--start-paused"]);
    std::thread::sleep(Duration::from_millis(1500));
    assert!(child.try_wait().unwrap().is_none(), "the paused replay finished without being resumed");
    let mut stdin = child.stdin.take().unwrap();
    stdin.write_all(b"resume\n").unwrap();
    let out = child.wait_with_output().unwrap();
    drop(stdin);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("paused at the start") && err.contains("resumed at 0.00 s"), "{err}");
    assert!(err.contains("3 of 3 recorded predictions reproduced"), "{err}");
    assert_eq!(String::from_utf8_lossy(&out.stdout).lines().count(), 3);
}

/// `pause` mid-replay holds it at the capture time reached; a line that is not a command is reported and
/// ignored; the end of stdin resumes, so a replay never hangs on a closed input.
#[test]
fn pause_holds_and_the_end_of_stdin_resumes() {
    // At 4x real time the recording takes a second or two: `pause` right away stops it near its start.
    let mut child = replay(&["--pause", "--rate", "4"]);
    let mut stdin = child.stdin.take().unwrap();
    stdin.write_all(b"pause\n").unwrap();
    std::thread::sleep(Duration::from_millis(2500));
    assert!(child.try_wait().unwrap().is_none(), "the paused replay finished");
    stdin.write_all(b"bogus\n").unwrap();
    drop(stdin);
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("paused at ") && err.contains("'bogus' is not a command"), "{err}");
    assert!(err.contains("stdin closed: resumed at"), "{err}");
    assert_eq!(String::from_utf8_lossy(&out.stdout).lines().count(), 3);
}
