//! The grip markers a marker set's `[shaft] grip` names, checked on `impactd replay` of a swing capture written by
//! the independent writer (tests/common/synth_capture.py, C3D through PyPI `c3d`): a club's length from the head's
//! markers replays, a marker named as the grip at another distance is refused with the marker and the distance,
//! whatever its label says.

use std::path::Path;
use std::process::Command;

use impactd::daemon::sim::{SimOptions, SimRig};
use impactd::equipment::ClubSpec;

use crate::common;

/// A 360 Hz swing of the `sim` rig's (one shot, noise-free truth, 0.1 mm of marker noise) as a C3D with a HANDLE
/// marker `grip_m` up the shaft from the hosel; the directory holds `swing.c3d`, `markers.toml` (the head's set)
/// and `impactd.toml` (the lab's `world_from_lab`).
fn capture(grip_m: f64) -> tempfile::TempDir {
    let options = SimOptions {
        shots: 1,
        rate_hz: 360.0,
        interval_s: 0.5,
        seed: 6,
        noise_mm: 0.0,
        noise_deg: 0.0,
        ..SimOptions::default()
    };
    let mut rig = SimRig::new("rig1", &options, 1_000_000_000, 6);
    let (mut poses, mut truth, mut samples) = (String::new(), None, Vec::new());
    while !rig.done() {
        let (s, t) = rig.next_sample().unwrap();
        let p = s.position_m;
        poses += &format!("{}\n", serde_json::json!({ "position_m": [p.x, p.y, p.z], "xyzw": s.orientation_xyzw }));
        samples.push(s.t_ns);
        truth = truth.or(t);
    }
    let t_impact_ns = truth.unwrap().t_impact_ns;
    let impact_frame = samples.iter().position(|t| *t >= t_impact_ns).unwrap();
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("truth.jsonl"), poses).unwrap();
    let c = ClubSpec::driver().face.center_m;
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/common/synth_capture.py");
    let out = common::python()
        .arg(script)
        .arg(dir.path().join("truth.jsonl"))
        .arg(dir.path())
        .args(["--rate", "360", "--lab", "z-up", "--noise-mm", "0.1", "--seed", "6"])
        .args(["--face-centre", &format!("{},{},{}", c.x, c.y, c.z), "--impact-frame", &impact_frame.to_string()])
        .args(["--grip-m", &grip_m.to_string()])
        .output()
        .unwrap();
    assert!(out.status.success(), "synth_capture.py: {}", String::from_utf8_lossy(&out.stderr));
    let lab: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("lab.json")).unwrap()).unwrap();
    let config = format!(
        "[[rig]]\nname = \"bay1\"\nclub = \"driver\"\n[rig.world_from_lab]\nrotation_xyzw = {}\ntranslation_m = {}\n",
        lab["rotation_xyzw"], lab["translation_m"]
    );
    std::fs::write(dir.path().join("impactd.toml"), config).unwrap();
    dir
}

/// `impactd replay` of the capture with the head's set plus `shaft` (a `[shaft]` table's lines): exit code,
/// launch lines, stderr.
fn replay(dir: &Path, shaft: &str) -> (i32, usize, String) {
    let set = std::fs::read_to_string(dir.join("markers.toml")).unwrap() + "[shaft]\n" + shaft;
    std::fs::write(dir.join("set.toml"), set).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .arg("replay")
        .arg(dir.join("swing.c3d"))
        .arg("--markers")
        .arg(dir.join("set.toml"))
        .arg("-c")
        .arg(dir.join("impactd.toml"))
        .args(["--rig", "bay1"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).lines().count(), err)
}

#[test]
fn a_grip_marker_the_marker_set_names_is_checked_for_a_clubs_length_on_replay() {
    let dir = capture(1.05);
    // HANDLE, 1.05 m up the shaft: a club's length, the swing replays.
    let (code, launches, err) = replay(dir.path(), "grip = [\"HANDLE\"]\n");
    assert_eq!((code, launches), (0, 1), "{err}");
    // SHAFT_HI (0.61 m up the shaft from the hosel) named as the grip: refused before any swing, with its distance.
    let (code, launches, err) = replay(dir.path(), "grip = [\"HANDLE\", \"SHAFT_HI\"]\n");
    assert_eq!((code, launches), (2, 0), "{err}");
    let d: f64 = err.split("the grip marker SHAFT_HI is ").nth(1).unwrap().split(' ').next().unwrap().parse().unwrap();
    assert!((0.6..0.7).contains(&d), "{d}: {err}");
    assert!(err.contains("m from the head's markers (frame") && err.contains("outside the 0.8-1.3 m"), "{err}");
    // A grip marker the capture does not have is named.
    let (code, _, err) = replay(dir.path(), "grip = [\"BUTT_CAP\"]\n");
    assert_ne!(code, 0);
    assert!(err.contains("marker `BUTT_CAP` of the marker set is not in the capture"), "{err}");
}
