//! The failures of a C3D capture's markers that issue 45 found silent, on a synthetic driver swing written by an
//! independent writer (PyPI `c3d`) and replayed with `impactd replay CAPTURE.c3d --markers SET.toml`: a marker
//! lost for 18 frames before the impact is named with its frames; a face centre 0.97 m from the head's markers
//! is refused before any swing.

use std::process::{Command, Output};

use crate::c3d_writer;
use impactd::equipment::ClubSpec;
use impactd::impact::Equipment;
use impactd::math::{Point3, Vector3};
use impactd::offline::swing::{Swing, SwingSpec};
use impactd::rng::Rng;

const RATE_HZ: f64 = 360.0;
const T_IMPACT_S: f64 = 0.3;

/// Three markers on the head at unequal distances (club frame = body frame: identity calibration).
const MARKERS: &str = "[markers]\nCROWN = [0.0, 0.03, 0.0]\nTOE = [0.02, 0.0, 0.045]\nHOSEL = [-0.01, 0.0, -0.04]\n";

fn labels() -> Vec<String> {
    ["CROWN", "TOE", "HOSEL"].iter().map(|s| s.to_string()).collect()
}

fn body_m() -> Vec<Vector3> {
    vec![Vector3::new(0.0, 0.03, 0.0), Vector3::new(0.02, 0.0, 0.045), Vector3::new(-0.01, 0.0, -0.04)]
}

/// The frame number (1-based) of the `k`-th frame before the impact (1: the newest).
fn frame_before_impact(k: u64) -> u64 {
    let t_impact = T_IMPACT_S + 0.37 / RATE_HZ;
    (t_impact * RATE_HZ).floor() as u64 + 1 - (k - 1)
}

/// Writes the capture: 0.1 mm of marker noise, every marker invalid outside 80 ms before to 30 ms after the
/// impact, and `lost(frame, marker)` invalid too.
fn capture(path: &std::path::Path, lost: impl Fn(u64, usize) -> bool) {
    let club = ClubSpec::driver();
    let mut spec = SwingSpec::random(&club, &mut Rng::new(21));
    spec.delivery.club_speed_mps = 45.0;
    let swing = Swing::new(&spec, &Equipment::new(club)).unwrap();
    let mut rng = Rng::new(5);
    let t_impact = T_IMPACT_S + 0.37 / RATE_HZ;
    let body = body_m();
    let mut last = vec![Vector3::zeros(); body.len()];
    let frames: Vec<Vec<(Vector3, bool)>> = (0..((T_IMPACT_S + 0.2) * RATE_HZ) as u64)
        .map(|i| {
            let tau = i as f64 / RATE_HZ - t_impact;
            let seen = (-0.08..0.03).contains(&tau);
            let pose = swing.pose(tau);
            body.iter()
                .enumerate()
                .map(|(k, b)| {
                    let noise = Vector3::new(rng.normal(), rng.normal(), rng.normal()) * 1e-4;
                    let valid = seen && !lost(i + 1, k);
                    if valid {
                        last[k] = (pose * Point3::from(*b)).coords + noise;
                    }
                    (last[k], valid)
                })
                .collect()
        })
        .collect();
    c3d_writer::write_c3d(&labels(), RATE_HZ, &frames, path);
}

fn replay(dir: &std::path::Path, extra: &[&str]) -> (Output, String) {
    let set = dir.join("head.toml");
    std::fs::write(&set, MARKERS).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .arg("replay")
        .arg(dir.join("swing.c3d"))
        .arg("--markers")
        .arg(&set)
        .args(extra)
        .current_dir(dir)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    (out, err)
}

#[test]
fn one_marker_lost_for_18_frames_names_the_marker_and_the_frames() {
    let dir = tempfile::tempdir().unwrap();
    let (first, last) = (frame_before_impact(18), frame_before_impact(1));
    capture(&dir.path().join("swing.c3d"), |frame, k| k == 1 && (first..=last).contains(&frame));
    let (out, err) = replay(dir.path(), &[]);
    assert!(
        err.contains(&format!("marker TOE lost in frames {first}-{last} (18 frames, 50.0 ms)")),
        "the marker and its frames: {err}"
    );
    assert!(err.contains("no prediction"), "{err}");
    assert_eq!(out.status.code(), Some(2), "{err}");
}

#[test]
fn a_face_centre_097_m_from_the_head_markers_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    capture(&dir.path().join("swing.c3d"), |_, _| false);
    // club_from_body puts the body 0.97 m from the face centre along the club's x axis.
    let c = ClubSpec::driver().face.center_m - Vector3::new(0.97, 0.0, 0.0);
    let config = dir.path().join("impactd.toml");
    std::fs::write(
        &config,
        format!(
            "[[rig]]\nname = \"c3d\"\nclub = \"driver\"\n[rig.club_from_body]\nrotation_xyzw = [0.0, 0.0, 0.0, 1.0]\n\
             translation_m = [{}, {}, {}]\n",
            c.x, c.y, c.z
        ),
    )
    .unwrap();
    let (out, err) = replay(dir.path(), &["-c", config.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("the face centre is 0.9") && err.contains("m from the nearest marker of the head's set"),
        "{err}"
    );
    assert!(err.contains("club_from_body is wrong"), "{err}");
    // The same capture with the identity calibration replays its swing.
    let (ok, err) = replay(dir.path(), &[]);
    assert!(ok.status.success() && String::from_utf8_lossy(&ok.stdout).lines().count() == 1, "{err}");
}
