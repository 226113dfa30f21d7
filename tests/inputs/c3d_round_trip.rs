//! Round trip: synthetic swings (`impactd::offline::swing`) written as markers to a C3D file by an independent writer
//! (PyPI `c3d`, pinned in scripts/test-requirements.txt), with 0.1 mm of marker noise, occluded markers whose
//! coordinates are left stale, a ghost marker and frames with too few markers; then `impactd import` and
//! `impactd replay` give the launches of the same swings replayed as exact JSON samples, within the spread that
//! the marker noise itself causes (measured here over 12 noise draws through the same pipeline).

#![allow(clippy::unwrap_used)]

use crate::c3d_writer;

use std::process::Command;

use impactd::daemon::DaemonConfig;
use impactd::equipment::ClubSpec;
use impactd::impact::Equipment;
use impactd::kinematics::{Calibration, ClubPose, MarkerFitter, MarkerSet};
use impactd::math::{Isometry3, Vector3};
use impactd::offline::swing::{Swing, SwingSpec};
use impactd::pipeline::{Event, Pipeline};
use impactd::rng::Rng;
use impactd::wire::{ClubheadSampleMsg, LaunchPrediction};

const RATE_HZ: f64 = 1000.0;
const NOISE_M: f64 = 1e-4;
const SWINGS: usize = 3;

/// The rig: a lab with z up (as Vicon and Qualisys set it) 2 m behind and 0.5 m left of the ball, and the marker
/// cluster's body frame 8 cm above the CG, turned 30 degrees.
const CONFIG: &str = r#"
[[rig]]
name = "bay1"
club = "driver"
[rig.world_from_lab]
rotation_xyzw = [-0.5, -0.5, -0.5, 0.5]
translation_m = [2.0, 0.0, 0.5]
[rig.club_from_body]
rotation_xyzw = [0.0, 0.258819, 0.0, 0.965926]
translation_m = [0.01, 0.08, -0.02]
"#;

/// Labels of different lengths: the writer pads them with trailing spaces.
const MARKERS: &str = r#"
[markers]
CH1 = [0.035, 0.0, 0.01]
CH2 = [-0.035, 0.004, 0.012]
TOE = [0.0, 0.025, -0.03]
HEEL = [0.012, -0.022, 0.028]
C = [-0.02, -0.015, -0.02]
"#;

struct Capture {
    /// Per frame, per marker: lab position (m) and whether it is valid.
    frames: Vec<Vec<(Vector3, bool)>>,
    /// The exact body poses as samples (the JSON swing).
    exact: Vec<ClubheadSampleMsg>,
}

fn calibration() -> Calibration {
    let (_, setups) = DaemonConfig::parse(CONFIG).unwrap();
    setups[0].calibration
}

fn swings() -> Vec<(f64, Swing)> {
    let club = ClubSpec::driver();
    let eq = Equipment::new(club.clone());
    let mut rng = Rng::new(30);
    (0..SWINGS)
        .map(|k| {
            (
                0.3 + 1.2 * k as f64 + 0.000_37 * (k + 1) as f64,
                Swing::new(&SwingSpec::random(&club, &mut rng), &eq).unwrap(),
            )
        })
        .collect()
}

/// The markers of the swings, frame by frame; `noise` draws the marker noise, occlusions and ghosts.
fn capture(set: &MarkerSet, noise: Option<&mut Rng>) -> Capture {
    let calibration = calibration();
    let swings = swings();
    let n_frames = ((0.3 + 1.2 * SWINGS as f64) * RATE_HZ) as u64;
    let mut frames = Vec::new();
    let mut exact = Vec::new();
    let mut noise = noise;
    let mut last: Vec<Vector3> = vec![Vector3::zeros(); set.len()];
    for i in 0..n_frames {
        let t = i as f64 / RATE_HZ;
        let t_ns = i * 1_000_000;
        let pose = swings
            .iter()
            .find(|(t_imp, _)| (t - t_imp) > -0.08 && (t - t_imp) < 0.03)
            .map(|(t_imp, s)| s.pose(t - t_imp));
        let Some(world_from_club) = pose else {
            // Between swings nothing is seen; the writer keeps the last coordinates with a -1 residual.
            frames.push(last.iter().map(|p| (*p, false)).collect());
            exact.push(ClubheadSampleMsg::from_sample(
                "bay1",
                &impactd::kinematics::ClubheadSample {
                    frame: i + 1,
                    t_ns,
                    position_m: Vector3::zeros(),
                    orientation_xyzw: [0.0, 0.0, 0.0, 1.0],
                    occluded: true,
                },
            ));
            continue;
        };
        let sample = ClubPose { frame: i + 1, t_ns, world_from_club }.to_sample(&calibration);
        exact.push(ClubheadSampleMsg::from_sample("bay1", &sample));
        let lab_from_body = calibration.lab_from_body(&world_from_club);
        let mut row = Vec::new();
        for (k, b) in set.body_m.iter().enumerate() {
            let mut p = lab_from_body * impactd::math::Point3::from(*b);
            let mut valid = true;
            if let Some(rng) = noise.as_deref_mut() {
                p.coords += Vector3::new(rng.normal(), rng.normal(), rng.normal()) * NOISE_M;
                if rng.chance(0.08) {
                    valid = false; // occluded: stale coordinates
                } else if rng.chance(0.01) {
                    p.coords += Vector3::new(0.0, 0.0, 0.04); // a ghost 4 cm off
                }
            }
            if valid {
                last[k] = p.coords;
            }
            row.push((if valid { p.coords } else { last[k] }, valid));
        }
        frames.push(row);
    }
    Capture { frames, exact }
}

/// Fits the capture's markers and runs the pipeline in-process: the launches (ball speed mph, launch angle,
/// direction, backspin, sidespin) per shot.
fn launches_in_process(set: &MarkerSet, capture: &Capture) -> Vec<[f64; 5]> {
    let fitter = MarkerFitter::new(set.clone());
    let (_, setups) = DaemonConfig::parse(CONFIG).unwrap();
    let mut pipeline = Pipeline::new(setups[0].clone());
    let mut out = Vec::new();
    for (i, row) in capture.frames.iter().enumerate() {
        let lab: Vec<_> = row.iter().map(|(p, v)| v.then_some(*p)).collect();
        let fit = fitter.fit(&lab);
        let pose = fit.as_ref().map(|f| f.lab_from_body).unwrap_or(Isometry3::identity());
        let sample = impactd::kinematics::ClubheadSample {
            frame: i as u64 + 1,
            t_ns: i as u64 * 1_000_000,
            position_m: pose.translation.vector,
            orientation_xyzw: [pose.rotation.i, pose.rotation.j, pose.rotation.k, pose.rotation.w],
            occluded: fit.is_err(),
        };
        let mut events = Vec::new();
        pipeline.on_sample(&sample, &mut events);
        out.extend(events.iter().filter_map(|e| match e {
            Event::Launch(l) => Some(numbers(l)),
            _ => None,
        }));
    }
    out
}

fn numbers(l: &LaunchPrediction) -> [f64; 5] {
    let m = &l.launch.launch;
    [m.ball_speed_mph, m.launch_angle_deg, m.launch_direction_deg, m.backspin_rpm, m.sidespin_rpm]
}

fn impactd(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_impactd")).args(args).output().unwrap();
    assert!(out.status.success(), "impactd {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

fn launches(stdout: &str) -> Vec<[f64; 5]> {
    stdout.lines().map(|l| numbers(&serde_json::from_str::<LaunchPrediction>(l).unwrap())).collect()
}

#[test]
fn a_capture_of_markers_gives_the_json_swings_launches() {
    let dir = tempfile::tempdir().unwrap();
    let set = MarkerSet::from_toml(MARKERS).unwrap();
    let config = dir.path().join("impactd.toml");
    std::fs::write(&config, CONFIG).unwrap();
    let set_path = dir.path().join("club.toml");
    std::fs::write(&set_path, MARKERS).unwrap();

    // The JSON swing: the exact body poses.
    let exact = capture(&set, None);
    let jsonl: String = exact.exact.iter().map(|s| serde_json::to_string(s).unwrap() + "\n").collect();
    let swing_jsonl = dir.path().join("swing.jsonl");
    std::fs::write(&swing_jsonl, jsonl).unwrap();
    let truth = launches(&impactd(&["replay", swing_jsonl.to_str().unwrap(), "-c", config.to_str().unwrap()]));
    assert_eq!(truth.len(), SWINGS, "one launch per swing");

    // The spread the marker noise causes, per shot and number: 12 draws through the same fit and pipeline.
    let draws: Vec<Vec<[f64; 5]>> =
        (0..12).map(|seed| launches_in_process(&set, &capture(&set, Some(&mut Rng::new(100 + seed))))).collect();
    let mut sigma = [[0.0f64; 5]; SWINGS];
    for (shot, s) in sigma.iter_mut().enumerate() {
        for (k, v) in s.iter_mut().enumerate() {
            let xs: Vec<f64> = draws.iter().map(|d| d[shot][k] - truth[shot][k]).collect();
            *v = (xs.iter().map(|x| x * x).sum::<f64>() / xs.len() as f64).sqrt();
        }
    }

    // The capture through C3D, import and replay.
    let noisy = capture(&set, Some(&mut Rng::new(7)));
    let c3d_path = dir.path().join("capture.c3d");
    c3d_writer::write_c3d(&set.labels, RATE_HZ, &noisy.frames, &c3d_path);
    let info: serde_json::Value =
        serde_json::from_str(&impactd(&["info", c3d_path.to_str().unwrap(), "--json"])).unwrap();
    assert_eq!(info["frames"], noisy.frames.len());
    assert_eq!(info["rate_hz"], RATE_HZ);
    assert_eq!(info["markers"], serde_json::json!(set.labels));
    let imported = dir.path().join("imported.jsonl");
    let (c, s, i) = (c3d_path.to_str().unwrap(), set_path.to_str().unwrap(), imported.to_str().unwrap());
    impactd(&["import", c, "--markers", s, "--rig", "bay1", "-o", i]);
    let samples: Vec<ClubheadSampleMsg> =
        std::fs::read_to_string(&imported).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(samples.len(), noisy.frames.len());
    for (k, (sample, row)) in samples.iter().zip(&noisy.frames).enumerate() {
        assert_eq!((sample.frame, sample.t_ns), (k as u64 + 1, k as u64 * 1_000_000));
        let valid = row.iter().filter(|(_, v)| *v).count();
        if valid < 3 {
            assert!(sample.occluded, "frame {k}: {valid} valid markers");
        }
    }
    let via_import = launches(&impactd(&["replay", i, "-c", config.to_str().unwrap()]));
    let direct = impactd(&["replay", c, "--markers", s, "-c", config.to_str().unwrap()]);
    assert_eq!(launches(&direct), via_import, "replay of the capture and of its import agree");
    assert_eq!(via_import.len(), SWINGS);
    let names = ["ball speed mph", "launch deg", "direction deg", "backspin rpm", "sidespin rpm"];
    for (shot, (got, want)) in via_import.iter().zip(&truth).enumerate() {
        for k in 0..5 {
            // 4 sigma of the noise's own spread; the floors are far below any launch monitor's resolution.
            let floor = [0.01, 0.01, 0.01, 1.0, 1.0][k];
            let limit = (4.0 * sigma[shot][k]).max(floor);
            eprintln!("shot {shot} {}: {:.3} vs {:.3} (noise sigma {:.3})", names[k], got[k], want[k], sigma[shot][k]);
            assert!(
                (got[k] - want[k]).abs() <= limit,
                "shot {shot} {}: {} vs {} (limit {limit})",
                names[k],
                got[k],
                want[k]
            );
        }
    }
}

/// A marker on top of the ball (14 mm marker, so its centre 28.35 mm above the ball's) 4 mm right of the
/// configured ball, read with `--ball-marker BALL --ball-offset-mm` (the offset in the capture's own z-up axes):
/// every launch says its ball was tracked, at the ball's centre; `import` writes the ball's lines beside the
/// samples and a replay of the import agrees with the replay of the capture.
#[test]
fn a_ball_marker_sets_the_ball_of_each_shot() {
    use impactd::wire::BallSource;
    let dir = tempfile::tempdir().unwrap();
    let set = MarkerSet::from_toml(MARKERS).unwrap();
    let config = dir.path().join("impactd.toml");
    std::fs::write(&config, CONFIG).unwrap();
    let set_path = dir.path().join("club.toml");
    std::fs::write(&set_path, MARKERS).unwrap();
    let world_from_lab = calibration().world_from_lab;
    let ball_world = Vector3::new(0.0, 0.0, 0.004);
    let above_m = 0.021335 + 0.007;
    let marker_lab =
        world_from_lab.inverse() * impactd::math::Point3::from(ball_world + Vector3::new(0.0, above_m, 0.0));
    let offset_lab_mm = world_from_lab.rotation.inverse() * Vector3::new(0.0, -above_m * 1e3, 0.0);
    let mut frames = capture(&set, None).frames;
    for row in &mut frames {
        row.push((marker_lab.coords, true));
    }
    let mut labels = set.labels.clone();
    labels.push("BALL".into());
    let c3d_path = dir.path().join("ball.c3d");
    c3d_writer::write_c3d(&labels, RATE_HZ, &frames, &c3d_path);
    let offset = format!("{:.6},{:.6},{:.6}", offset_lab_mm.x, offset_lab_mm.y, offset_lab_mm.z);
    let (c, s, cfg) = (c3d_path.to_str().unwrap(), set_path.to_str().unwrap(), config.to_str().unwrap());
    let ball_flags = ["--ball-marker", "BALL", "--ball-offset-mm", offset.as_str()];
    let direct = impactd(&[&["replay", c, "--markers", s, "-c", cfg], &ball_flags[..]].concat());
    let launches: Vec<LaunchPrediction> = direct.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(launches.len(), SWINGS);
    for l in &launches {
        let used = l.ball.unwrap();
        assert_eq!(used.source, BallSource::Tracked);
        let err = (Vector3::from(used.position_m) - ball_world).norm();
        assert!(err < 1e-6, "shot {}: ball at {:?} ({err} m off)", l.shot, used.position_m);
    }
    let imported = dir.path().join("imported.jsonl");
    let i = imported.to_str().unwrap();
    impactd(&[&["import", c, "--markers", s, "--rig", "bay1", "-o", i], &ball_flags[..]].concat());
    let text = std::fs::read_to_string(&imported).unwrap();
    assert_eq!(text.lines().filter(|l| l.contains("\"occluded\"") && !l.contains("orientation")).count(), frames.len());
    assert_eq!(impactd(&["replay", i, "-c", cfg]), direct, "the import replays as the capture does");
}
