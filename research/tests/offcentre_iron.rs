//! The 7-iron's off-centre strikes against the published measurements of research/offcentre-iron.md, through
//! `impactd predict --club iron7`.

#![allow(clippy::unwrap_used)]

use std::io::Write;
use std::process::{Command, Stdio};

/// (ball speed mph, backspin rpm, sidespin rpm) of `model` at each impact location (toe +, up +, mm), for the
/// measured shot pair's delivery: 85 mph (Golf Australia, July 2019), attack -4.5 deg (TrackMan's tour 8-iron
/// average), dynamic loft 32 deg.
fn predict(model: &str, at: &[(f64, f64)]) -> Vec<(f64, f64, f64)> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(["predict", "--club", "iron7", "--model", model])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut input = String::new();
    for (h, v) in at {
        input += &format!(
            "{{\"club_speed_mph\":85,\"attack_angle_deg\":-4.5,\"dynamic_loft_deg\":32,\"impact_h_mm\":{h},\"impact_v_mm\":{v}}}\n"
        );
    }
    child.stdin.take().unwrap().write_all(input.as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| {
            let j: serde_json::Value = serde_json::from_str(l).unwrap();
            let f = |k: &str| j[k].as_f64().unwrap();
            (f("ball_speed_mph"), f("backspin_rpm"), f("sidespin_rpm"))
        })
        .collect()
}

const AT: [(f64, f64); 5] = [(0.0, 0.0), (17.0, 0.0), (17.0, -3.0), (-17.0, 0.0), (0.0, -8.0)];

/// Measured (Golf Australia 2019, GC Quad, 8-iron at 85 mph): a toe strike 17 mm from the middle, slightly low,
/// lost 5.7 % of ball speed (106 -> 100 mph) and gained 6.0 % backspin (6,814 -> 7,224 rpm). One shot pair: the
/// adjusted model's loss must be within 3 points of it (strike location and shot scatter, research/offcentre-iron.md).
#[test]
fn the_adjusted_model_loses_ball_speed_at_the_toe_as_measured() {
    let r = predict("adjusted", &AT);
    for (i, what) in [(1, "17 mm toe"), (2, "17 mm toe, 3 mm low")] {
        let loss_pct = 100.0 * (1.0 - r[i].0 / r[0].0);
        assert!((loss_pct - 5.7).abs() <= 3.0, "{what}: {loss_pct:.2} % against the measured 5.7 %");
    }
    // The measured toe-and-low strike gained backspin.
    assert!(r[2].1 > r[0].1, "{r:?}");
}

/// The directions every source agrees on, for both models: toe strikes draw (sidespin < 0), heel strikes fade,
/// a lower strike spins more (the seed's section 4.4 conclusions; Golf Australia 2019's "one groove lower adds
/// about 400 rpm"), and a toe strike loses ball speed.
#[test]
fn both_models_turn_the_ball_the_measured_way() {
    for model in ["adjusted", "continuous"] {
        let r = predict(model, &AT);
        assert!(r[1].2 < r[0].2 && r[1].2 < 0.0, "{model}: toe draw {r:?}");
        assert!(r[3].2 > r[0].2 && r[3].2 > 0.0, "{model}: heel fade {r:?}");
        assert!(r[4].1 > r[0].1 + 200.0, "{model}: 8 mm low spins more {r:?}");
        assert!(r[1].0 < r[0].0, "{model}: toe loses ball speed {r:?}");
    }
}
