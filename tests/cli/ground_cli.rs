//! The ground model as a user runs it: `impactd predict --model ground [--soil ...] [--trace]`, `impactd plot
//! ground`, `impactd map --model ground`, and the soil ordering of fat strikes (seed section 4.3).

#![allow(clippy::unwrap_used)]

use std::process::{Command, Output};

use impactd::equipment::soil::SoilSpec;
use impactd::equipment::ClubSpec;
use impactd::impact::continuous::iron_ground::{reference_swing, GroundModel, Strike};
use impactd::impact::Equipment;

fn impactd(args: &[&str], stdin: &str) -> Output {
    use std::io::Write;
    let mut child = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(args)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // A command that refuses its arguments exits without reading its input: a broken pipe here is not a failure.
    let _ = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    child.wait_with_output().unwrap()
}

/// The seed's swing over the face (section 4.3, as in crates/golf-physics/tests/ground.rs): 90 mph, 4.3° down, 25° dynamic loft,
/// 27 rad/s about the normal of a 60° swing plane, struck `v_mm` up the face.
fn line(v_mm: f64) -> String {
    let p = 60f64.to_radians();
    format!(
        "{{\"club_speed_mph\":90,\"attack_angle_deg\":-4.3,\"dynamic_loft_deg\":25,\"impact_v_mm\":{v_mm},\
         \"club_angular_velocity_radps\":[0,{},{}]}}\n",
        27.0 * p.cos(),
        27.0 * p.sin()
    )
}

fn answers(args: &[&str], input: &str) -> Vec<serde_json::Value> {
    let out = impactd(args, input);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect()
}

/// A fat strike (15 mm up the face: the sole meets the turf ~3 ms before the ball, docs/ground.md) slows and
/// de-lofts the club and digs a divot; a thin one (10 mm below the centre) never touches the ground before the
/// ball and keeps the club's speed.
#[test]
fn predict_adds_the_ground_object_for_fat_and_thin_strikes() {
    let input = format!("{}{}", line(15.0), line(-10.0));
    let lines = answers(&["predict", "--club", "iron7", "--model", "ground", "--soil", "firm"], &input);
    let (fat, thin) = (&lines[0]["ground"], &lines[1]["ground"]);
    let f = |g: &serde_json::Value, k: &str| g[k].as_f64().unwrap();
    assert_eq!(fat["strike"], "fat");
    assert!(f(fat, "ground_contact_before_ball_ms") > 1.0, "{fat}");
    assert!(f(fat, "club_speed_loss_mph") > 0.1, "{fat}");
    assert!(f(fat, "dynamic_loft_change_deg") < 0.0, "the turf holds the sole back: de-lofted, {fat}");
    assert!(f(fat, "divot_depth_mm") > 5.0 && f(fat, "divot_length_mm") > 100.0, "{fat}");
    assert!(f(fat, "peak_ground_force_n") > 50.0, "{fat}");
    assert!(f(fat, "face_angle_change_deg").is_finite());
    assert_eq!(thin["strike"], "thin");
    // No ground before the ball: only the shaft's own numerical settling (< 1e-3 mph).
    assert!(f(thin, "club_speed_loss_mph").abs() < 1e-3, "{thin}");
    assert!(thin["ground_contact_before_ball_ms"].is_null(), "{thin}");
    assert!(f(thin, "peak_ground_force_n") < 1e-9, "{thin}");
    // The launch is there beside it, slower for the fat strike (Figure 4.11).
    assert!(lines[0]["ball_speed_mph"].as_f64().unwrap() < lines[1]["ball_speed_mph"].as_f64().unwrap());

    // --trace: the ground's forces and the face angle and loft over time.
    let traced = answers(&["predict", "--club", "iron7", "--model", "ground", "--trace"], &line(15.0));
    let trace = traced[0]["trace"].as_array().unwrap();
    assert!(trace.len() > 50);
    for key in ["t_ms", "sole_vertical_n", "face_horizontal_n", "ground_vertical_n", "ground_horizontal_n"] {
        assert!(trace.iter().all(|p| p[key].is_f64()), "{key}");
    }
    assert!(trace.iter().any(|p| p["ground_vertical_n"].as_f64().unwrap() > 50.0));
    assert!(trace.iter().all(|p| p["face_angle_deg"].is_f64() && p["dynamic_loft_deg"].is_f64()));
    assert_eq!(traced[0]["ground"], lines[0]["ground"], "the trace does not change the strike");

    // Bad soils and a soil without the ground model are refused, naming the flag.
    for args in [
        &["predict", "--club", "iron7", "--model", "ground", "--soil", "mud"][..],
        &["predict", "--club", "iron7", "--model", "adjusted", "--soil", "firm"][..],
    ] {
        let out = impactd(args, &line(0.0));
        assert!(!out.status.success());
        assert!(String::from_utf8_lossy(&out.stderr).contains("--soil"), "{args:?}");
    }
}

/// The same fat strike on the three soils of Table 4.3, read literally (k_c in kN/m^(n+1), k_phi in kN/m^(n+2), z
/// and b in metres). The grip follows the swing, so the sole sinks about as deep on every soil (within 5 %:
/// measured 16.3 / 17.0 / 16.8 mm); the firm soil pushes hardest, but the medium soil less than the soft one,
/// because below 14.7 mm of sinkage the soft soil's smaller exponent (n = 0.66) makes it the stiffer
/// (docs/ground.md): the seed's soft < medium < firm (Figure 4.10) holds for firm only.
#[test]
fn the_same_fat_strike_on_three_soils() {
    let eq = Equipment::new(ClubSpec::iron7());
    let delivery = reference_swing(0.0, 15.0);
    let state = delivery.to_state(&eq).unwrap();
    let runs: Vec<_> = [SoilSpec::soft(), SoilSpec::medium(), SoilSpec::firm()]
        .into_iter()
        .map(|soil| GroundModel::new(soil).prepare(&eq).unwrap().simulate(&state, 0).unwrap())
        .collect();
    for r in &runs {
        println!(
            "depth {:.2} mm, length {:.0} mm, peak {:.0} N, loss {:.3} mph, strike {:?}",
            r.divot_depth_mm, r.divot_length_mm, r.peak_ground_force_n, r.club_speed_loss_mph, r.strike
        );
        assert_eq!(r.strike, Strike::Fat);
        assert!((r.divot_depth_mm / runs[2].divot_depth_mm - 1.0).abs() < 0.05);
    }
    let peak: Vec<f64> = runs.iter().map(|r| r.peak_ground_force_n).collect();
    assert!(peak[2] > peak[0] && peak[2] > peak[1], "firm pushes hardest: {peak:?}");
    assert!(peak[1] < peak[0], "the literal Table 4.3 orders medium below soft at this sinkage: {peak:?}");
}

/// `impactd plot ground` draws Figures 4.10 and 4.15 and refuses strikes that are not what they are called.
#[test]
fn plot_ground_writes_an_svg_and_refuses_impossible_strikes() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("ground.svg");
    let out = impactd(&["plot", "ground", "--soil", "medium", "-o", svg.to_str().unwrap()], "");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.len() > 5000 && text.contains("Figure 4.10"));
    assert!(text.contains("<polyline") || text.contains("<path"));
    for (args, says) in [
        (&["plot", "ground", "--fat-v-mm", "-10"][..], "not fat"),
        (&["plot", "ground", "--good-v-mm", "15"][..], "fat too"),
        (&["plot", "ground", "--soil", "mud"][..], "mud"),
        (&["plot", "ground", "--club-speed-mph", "900"][..], "club_speed_mph"),
    ] {
        let o = dir.path().join("no.svg");
        let mut a = args.to_vec();
        a.extend(["-o", o.to_str().unwrap()]);
        let out = impactd(&a, "");
        assert!(!out.status.success(), "{args:?}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains(says),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(!o.exists());
    }
}

/// `impactd map --model ground --soil firm` colours the face like `--model continuous`.
#[test]
fn map_runs_the_ground_model_over_the_face() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("map.svg");
    let args = ["map", "--club", "iron7", "--model", "ground", "--soil", "firm", "--metric", "sidespin"];
    let out = impactd(&[&args[..], &["--cells", "5", "-o", svg.to_str().unwrap()]].concat(), "");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("ground") && text.matches("<rect").count() > 25, "5 x 5 cells drawn");
}

/// `--soil none`: the same fat strike off a tee. The strike reads `teed`, no ground acts (no divot, no speed lost
/// before the ball), and the fat strike on firm soil differs from it by what the turf did (docs/ground.md: within a
/// few mph at v = +15 mm).
#[test]
fn soil_none_is_the_same_strike_off_a_tee() {
    let args = |soil: &'static str| ["predict", "--club", "iron7", "--model", "ground", "--soil", soil];
    let teed = answers(&args("none"), &line(15.0));
    let fat = answers(&args("firm"), &line(15.0));
    let (t, f) = (&teed[0], &fat[0]);
    assert_eq!((t["ground"]["strike"].as_str(), f["ground"]["strike"].as_str()), (Some("teed"), Some("fat")));
    assert_eq!(t["ground"]["divot_depth_mm"].as_f64(), Some(0.0));
    // The shaft's own response to the ball's first microsecond, nothing from the turf.
    assert!(t["ground"]["club_speed_loss_mph"].as_f64().unwrap().abs() < 1e-3, "{t}");
    let mph = |v: &serde_json::Value| v["ball_speed_mph"].as_f64().unwrap();
    assert!(mph(t) > 100.0 && (mph(t) - mph(f)).abs() < 5.0, "teed {} vs fat {}", mph(t), mph(f));
    let refused = impactd(&args("mud"), &line(15.0));
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("none"));
}
