//! TrackMan report JSON through `impactd compare`: the report files of tests/data/trackman/ (TrackMan's web API
//! `multiGroupReport`, from github.com/btmcintyre/Trackman-converter; only names replaced) read stroke by stroke as
//! the CSV export would be, the API's club names on the presets, clubs with no preset left out and counted, and a
//! shot the club refuses left out and counted instead of stopping the comparison. Only validation sessions are
//! read here (tests/data/trackman/README.md: the held-out ones are not).

#![allow(clippy::unwrap_used)]

use std::process::Command;

use impactd::offline::identify::by_club::preset_for_club_name;
use impactd::session::trackman_report::{csv_club_name, read_labelled};
use impactd::units::MPS_PER_MPH;
use serde_json::Value;

fn data(name: &str) -> String {
    format!("{}/tests/data/trackman/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn compare(args: &[&str]) -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_impactd")).arg("compare").args(args).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

fn by_club(models: &str, file: &str) -> Value {
    compare(&["--by-club", "--located", "--json", "--soil", "none", "--models", models, file])
}

/// Stroke 65 of `report-2025-03-13-pw-driver-5w-7i.json` (Id 4e9b2ceb-b91a-4172-8560-9fa8bb8850ce, a 7-iron),
/// its `Measurement` as the file holds it: ClubSpeed 29.99 m/s, AttackAngle -3.4, ClubPath 1.4, FaceAngle 1.259,
/// DynamicLoft 24.478, DynamicLie 62.28613101870554 deg, ImpactOffset -0.009073607442296912 m, ImpactHeight
/// 0.00010579276296898382 m, BallSpeed 40.2583 m/s, LaunchAngle 19.034, LaunchDirection 1.286 deg, SpinRate
/// 4863.07 rpm, SpinAxis -0.185 deg, no ReducedAccuracy.
#[test]
fn a_report_stroke_reads_as_the_file_says() {
    let text = std::fs::read_to_string(data("report-2025-03-13-pw-driver-5w-7i.json")).unwrap();
    let (rows, _) = read_labelled(&text).unwrap();
    // m/s to mph by the CSV reader's factor for a `[m/s]` column, exactly.
    let mph = |mps: f64| mps * (1.0 / MPS_PER_MPH);
    let found: Vec<_> = rows
        .iter()
        .filter(|(d, _)| d.delivery.club_speed_mph == mph(29.99) && d.delivery.attack_angle_deg == -3.4)
        .collect();
    assert_eq!(found.len(), 1);
    let (line, labels) = found[0];
    let d = &line.delivery;
    assert_eq!((d.club_path_deg, d.face_angle_deg, d.dynamic_loft_deg), (1.4, 1.259, Some(24.478)));
    assert_eq!(d.dynamic_lie_deg, Some(62.28613101870554));
    assert_eq!((d.impact_h_mm, d.impact_v_mm), (-9.073607442296912, 0.10579276296898382));
    let m = &line.measured;
    assert_eq!((m.ball_speed_mph, m.launch_angle_deg, m.launch_direction_deg), (mph(40.2583), 19.034, 1.286));
    let axis = (-0.185f64).to_radians();
    assert_eq!((m.backspin_rpm, m.sidespin_rpm), (4863.07 * axis.cos(), 4863.07 * axis.sin()));
    assert_eq!(labels.club.as_deref(), Some("7 Iron"));
    assert!(labels.spin_measured && labels.axis_measured && labels.impact_located);
}

/// The API's club spellings on the presets; a name with no preset stays without one.
#[test]
fn api_club_names_find_their_presets() {
    for (api, preset) in [
        ("Driver", Some("driver")),
        ("7Iron", Some("iron7")),
        ("PitchingWedge", Some("pw")),
        ("4Iron", Some("iron4")),
        ("5Wood", None),
        ("5Hybrid", None),
    ] {
        assert_eq!(preset_for_club_name(&csv_club_name(api)), preset, "{api}");
    }
}

/// The report and `scripts/trackman-report-to-csv.py`'s CSV of it (an independent reading of the layout, kept as
/// `report-2026-02-14-driver-7i.converted.csv`) give the same clubs, shots and statistics to the last digit.
#[test]
fn a_report_and_its_csv_give_the_same_comparison() {
    let models = "standard,adjusted,slip,continuous";
    let json = by_club(models, &data("report-2026-02-14-driver-7i.json"));
    let csv = by_club(models, &data("report-2026-02-14-driver-7i.converted.csv"));
    assert_eq!(json["clubs"], csv["clubs"]);
    assert_eq!(json["unlocated_left_out"], csv["unlocated_left_out"]);
    let clubs: Vec<(&str, u64)> = json["clubs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| (c["club"].as_str().unwrap(), c["shots"].as_u64().unwrap()))
        .collect();
    // 21 driver and 18 7-iron strokes; one driver stroke has no club data, 7 more no impact location.
    assert_eq!(clubs, vec![("driver", 14), ("iron7", 17)]);
    assert_eq!(json["skipped_rows"]["incomplete_club_data"], 1);
    assert_eq!(json["unlocated_left_out"], 7);
}

/// 2025-03-13 has a 5-wood (24 strokes), which has no preset: left out, counted, and the other clubs compared.
#[test]
fn a_club_with_no_preset_is_left_out_and_counted() {
    let r = by_club("standard", &data("report-2025-03-13-pw-driver-5w-7i.json"));
    assert_eq!(r["no_preset"], serde_json::json!([{ "label": "5 Wood", "shots": 24 }]));
    let labels: Vec<&str> = r["clubs"].as_array().unwrap().iter().map(|c| c["label"].as_str().unwrap()).collect();
    assert_eq!(labels.len(), 3, "{labels:?}");
    assert!(!labels.contains(&"5 Wood"));
}

/// A row whose impact location is off the face (90 mm toward the toe on the converted CSV's first located
/// 7-iron row) is refused by the club: it is left out and counted by reason, with `--by-club` and without, and
/// the other shots are compared.
#[test]
fn a_refused_shot_is_counted_not_fatal() {
    let text = std::fs::read_to_string(data("report-2026-02-14-driver-7i.converted.csv")).unwrap();
    let mut reader = csv::ReaderBuilder::new().has_headers(false).from_reader(text.as_bytes());
    let mut records: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    let col = |name: &str| records[0].iter().position(|h| h == name).unwrap();
    let (club, offset, height) = (col("Club"), col("Impact Offset"), col("Impact Height"));
    let row = records.iter().position(|r| &r[club] == "7 Iron" && !r[height].is_empty()).unwrap();
    let mut edited: Vec<String> = records[row].iter().map(str::to_string).collect();
    edited[offset] = "90".into();
    records[row] = csv::StringRecord::from(edited);
    let mut w = csv::Writer::from_writer(Vec::new());
    for r in &records {
        w.write_record(r).unwrap();
    }
    let dir = std::env::temp_dir().join(format!("impactd-refused-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("off-face.csv");
    std::fs::write(&path, w.into_inner().unwrap()).unwrap();
    let path = path.to_str().unwrap();

    let r = by_club("standard,ground", path);
    let iron7 = r["clubs"].as_array().unwrap().iter().find(|c| c["club"] == "iron7").unwrap();
    assert_eq!(iron7["shots"], 16);
    assert_eq!(iron7["refused"], serde_json::json!({ "impact location off the face": 1 }));
    assert_eq!(iron7["models"][0]["ball_speed_mph"]["n"], 16);

    // Without --by-club every row runs on the one club (driver rows on the 7-iron too, some off its face): one
    // refusal more than the file as converted.
    let off_face = |file: &str| {
        let r = compare(&["--json", "--club", "iron7", "--models", "standard", file]);
        r["refused"]["impact location off the face"].as_u64().unwrap_or(0)
    };
    assert_eq!(off_face(path), off_face(&data("report-2026-02-14-driver-7i.converted.csv")) + 1);
    std::fs::remove_dir_all(&dir).unwrap();
}
