//! The examples a newcomer meets launch like golfers' shots: every shot of the shipped recordings (replayed) and
//! of `impactd demo` has its spin axis within +-30 deg, its backspin within the club's tour-to-amateur range, and
//! no sanity flag (`warnings` empty).
//!
//! The backspin range is `GolferProfile::backspin_range_rpm` (docs/synthetic-golfers.md): from TrackMan's PGA
//! Tour averages (driver 2686 rpm, 7-iron 7097 rpm: reference/trackman-pga-tour-averages.csv) to the average
//! amateur's estimate, widened by the shot-to-shot spread: driver 1900-3900 rpm, 7-iron 4200-8000 rpm.

#![allow(clippy::unwrap_used)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use impactd::equipment::ClubSpec;
use impactd::offline::swing::GolferProfile;

fn recording(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("recordings").join(name)
}

fn impactd(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(args)
        .env("RUST_LOG", "error")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .output()
        .unwrap()
}

fn backspin_range_rpm(club: &str) -> (f64, f64) {
    let club = match club {
        "driver" => ClubSpec::driver(),
        "iron7" => ClubSpec::iron7(),
        other => panic!("no preset {other}"),
    };
    GolferProfile::for_club(&club).backspin_range_rpm
}

/// Checks every launch prediction line of `stdout`; returns how many there were.
fn check_launches(what: &str, stdout: &[u8]) -> usize {
    let text = String::from_utf8_lossy(stdout);
    let mut n = 0;
    for line in text.lines().filter(|l| l.starts_with('{')) {
        let p: serde_json::Value = serde_json::from_str(line).unwrap();
        let club = p["club"].as_str().unwrap();
        let launch = &p["launch"];
        let axis = launch["spin_axis_deg"].as_f64().unwrap();
        let backspin = launch["backspin_rpm"].as_f64().unwrap();
        let (lo, hi) = backspin_range_rpm(club);
        let shot = &p["shot"];
        assert!(axis.abs() <= 30.0, "{what} shot {shot}: spin axis {axis:.1} deg");
        assert!((lo..=hi).contains(&backspin), "{what} shot {shot}: backspin {backspin:.0} rpm outside {lo}-{hi}");
        assert_eq!(launch["warnings"], serde_json::json!([]), "{what} shot {shot}: flagged");
        n += 1;
    }
    n
}

/// Both shipped recordings, replayed (which reproduces their predictions byte for byte: exit 0).
#[test]
fn the_shipped_recordings_are_golfers_shots() {
    for name in ["driver.mcap", "iron7.mcap"] {
        let file = recording(name);
        let out = impactd(&["replay", file.to_str().unwrap()]);
        assert!(out.status.success(), "{name}: {}", String::from_utf8_lossy(&out.stderr));
        assert_eq!(check_launches(name, &out.stdout), 3, "{name}: three shots each (recordings/make.sh)");
    }
}

/// A recording made while models were published under former names (`impulse/adjusted`: the shipped driver
/// recording as it was, tests/data/driver-former-names.mcap) still reproduces: its names are read as today's
/// registry names (docs/topics.md), the replay says so, and its output carries today's names.
#[test]
fn a_recording_with_former_model_names_reproduces() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/driver-former-names.mcap");
    let out = impactd(&["replay", file.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("recorded model name impulse/adjusted is now adjusted"), "{err}");
    assert!(err.contains("3 of 3 recorded predictions reproduced byte for byte"), "{err}");
    assert_eq!(check_launches("driver-former-names.mcap", &out.stdout), 3);
    let first: serde_json::Value = serde_json::from_slice(out.stdout.split(|b| *b == b'\n').next().unwrap()).unwrap();
    assert_eq!(first["model"], "adjusted");
}

/// `impactd demo` as the README runs it (5 shots, seed 1) and a longer run with another seed, for both presets:
/// every shot predicted, none flagged, each within the ranges. The four demos run side by side (each paces its
/// swings in real time, and each is its own process with its own recording).
#[test]
fn the_demo_shots_are_golfers_shots() {
    let dir = tempfile::tempdir().unwrap();
    let runs: Vec<(String, String, String)> = ["driver", "iron7"]
        .iter()
        .flat_map(|club| [("5", "1"), ("12", "3")].map(|(shots, seed)| (club.to_string(), shots.into(), seed.into())))
        .collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = runs
            .iter()
            .map(|(club, shots, seed)| {
                let record = dir.path().join(format!("{club}-{seed}.mcap"));
                scope.spawn(move || {
                    let args = ["demo", "--club", club, "--json", "--shots", shots, "--seed", seed];
                    let out = impactd(&[&args[..], &["--record", record.to_str().unwrap()]].concat());
                    (args.map(String::from), out)
                })
            })
            .collect();
        for (handle, (club, shots, seed)) in handles.into_iter().zip(&runs) {
            let (args, out) = handle.join().unwrap();
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(out.status.success(), "{args:?}: {err}");
            assert!(!err.contains("sanity flags raised"), "{args:?}: {err}");
            let n = check_launches(&format!("demo {club} seed {seed}"), &out.stdout);
            assert_eq!(n.to_string(), *shots, "{args:?}: every shot predicted");
        }
    });
}
