//! The command line as a user meets it, through the real binary: negative numbers, humidity in percent, each
//! error once and non-zero, impossible arguments refused, progress as plain lines off a terminal, replay's
//! options and its refusal to overwrite its input, `info`'s dates, rates and order, `predict --flight`, and the
//! pictures' top view, marks, conditions and units.

#![allow(clippy::unwrap_used)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn impactd(args: &[&str], stdin: &str) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(args)
        .env("RUST_LOG", "warn")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // A command that refuses its arguments exits without reading its input: a broken pipe here is not a failure.
    let _ = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    child.wait_with_output().unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn recording(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("recordings").join(name)
}

/// Regression: `--cor -0.2` was taken for an unknown flag `-0`; a negative value reaches the command's own check.
#[test]
fn negative_numbers_are_values() {
    let out = impactd(&["predict", "--cor", "-0.2"], "");
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("--cor must be within 0 and 1, got -0.2"), "{}", text(&out.stderr));
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("f.svg");
    let out = impactd(
        &["plot", "forces", "--attack-angle-deg", "-3", "--club-path-deg", "-2.5", "-o", svg.to_str().unwrap()],
        "",
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let svg = std::fs::read_to_string(svg).unwrap();
    // The delivery is in the title, "µs" on the time axis.
    assert!(svg.contains("attack -3.0°, path -2.5°"), "{svg}");
    assert!(svg.contains("time from first contact (µs)") && !svg.contains("(us)"));
}

/// `--humidity` is relative humidity in percent, as weather services give it: 80 flies, 150 is refused.
#[test]
fn humidity_is_in_percent() {
    let launch = r#"{"ball_speed_mph": 150, "launch_angle_deg": 12, "backspin_rpm": 2800}"#;
    let carry = |h: &str| {
        let out = impactd(&["flight", "--humidity", h], launch);
        assert!(out.status.success(), "{}", text(&out.stderr));
        serde_json::from_str::<serde_json::Value>(&text(&out.stdout)).unwrap()["carry_m"].as_f64().unwrap()
    };
    // Humid air is lighter: the ball carries a little farther, by a metre or so.
    let (dry, humid) = (carry("0"), carry("100"));
    assert!(humid > dry && humid - dry < 3.0, "{dry} {humid}");
    let out = impactd(&["flight", "--humidity", "150"], launch);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("percent, 0-100"), "{}", text(&out.stderr));
    assert!(text(&impactd(&["flight", "--help"], "").stdout).contains("Relative humidity in percent"));
}

/// Regression: "No such file or directory (os error 2): No such file or directory (os error 2)".
#[test]
fn each_error_is_printed_once() {
    for args in [vec!["info", "/nonexistent/x.mcap"], vec!["replay", "/nonexistent/x.mcap"]] {
        let out = impactd(&args, "");
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert_eq!(err.matches("No such file or directory").count(), 1, "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}

/// Impossible arguments are refused with a message and a non-zero exit, not answered with NaN, an empty table
/// or a blank picture.
#[test]
fn impossible_arguments_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("map.svg");
    let iron7 = recording("iron7.mcap");
    let cases: [(Vec<&str>, &str); 5] = [
        (vec!["eval", "extrapolation", "--shots", "0"], "0 is not a count within 1"),
        // A pace so slow that a gap between two samples would overflow a `Duration`.
        (
            vec!["replay", iron7.to_str().unwrap(), "--rate", "1e-12"],
            "0.000000000001 is not a multiple of real time within 0.001 and 1000000",
        ),
        (vec!["bench", "--filter", "nosuch"], "no stage's name contains it"),
        (vec!["map", "--club-speed-mph", "0", "-o", map.to_str().unwrap()], "club_speed_mph"),
        (vec!["map", "--club-speed-mph", "900", "-o", map.to_str().unwrap()], "club_speed_mph"),
    ];
    for (args, says) in cases {
        let out = impactd(&args, "");
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(text(&out.stderr).contains(says), "{args:?}: {}", text(&out.stderr));
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    assert!(!map.exists());
}

/// Off a terminal, progress is plain lines, each ending in a newline (no carriage returns).
#[test]
fn progress_off_a_terminal_is_plain_lines() {
    let out = impactd(&["eval", "extrapolation", "--shots", "20", "--estimators", "linear2"], "");
    assert!(out.status.success(), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    assert!(!err.contains('\r'), "{err:?}");
    assert!(err.ends_with('\n') && err.contains("20/20 swings\n"), "{err:?}");
}

/// Every argument of every command says what it is in `--help`.
#[test]
fn help_names_every_default() {
    let help = text(&impactd(&["map", "--help"], "").stdout);
    for needle in ["[default: driver]", "[default: slip]", "[default: 100]", "[default: map.svg]"] {
        assert!(help.contains(needle), "{needle}: {help}");
    }
}

/// Regression: `replay IN.mcap -o IN.mcap` destroyed its input and exited 0.
#[test]
fn replay_refuses_to_write_over_its_input() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in.mcap");
    std::fs::copy(recording("driver.mcap"), &input).unwrap();
    let before = std::fs::read(&input).unwrap();
    let dotted = dir.path().join(".").join("in.mcap");
    let out = impactd(&["replay", input.to_str().unwrap(), "-o", dotted.to_str().unwrap()], "");
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("that is the input"), "{}", text(&out.stderr));
    assert_eq!(std::fs::read(&input).unwrap(), before);
}

/// A model other than the recorded one is a comparison (exit 0), and a part of a recording is not a failure.
#[test]
fn replay_compares_models_and_replays_parts() {
    let file = recording("driver.mcap");
    // The whole file with its own configuration: a reproduction (exit 1 when the shipped recording predates a
    // model change; either way it is judged, not compared).
    let whole = impactd(&["replay", file.to_str().unwrap()], "");
    assert!(matches!(whole.status.code(), Some(0 | 1)), "{}", text(&whole.stderr));
    let shots = text(&whole.stdout).lines().count();
    assert!(text(&whole.stderr).contains("including loading"), "{}", text(&whole.stderr));

    let other = impactd(&["replay", file.to_str().unwrap(), "--model", "standard"], "");
    assert!(other.status.success(), "{}", text(&other.stderr));
    assert!(text(&other.stderr).contains("comparison, not a reproduction"), "{}", text(&other.stderr));
    let first: serde_json::Value = serde_json::from_str(text(&other.stdout).lines().next().unwrap()).unwrap();
    assert_eq!(first["model"], "standard");

    let part = impactd(&["replay", file.to_str().unwrap(), "--start-offset", "0", "--duration", "2.5"], "");
    assert!(part.status.success(), "{}", text(&part.stderr));
    assert!(text(&part.stdout).lines().count() < shots, "{}", text(&part.stderr));

    let out = impactd(&["replay", file.to_str().unwrap(), "--rig", "nosuch"], "");
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("no samples of that rig"), "{}", text(&out.stderr));
}

/// A JSONL session says which club it is replayed with, and `--club` sets it: a 7-iron session does not run
/// silently as a driver.
#[test]
fn replay_of_jsonl_takes_club_and_model() {
    let dir = tempfile::tempdir().unwrap();
    let mcap = recording("iron7.mcap");
    let samples: Vec<String> = mcap_samples(&mcap);
    let jsonl = dir.path().join("iron7.jsonl");
    std::fs::write(&jsonl, samples.join("\n")).unwrap();
    let plain = impactd(&["replay", jsonl.to_str().unwrap()], "");
    assert!(
        text(&plain.stderr).contains("no configuration stored: replaying with club driver"),
        "{}",
        text(&plain.stderr)
    );
    let iron = impactd(&["replay", jsonl.to_str().unwrap(), "--club", "iron7", "--model", "standard"], "");
    assert!(iron.status.success(), "{}", text(&iron.stderr));
    let first: serde_json::Value = serde_json::from_str(text(&iron.stdout).lines().next().unwrap()).unwrap();
    assert_eq!(first["model"], "standard");
    assert!(first["club"].as_str().unwrap().contains("iron"), "{first}");
}

/// The clubhead samples of a recording as JSONL lines (through `impactd replay`'s own reader).
fn mcap_samples(path: &Path) -> Vec<String> {
    let input = impactd::daemon::replay::load(path).unwrap();
    input.samples.iter().map(|s| serde_json::to_string(s).unwrap()).collect()
}

/// `info` says when (UTC), how long (for people), how compressed, how many messages and how often per topic, in
/// natural rig order, and whether the file was recovered.
#[test]
fn info_says_dates_rates_compression_and_recovery() {
    let file = recording("driver.mcap");
    let out = impactd(&["info", file.to_str().unwrap()], "");
    assert!(out.status.success());
    let info = text(&out.stdout);
    for needle in ["start:       20", "Z (UTC)\n", "end:         ", "compression: zstd", "recovered:   no", " Hz\n"] {
        assert!(info.contains(needle), "{needle}: {info}");
    }
    let dir = tempfile::tempdir().unwrap();
    let fixed = dir.path().join("fixed.mcap");
    let out = impactd(&["recover", file.to_str().unwrap(), "-o", fixed.to_str().unwrap()], "");
    assert!(out.status.success(), "{}", text(&out.stderr));
    let info = text(&impactd(&["info", fixed.to_str().unwrap()], "").stdout);
    assert!(info.contains("recovered:   yes, by `impactd recover` from "), "{info}");
}

/// `predict --flight` adds the flight to each line, and `predict | flight` keeps the launch's fields: the same
/// line either way.
#[test]
fn predict_with_flight_keeps_the_launch() {
    let delivery = r#"{"club_speed_mph": 105, "attack_angle_deg": 3, "dynamic_loft_deg": 13}"#;
    let out = impactd(&["predict", "--flight"], delivery);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let with: serde_json::Value = serde_json::from_str(&text(&out.stdout)).unwrap();
    for field in ["ball_speed_mph", "backspin_rpm", "carry_yd", "total_yd", "apex_m", "offline_yd"] {
        assert!(with[field].is_number(), "{field}: {with}");
    }
    let plain = text(&impactd(&["predict"], delivery).stdout);
    let piped: serde_json::Value = serde_json::from_str(&text(&impactd(&["flight"], &plain).stdout)).unwrap();
    assert_eq!(piped, with);
    // The sanity flags and the turf's summary travel with the launch: a fat 7-iron off firm turf flies too.
    let iron = r#"{"club_speed_mph": 90, "attack_angle_deg": -4.3, "dynamic_loft_deg": 25, "impact_v_mm": 12}"#;
    let out = impactd(&["predict", "--club", "iron7", "--model", "ground", "--soil", "firm", "--flight"], iron);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let fat: serde_json::Value = serde_json::from_str(&text(&out.stdout)).unwrap();
    assert!(fat.get("flight_error").is_none(), "{fat}");
    assert!(fat["carry_yd"].is_number() && fat["ground"]["strike"] == "fat", "{fat}");
    assert!(fat["warnings"].is_array(), "{fat}");
}

/// The trajectory picture: a true top view (offline across, downrange up), the landings marked, the
/// conditions written, and the frame padded beyond the longest carry.
#[test]
fn trajectory_picture_is_a_report_picture() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("t.svg");
    let launches =
        "{\"ball_speed_mph\": 160, \"launch_angle_deg\": 11, \"backspin_rpm\": 2600, \"sidespin_rpm\": 400}\n\
                    {\"ball_speed_mph\": 120, \"launch_angle_deg\": 16, \"backspin_rpm\": 6000}\n";
    let out = impactd(
        &["plot", "trajectory", "--wind-mps", "3", "--wind-dir-deg", "-90", "-o", svg.to_str().unwrap()],
        launches,
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let svg = std::fs::read_to_string(svg).unwrap();
    assert!(svg.contains("top view (downrange up, right of the target to the right)"));
    assert!(svg.contains("offline (yd, right +)"));
    assert!(svg.contains("wind 3.0 m/s toward -90°") && svg.contains("firmness 0.50"), "conditions");
    assert_eq!(svg.matches("<circle").count(), 4, "a landing mark per shot in each view");
}

/// `bench --baseline`: every stage against a saved `--json` run, those slower by more than 20 % named, with the
/// date and the machine.
#[test]
fn bench_names_the_stages_slower_than_the_baseline() {
    let dir = tempfile::tempdir().unwrap();
    let saved = dir.path().join("saved.json");
    let name = "standard/iron7";
    // A saved run a thousand times faster than any machine: the stage is named; an absurdly slow one: not.
    for (ns, slower) in [(1e-3, true), (1e9, false)] {
        std::fs::write(&saved, format!(r#"{{"stages": [{{"name": "{name}", "ns_per_op": {ns}}}]}}"#)).unwrap();
        let out = impactd(&["bench", "--filter", name, "--json", "--baseline", saved.to_str().unwrap()], "");
        assert!(out.status.success(), "{}", text(&out.stderr));
        let doc: serde_json::Value = serde_json::from_str(&text(&out.stdout)).unwrap();
        assert_eq!(doc["slower"].as_array().unwrap().len(), usize::from(slower), "{doc}");
        assert_eq!(doc["stages"][0]["slower"].as_bool(), Some(slower));
        assert!(doc["stages"][0]["ratio"].as_f64().unwrap() > 0.0);
        assert!(doc["date"].as_str().unwrap().len() == 10 && doc["machine"].as_str().unwrap().contains("cores"));
        assert_eq!(text(&out.stderr).contains(name), slower, "{}", text(&out.stderr));
    }
    std::fs::write(&saved, "{}").unwrap();
    let out = impactd(&["bench", "--filter", name, "--baseline", saved.to_str().unwrap()], "");
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("no `stages` array"), "{}", text(&out.stderr));
}

/// Regression: `plot maw-plate` (default `-o docs/maw-plate.svg`) failed where there is no `docs/`; an output's
/// directory is made.
#[test]
fn plot_output_directory_is_made() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("docs/maw-plate.svg");
    let out = impactd(&["plot", "maw-plate", "--rings", "5", "-o", svg.to_str().unwrap()], "");
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
}

/// `predict | flight | plot trajectory` is a pipe: the fields each step does not read (labels, `warnings`,
/// `apex_m`) pass through instead of being refused.
#[test]
fn predict_flight_plot_is_a_pipe() {
    let predicted =
        impactd(&["predict", "--model", "both"], "{\"club_speed_mph\":105,\"player\":\"ann\",\"club\":\"D\"}\n");
    assert!(predicted.status.success(), "{}", text(&predicted.stderr));
    let flown = impactd(&["flight"], &text(&predicted.stdout));
    assert!(flown.status.success(), "{}", text(&flown.stderr));
    let lines: Vec<serde_json::Value> = text(&flown.stdout).lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines.len(), 2, "one line per model");
    assert!(lines.iter().all(|l| l["player"] == "ann" && l["club"] == "D" && l["carry_yd"].is_number()));
    assert_ne!(lines[0]["model"], lines[1]["model"]);
    let again = impactd(&["flight"], &text(&flown.stdout));
    assert!(again.status.success(), "{}", text(&again.stderr));
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("t.svg");
    let plotted = impactd(&["plot", "trajectory", "-o", svg.to_str().unwrap()], &text(&again.stdout));
    assert!(plotted.status.success(), "{}", text(&plotted.stderr));
}

/// `both` means the same models in `compare --by-club` as in `predict` and the daemon (impact::registry::resolve):
/// slip and continuous, or slip and ground with a soil.
#[test]
fn compare_by_club_resolves_both_as_everywhere() {
    let csv = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/trackman/validation-8i-5i.csv");
    for (soil, second) in [(None, "continuous"), (Some("none"), "ground")] {
        let mut args = vec!["compare", "--by-club", "--json", "--models", "both", csv];
        if let Some(soil) = soil {
            args.extend(["--soil", soil]);
        }
        let out = impactd(&args, "");
        assert!(out.status.success(), "{}", text(&out.stderr));
        let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let models: Vec<&str> =
            report["clubs"][0]["models"].as_array().unwrap().iter().map(|m| m["model"].as_str().unwrap()).collect();
        assert_eq!(models, ["slip", second], "with soil {soil:?}");
    }
}
