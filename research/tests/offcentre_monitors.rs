//! research/offcentre-monitors.md's tables, asserted: `research/scripts/offcentre-monitors.py` run on the kept
//! VALIDATION sessions (tests/data/trackman: the third player's four report sessions and the validation CSV;
//! the held-out files in research/data/trackman are not read) through the binary, each model on every stroke with
//! club data, an impact location and measured spin. The numbers are the page's, to the digits it prints: the
//! ball-speed error's MAE, bias and slopes against impact height and offset, the spin MAE, and for the driver the
//! spin axis' MAE and its partial slopes against face to path and offset (TrackMan's measured slopes beside them).
//! A change to the models or presets that moves a finding fails here and sends the page to be regenerated.
#![allow(clippy::unwrap_used)]

use std::process::Command;

/// (clubs, reading, model, shots, ball MAE, ball bias, slope vs height, slope vs offset, spin MAE, and for the
/// driver the axis MAE and the axis' slopes against face to path and offset).
type Row = (&'static str, &'static str, &'static str, u64, f64, f64, f64, f64, f64, Option<(f64, f64, f64)>);

const PAGE: [Row; 12] = [
    ("irons", "centre", "standard", 116, 3.04, 1.88, -0.274, -0.038, 697.0, None),
    ("irons", "centre", "adjusted", 116, 3.40, 2.58, -0.278, -0.034, 736.0, None),
    ("irons", "centre", "slip", 116, 3.06, 1.96, -0.277, -0.041, 431.0, None),
    ("irons", "centre", "continuous", 116, 4.73, 3.88, -0.507, 0.000, 937.0, None),
    ("driver", "centre", "standard", 64, 2.61, -2.51, -0.202, 0.063, 219.0, Some((8.18, 5.22, -0.340))),
    ("driver", "centre", "adjusted", 64, 2.23, -2.01, -0.207, 0.064, 517.0, Some((12.60, 6.62, -0.487))),
    ("driver", "centre", "slip", 64, 2.61, -2.51, -0.202, 0.063, 220.0, Some((8.02, 5.21, -0.355))),
    ("driver", "centre", "continuous", 64, 2.04, -1.44, -0.246, 0.073, 342.0, Some((7.07, 5.45, -0.558))),
    ("driver", "contact", "standard", 64, 2.04, -1.92, -0.117, 0.029, 232.0, Some((3.42, 5.29, -1.202))),
    ("driver", "contact", "adjusted", 64, 1.65, -1.41, -0.127, 0.029, 623.0, Some((6.93, 6.92, -1.585))),
    ("driver", "contact", "slip", 64, 2.04, -1.92, -0.117, 0.029, 245.0, Some((3.40, 5.28, -1.215))),
    ("driver", "contact", "continuous", 64, 1.32, -0.74, -0.158, 0.033, 415.0, Some((4.50, 5.55, -1.475))),
];

fn run_script() -> Vec<serde_json::Value> {
    let python = std::env::var_os("IMPACTD_PYTHON").unwrap_or_else(|| "python3".into());
    let out = Command::new(python)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["research/scripts/offcentre-monitors.py", env!("CARGO_BIN_EXE_impactd"), "test"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect()
}

#[test]
fn the_off_centre_tables_hold_on_the_kept_sessions() {
    let lines = run_script();
    assert_eq!(lines.len(), PAGE.len());
    let close = |got: &serde_json::Value, want: f64, tol: f64, what: &str| {
        let got = got.as_f64().unwrap_or_else(|| panic!("{what}: {got}"));
        assert!((got - want).abs() <= tol, "{what}: {got} against the page's {want}");
    };
    for (clubs, reading, model, shots, mae, bias, s_h, s_o, spin, axis) in PAGE {
        let l = lines
            .iter()
            .find(|l| l["clubs"] == clubs && l["reading"] == reading && l["model"] == model)
            .unwrap_or_else(|| panic!("no line for {clubs} {reading} {model}"));
        let what = |field: &str| format!("{clubs} {reading} {model} {field}");
        assert_eq!(l["shots"].as_u64(), Some(shots), "{}", what("shots"));
        close(&l["ball_mae_mph"], mae, 0.005, &what("ball-speed MAE"));
        close(&l["ball_bias_mph"], bias, 0.005, &what("ball-speed bias"));
        close(&l["ball_slope_height_mph_per_mm"], s_h, 0.0005, &what("ball-speed error against height"));
        close(&l["ball_slope_offset_mph_per_mm"], s_o, 0.0005, &what("ball-speed error against offset"));
        close(&l["spin_mae_rpm"], spin, 0.5, &what("spin MAE"));
        if let Some((axis_mae, per_face_to_path, per_offset)) = axis {
            close(&l["axis_mae_deg"], axis_mae, 0.005, &what("axis MAE"));
            close(&l["axis_slopes_model"][0], per_face_to_path, 0.005, &what("axis against face to path"));
            close(&l["axis_slopes_model"][1], per_offset, 0.0005, &what("axis against offset"));
            close(&l["axis_slopes_measured"][0], 3.72, 0.005, &what("TrackMan's axis against face to path"));
            close(&l["axis_slopes_measured"][1], -0.766, 0.0005, &what("TrackMan's axis against offset"));
        }
    }
}

/// The page's default-model finding: only the slip model keeps iron spin within 600 rpm on every kept session.
#[test]
fn only_the_slip_model_keeps_iron_spin_within_600_rpm_on_every_session() {
    let lines = run_script();
    for l in lines.iter().filter(|l| l["clubs"] == "irons") {
        let worst =
            l["spin_mae_by_session"].as_object().unwrap().values().map(|v| v.as_f64().unwrap()).fold(0.0, f64::max);
        assert_eq!(worst <= 600.0, l["model"] == "slip", "{}: worst session {worst} rpm", l["model"]);
    }
}
