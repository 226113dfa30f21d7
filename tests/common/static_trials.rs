//! Synthetic static trials of a bay, with a known `world_from_lab` and `club_from_body`: floor and target-line
//! markers, a taped ball, a driver at address with four head markers at unequal distances and two shaft markers,
//! and a pointer touching the face; written as C3D (PyPI `c3d`, tests/common/c3d_writer.rs) with 0.2 mm of noise
//! per axis over 50 frames, in a Z-up or a Y-up lab.

#![allow(clippy::unwrap_used, dead_code)]

use std::path::Path;
use std::process::{Command, Output};

use impactd::equipment::ClubSpec;
use impactd::math::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion, Vector3};
use impactd::rng::Rng;

pub const NOISE_M: f64 = 2e-4;
pub const FRAMES: usize = 50;
pub const RATE_HZ: f64 = 240.0;
pub const BALL_RADIUS_M: f64 = 0.021335;
pub const MARKER_RADIUS_M: f64 = 0.007;

/// The lab: origin 1.5 m behind and 0.8 m right of the ball, 3 cm below the floor, turned 20 degrees about the
/// vertical; its up axis z (Vicon, Qualisys) or y (OptiTrack, OpenSim).
pub fn world_from_lab(z_up: bool) -> Isometry3 {
    world_from_lab_turned(z_up, 20.0)
}

/// The same lab turned `turn_deg` about the vertical (0: a lab axis along the target line).
pub fn world_from_lab_turned(z_up: bool, turn_deg: f64) -> Isometry3 {
    let axes = if z_up {
        UnitQuaternion::from_quaternion(Quaternion::new(0.5, -0.5, -0.5, -0.5))
    } else {
        UnitQuaternion::identity()
    };
    let turn = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), turn_deg.to_radians());
    Isometry3::from_parts(Translation3::new(-1.5, -0.03 - BALL_RADIUS_M, 0.8), turn * axes)
}

pub fn club_from_body() -> Isometry3 {
    Isometry3::new(Vector3::new(0.012, 0.085, -0.025), Vector3::new(0.2, 0.5, -0.1))
}

/// Head markers in the body frame (m): crown, toe, hosel, back, at unequal distances from each other.
pub const BODY: [(&str, [f64; 3]); 4] = [
    ("CROWN", [0.035, 0.0, 0.01]),
    ("TOE", [-0.04, 0.006, 0.014]),
    ("HOSEL", [0.0, 0.028, -0.035]),
    ("BACK", [0.016, -0.022, 0.03]),
];

/// The marker set's TOML (optionally with the face it states in the body frame).
pub fn marker_set(with_face: bool, club: &ClubSpec) -> String {
    let mut text = String::from("[markers]\n");
    for (l, p) in BODY {
        text += &format!("{l} = [{}, {}, {}]\n", p[0], p[1], p[2]);
    }
    if with_face {
        let body_from_club = club_from_body().inverse();
        let c = body_from_club * Point3::from(club.face.center_m);
        let n = body_from_club.rotation * club.face.n0();
        text += &format!("[face]\ncentre_m = [{}, {}, {}]\nnormal = [{}, {}, {}]\n", c.x, c.y, c.z, n.x, n.y, n.z);
    }
    text
}

/// The club at address (world): 3 deg of forward lean, the face 1.5 deg open, the toe 1 deg up, its CG 35 cm
/// behind and 5 cm inside the ball.
pub fn world_from_club_at_address() -> Isometry3 {
    let lean = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), -3f64.to_radians());
    let open = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), -1.5f64.to_radians());
    let toe_up = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), -1f64.to_radians());
    Isometry3::from_parts(Translation3::new(-0.35, 0.02, -0.05), open * lean * toe_up)
}

/// The markers of the club at `world_from_club`: the head's and two on the shaft (20 and 50 cm up it, on one
/// side of it), world positions.
pub fn club_markers(club: &ClubSpec, world_from_club: &Isometry3) -> Vec<(String, Vector3)> {
    let world_from_body = world_from_club * club_from_body();
    let mut out: Vec<(String, Vector3)> =
        BODY.iter().map(|(l, b)| (l.to_string(), (world_from_body * Point3::from(Vector3::from(*b))).coords)).collect();
    let hosel = Vector3::new(0.0, 0.03, -0.06);
    let side = Vector3::new(0.012, 0.0, 0.0);
    for (l, up) in [("SHAFT1", 0.2), ("SHAFT2", 0.5)] {
        let p = hosel + club.shaft_axis_up() * up + side;
        out.push((l.to_string(), (world_from_club * Point3::from(p)).coords));
    }
    out
}

/// Floor markers (world, centres a marker radius above the floor): a rear and a front target-line marker and
/// three more spread over the floor.
pub fn floor_markers() -> Vec<(String, Vector3)> {
    let y = -BALL_RADIUS_M + MARKER_RADIUS_M;
    [("REAR", -0.3, 0.0), ("FRONT", 2.5, 0.0), ("F1", 1.0, 1.2), ("F2", -0.5, -1.0), ("F3", 1.5, -0.9)]
        .iter()
        .map(|(l, x, z)| (l.to_string(), Vector3::new(*x, y, *z)))
        .collect()
}

/// A pointer of three markers on one line (12, 20 and 32 cm from its tip) touching `tip_world`, held along
/// `toward` (from the tip up the wand).
pub fn wand(tip_world: &Vector3, toward: &Vector3) -> Vec<(String, Vector3)> {
    let d = toward.normalize();
    [("W1", 0.12), ("W2", 0.20), ("W3", 0.32)].iter().map(|(l, s)| (l.to_string(), tip_world + d * *s)).collect()
}

/// Writes `frames` noisy copies of markers at world positions into a C3D in the lab `world_from_lab`; `moving`
/// drifts the markers named that many metres along x over the frames (a club that moved).
pub fn write_trial(
    path: &Path,
    world_from_lab: &Isometry3,
    world_m: &[(String, Vector3)],
    seed: u64,
    moving: (&[&str], f64),
) {
    write_trial_of(FRAMES, path, world_from_lab, world_m, seed, moving);
}

/// [`write_trial`] with `count` frames.
pub fn write_trial_of(
    count: usize,
    path: &Path,
    world_from_lab: &Isometry3,
    world_m: &[(String, Vector3)],
    seed: u64,
    moving: (&[&str], f64),
) {
    let mut rng = Rng::new(seed);
    let labels: Vec<String> = world_m.iter().map(|(l, _)| l.clone()).collect();
    let frames = stretch(count, world_from_lab, world_m, &mut rng, moving);
    crate::c3d_writer::write_c3d(&labels, RATE_HZ, &frames, path);
}

/// Writes one C3D of still stretches of `FRAMES` frames each, one after the other (the same labels in each).
pub fn write_stretches(path: &Path, world_from_lab: &Isometry3, stretches: &[Vec<(String, Vector3)>], seed: u64) {
    let mut rng = Rng::new(seed);
    let labels: Vec<String> = stretches[0].iter().map(|(l, _)| l.clone()).collect();
    let frames: Vec<Vec<(Vector3, bool)>> =
        stretches.iter().flat_map(|world_m| stretch(FRAMES, world_from_lab, world_m, &mut rng, STILL)).collect();
    crate::c3d_writer::write_c3d(&labels, RATE_HZ, &frames, path);
}

fn stretch(
    count: usize,
    world_from_lab: &Isometry3,
    world_m: &[(String, Vector3)],
    rng: &mut Rng,
    moving: (&[&str], f64),
) -> Vec<Vec<(Vector3, bool)>> {
    let lab_from_world = world_from_lab.inverse();
    (0..count)
        .map(|k| {
            world_m
                .iter()
                .map(|(l, p)| {
                    let noise = Vector3::new(rng.normal(), rng.normal(), rng.normal()) * NOISE_M;
                    let drift = match moving {
                        (names, metres) if names.contains(&l.as_str()) => {
                            Vector3::x() * metres * k as f64 / (count - 1) as f64
                        }
                        _ => Vector3::zeros(),
                    };
                    ((lab_from_world * Point3::from(*p + drift)).coords + noise, true)
                })
                .collect()
        })
        .collect()
}

pub fn impactd(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_impactd")).args(args).output().unwrap()
}

/// Runs impactd, which must succeed; its standard error.
pub fn impactd_ok(args: &[&str]) -> String {
    let out = impactd(args);
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(out.status.success(), "impactd {args:?}: {err}");
    err
}

/// Runs impactd, which must fail; its standard error.
pub fn impactd_refused(args: &[&str]) -> String {
    let out = impactd(args);
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(!out.status.success(), "impactd {args:?} succeeded: {err}");
    err
}

/// The pose of a `[rig.NAME]` section.
pub fn pose(path: &Path, name: &str) -> Isometry3 {
    let v: toml::Value = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let s = &v["rig"][name];
    let f = |k: &str| s[k].as_array().unwrap().iter().map(|x| x.as_float().unwrap()).collect::<Vec<_>>();
    let (q, t) = (f("rotation_xyzw"), f("translation_m"));
    Isometry3::from_parts(
        Translation3::new(t[0], t[1], t[2]),
        UnitQuaternion::from_quaternion(Quaternion::new(q[3], q[0], q[1], q[2])),
    )
}

/// How far `got` is from `want`: (deg, mm); printed, for the record.
pub fn error_of(got: &Isometry3, want: &Isometry3, what: &str) -> (f64, f64) {
    let angle_deg = got.rotation.angle_to(&want.rotation).to_degrees();
    let offset_mm = (got.translation.vector - want.translation.vector).norm() * 1e3;
    eprintln!("{what}: {angle_deg:.4} deg, {offset_mm:.4} mm off");
    (angle_deg, offset_mm)
}

/// Within the calibration's targets: 0.2 deg and 1 mm.
pub fn assert_recovered(got: &Isometry3, want: &Isometry3, what: &str) {
    assert_within(got, want, 0.2, what);
}

/// Within `deg` and 1 mm.
pub fn assert_within(got: &Isometry3, want: &Isometry3, deg: f64, what: &str) {
    let (angle_deg, mm) = error_of(got, want, what);
    assert!(angle_deg < deg && mm < 1.0, "{what}: {angle_deg} deg, {mm} mm off (limit {deg} deg, 1 mm)");
}

/// A still trial: no marker moves.
pub const STILL: (&[&str], f64) = (&[], 0.0);

/// A configuration with the bay's rig and its true `world_from_lab`.
pub fn config(path: &Path, w: &Isometry3) {
    std::fs::write(
        path,
        format!(
            "[[rig]]\nname = \"bay1\"\nclub = \"driver\"\n[rig.world_from_lab]\nrotation_xyzw = [{}, {}, {}, {}]\ntranslation_m = [{}, {}, {}]\n",
            w.rotation.i, w.rotation.j, w.rotation.k, w.rotation.w, w.translation.x, w.translation.y, w.translation.z
        ),
    )
    .unwrap();
}
