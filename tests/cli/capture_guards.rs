//! The failures issue 45 found silent, each reproduced on a synthetic swing written as JSONL samples and run
//! through `impactd replay`: each now fails or warns with its reason. And the impact instant measured from the
//! head's speed step beside the geometric contact, and one the user gives (`--impact-frame`).

use std::process::{Command, Output};

use impactd::equipment::ClubSpec;
use impactd::impact::Equipment;
use impactd::kinematics::ClubheadSample;
use impactd::math::{Isometry3, Point3, Vector3};
use impactd::offline::swing::{Swing, SwingSpec};
use impactd::rng::Rng;
use impactd::wire::{ClubheadSampleMsg, LaunchPrediction};

/// When the impact falls (s from the first frame).
const T_IMPACT_S: f64 = 0.3;

/// A driver swing at `club_speed_mps`.
fn swing(club_speed_mps: f64, seed: u64) -> Swing {
    let club = ClubSpec::driver();
    let mut spec = SwingSpec::random(&club, &mut Rng::new(seed));
    spec.delivery.club_speed_mps = club_speed_mps;
    Swing::new(&spec, &Equipment::new(club)).unwrap()
}

/// The swing's frames at `rate_hz` as JSONL (the club's pose, identity calibration, the ball at the origin), from
/// 80 ms before the impact to 30 ms after it, occluded outside; `keep(frame, tau)` drops frames, `edit` moves a
/// pose, `noise_m` is Gaussian noise on each position.
fn jsonl(
    s: &Swing,
    rate_hz: f64,
    noise_m: f64,
    keep: impl Fn(u64, f64) -> bool,
    edit: impl Fn(Isometry3) -> Isometry3,
) -> String {
    let mut rng = Rng::new(7);
    let frames = ((T_IMPACT_S + 0.2) * rate_hz) as u64;
    let t_impact = T_IMPACT_S + 0.37 / rate_hz;
    let mut out = String::new();
    for i in 0..frames {
        let (frame, t) = (i + 1, i as f64 / rate_hz);
        let tau = t - t_impact;
        if !keep(frame, tau) {
            continue;
        }
        let seen = (-0.08..0.03).contains(&tau);
        let pose = if seen { edit(s.pose(tau)) } else { Isometry3::identity() };
        let noise = Vector3::new(rng.normal(), rng.normal(), rng.normal()) * noise_m;
        let q = pose.rotation;
        let sample = ClubheadSample {
            frame,
            t_ns: (t * 1e9).round() as u64,
            position_m: pose.translation.vector + if seen { noise } else { Vector3::zeros() },
            orientation_xyzw: [q.i, q.j, q.k, q.w],
            occluded: !seen,
        };
        out += &serde_json::to_string(&ClubheadSampleMsg::from_sample("bay1", &sample)).unwrap();
        out.push('\n');
    }
    out
}

/// The frame numbers just before the impact (`k` = 1: the newest before it).
fn frame_before_impact(rate_hz: f64, k: u64) -> u64 {
    let t_impact = T_IMPACT_S + 0.37 / rate_hz;
    (t_impact * rate_hz).floor() as u64 + 1 - (k - 1)
}

fn replay(lines: &str, extra: &[&str]) -> (Output, Vec<LaunchPrediction>, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("swing.jsonl");
    std::fs::write(&path, lines).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .arg("replay")
        .arg(&path)
        .args(extra)
        .current_dir(dir.path())
        .output()
        .unwrap();
    let launches = String::from_utf8_lossy(&out.stdout).lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    (out, launches, err)
}

fn config(dir: &std::path::Path, extra: &str) -> String {
    let path = dir.join("impactd.toml");
    std::fs::write(&path, format!("[[rig]]\nname = \"bay1\"\nclub = \"driver\"\n{extra}")).unwrap();
    path.to_str().unwrap().to_string()
}

/// Inches read as centimetres: every distance 2.54 times too long, so a 52.1 m/s (116.5 mph) swing is a 296 mph
/// one. The face centre's path is scaled about its place at impact, so the impact is still found, and refused.
#[test]
fn a_capture_in_the_wrong_units_is_refused_by_the_speed_bound() {
    let s = swing(52.1, 11);
    let r_fc = ClubSpec::driver().face.center_m;
    let at_impact = (s.pose(0.0) * Point3::from(r_fc)).coords;
    let scaled = |pose: Isometry3| {
        let face = pose * Point3::from(r_fc);
        let moved = at_impact + (face.coords - at_impact) * 2.54 - pose.rotation * r_fc;
        Isometry3::from_parts(moved.into(), pose.rotation)
    };
    let (out, launches, err) = replay(&jsonl(&s, 360.0, 0.0, |_, _| true, scaled), &[]);
    assert!(launches.is_empty(), "no launch from a 296 mph club");
    assert!(err.contains("no prediction: the club head moves at"), "{err}");
    assert!(err.contains("faster than any golfer swings (bound 70 m/s)"), "{err}");
    let mph: f64 = err.split(" mph)").next().unwrap().rsplit('(').next().unwrap().parse().unwrap();
    assert!((mph - 296.0).abs() < 3.0, "{mph} mph: {err}");
    assert_eq!(out.status.code(), Some(2), "swings found, none predicted: {err}");
}

/// Three frames lost shortly before the impact at 360 Hz: the launch warns and says how many and how long.
#[test]
fn a_gap_of_three_frames_before_impact_is_a_warning_with_the_gap() {
    let s = swing(45.0, 12);
    let lost: Vec<u64> = (2..=4).map(|k| frame_before_impact(360.0, k)).collect();
    let (out, launches, err) = replay(&jsonl(&s, 360.0, 0.0, |f, _| !lost.contains(&f), |p| p), &[]);
    assert!(out.status.success(), "{err}");
    assert_eq!(launches.len(), 1, "{err}");
    let l = &launches[0];
    assert!(l.launch.warnings.iter().any(|w| w.as_str() == "frame_gap_before_impact"), "{:?}", l.launch.warnings);
    let gap = l.impact_timing.unwrap().frame_gap.unwrap();
    assert_eq!(gap.frames, 3, "{gap:?}");
    assert!((gap.gap_ms - 4.0 / 0.36).abs() < 0.01, "{gap:?}");
    assert!(err.contains("warning: 3 frames missing before the impact (11.1 ms without a frame"), "{err}");
    // The same swing without the gap has no warning and nothing in `impact_timing`.
    let (_, clean, _) = replay(&jsonl(&s, 360.0, 0.0, |_, _| true, |p| p), &[]);
    assert!(clean[0].launch.warnings.is_empty() && clean[0].impact_timing.is_none(), "{:?}", clean[0]);
}

/// A ball 12 cm beside the face's path: the swing passes it. The replay used to print "0 predictions, 0 failed"
/// and exit 0; it now says how the swing missed and exits 2.
#[test]
fn a_replay_whose_swings_predict_nothing_exits_2_and_says_why_for_each_swing() {
    let s = swing(45.0, 13);
    let dir = tempfile::tempdir().unwrap();
    let c = config(dir.path(), "ball_position_m = [0.0, 0.12, 0.0]\n");
    let (out, launches, err) = replay(&jsonl(&s, 360.0, 0.0, |_, _| true, |p| p), &["-c", &c]);
    assert!(launches.is_empty(), "{err}");
    assert!(err.contains("0 predictions, 0 failed"), "{err}");
    assert!(err.contains("no prediction: a swing (frames"), "{err}");
    assert!(err.contains("did not reach the ball: the ball was") && err.contains("mm above the face"), "{err}");
    assert!(err.contains("1 swings found") && err.contains("exit 2"), "{err}");
    assert_eq!(out.status.code(), Some(2), "{err}");
}

/// At 720 and 360 Hz the head's speed step (the impulse-momentum model's, about a third of the speed) is placed
/// within the frame interval of the geometric contact, and the replay says both.
#[test]
fn the_speed_step_is_reported_beside_the_geometric_contact() {
    for rate in [720.0, 360.0] {
        let s = swing(45.0, 14);
        let (out, launches, err) = replay(&jsonl(&s, rate, 0.2e-3, |_, _| true, |p| p), &[]);
        assert!(out.status.success() && launches.len() == 1, "{rate} Hz: {err}");
        let line = err.lines().find(|l| l.contains("impact at the geometric contact")).unwrap_or_default();
        assert!(line.contains("the head's speed steps down at") && line.contains("within the frame interval"), "{err}");
    }
}

/// The ball configured 8 cm further along the path than the swing's real ball: the geometric contact comes about
/// 2 ms after the step the head shows, more than a 720 Hz frame interval, and the replay warns.
#[test]
fn a_geometric_contact_that_disagrees_with_the_speed_step_is_warned() {
    let s = swing(45.0, 15);
    let dir = tempfile::tempdir().unwrap();
    let v = s.delivery.direction();
    let c = config(dir.path(), &format!("ball_position_m = [{}, {}, {}]\n", 0.08 * v.x, 0.08 * v.y, 0.08 * v.z));
    let (_, _, err) = replay(&jsonl(&s, 720.0, 0.0, |_, _| true, |p| p), &["-c", &c]);
    let line = err.lines().find(|l| l.contains("impact at the geometric contact")).unwrap_or_default();
    assert!(line.contains("warning: more than the frame interval"), "{err}");
}

/// `--impact-frame N`: the estimate is at that frame, and the launch and the replay say so.
#[test]
fn an_impact_frame_the_user_gives_is_used_and_said() {
    let s = swing(45.0, 16);
    let frame = frame_before_impact(360.0, 1);
    let (out, launches, err) =
        replay(&jsonl(&s, 360.0, 0.0, |_, _| true, |p| p), &["--impact-frame", &frame.to_string()]);
    assert!(out.status.success() && launches.len() == 1, "{err}");
    let timing = launches[0].impact_timing.unwrap();
    assert_eq!(timing.instant, impactd::wire::ImpactInstant::Given);
    assert!(
        err.contains("the impact instant is given (--impact-frame") && err.contains("impact at the given instant"),
        "{err}"
    );
}

/// The swing's frames as a pose table (CSV: time in s, the club's position in m, its quaternion xyzw), `swings`
/// copies of the swing one after the other (each `T_IMPACT_S + 0.2` s long), empty cells where it is not seen:
/// what `impactd import` reads with `--columns`.
fn pose_table(s: &Swing, rate_hz: f64, swings: u64) -> String {
    let per_swing = ((T_IMPACT_S + 0.2) * rate_hz) as u64;
    let t_impact = T_IMPACT_S + 0.37 / rate_hz;
    let mut out = String::from("t,x,y,z,qx,qy,qz,qw\n");
    for i in 0..per_swing * swings {
        let t = i as f64 / rate_hz;
        let tau = (i % per_swing) as f64 / rate_hz - t_impact;
        if !(-0.08..0.03).contains(&tau) {
            out += &format!("{t:.9},,,,,,,\n");
            continue;
        }
        let pose = s.pose(tau);
        let (p, q) = (pose.translation.vector, pose.rotation);
        out += &format!("{t:.9},{:.9},{:.9},{:.9},{:.12},{:.12},{:.12},{:.12}\n", p.x, p.y, p.z, q.i, q.j, q.k, q.w);
    }
    out
}

const POSE_COLUMNS: &str = "time=t:s; position=x,y,z:m; quaternion-xyzw=qx,qy,qz,qw";

/// `impactd import` of a pose table into `samples.jsonl` with `extra`; its exit, stderr and the samples' lines.
fn import(table: &str, extra: &[&str]) -> (Output, String, usize) {
    let dir = tempfile::tempdir().unwrap();
    let (path, samples) = (dir.path().join("swing.csv"), dir.path().join("samples.jsonl"));
    std::fs::write(&path, table).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .arg("import")
        .arg(&path)
        .args(["--columns", POSE_COLUMNS, "--rig", "bay1", "-o"])
        .arg(&samples)
        .args(extra)
        .current_dir(dir.path())
        .output()
        .unwrap();
    let lines = std::fs::read_to_string(&samples).map(|t| t.lines().count()).unwrap_or(0);
    (out.clone(), String::from_utf8_lossy(&out.stderr).into_owned(), lines)
}

/// Two swings that pass a ball configured 12 cm beside the face's path: `import -c` writes every sample all the
/// same, says for each swing how it missed, and exits 2 (a capture checked that predicts nothing).
#[test]
fn an_import_whose_swings_predict_nothing_exits_2_and_says_why_for_each_swing() {
    let s = swing(45.0, 13);
    let dir = tempfile::tempdir().unwrap();
    let c = config(dir.path(), "ball_position_m = [0.0, 0.12, 0.0]\n");
    let table = pose_table(&s, 360.0, 2);
    let (out, err, lines) = import(&table, &["-c", &c]);
    assert_eq!(lines, table.lines().count() - 1, "a sample a row, checked or not: {err}");
    assert_eq!(err.matches("no prediction: a swing (frames").count(), 2, "each swing's reason: {err}");
    assert_eq!(err.matches("did not reach the ball: the ball was").count(), 2, "{err}");
    assert!(err.contains("mm above the face"), "{err}");
    assert!(err.contains("checked with rig bay1: 0 predictions, 0 failed, 2 swings missed"), "{err}");
    assert!(err.contains("2 swings found") && err.contains("exit 2"), "{err}");
    assert_eq!(out.status.code(), Some(2), "{err}");
}

/// The same swings and the ball where the swing meets it: `import -c` checks them, a prediction each, exit 0; and
/// without -c it says the swings were not checked.
#[test]
fn an_import_checked_with_its_config_gives_each_swings_launch_and_exits_0() {
    let s = swing(45.0, 13);
    let dir = tempfile::tempdir().unwrap();
    let c = config(dir.path(), "");
    let table = pose_table(&s, 360.0, 2);
    let (out, err, lines) = import(&table, &["-c", &c]);
    assert!(out.status.success(), "{err}");
    assert_eq!(lines, table.lines().count() - 1, "{err}");
    assert!(err.contains("checked with rig bay1: 2 predictions, 0 failed, 0 swings missed"), "{err}");
    assert!(!err.contains("no prediction"), "{err}");
    let (out, err, _) = import(&table, &[]);
    assert!(out.status.success() && err.contains("swings not checked: import with -c CONFIG"), "{err}");
}
