//! Real TrackMan shots: the validation session of tests/data/trackman/ (a TrackMan Performance Studio export
//! published in github.com/MCI1980/fantastic-fortnight, `tests/sample_tps_export.csv`, commit 10bbca7f; one
//! player's 8- and 5-iron, 2026-02-19) through `impactd compare --by-club --located --json`: TrackMan's club data
//! and impact location are the delivery, each club on its preset, spin compared only where TrackMan measured it.
//! The bounds are the accuracy research/real-shots.md reports, with a margin of about a tenth; the held-out session is
//! not read here (research/real-shots.md has its numbers, computed once).

#![allow(clippy::unwrap_used)]

use crate::predict;

use std::process::Command;

use serde_json::Value;

const VALIDATION: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/trackman/validation-8i-5i.csv");

fn by_club(models: &str) -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(["compare", "--by-club", "--located", "--json", "--soil", "none", "--models", models, VALIDATION])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

/// (mae, bias, n) of `field` for `model` on the club labelled `club`.
fn stat(r: &Value, club: &str, model: &str, field: &str) -> (f64, f64, u64) {
    let c = r["clubs"].as_array().unwrap().iter().find(|c| c["label"] == club).unwrap();
    let m = c["models"].as_array().unwrap().iter().find(|m| m["model"] == model).unwrap();
    let e = &m[field];
    (e["mae"].as_f64().unwrap(), e["bias"].as_f64().unwrap(), e["n"].as_u64().unwrap())
}

/// The session's located shots: 12 8-iron (6 with measured spin) and 14 5-iron (2); 10 rows have club data
/// but no impact location and are left out.
#[test]
fn the_validation_session_reads_as_trackman_wrote_it() {
    let r = by_club("adjusted");
    assert_eq!(r["unlocated_left_out"], 10);
    let clubs: Vec<(String, u64, u64)> = r["clubs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| {
            (c["club"].as_str().unwrap().to_string(), c["shots"].as_u64().unwrap(), c["spin_shots"].as_u64().unwrap())
        })
        .collect();
    assert_eq!(clubs, vec![("iron8".to_string(), 12, 6), ("iron5".to_string(), 14, 2)]);
}

/// Ball speed with the shaft's share of the heel-toe inertia in the presets: the impulse-momentum models
/// (seed 3.1) and the continuous model now miss the 8-iron by about 3 mph (it was 6.4-8.7 mph on these shots
/// with the free head alone) and the 5-iron by 6.5-7 mph (13.3-15.7). The target of 3 mph is met for
/// neither club by a margin: the 5-iron's high strikes still lose too much (research/real-shots.md).
#[test]
fn ball_speed_on_the_validation_session() {
    let r = by_club("adjusted,slip,continuous,ground");
    for (model, iron8, iron5) in
        [("adjusted", 3.5, 7.1), ("slip", 4.1, 7.7), ("continuous", 3.6, 7.8), ("ground", 3.5, 7.6)]
    {
        let (m8, _, _) = stat(&r, "8 Iron", model, "ball_speed_mph");
        let (m5, _, _) = stat(&r, "5 Iron", model, "ball_speed_mph");
        assert!(m8 <= iron8, "{model}: 8-iron ball speed MAE {m8:.2} mph > {iron8}");
        assert!(m5 <= iron5, "{model}: 5-iron ball speed MAE {m5:.2} mph > {iron5}");
    }
}

/// Launch angle within the 1 deg for every model but Maw; spin axis within its 2.5 deg on the 8-iron's
/// measured spins (the 5-iron has two); spin within 600 rpm for the slip model only, every model's bias on the
/// 8-iron negative (too little backspin, as against the tour's irons, research/real-shots.md).
#[test]
fn launch_spin_and_axis_on_the_validation_session() {
    let r = by_club("standard,adjusted,slip,continuous,ground");
    for model in ["standard", "adjusted", "slip", "continuous", "ground"] {
        for club in ["8 Iron", "5 Iron"] {
            let (la, _, _) = stat(&r, club, model, "launch_angle_deg");
            assert!(la <= 1.0, "{model} {club}: launch MAE {la:.2} deg");
        }
        let (axis, _, n) = stat(&r, "8 Iron", model, "spin_axis_deg");
        assert_eq!(n, 6);
        assert!(axis <= 2.5, "{model}: 8-iron spin axis MAE {axis:.2} deg");
        let (_, spin_bias, _) = stat(&r, "8 Iron", model, "spin_rpm");
        assert!(spin_bias < 0.0, "{model}: 8-iron spin bias {spin_bias:.0} rpm");
    }
    let (spin, _, _) = stat(&r, "8 Iron", "slip", "spin_rpm");
    assert!(spin <= 600.0, "slip: 8-iron spin MAE {spin:.0} rpm");
}

/// The share is what the seed's shaft does: on the 5-iron preset, the continuous model's free head loses as
/// much ball speed from the face centre to 10 mm above it as the same head on the Table 4.1 shaft (the ground
/// model on a tee) within 0.3 mph (8.35 mph at 85 mph), where the head alone loses 16.5
/// (research/scripts/shaft-share.py).
#[test]
fn the_shaft_share_reproduces_the_flexible_shaft() {
    let drop = |model: &str, extra: &[&str]| {
        let lines = "{\"club_speed_mph\":85,\"attack_angle_deg\":-4,\"dynamic_loft_deg\":19.5,\"impact_v_mm\":0}\n\
                     {\"club_speed_mph\":85,\"attack_angle_deg\":-4,\"dynamic_loft_deg\":19.5,\"impact_v_mm\":10}\n";
        let args = [&["predict", "--club", "iron5", "--model", model][..], extra].concat();
        let v = predict::answers(&args, lines);
        v[0]["ball_speed_mph"].as_f64().unwrap() - v[1]["ball_speed_mph"].as_f64().unwrap()
    };
    let (free, shaft) = (drop("continuous", &[]), drop("ground", &["--soil", "none"]));
    assert!((free - shaft).abs() < 0.3, "free head with the share {free:.2} mph, on the shaft {shaft:.2} mph");
}

/// Ball speeds (mph) of `predict --club PRESET --model MODEL` on the given delivery lines.
fn ball_speeds(preset: &str, model: &str, lines: &str) -> Vec<f64> {
    predict::answers(&["predict", "--club", preset, "--model", model], lines)
        .iter()
        .map(|a| a["ball_speed_mph"].as_f64().unwrap())
        .collect()
}

/// The slope of ball speed against impact height on the iron presets is the head's effective mass and nothing
/// else: at normal incidence (attack angle and dynamic loft 0, the face normal along the face's velocity) the
/// standard model's ball speed 14 mm above the sweet spot over its speed at the sweet spot is the closed form of
/// a rigid head, `m_eff / (m_eff + m_ball)` over its value at the sweet spot, with
/// `1/m_eff = 1/m + (r x n) · I^-1 (r x n)` (r from the CG to the contact point, n the face normal, I the head's
/// tensor with the shaft's share, Table 3.1's 45.9 g ball), to 0.1 %. The sweet spot is the CG's projection on
/// the face, 2.35 mm below the face centre on every iron preset (Table 3.1's 7-iron; research/real-shots.md, "The
/// slope"): the 5-iron keeps 93.4 % of its speed there, where TrackMan's smash on the validation session does not
/// fall from the lowest strikes to 13 mm above the centre.
#[test]
fn the_slope_against_impact_height_is_the_heads_effective_mass() {
    use impactd::math::Vector3;
    for (preset, expected) in [("iron8", 0.934), ("iron5", 0.934)] {
        let club = impactd::equipment::presets::find(preset).unwrap().load().unwrap().club;
        let (l, c) = (club.face.loft_rad, club.face.center_m);
        let n = Vector3::new(l.cos(), l.sin(), 0.0);
        let u = Vector3::new(-l.sin(), l.cos(), 0.0);
        let sweet_mm = -c.dot(&u) * 1e3;
        assert!((sweet_mm + 2.347).abs() < 0.01, "{preset}: sweet spot {sweet_mm:.3} mm");
        let share = |v_mm: f64| {
            let k = (c + u * (v_mm * 1e-3)).cross(&n);
            let m_eff = 1.0 / (1.0 / club.mass_kg + k.dot(&(club.inertia_inv_kg_m2 * k)));
            m_eff / (m_eff + impactd::equipment::BallSpec::SEED.mass_kg)
        };
        let closed = share(sweet_mm + 14.0) / share(sweet_mm);
        let lines: String = [sweet_mm, sweet_mm + 14.0]
            .iter()
            .map(|v| {
                format!("{{\"club_speed_mph\":95,\"attack_angle_deg\":0,\"dynamic_loft_deg\":0,\"impact_v_mm\":{v}}}\n")
            })
            .collect();
        let v = ball_speeds(preset, "standard", &lines);
        let model = v[1] / v[0];
        assert!((model / closed - 1.0).abs() < 1e-3, "{preset}: model {model:.5}, closed form {closed:.5}");
        assert!((closed - expected).abs() < 0.005, "{preset}: closed form {closed:.4}");
    }
}

/// The validation export's rows as column name -> cell (TrackMan's layout: `sep=,`, header, units row).
fn validation_rows() -> Vec<std::collections::HashMap<String, String>> {
    let text = std::fs::read_to_string(VALIDATION).unwrap();
    let text = text.trim_start_matches('\u{feff}');
    let body = text.split_once('\n').unwrap().1;
    let mut reader = csv::ReaderBuilder::new().flexible(true).from_reader(body.as_bytes());
    let head: Vec<String> = reader.headers().unwrap().iter().map(str::to_string).collect();
    reader
        .records()
        .skip(1)
        .map(|r| head.iter().cloned().zip(r.unwrap().iter().map(str::to_string)).collect())
        .collect()
}

fn cell(row: &std::collections::HashMap<String, String>, column: &str) -> Option<f64> {
    row.get(column).and_then(|c| c.trim().parse().ok())
}

/// TrackMan's `Low Point Height` is no height above the ground: on every row with club data it is minus the drop
/// of a circular arc from the impact point to its low point, `tan(AA)^2 R / (2 sin(plane))` (attack angle AA,
/// `Swing Radius` R, `Swing Plane`), to 1.2 mm (its 1 mm rounding). So the export cannot place the leading edge
/// against the ball, and a crosshair height cannot be derived from it (research/real-shots.md).
#[test]
fn low_point_height_is_the_arcs_drop_below_the_impact_point() {
    let mut n = 0;
    for row in validation_rows() {
        let (Some(aa), Some(radius_in), Some(plane), Some(height_mm)) = (
            cell(&row, "Attack Angle"),
            cell(&row, "Swing Radius"),
            cell(&row, "Swing Plane"),
            cell(&row, "Low Point Height"),
        ) else {
            continue;
        };
        let drop_mm = aa.to_radians().tan().powi(2) * radius_in * 25.4 / (2.0 * plane.to_radians().sin());
        assert!((height_mm + drop_mm).abs() <= 1.2, "low point height {height_mm} mm, the arc's drop {drop_mm:.2} mm");
        n += 1;
    }
    assert_eq!(n, 36);
}

/// Spin against launch on TrackMan's own face: a homogeneous ball (Table 3.1's `I = 0.4 m R^2`) leaving a face
/// at angle `a` below its normal spins `2.5 v sin(a) / R`. On the validation 8-iron's located shots with measured
/// spin (6), TrackMan's numbers put the ball 5.26 deg below its face on average; its spin needs 5.97 deg: a model
/// with that ball reaches TrackMan's spin only by launching 0.72 deg (0.66-0.78) below TrackMan's launch, and at
/// TrackMan's launch misses its spin by 757 rpm MAE, over the 600 rpm target (research/real-shots.md, "spin and
/// launch"). The closed form of the angular momentum bound, on TrackMan's numbers alone.
#[test]
fn the_seeds_ball_reaches_trackmans_spin_only_below_trackmans_launch() {
    let (r, mps) = (0.0213, 0.44704);
    let mut shots = Vec::new();
    for row in validation_rows() {
        let measured = row.get("Spin Rate Type").is_some_and(|t| t == "Measured");
        if !measured || row.get("Club").map(String::as_str) != Some("8 Iron") || cell(&row, "Impact Height").is_none() {
            continue;
        }
        let (Some(loft), Some(face), Some(la), Some(ld), Some(v), Some(spin)) = (
            cell(&row, "Dyn. Loft"),
            cell(&row, "Face Angle"),
            cell(&row, "Launch Angle"),
            cell(&row, "Launch Direction"),
            cell(&row, "Ball Speed"),
            cell(&row, "Spin Rate"),
        ) else {
            continue;
        };
        let dir = |e: f64, a: f64| {
            let (e, a) = (e.to_radians(), a.to_radians());
            [e.cos() * a.cos(), e.sin(), e.cos() * a.sin()]
        };
        let (n, b) = (dir(loft, face), dir(la, ld));
        let a = (n[0] * b[0] + n[1] * b[1] + n[2] * b[2]).clamp(-1.0, 1.0).acos();
        let w = spin * std::f64::consts::TAU / 60.0;
        let need = (w * r / (2.5 * v * mps)).asin();
        let at_launch_rpm = 2.5 * v * mps * a.sin() / r * 60.0 / std::f64::consts::TAU;
        shots.push((a.to_degrees(), need.to_degrees(), (at_launch_rpm - spin).abs()));
    }
    assert_eq!(shots.len(), 6);
    let mean = |f: fn(&(f64, f64, f64)) -> f64| shots.iter().map(f).sum::<f64>() / shots.len() as f64;
    assert!((mean(|s| s.0) - 5.26).abs() < 0.01, "{}", mean(|s| s.0));
    assert!((mean(|s| s.1 - s.0) - 0.72).abs() < 0.01, "{}", mean(|s| s.1 - s.0));
    assert!(shots.iter().all(|s| (0.65..0.79).contains(&(s.1 - s.0))));
    assert!((mean(|s| s.2) - 757.0).abs() < 2.0, "{}", mean(|s| s.2));
}

/// `compare --by-club` reads a wood's dynamic loft and face angle as TrackMan defines them, at the contact point:
/// a one-row export (a driver, 100 mph, attack +2 deg, square path and face, loft 13 deg, struck 20 mm toward the
/// heel, spin axis 0) gives the standard model's spin axis of the face-centre delivery
/// `offline::identify::trackman_reading::at_face_centre` finds, to 1e-6 deg, whose face centre is open by the
/// bulge's turn (3.86 deg: the torus of ARCHITECTURE.md section 2 on the seed's 305 mm bulge at 13 deg of loft), and
/// that axis fades by about the D-plane tilt of that turn more than the row read as the face centre's.
#[test]
fn a_driver_rows_loft_and_face_are_the_contact_points() {
    use impactd::equipment::{load_club, BallSpec};
    use impactd::impact::registry::{build_one, BuildOptions};
    use impactd::impact::{Equipment, LaunchMetrics};
    use impactd::offline::identify::trackman_reading::at_face_centre;
    use impactd::wire::DeliveryInput;

    let header = ["Club", "Club Speed", "Attack Angle", "Club Path", "Dyn. Loft", "Face Angle", "Ball Speed"];
    let header = [&header[..], &["Launch Angle", "Launch Direction", "Spin Rate", "Spin Rate Type", "Spin Axis"]]
        .concat()
        .into_iter()
        .chain(["Impact Offset", "Impact Height"])
        .map(|h| format!("\"{h}\""))
        .collect::<Vec<_>>()
        .join(",");
    let units = "\"\",\"[mph]\",\"[deg]\",\"[deg]\",\"[deg]\",\"[deg]\",\"[mph]\",\"[deg]\",\"[deg]\",\"[rpm]\",\"\",\"[deg]\",\"[mm]\",\"[mm]\"";
    let row =
        "\"Driver\",\"100\",\"2\",\"0\",\"13\",\"0\",\"145\",\"13\",\"0\",\"2500\",\"Measured\",\"0\",\"-20\",\"0\"";
    let dir = std::env::temp_dir().join(format!("impactd-real-shots-driver-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("driver.csv");
    std::fs::write(&path, format!("sep=,\n{header}\n{units}\n{row}\n")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(["compare", "--by-club", "--json", "--models", "standard"])
        .arg(&path)
        .output()
        .unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    let (axis, _, n) = stat(&r, "Driver", "standard", "spin_axis_deg");
    assert_eq!(n, 1);

    let club = load_club("driver").unwrap();
    let eq = Equipment::new(club.club.clone());
    let model = build_one("standard", &club, &BuildOptions { ball: BallSpec::SEED, ..Default::default() }).unwrap();
    let axis_of = |d: &DeliveryInput| {
        let l = model.predict(&d.to_state(&eq).unwrap(), &eq).unwrap();
        LaunchMetrics::from_ball(&l.ball_velocity_mps, &l.ball_spin_radps).spin_axis_deg
    };
    let row = DeliveryInput {
        club_speed_mph: 100.0,
        attack_angle_deg: 2.0,
        dynamic_loft_deg: Some(13.0),
        impact_h_mm: -20.0,
        ..Default::default()
    };
    let read = at_face_centre(&row, &eq).unwrap();
    assert!((read.face_angle_deg - 3.86).abs() < 0.02, "face centre {:.3} deg", read.face_angle_deg);
    assert!((axis - axis_of(&read)).abs() < 1e-6, "compare {axis:.6}, the reading {:.6}", axis_of(&read));
    // Read at the face centre, the contact normal is the bulge's 3.86 deg closed: the plane of the club's velocity
    // (attack 2 deg, path 0) and that normal (loft 13 deg) is tilted `atan(v x n)` 18.9 deg toward a draw (the
    // D-plane's closed form); the reading takes that tilt away, and the model's axis moves by it within 4 deg (the
    // gear effect's share changes with the contact normal: 22.3 deg here).
    let (a, dl, f) = (2.0_f64.to_radians(), 13.0_f64.to_radians(), -(read.face_angle_deg).to_radians());
    let n = [dl.cos() * f.cos(), dl.sin(), dl.cos() * f.sin()];
    let axis_vector = [a.sin() * n[2], -a.cos() * n[2], a.cos() * n[1] - a.sin() * n[0]];
    let tilt = axis_vector[1].atan2(axis_vector[0].hypot(axis_vector[2])).to_degrees();
    assert!((tilt - 18.9).abs() < 0.1, "D-plane tilt {tilt:.2} deg");
    let more_fade = axis - axis_of(&row);
    assert!((more_fade - tilt).abs() < 4.0, "axis {axis:.2} deg, read at the face centre {:.2}", axis_of(&row));
}

/// `compare --by-club --spin-relation`: TrackMan's loft and face read through its spin relation (1.136, the ratio
/// `research/tests/tour_iron_spin.rs` measures on every measured shot) give the seed's ball TrackMan's spin at
/// TrackMan's launch. On the validation 8-iron the default model's spin then meets the 600 rpm (497 rpm MAE;
/// 633 without) and its launch bias vanishes (-0.04 deg; -0.60 without), for 0.6 mph more ball speed error (3.75;
/// 3.14 without): the bounds are research/real-shots.md's numbers with a margin of about a tenth.
#[test]
fn trackmans_loft_through_its_relation_trades_speed_for_spin() {
    let out = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(["compare", "--by-club", "--located", "--json", "--spin-relation", "--models", "adjusted", VALIDATION])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(r["spin_relation"], true);
    let plain = by_club("adjusted");
    let (spin, _, n) = stat(&r, "8 Iron", "adjusted", "spin_rpm");
    let (launch, launch_bias, _) = stat(&r, "8 Iron", "adjusted", "launch_angle_deg");
    let (speed, _, _) = stat(&r, "8 Iron", "adjusted", "ball_speed_mph");
    assert_eq!(n, 6);
    assert!(spin <= 550.0, "spin MAE {spin:.0} rpm");
    assert!(launch <= 0.3 && launch_bias.abs() <= 0.1, "launch MAE {launch:.2} deg, bias {launch_bias:+.2}");
    assert!((3.4..=4.1).contains(&speed), "ball speed MAE {speed:.2} mph");
    let (plain_spin, _, _) = stat(&plain, "8 Iron", "adjusted", "spin_rpm");
    let (plain_speed, _, _) = stat(&plain, "8 Iron", "adjusted", "ball_speed_mph");
    assert!(plain_spin > 600.0 && plain_speed < speed, "without: {plain_spin:.0} rpm, {plain_speed:.2} mph");
}
