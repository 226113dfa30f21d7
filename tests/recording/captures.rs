//! Captures of every kind a lab has: one synthetic swing of known truth (the `sim` rig's, noise-free) written by an
//! independent writer (`tests/common/synth_capture.py`: C3D through PyPI `c3d`, TRC and a pose table by hand) in a
//! Y-up and a Z-up lab at 240, 360 and 720 Hz, with 0.1-0.3 mm of marker noise, dropouts and a ghost near impact;
//! `impactd replay` of each form finds the same impact and club speed, and the truth's. Missing and wrong units and
//! malformed headers fail with the line and what is wrong.

use std::path::{Path, PathBuf};
use std::process::Command;

use impactd::daemon::sim::{SimOptions, SimRig};
use impactd::equipment::ClubSpec;
use impactd::wire::TruthMessage;
use serde_json::Value;

use crate::common;

struct Case {
    lab: &'static str,
    rate_hz: f64,
    noise_mm: f64,
    orientation: &'static str,
    trc_units: &'static str,
    seed: u64,
}

/// A written capture and its truth (times from the capture's first frame).
struct Written {
    dir: PathBuf,
    truth: TruthMessage,
    t_impact_ns: u64,
    frames: usize,
    ball_offset_mm: [f64; 3],
    _tmp: tempfile::TempDir,
}

fn write(case: &Case) -> Written {
    let options = SimOptions {
        shots: 1,
        rate_hz: case.rate_hz,
        interval_s: 0.5,
        seed: case.seed,
        noise_mm: 0.0,
        noise_deg: 0.0,
        ..SimOptions::default()
    };
    let mut rig = SimRig::new("rig1", &options, 1_000_000_000, case.seed);
    let (mut samples, mut truth) = (Vec::new(), None);
    while !rig.done() {
        let (s, t) = rig.next_sample().unwrap();
        samples.push(s);
        truth = truth.or(t);
    }
    let truth = truth.unwrap();
    let t0 = samples[0].t_ns;
    let impact_frame = samples.iter().position(|s| s.t_ns >= truth.t_impact_ns).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().to_path_buf();
    let poses: String = samples
        .iter()
        .map(|s| {
            let p = s.position_m;
            format!("{}\n", serde_json::json!({ "position_m": [p.x, p.y, p.z], "xyzw": s.orientation_xyzw }))
        })
        .collect();
    std::fs::write(dir.join("truth.jsonl"), poses).unwrap();
    let c = ClubSpec::driver().face.center_m;
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/common/synth_capture.py");
    let out = common::python()
        .arg(script)
        .arg(dir.join("truth.jsonl"))
        .arg(&dir)
        .args(["--rate", &case.rate_hz.to_string(), "--lab", case.lab, "--noise-mm", &case.noise_mm.to_string()])
        .args(["--seed", &case.seed.to_string(), "--face-centre", &format!("{},{},{}", c.x, c.y, c.z)])
        .args(["--impact-frame", &impact_frame.to_string(), "--trc-units", case.trc_units])
        .args(["--orientation", case.orientation])
        .output()
        .unwrap();
    assert!(out.status.success(), "synth_capture.py: {}", String::from_utf8_lossy(&out.stderr));
    let lab: Value = serde_json::from_str(&std::fs::read_to_string(dir.join("lab.json")).unwrap()).unwrap();
    let config = format!(
        "[[rig]]\nname = \"bay1\"\nclub = \"driver\"\n[rig.world_from_lab]\nrotation_xyzw = {}\ntranslation_m = {}\n",
        lab["rotation_xyzw"], lab["translation_m"]
    );
    std::fs::write(dir.join("impactd.toml"), config).unwrap();
    let offset: Vec<f64> = serde_json::from_value(lab["ball_offset_mm"].clone()).unwrap();
    Written {
        dir,
        t_impact_ns: truth.t_impact_ns - t0,
        truth,
        frames: samples.len(),
        ball_offset_mm: [offset[0], offset[1], offset[2]],
        _tmp: tmp,
    }
}

fn impactd(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_impactd")).args(args).output().unwrap();
    let text = |b: &[u8]| String::from_utf8_lossy(b).into_owned();
    (out.status.code().unwrap_or(-1), text(&out.stdout), text(&out.stderr))
}

/// The arguments that replay or import one form of a written capture.
fn form_args(w: &Written, file: &str) -> Vec<String> {
    let path = w.dir.join(file).display().to_string();
    let mut args = vec![path];
    if !file.ends_with(".csv") {
        let o = w.ball_offset_mm;
        args.extend(["--markers".into(), w.dir.join("markers.toml").display().to_string()]);
        args.extend(["--ball-marker".into(), "BALL".into(), format!("--ball-offset-mm={},{},{}", o[0], o[1], o[2])]);
    }
    args
}

/// The replay's one launch of `file`.
fn replay(w: &Written, file: &str, extra: &[&str]) -> (Value, String) {
    let config = w.dir.join("impactd.toml").display().to_string();
    let mut args = vec!["replay".to_string()];
    args.extend(form_args(w, file));
    args.extend(["-c".to_string(), config, "--rig".into(), "bay1".into()]);
    args.extend(extra.iter().map(|s| s.to_string()));
    let (code, out, err) = impactd(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(code, 0, "replay {file}: {err}");
    let launches: Vec<Value> = out.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(launches.len(), 1, "replay {file}: one swing, one launch: {out}\n{err}");
    (launches[0].clone(), err)
}

fn club_speed_mph(launch: &Value) -> f64 {
    launch["delivery"]["club_speed_mph"].as_f64().unwrap()
}

fn t_impact_ns(launch: &Value) -> f64 {
    launch["t_impact_ns"].as_f64().unwrap()
}

const CASES: [Case; 3] = [
    Case { lab: "y-up", rate_hz: 240.0, noise_mm: 0.2, orientation: "quaternion", trc_units: "mm", seed: 3 },
    Case { lab: "z-up", rate_hz: 360.0, noise_mm: 0.1, orientation: "matrix", trc_units: "m", seed: 4 },
    Case { lab: "z-up", rate_hz: 720.0, noise_mm: 0.3, orientation: "euler-ZYX", trc_units: "cm", seed: 5 },
];

#[test]
fn one_swing_as_c3d_trc_and_a_pose_table_gives_one_impact_and_club_speed_and_the_truths() {
    for case in &CASES {
        let w = write(case);
        let truth_mph = w.truth.delivery.club_speed_mph;
        let mut seen = Vec::new();
        for file in ["swing.c3d", "swing.trc", "swing.csv"] {
            let (launch, err) = replay(&w, file, &[]);
            let (mph, t) = (club_speed_mph(&launch), t_impact_ns(&launch));
            eprintln!(
                "{} {} Hz {} mm {file}: club {mph:.3} mph (truth {truth_mph:.3}), impact {:.1} us from the truth's; ball \
                 {}",
                case.lab,
                case.rate_hz,
                case.noise_mm,
                (t - w.t_impact_ns as f64) * 1e-3,
                launch["ball"]
            );
            assert!((mph - truth_mph).abs() < 0.5, "{file} at {} Hz: {mph} mph, the truth {truth_mph}", case.rate_hz);
            assert!(
                (t - w.t_impact_ns as f64).abs() < 50e3,
                "{file} at {} Hz: impact at {t} ns, the truth's at {}",
                case.rate_hz,
                w.t_impact_ns
            );
            assert_eq!(launch["ball"]["source"], "tracked", "{file}: the capture's ball is the one used");
            if file.ends_with(".trc") && case.trc_units != "mm" {
                assert!(!err.contains("warning: units"), "units stated, nothing overridden: {err}");
            }
            seen.push((file, mph, t));
        }
        // The TRC holds the C3D's markers (to its printed 0.01 um): the same launch; the pose table its own noise.
        let (_, mph0, t0) = seen[0];
        let (_, trc_mph, trc_t) = seen[1];
        assert!(
            (trc_mph - mph0).abs() < 0.01 && (trc_t - t0).abs() < 1e3,
            "TRC {trc_mph} mph {trc_t} ns, C3D {mph0} {t0}"
        );
        let (_, table_mph, table_t) = seen[2];
        assert!((table_mph - mph0).abs() < 0.4, "the pose table: {table_mph} mph where the C3D gives {mph0}");
        assert!((table_t - t0).abs() < 50e3, "the pose table: impact at {table_t} ns where the C3D gives {t0}");
    }
}

#[test]
fn import_writes_a_sample_a_frame_of_every_form_and_says_what_it_saw() {
    let w = write(&CASES[0]);
    for (file, extra, counts) in [
        ("swing.trc", vec![], "0 occluded"),
        ("swing.c3d", vec![], "0 occluded"),
        ("swing.csv", vec!["--club", "driver"], "2 occluded (empty position or orientation cells)"),
    ] {
        let out = w.dir.join(format!("{file}.jsonl"));
        let mut args = vec!["import".to_string()];
        args.extend(form_args(&w, file));
        args.extend(["--rig".into(), "bay1".into(), "-o".into(), out.display().to_string()]);
        args.extend(extra.iter().map(|s| s.to_string()));
        let (code, _, err) = impactd(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert_eq!(code, 0, "import {file}: {err}");
        assert!(err.contains(&format!("{} ", w.frames)) && err.contains(counts), "import {file}: {err}");
        let text = std::fs::read_to_string(&out).unwrap();
        let samples = text.lines().filter(|l| l.contains("\"orientation\"")).count();
        assert_eq!(samples, w.frames, "import {file}: a sample a frame");
        assert!(text.lines().filter(|l| !l.contains("\"orientation\"")).count() > 0, "{file}: ball lines");
    }
    // A face-centre table needs the club whose face centre it is.
    let (code, _, err) = impactd(&["import", w.dir.join("swing.csv").to_str().unwrap(), "--rig", "bay1", "-o", "-"]);
    assert_ne!(code, 0);
    assert!(err.contains("origin=face-centre") && err.contains("--club"), "{err}");
}

/// The TRC's lines with `edit` applied to the one numbered `n` (1-based), written as `name`.
fn edit_trc(w: &Written, name: &str, n: usize, edit: impl Fn(&str) -> String) -> String {
    let text = std::fs::read_to_string(w.dir.join("swing.trc")).unwrap();
    let lines: Vec<String> =
        text.lines().enumerate().map(|(i, l)| if i + 1 == n { edit(l) } else { l.to_string() }).collect();
    std::fs::write(w.dir.join(name), lines.join("\n") + "\n").unwrap();
    name.to_string()
}

fn replay_fails(w: &Written, file: &str, extra: &[&str]) -> String {
    let mut args = vec!["replay".to_string()];
    args.extend(form_args(w, file));
    args.extend(["--rig".into(), "bay1".into()]);
    args.extend(extra.iter().map(|s| s.to_string()));
    let (code, out, err) = impactd(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert_ne!(code, 0, "replay {file} should fail: {out}\n{err}");
    err
}

#[test]
fn missing_or_unknown_units_and_malformed_headers_are_refused_with_their_line() {
    let w = write(&CASES[0]);
    // No Units: named on the header's line 2, not guessed.
    let drop_units =
        |l: &str| l.split('\t').enumerate().filter(|(i, _)| *i != 4).map(|(_, c)| c).collect::<Vec<_>>().join("\t");
    edit_trc(&w, "a.trc", 2, drop_units);
    let text = std::fs::read_to_string(w.dir.join("a.trc")).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    lines[2] = drop_units(&lines[2]);
    std::fs::write(w.dir.join("no_units.trc"), lines.join("\n") + "\n").unwrap();
    let err = replay_fails(&w, "no_units.trc", &[]);
    assert!(err.contains("TRC line 2: no `Units`") && err.contains("--units"), "{err}");
    // Given with --units, it reads, and says so.
    let (_, err) = replay(&w, "no_units.trc", &["--units", "mm"]);
    assert!(err.contains("units: the file states no units; read as mm (--units)"), "{err}");
    // A unit not known.
    edit_trc(&w, "furlong.trc", 3, |l| l.replace("\tmm\t", "\tfurlong\t"));
    let err = replay_fails(&w, "furlong.trc", &[]);
    assert!(err.contains("TRC line 3: Units `furlong` is not one of mm, cm, dm, m, in, ft"), "{err}");
    // Overriding a stated unit is reported.
    let (_, err) = replay(&w, "swing.trc", &["--units", "mm"]);
    assert!(err.contains("units: the file states `mm`; read as mm (--units)"), "{err}");
    let err = replay_fails(&w, "swing.trc", &["--units", "parsec"]);
    assert!(err.contains("units `parsec`: not one of"), "{err}");
    // Malformed headers.
    edit_trc(&w, "no_frame.trc", 4, |l| l.replacen("Frame#", "Frame", 1));
    let err = replay_fails(&w, "no_frame.trc", &[]);
    assert!(err.contains("TRC line 4: the marker-name line starts with `Frame#` and `Time`"), "{err}");
    edit_trc(&w, "count.trc", 3, |l| l.replacen("\t12\t", "\t13\t", 1));
    let err = replay_fails(&w, "count.trc", &[]);
    assert!(err.contains("TRC line 4: 12 marker names, where NumMarkers (line 3) is 13"), "{err}");
    edit_trc(&w, "rate.trc", 3, |l| format!("fast{l}"));
    let err = replay_fails(&w, "rate.trc", &[]);
    assert!(err.contains("TRC line 3: DataRate `fast240.00` is not a number"), "{err}");
    edit_trc(&w, "cell.trc", 9, |l| {
        let mut c: Vec<&str> = l.split('\t').collect();
        c[5] = "1.2.3";
        c.join("\t")
    });
    let err = replay_fails(&w, "cell.trc", &[]);
    assert!(err.contains("TRC line 9: marker 2 (TOE) X: `1.2.3` is not a number"), "{err}");
    std::fs::write(w.dir.join("not.trc"), "Frame#\tTime\n1\t0\n").unwrap();
    let err = replay_fails(&w, "not.trc", &[]);
    assert!(err.contains("is named .trc but does not start as a TRC file does"), "{err}");
    // A pose table: its column spec is required, units and all.
    std::fs::copy(w.dir.join("swing.csv"), w.dir.join("bare.csv")).unwrap();
    let err = replay_fails(&w, "bare.csv", &[]);
    assert!(err.contains("is a pose table: say what its columns are with --columns"), "{err}");
    let spec = "time=time_s:s; position=fc_x_mm,fc_y_mm,fc_z_mm; quaternion-wxyz=qw,qx,qy,qz";
    let err = replay_fails(&w, "bare.csv", &["--columns", spec]);
    assert!(err.contains("the position's unit is required"), "{err}");
    let spec = "time=time_s:s; position=fc_x_mm,fc_y_mm,nope:mm; quaternion-wxyz=qw,qx,qy,qz";
    let err = replay_fails(&w, "bare.csv", &["--columns", spec]);
    assert!(err.contains("pose table line 2: the column spec names column `nope`, which the header does not"), "{err}");
}

/// Every frame of a capture read through the library (a C3D, TRC or pose table), or the first error.
fn read_all(path: &Path) -> Result<u64, impactd::captures::CaptureError> {
    let format = impactd::captures::format_of(path, None)?.unwrap();
    let set = impactd::kinematics::MarkerSet::from_toml(
        "[markers]\nCROWN = [-0.040, 0.030, 0.005]\nTOE = [-0.010, 0.012, 0.055]\nHOSEL = [0.005, 0.040, -0.045]\n",
    )
    .unwrap();
    let options = impactd::captures::CaptureOptions {
        rig: "bay1".into(),
        fitter: format.markers.is_some().then(|| impactd::kinematics::MarkerFitter::new(set)),
        face_centre_club_m: Some(ClubSpec::driver().face.center_m),
        ..Default::default()
    };
    let mut samples = (format.open)(path, &options)?;
    let mut n = 0;
    while samples.next_sample()?.is_some() {
        n += 1;
    }
    Ok(n)
}

#[test]
fn mutated_trc_files_and_pose_tables_never_panic() {
    let w = write(&CASES[0]);
    let mut rng = impactd::rng::Rng::new(45);
    for (file, sidecar) in [("swing.trc", None), ("swing.csv", Some("swing.csv.columns"))] {
        let original = std::fs::read(w.dir.join(file)).unwrap();
        assert_eq!(read_all(&w.dir.join(file)).unwrap(), w.frames as u64, "{file} reads whole");
        let (mut refused, mut read) = (0, 0);
        for k in 0..200 {
            let mut bytes = original.clone();
            match k % 3 {
                // A cut anywhere.
                0 => bytes.truncate((rng.unit() * bytes.len() as f64) as usize),
                // Bytes changed, often in the header.
                1 => {
                    let within = if rng.chance(0.5) { 600 } else { bytes.len() };
                    for _ in 0..1 + (rng.unit() * 8.0) as usize {
                        let at = (rng.unit() * within.min(bytes.len()) as f64) as usize;
                        bytes[at] = (rng.next_u64() & 0xff) as u8;
                    }
                }
                // A line doubled or dropped.
                _ => {
                    let text = String::from_utf8_lossy(&bytes).into_owned();
                    let mut lines: Vec<&str> = text.lines().collect();
                    let at = (rng.unit() * lines.len() as f64) as usize;
                    if rng.chance(0.5) {
                        lines.insert(at, lines[at]);
                    } else {
                        lines.remove(at);
                    }
                    bytes = (lines.join("\n") + "\n").into_bytes();
                }
            }
            let name = format!("m{k}.{}", if sidecar.is_some() { "csv" } else { "trc" });
            let path = w.dir.join(&name);
            std::fs::write(&path, &bytes).unwrap();
            if let Some(s) = sidecar {
                std::fs::copy(w.dir.join(s), w.dir.join(format!("{name}.columns"))).unwrap();
            }
            match read_all(&path) {
                Ok(_) => read += 1,
                Err(e) => {
                    let text = e.to_string();
                    assert!(!text.is_empty(), "{file} mutation {k}: an error says what");
                    refused += 1;
                }
            }
        }
        eprintln!("{file}: 200 mutations: {read} read, {refused} refused with a reason");
        assert!(refused > 20 && read > 20, "{file}: {read} read, {refused} refused");
    }
}
