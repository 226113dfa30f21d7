//! Every failure shows in the exit code of the real binary: flags that would panic or run away, replays of
//! files that hold no samples, a recording on a full disk, recordings whose data or summary changed after they
//! were written, outputs that already exist, and inputs with no line end.

#![allow(clippy::unwrap_used)]
#![cfg(feature = "daemon")]

use std::path::Path;
use std::process::{Command, Output, Stdio};

fn impactd(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_impactd")).args(args).stdin(Stdio::null()).output().unwrap()
}

fn refused(args: &[&str], says: &str) {
    let out = impactd(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{args:?} exited 0: {err}");
    assert!(out.status.code().is_some(), "{args:?} died on a signal: {err}");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    assert!(err.contains(says), "{args:?}: {err}");
}

#[test]
fn flags_that_become_durations_rates_or_counts_are_validated() {
    refused(&["sim", "--interval", "NaN"], "--interval");
    refused(&["sim", "--interval", "1e300"], "--interval");
    refused(&["sim", "--rigs", "0"], "--rigs");
    refused(&["sim", "--noise-mm", "NaN"], "--noise-mm");
    refused(&["sim", "--rate", "inf"], "--rate");
    refused(&["demo", "--shots", "18446744073709551615"], "--shots");
    refused(&["demo", "--rate", "NaN"], "--rate");
    refused(&["replay", "x.mcap", "--rate", "NaN"], "--rate");
    refused(&["replay", "x.mcap", "--duration", "-1"], "--duration");
    refused(&["flight", "--points-s", "NaN"], "--points-s");
    refused(&["eval", "extrapolation", "--shots", "18446744073709551615"], "--shots");
}

#[test]
fn a_replay_of_nothing_replayable_fails() {
    let dir = tempfile::tempdir().unwrap();
    let recording = Path::new(env!("CARGO_MANIFEST_DIR")).join("recordings/driver.mcap");
    let bytes = std::fs::read(&recording).unwrap();
    let cases: [(&str, &[u8]); 4] = [
        ("empty.mcap", b""),
        ("truncated.mcap", &bytes[..7]),
        ("text.mcap", b"hello\n"),
        (
            "dataset.jsonl",
            br#"{"delivery":{"club_speed_mph":100},"measured":{"ball_speed_mph":150,"launch_angle_deg":12,"launch_direction_deg":0,"backspin_rpm":2500,"sidespin_rpm":0}}
"#,
        ),
    ];
    for (name, content) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, content).unwrap();
        refused(&["replay", path.to_str().unwrap()], "no clubhead samples");
    }
    refused(&["replay", "/dev/zero"], "limit");
}

#[test]
fn a_sample_at_the_end_of_time_is_replayed() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("samples.jsonl");
    let line = |frame: u64, t_ns: u64| {
        format!(
            r#"{{"rig":"bay1","frame":{frame},"t_ns":{t_ns},"position_m":[0,0,0],"orientation":{{"x":0,"y":0,"z":0,"w":1}}}}"#
        )
    };
    std::fs::write(&path, format!("{}\n{}\n", line(1, 1_000_000), line(2, u64::MAX))).unwrap();
    let out = impactd(&["replay", path.to_str().unwrap(), "--club", "driver"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("replayed 2 samples"), "{err}");
    assert!(!err.contains("partial"), "{err}");
}

#[test]
fn a_recording_on_a_full_disk_fails_the_demo() {
    if !Path::new("/dev/full").exists() {
        return;
    }
    let out = impactd(&["demo", "--shots", "1", "--record", "/dev/full", "--overwrite"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("the recording /dev/full failed"), "{err}");
    assert!(!err.contains("Recording: /dev/full"), "the demo named a failed recording as written: {err}");
}

#[test]
fn no_command_replaces_an_existing_file_without_overwrite() {
    let dir = tempfile::tempdir().unwrap();
    let existing = dir.path().join("existing");
    std::fs::write(&existing, "keep me").unwrap();
    let recording = Path::new(env!("CARGO_MANIFEST_DIR")).join("recordings/driver.mcap");
    let (rec, out) = (recording.to_str().unwrap(), existing.to_str().unwrap());
    refused(&["recover", rec, "-o", out], "--overwrite");
    refused(&["replay", rec, "-o", out], "--overwrite");
    refused(&["demo", "--shots", "1", "--record", out], "--overwrite");
    refused(&["fit", "--model", "adjusted", rec, "-o", out], "--overwrite");
    assert_eq!(std::fs::read_to_string(&existing).unwrap(), "keep me");
    let copy = dir.path().join("copy.mcap");
    std::fs::write(&copy, "old").unwrap();
    let ok = impactd(&["recover", rec, "-o", copy.to_str().unwrap(), "--overwrite"]);
    assert!(ok.status.success(), "{}", String::from_utf8_lossy(&ok.stderr));
}

#[test]
fn a_flip_outside_the_chunks_is_found_by_info_and_recover() {
    let dir = tempfile::tempdir().unwrap();
    let recording = Path::new(env!("CARGO_MANIFEST_DIR")).join("recordings/driver.mcap");
    let bytes = std::fs::read(&recording).unwrap();
    let intact = impactd(&["recover", recording.to_str().unwrap(), "-o", dir.path().join("ok.mcap").to_str().unwrap()]);
    assert!(intact.status.success(), "{}", String::from_utf8_lossy(&intact.stderr));

    // The recorded configuration: cor 0.83 becomes 0.82 (metadata, in the data section).
    let at = bytes.windows(10).position(|w| w == b"cor = 0.83").expect("the recorded config");
    let mut config_flip = bytes.clone();
    config_flip[at + 9] = b'2';
    // The summary: a byte of the statistics and indexes between the summary's start and the footer.
    let footer = bytes.len() - 8 - 29;
    let summary_start = u64::from_le_bytes(bytes[footer + 9..footer + 17].try_into().unwrap()) as usize;
    assert!(summary_start > 0 && summary_start < footer);
    let mut summary_flip = bytes.clone();
    summary_flip[(summary_start + footer) / 2] ^= 0x01;

    for (name, damaged) in [("config", config_flip), ("summary", summary_flip)] {
        let path = dir.path().join(format!("{name}.mcap"));
        std::fs::write(&path, damaged).unwrap();
        let info = impactd(&["info", path.to_str().unwrap()]);
        let text = format!("{}{}", String::from_utf8_lossy(&info.stdout), String::from_utf8_lossy(&info.stderr));
        assert!(!info.status.success(), "{name}: info exited 0: {text}");
        assert!(text.contains("CRC"), "{name}: {text}");
        let out = dir.path().join(format!("{name}-recovered.mcap"));
        let r = impactd(&["recover", path.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        assert_eq!(r.status.code(), Some(3), "{name}: recover: {}", String::from_utf8_lossy(&r.stderr));
    }
}

#[test]
fn impossible_measured_values_are_refused_with_the_line_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let line = |speed: &str| {
        format!(
            r#"{{"delivery":{{"club_speed_mph":100}},"measured":{{"ball_speed_mph":{speed},"launch_angle_deg":12,"launch_direction_deg":0,"backspin_rpm":2500,"sidespin_rpm":0}}}}"#
        )
    };
    for speed in ["1e300", "-5"] {
        let path = dir.path().join("shots.jsonl");
        std::fs::write(&path, format!("{}\n{}\n", line("150"), line(speed))).unwrap();
        refused(&["compare", path.to_str().unwrap()], "line 2");
        refused(&["compare", path.to_str().unwrap()], "measured.ball_speed_mph");
        let out = dir.path().join("fitted.toml");
        refused(&["fit", "--model", "adjusted", path.to_str().unwrap(), "-o", out.to_str().unwrap()], "ball_speed_mph");
        assert!(!out.exists(), "a club file was written from impossible values");
    }
    // A huge field is never echoed whole.
    let path = dir.path().join("huge.jsonl");
    std::fs::write(&path, format!("{{\"delivery\":{{\"club_speed_mph\":\"{}\"}}}}\n", "9".repeat((1 << 20) - 64)))
        .unwrap();
    let out = impactd(&["compare", path.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(out.stderr.len() < 4096, "{} bytes of error", out.stderr.len());
}

#[test]
fn fit_on_one_shot_claims_no_bound() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("one.jsonl");
    let synth = impactd(&["synth", "--model", "adjusted", "--shots", "1", "-o", data.to_str().unwrap()]);
    assert!(synth.status.success(), "{}", String::from_utf8_lossy(&synth.stderr));
    let out = impactd(&[
        "fit",
        "--model",
        "adjusted",
        data.to_str().unwrap(),
        "--folds",
        "0",
        "--generations",
        "3",
        "--local-evaluations",
        "20",
        "--json",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for p in v["params"].as_array().unwrap() {
        // No bound (null: infinite) rather than a bound of 0 from residuals one shot fits exactly.
        assert_eq!(p["std_error"], serde_json::Value::Null, "{}: {p}", p["name"]);
    }
}

fn flight(line: &str) -> (bool, String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .arg("flight")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    use std::io::Write;
    child.stdin.take().unwrap().write_all(format!("{line}\n").as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn flight_refuses_what_it_cannot_fly_and_what_it_would_not_fly() {
    // 70 m/s at 0.5 deg: a kilometre of roll before; refused now, with the reason.
    let (ok, out, err) = flight(r#"{"ball_speed_mps":70,"launch_angle_deg":0.5}"#);
    assert!(!ok && err.contains("roll"), "{out}{err}");
    // Vectors fly; a scalar beside them that says otherwise is refused, not echoed as if it had flown.
    let (ok, out, err) = flight(
        r#"{"ball_velocity_mps":[60,12,0],"ball_spin_radps":[0,0,-280],"ball_speed_mph":200,"launch_angle_deg":11.31}"#,
    );
    assert!(!ok && err.contains("ball_speed_mph"), "{out}{err}");
    // A predicted line (vectors and scalars agreeing) flies.
    let dir = tempfile::tempdir().unwrap();
    let delivery = dir.path().join("delivery.jsonl");
    std::fs::write(&delivery, "{\"club_speed_mph\":100}\n").unwrap();
    let predicted = impactd(&["predict", "-i", delivery.to_str().unwrap()]);
    let (ok, out, err) = flight(String::from_utf8_lossy(&predicted.stdout).trim());
    assert!(ok && out.contains("carry_yd"), "{out}{err}");
}

#[test]
fn a_device_that_never_ends_is_refused_at_once() {
    for args in [vec!["info", "/dev/zero"], vec!["recover", "/dev/zero", "-o", "/dev/null", "--overwrite"]] {
        refused(&args, "not an MCAP file");
    }
    refused(&["compare", "/dev/zero"], "limit");
    refused(&["predict", "-i", "/dev/zero"], "limit");
    refused(&["flight", "-i", "/dev/zero"], "limit");
}

/// The README's first command can be run again: the demo replaces its own recording (impactd-demo.mcap in the
/// working directory), while a recording named with --record is kept (the test above).
#[test]
fn the_demo_replaces_its_own_recording() {
    let dir = tempfile::tempdir().unwrap();
    for run in 0..2 {
        let out = Command::new(env!("CARGO_BIN_EXE_impactd"))
            .args(["demo", "--shots", "1"])
            .current_dir(dir.path())
            .stdin(Stdio::null())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "demo run {run}: {err}");
        assert!(err.contains("impactd-demo.mcap"), "{err}");
    }
    assert!(dir.path().join("impactd-demo.mcap").metadata().unwrap().len() > 0);
}

/// A rig file's bad club, soil, models, conditions or labels stop `run` with exit code 2 and one line: the field,
/// then the reason, each cause said once (the causes are kept as the error's sources, and the line does not
/// repeat them).
#[test]
fn a_bad_rig_file_exits_2_naming_the_field_and_its_cause_once() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "club = \"iron7\"\nmodel = \"ground\"\nsoil = \"mud\"",
            "config field `rig[0].soil` model parameter `[soil]` unknown soil 'mud' (expected soft, medium or firm, \
             or a path to a soil .toml file); or none for the ball on a tee",
        ),
        (
            "club = \"iron7\"\nmodel = \"adjusted\"\nsoil = \"firm\"",
            "config field `rig[0].soil` model parameter `soil` needs the ground model (model ground or both), not \
             adjusted",
        ),
        (
            "model = \"fast\"",
            "config field `rig[0].model` driver: unknown model 'fast' (expected standard, adjusted, slip, \
             continuous, maw, arakawa, ground, both)",
        ),
        (
            "[rig.clubs]\nseven = \"putter\"",
            "config field `rig[0].clubs.seven` rig[0].clubs.seven `putter`: unknown club preset 'putter' (expected \
             driver, wood3, hybrid, iron4-iron9, pw, gw, sw or lw, or a path to a .toml file)",
        ),
        (
            "[rig.conditions]\nwind_mps = -1.0",
            "config field `rig[0].conditions` `wind_mps` must be within 0 and 40, got -1",
        ),
        (
            "[rig.conditions]\nhumidity_pct = 150.0",
            "config field `rig[0].conditions` `humidity_pct` is relative humidity in percent, 0-100, got 150",
        ),
        (
            "[rig.conditions]\nfirmness = 2.0",
            "config field `rig[0].conditions` `firmness` must be within 0 and 1, got 2",
        ),
    ];
    for (i, (rig, says)) in cases.iter().enumerate() {
        let path = dir.path().join(format!("rig{i}.toml"));
        std::fs::write(&path, format!("[[rig]]\nname = \"a\"\n{rig}\n")).unwrap();
        let out = impactd(&["run", "-c", path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{rig}: {err}");
        assert_eq!(err.trim_end(), format!("impactd: {says}"), "{rig}");
    }
}

/// One rule for input lines (docs/commands.md): a line a command cannot read or answer exits 2, for every
/// command that reads lines. `predict`, `flight` and `replay`, whose lines stand alone, answer the others first;
/// `compare` and `fit`, whose numbers are over every line, stop at it.
#[test]
fn a_malformed_line_exits_2_for_every_command_that_reads_lines() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let deliveries = write("deliveries.jsonl", "{\"club_speed_mph\":100}\nnot json\n");
    let out = impactd(&["predict", "-i", &deliveries]);
    let answers = String::from_utf8_lossy(&out.stdout).to_string();
    assert_eq!(out.status.code(), Some(2), "predict: {}", String::from_utf8_lossy(&out.stderr));
    let lines: Vec<serde_json::Value> = answers.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert!(lines[0]["ball_speed_mph"].is_number() && lines[1]["line"] == 2, "{answers}");

    let launches = write("launches.jsonl", &format!("{}\n{{\"ball_speed_mph\": \n", answers.lines().next().unwrap()));
    let out = impactd(&["flight", "-i", &launches]);
    assert_eq!(out.status.code(), Some(2), "flight: {}", String::from_utf8_lossy(&out.stderr));
    let first: serde_json::Value =
        serde_json::from_str(String::from_utf8_lossy(&out.stdout).lines().next().unwrap()).unwrap();
    assert!(first["carry_yd"].is_number(), "{first}");

    let sample =
        r#"{"rig":"bay1","frame":1,"t_ns":1000000,"position_m":[0,0,0],"orientation":{"x":0,"y":0,"z":0,"w":1}}"#;
    let samples = write("samples.jsonl", &format!("{sample}\nnot json\n"));
    let out = impactd(&["replay", &samples, "--club", "driver"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "replay: {err}");
    assert!(err.contains("replayed 1 samples") && err.contains("line 2"), "{err}");

    let bad = write("bad.jsonl", "not json\n");
    let fitted = dir.path().join("fitted.toml");
    let fitted = fitted.to_str().unwrap();
    for args in [vec!["compare", bad.as_str()], vec!["fit", "--model", "adjusted", bad.as_str(), "-o", fitted]] {
        let out = impactd(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    }
}
