//! `impactd calibrate lab` on synthetic static trials (0.2 mm of marker noise, 50 frames, tests/common/
//! static_trials.rs): `world_from_lab` recovered within 0.2 deg and 1 mm in a Z-up and a Y-up lab with the up
//! axis found from the capture, a stated target axis and ball position in place of the target line; a stated
//! `--lab-up` that the capture contradicts and floor markers near one line refused with their reasons.

use crate::static_trials::*;

use impactd::equipment::ClubSpec;
use impactd::math::{Point3, Vector3};

/// The bay: floor and target-line markers, a taped ball at the origin, the club at address.
fn bay() -> Vec<(String, Vector3)> {
    let mut m = floor_markers();
    m.push(("BALL".into(), Vector3::zeros()));
    m.extend(club_markers(&ClubSpec::driver(), &world_from_club_at_address()));
    m
}

const FLOOR: &str = "REAR,FRONT,F1,F2,F3";

#[test]
fn calibrate_lab_recovers_world_from_lab_in_z_up_and_y_up_labs() {
    let dir = tempfile::tempdir().unwrap();
    for (z_up, seed) in [(true, 1), (false, 2)] {
        let truth = world_from_lab(z_up);
        let capture = dir.path().join("lab.c3d");
        write_trial(&capture, &truth, &bay(), seed, STILL);
        let out = dir.path().join("lab.toml");
        let (c, o) = (capture.to_str().unwrap(), out.to_str().unwrap());
        let base = ["calibrate", "lab", c, "--frames", "50", "--floor", FLOOR, "--marker-radius-mm", "7", "-o", o];
        // No --lab-up: the club's and the ball's markers stand above the floor.
        let err = impactd_ok(&[&base[..], &["--target-line", "REAR,FRONT", "--ball", "BALL"]].concat());
        assert!(err.contains("from the side 6 markers off the floor stand on"), "{err}");
        assert!(err.contains("ball: the marker BALL"), "{err}");
        let lab = if z_up { "Z-up" } else { "Y-up" };
        assert_recovered(&pose(&out, "world_from_lab"), &truth, &format!("world_from_lab, {lab} lab (ball marker)"));
        // The lab's own up axis, stated, agrees.
        let up = if z_up { "z" } else { "y" };
        let err = impactd_ok(&[&base[..], &["--target-line", "REAR,FRONT", "--ball", "BALL", "--lab-up", up]].concat());
        assert!(err.contains("as --lab-up states"), "{err}");
    }
}

#[test]
fn calibrate_lab_takes_a_target_axis_a_stated_ball_and_a_ball_trial() {
    let dir = tempfile::tempdir().unwrap();
    for z_up in [true, false] {
        // Turned so that a lab axis runs along the target line.
        let truth = world_from_lab_turned(z_up, 0.0);
        let lab_from_world = truth.inverse();
        let toward = lab_from_world.rotation * Vector3::x();
        let i = toward.iamax();
        let target = format!("{}{}", if toward[i] > 0.0 { "+" } else { "-" }, ["x", "y", "z"][i]);
        // No target-line pair: floor markers and the club only.
        let markers: Vec<(String, Vector3)> =
            bay().into_iter().filter(|(l, _)| l != "REAR" && l != "FRONT" && l != "BALL").collect();
        let capture = dir.path().join("bay.c3d");
        write_trial(&capture, &truth, &markers, 3, STILL);
        let out = dir.path().join("lab.toml");
        let (c, o) = (capture.to_str().unwrap(), out.to_str().unwrap());
        let ball = (lab_from_world * Point3::origin()).coords * 1e3;
        let at = format!("{},{},{}", ball.x, ball.y, ball.z);
        let base = ["calibrate", "lab", c, "--frames", "50", "--floor", "F1,F2,F3", "--marker-radius-mm", "7", "-o", o];
        let err = impactd_ok(&[&base[..], &["--target", &target, "--ball-at", &at]].concat());
        assert!(err.contains(&format!("target: the lab's {target}")) && err.contains("ball: stated"), "{err}");
        assert_recovered(
            &pose(&out, "world_from_lab"),
            &truth,
            &format!("world_from_lab, --target {target}, --ball-at"),
        );

        // The ball from a static ball trial of its own.
        let ball_trial = dir.path().join("ball.c3d");
        write_trial(&ball_trial, &truth, &[("BALL".into(), Vector3::zeros())], 4, STILL);
        let b = ball_trial.to_str().unwrap();
        let err = impactd_ok(&[&base[..], &["--target", &target, "--ball", "BALL", "--ball-trial", b]].concat());
        assert!(err.contains("static ball trial"), "{err}");
        assert_recovered(
            &pose(&out, "world_from_lab"),
            &truth,
            &format!("world_from_lab, --target {target}, ball trial"),
        );

        // Without any ball there is no origin.
        let err = impactd_refused(&[&base[..], &["--target", &target]].concat());
        assert!(err.contains("no ball"), "{err}");
        // A ball typed in metres where millimetres are asked for sits in the floor.
        let metres = format!("{},{},{}", ball.x * 1e-3, ball.y * 1e-3, ball.z * 1e-3);
        let err = impactd_refused(&[&base[..], &["--target", &target, "--ball-at", &metres]].concat());
        assert!(err.contains("above the floor"), "{err}");
    }
}

#[test]
fn lab_up_disagreeing_with_the_floor_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let capture = dir.path().join("lab.c3d");
    let c = capture.to_str().unwrap();
    let base = ["calibrate", "lab", c, "--frames", "50", "--target-line", "REAR,FRONT", "--floor", FLOOR];
    // A Y-up capture read with the Z-up default of old: the floor's normal is the lab's y.
    write_trial(&capture, &world_from_lab(false), &bay(), 5, STILL);
    let err = impactd_refused(&[&base[..], &["--lab-up", "z"]].concat());
    assert!(err.contains("--lab-up z disagrees with the capture") && err.contains("nearest y"), "{err}");
    assert!(err.contains("90 deg from the stated z"), "{err}");
    // Upside down in a Z-up lab: the club stands on the other side.
    write_trial(&capture, &world_from_lab(true), &bay(), 6, STILL);
    let err = impactd_refused(&[&base[..], &["--lab-up", "-z"]].concat());
    assert!(err.contains("--lab-up -z disagrees") && err.contains("nearest z") && err.contains("180 deg"), "{err}");
    // With only floor markers the capture cannot tell which side is up: that must be said, not guessed.
    write_trial(&capture, &world_from_lab(false), &floor_markers(), 7, STILL);
    let err = impactd_refused(&base);
    assert!(err.contains("to tell which side of it is up: give --lab-up"), "{err}");
    // Nor can a stated axis across the floor stand.
    let err = impactd_refused(&[&base[..], &["--lab-up", "x"]].concat());
    assert!(err.contains("--lab-up x disagrees") && err.contains("90 deg from the stated x"), "{err}");
    impactd_ok(&[&base[..], &["--lab-up", "y"]].concat());
}

#[test]
fn collinear_floor_markers_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let capture = dir.path().join("lab.c3d");
    // Foot markers along the target line, 3 cm either side of it: an RMS spread of 30 mm across it.
    let y = -BALL_RADIUS_M + MARKER_RADIUS_M;
    let mut markers = bay();
    for (l, x, z) in [("FOOT1", 0.2, 0.03), ("FOOT2", 0.5, -0.03), ("FOOT3", 1.0, 0.03), ("FOOT4", 1.3, -0.03)] {
        markers.push((l.to_string(), Vector3::new(x, y, z)));
    }
    write_trial(&capture, &world_from_lab(true), &markers, 8, STILL);
    let c = capture.to_str().unwrap();
    let base = ["calibrate", "lab", c, "--frames", "50", "--target-line", "REAR,FRONT", "--ball", "BALL"];
    let err = impactd_refused(&[&base[..], &["--floor", "FOOT1,FOOT2,FOOT3,FOOT4"]].concat());
    assert!(err.contains("nearly on one line") && err.contains("under the 50 mm"), "{err}");
    let spread: f64 = err.split("they spread ").nth(1).unwrap().split(" mm").next().unwrap().parse().unwrap();
    assert!((spread - 30.0).abs() < 3.0, "{err}");
    // With the target-line markers they span the floor.
    impactd_ok(&[&base[..], &["--floor", "REAR,FRONT,FOOT1,FOOT2,FOOT3,FOOT4,F1"]].concat());
    // A marker off the floor's plane (a foot's instep) is named.
    markers.push(("INSTEP".into(), Vector3::new(0.8, y + 0.04, 0.6)));
    write_trial(&capture, &world_from_lab(true), &markers, 9, STILL);
    let err = impactd_refused(&[&base[..], &["--floor", "REAR,FRONT,F1,F2,INSTEP"]].concat());
    assert!(err.contains("floor marker `INSTEP`") && err.contains("off the plane"), "{err}");
}
