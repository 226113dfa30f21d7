//! Calibration from synthetic static trials with a known `club_from_body` and `world_from_lab`, written as C3D
//! by an independent writer (PyPI `c3d`) with 0.1 mm of marker noise per axis: `impactd calibrate lab`, `club`
//! and `body` recover them within 0.1 deg and 0.5 mm (the targets), averaging 200 frames.

#![allow(clippy::unwrap_used)]

use crate::c3d_writer;

use std::path::Path;
use std::process::Command;

use impactd::equipment::ClubSpec;
use impactd::kinematics::MarkerSet;
use impactd::math::{Isometry3, Point3, Vector3};
use impactd::rng::Rng;

const NOISE_M: f64 = 1e-4;
const FRAMES: usize = 200;
const BALL_RADIUS_M: f64 = 0.021335;
const MARKER_RADIUS_M: f64 = 0.007;

/// The lab: z up, origin 1.5 m behind and 0.8 m right of the ball, 3 cm below the floor, turned 20 degrees
/// about the vertical.
fn world_from_lab() -> Isometry3 {
    let z_up = impactd::math::UnitQuaternion::from_quaternion(impactd::math::Quaternion::new(0.5, -0.5, -0.5, -0.5));
    let turn = impactd::math::UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 20f64.to_radians());
    Isometry3::from_parts(impactd::math::Translation3::new(-1.5, -0.03 - BALL_RADIUS_M, 0.8), turn * z_up)
}

fn club_from_body() -> Isometry3 {
    Isometry3::new(Vector3::new(0.012, 0.085, -0.025), Vector3::new(0.2, 0.5, -0.1))
}

const BODY: [(&str, [f64; 3]); 4] = [
    ("CH1", [0.035, 0.0, 0.01]),
    ("CH2", [-0.035, 0.004, 0.012]),
    ("TOE", [0.0, 0.025, -0.03]),
    ("HEEL", [0.012, -0.022, 0.028]),
];

/// `frames` noisy copies of the markers at their world positions, in the lab.
fn trial(world_m: &[(String, Vector3)], rng: &mut Rng) -> (Vec<String>, Vec<Vec<(Vector3, bool)>>) {
    let lab_from_world = world_from_lab().inverse();
    let labels = world_m.iter().map(|(l, _)| l.clone()).collect();
    let frames = (0..FRAMES)
        .map(|_| {
            world_m
                .iter()
                .map(|(_, p)| {
                    let noise = Vector3::new(rng.normal(), rng.normal(), rng.normal()) * NOISE_M;
                    ((lab_from_world * Point3::from(*p)).coords + noise, true)
                })
                .collect()
        })
        .collect();
    (labels, frames)
}

fn impactd(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_impactd")).args(args).output().unwrap();
    assert!(out.status.success(), "impactd {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap() + &String::from_utf8(out.stderr).unwrap()
}

/// The pose of a `[rig.NAME]` section.
fn pose(path: &Path, name: &str) -> Isometry3 {
    let text = std::fs::read_to_string(path).unwrap();
    let v: toml::Value = toml::from_str(&text).unwrap();
    let s = &v["rig"][name];
    let f = |k: &str| s[k].as_array().unwrap().iter().map(|x| x.as_float().unwrap()).collect::<Vec<_>>();
    let (q, t) = (f("rotation_xyzw"), f("translation_m"));
    Isometry3::from_parts(
        impactd::math::Translation3::new(t[0], t[1], t[2]),
        impactd::math::UnitQuaternion::from_quaternion(impactd::math::Quaternion::new(q[3], q[0], q[1], q[2])),
    )
}

fn assert_close(got: &Isometry3, want: &Isometry3, what: &str) {
    let angle_deg = got.rotation.angle_to(&want.rotation).to_degrees();
    let offset_mm = (got.translation.vector - want.translation.vector).norm() * 1e3;
    eprintln!("{what}: {angle_deg:.4} deg, {offset_mm:.4} mm off");
    assert!(angle_deg < 0.1 && offset_mm < 0.5, "{what}: {angle_deg} deg, {offset_mm} mm off");
}

#[test]
fn lab_from_the_target_line_and_the_floor() {
    let dir = tempfile::tempdir().unwrap();
    let floor_y = -BALL_RADIUS_M + MARKER_RADIUS_M; // marker centres on the floor
    let world = |l: &str, x: f64, z: f64| (l.to_string(), Vector3::new(x, floor_y, z));
    let markers = vec![
        world("REAR", 0.0, 0.0),
        world("FRONT", 2.5, 0.0),
        world("F1", 1.0, 1.2),
        world("F2", -0.5, -1.0),
        world("F3", 1.5, -0.9),
    ];
    let (labels, frames) = trial(&markers, &mut Rng::new(1));
    let capture = dir.path().join("lab.c3d");
    c3d_writer::write_c3d(&labels, 100.0, &frames, &capture);
    let out = dir.path().join("lab.toml");
    let (c, o) = (capture.to_str().unwrap(), out.to_str().unwrap());
    let frames = FRAMES.to_string();
    let r =
        ["calibrate", "lab", c, "--frames", &frames, "--target-line", "REAR,FRONT", "--floor", "REAR,FRONT,F1,F2,F3"];
    // Only floor markers and a ball 14 mm above their plane: nothing stands off the floor to say which side is up.
    let r = [&r[..], &["--lab-up", "z"]].concat();
    impactd(&[&r[..], &["--marker-radius-mm", "7", "-o", o]].concat());
    assert_close(&pose(&out, "world_from_lab"), &world_from_lab(), "world_from_lab (ball at the rear marker)");

    // A taped ball 30 cm in front of the rear marker on the line sets the origin instead.
    let mut with_ball = markers.clone();
    with_ball[0].1.x = -0.3;
    with_ball.push(("BALL".into(), Vector3::zeros()));
    let (labels, frames) = trial(&with_ball, &mut Rng::new(2));
    c3d_writer::write_c3d(&labels, 100.0, &frames, &capture);
    impactd(&[&r[..], &["--ball", "BALL", "-o", o]].concat());
    assert_close(&pose(&out, "world_from_lab"), &world_from_lab(), "world_from_lab (ball marker)");
}

/// The club at a square address (world axes), its body's markers and face stickers.
fn address(club: &ClubSpec, cg_world: Vector3) -> (Isometry3, Vec<(String, Vector3)>) {
    let world_from_club =
        Isometry3::from_parts(impactd::math::Translation3::from(cg_world), impactd::math::UnitQuaternion::identity());
    let world_from_body = world_from_club * club_from_body();
    let mut markers: Vec<(String, Vector3)> =
        BODY.iter().map(|(l, b)| (l.to_string(), (world_from_body * Point3::from(Vector3::from(*b))).coords)).collect();
    let loft = club.face.loft_rad;
    let (n0, u0, t0) =
        (Vector3::new(loft.cos(), loft.sin(), 0.0), Vector3::new(-loft.sin(), loft.cos(), 0.0), Vector3::z());
    let c = club.face.center_m;
    for (l, h, v) in
        [("FHEEL", -0.03, 0.0), ("FTOE", 0.03, 0.0), ("FUP", 0.0, 0.012), ("FDOWN", 0.0, -0.012), ("FC", 0.0, 0.0)]
    {
        let club_p = c + t0 * h + u0 * v + n0 * MARKER_RADIUS_M;
        markers.push((l.to_string(), (world_from_club * Point3::from(club_p)).coords));
    }
    (world_from_club, markers)
}

#[test]
fn club_from_face_markers_and_from_a_square_address() {
    let dir = tempfile::tempdir().unwrap();
    let club = ClubSpec::driver();
    let config = dir.path().join("impactd.toml");
    let w = world_from_lab();
    std::fs::write(
        &config,
        format!(
            "[[rig]]\nname = \"bay1\"\nclub = \"driver\"\n[rig.world_from_lab]\nrotation_xyzw = [{}, {}, {}, {}]\ntranslation_m = [{}, {}, {}]\n",
            w.rotation.i, w.rotation.j, w.rotation.k, w.rotation.w, w.translation.x, w.translation.y, w.translation.z
        ),
    )
    .unwrap();
    let set = dir.path().join("club.toml");
    let body = MarkerSet::new(BODY.iter().map(|(l, p)| (l.to_string(), Vector3::from(*p)))).unwrap();
    std::fs::write(&set, body.to_toml()).unwrap();
    let capture = dir.path().join("club.c3d");
    let out = dir.path().join("club_from_body.toml");
    let frames = FRAMES.to_string();
    let (c, s, o, cfg) =
        (capture.to_str().unwrap(), set.to_str().unwrap(), out.to_str().unwrap(), config.to_str().unwrap());
    let base = ["calibrate", "club", c, "--markers", s, "--frames", &frames, "-c", cfg, "-o", o];

    // Face markers, with and without the face-centre marker; the club anywhere (here 40 cm from the ball).
    let (_, markers) = address(&club, Vector3::new(-0.4, 0.1, 0.3));
    let (labels, trial_frames) = trial(&markers, &mut Rng::new(3));
    c3d_writer::write_c3d(&labels, 200.0, &trial_frames, &capture);
    let log = impactd(
        &[&base[..], &["--face", "FHEEL,FTOE,FUP,FDOWN", "--face-centre", "FC", "--marker-radius-mm", "7"]].concat(),
    );
    assert_close(&pose(&out, "club_from_body"), &club_from_body(), "club_from_body (face markers and centre)");
    // The club was at its own loft and lie: the residuals against the club file are within the noise.
    let residual: f64 = log.split("deg (").nth(1).unwrap().split(" deg against").next().unwrap().parse().unwrap();
    let lie: f64 = log.split("lie ").nth(1).unwrap().split(" deg").next().unwrap().parse().unwrap();
    assert!(residual.abs() < 0.1 && lie.abs() < 0.1, "{log}");
    impactd(&[&base[..], &["--face", "FHEEL,FTOE,FUP,FDOWN", "--marker-radius-mm", "7"]].concat());
    assert_close(&pose(&out, "club_from_body"), &club_from_body(), "club_from_body (face markers)");

    // Soled square with the face centre against the ball at the origin.
    let loft = club.face.loft_rad;
    let face_centre = -Vector3::new(loft.cos(), loft.sin(), 0.0) * impactd::equipment::BallSpec::default().radius_m;
    let (_, markers) = address(&club, face_centre - club.face.center_m);
    let (labels, trial_frames) = trial(&markers[..BODY.len()], &mut Rng::new(4));
    c3d_writer::write_c3d(&labels, 200.0, &trial_frames, &capture);
    impactd(&base);
    assert_close(&pose(&out, "club_from_body"), &club_from_body(), "club_from_body (soled square)");

    // And `calibrate body` gives a set the static trial fits with no residual beyond the noise.
    let set_out = dir.path().join("body.toml");
    impactd(&[
        "calibrate",
        "body",
        c,
        "--frames",
        &frames,
        "--labels",
        "CH1,CH2,TOE,HEEL",
        "-o",
        set_out.to_str().unwrap(),
    ]);
    let fitted = MarkerSet::from_toml(&std::fs::read_to_string(&set_out).unwrap()).unwrap();
    let order = body.indices_in(&fitted.labels).unwrap();
    for (k, b) in body.body_m.iter().enumerate() {
        // Same shape: distances between markers agree to the averaged noise (0.1 mm / sqrt(200) per axis).
        let a = fitted.body_m[order[k]] - fitted.body_m[order[0]];
        assert!((a.norm() - (b - body.body_m[0]).norm()).abs() < 5e-5, "{}", body.labels[k]);
    }
}
