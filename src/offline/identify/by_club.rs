//! Accuracy per club in the terms a launch monitor reports: ball speed, launch angle, total spin and spin axis,
//! each as mean absolute error and bias (mean of predicted - measured). Spin is compared only on shots whose
//! spin was measured (a TrackMan export marks spin its launch model estimated; it is no measurement).

use serde::Serialize;

use crate::math::Real;

/// One compared quantity: mean absolute error, bias (mean signed error) and the number of shots it is over.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ErrorStats {
    pub mae: Real,
    pub bias: Real,
    pub n: usize,
}

impl ErrorStats {
    /// Of the signed errors `e` (an empty set gives NaN, n = 0).
    pub fn of(e: &[Real]) -> Self {
        let n = e.len();
        let mean = |f: &dyn Fn(Real) -> Real| e.iter().map(|x| f(*x)).sum::<Real>() / n as Real;
        ErrorStats { mae: mean(&|x| x.abs()), bias: mean(&|x| x), n }
    }
}

/// One model's accuracy on one club's shots.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClubModelStats {
    pub model: String,
    /// Shots the model failed on (left out of every statistic).
    pub failed: usize,
    pub ball_speed_mph: ErrorStats,
    pub launch_angle_deg: ErrorStats,
    pub spin_rpm: ErrorStats,
    pub spin_axis_deg: ErrorStats,
}

/// Total spin (rpm) and spin axis (deg, right +) of the five compared fields (backspin at index 3, sidespin at
/// index 4, TrackMan's definition `axis = atan2(sidespin, backspin)`).
pub fn spin_and_axis(fields: &[Real; 5]) -> (Real, Real) {
    (fields[3].hypot(fields[4]), fields[4].atan2(fields[3]).to_degrees())
}

/// Whether a shot's spin rate and its spin axis were measured (an axis only with its spin).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SpinMeasured {
    pub spin: bool,
    pub axis: bool,
}

/// The statistics of `predicted` against `measured` (the five compared fields each), spin only where it was
/// measured, the spin axis only where it was too (a shot with no axis is not one with axis 0).
pub fn club_model_stats(
    model: &str,
    predicted: &[Option<[Real; 5]>],
    measured: &[[Real; 5]],
    spin_measured: &[SpinMeasured],
) -> ClubModelStats {
    let (mut speed, mut launch, mut spin, mut axis) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut failed = 0;
    for ((p, m), ok) in predicted.iter().zip(measured).zip(spin_measured) {
        let Some(p) = p else {
            failed += 1;
            continue;
        };
        speed.push(p[0] - m[0]);
        launch.push(p[1] - m[1]);
        let ((sp, ap), (sm, am)) = (spin_and_axis(p), spin_and_axis(m));
        if ok.spin {
            spin.push(sp - sm);
        }
        if ok.spin && ok.axis {
            axis.push(ap - am);
        }
    }
    ClubModelStats {
        model: model.to_string(),
        failed,
        ball_speed_mph: ErrorStats::of(&speed),
        launch_angle_deg: ErrorStats::of(&launch),
        spin_rpm: ErrorStats::of(&spin),
        spin_axis_deg: ErrorStats::of(&axis),
    }
}

/// The club preset a launch monitor's club name means (TrackMan's `Club` column: "Driver", "7 Iron",
/// "Pitching Wedge", "3 Wood", "Hybrid", ...), or `None` for a name with no preset.
pub fn preset_for_club_name(name: &str) -> Option<&'static str> {
    let n = name.trim().to_ascii_lowercase().replace(['-', '_'], " ");
    let preset = match n.as_str() {
        "driver" | "dr" => "driver",
        "3 wood" | "3w" | "wood 3" => "wood3",
        "hybrid" | "3 hybrid" | "4 hybrid" => "hybrid",
        "4 iron" | "4i" => "iron4",
        "5 iron" | "5i" => "iron5",
        "6 iron" | "6i" => "iron6",
        "7 iron" | "7i" => "iron7",
        "8 iron" | "8i" => "iron8",
        "9 iron" | "9i" => "iron9",
        "pitching wedge" | "pw" => "pw",
        "gap wedge" | "gw" | "approach wedge" | "aw" => "gw",
        "sand wedge" | "sw" => "sw",
        "lob wedge" | "lw" => "lw",
        _ => return None,
    };
    Some(preset)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Spin and axis follow TrackMan's split; a failed prediction and an estimated spin are left out where they
    /// must be.
    #[test]
    fn statistics_follow_the_definitions() {
        let m = [[100.0, 10.0, 0.0, 3000.0, 0.0], [100.0, 10.0, 0.0, 3000.0, 0.0], [100.0, 10.0, 0.0, 3000.0, 0.0]];
        let side = 4000.0 * 5f64.to_radians().sin();
        let p = [
            Some([103.0, 9.0, 0.0, 4000.0 * 5f64.to_radians().cos(), side]),
            Some([99.0, 11.0, 0.0, 3000.0, 0.0]),
            None,
        ];
        let yes = SpinMeasured { spin: true, axis: true };
        let no = SpinMeasured { spin: false, axis: false };
        let s = club_model_stats("x", &p, &m, &[yes, no, yes]);
        assert_eq!(s.failed, 1);
        assert!((s.ball_speed_mph.mae - 2.0).abs() < 1e-12 && (s.ball_speed_mph.bias - 1.0).abs() < 1e-12);
        assert!((s.launch_angle_deg.mae - 1.0).abs() < 1e-12 && s.launch_angle_deg.bias.abs() < 1e-12);
        assert_eq!(s.spin_rpm.n, 1);
        assert!((s.spin_rpm.bias - 1000.0).abs() < 1e-9 && (s.spin_axis_deg.bias - 5.0).abs() < 1e-9);
        // A measured spin without an axis: its spin compared, its axis (read as 0) not.
        let s = club_model_stats("x", &p, &m, &[SpinMeasured { spin: true, axis: false }, no, yes]);
        assert_eq!((s.spin_rpm.n, s.spin_axis_deg.n), (1, 0));
    }

    #[test]
    fn trackman_club_names_map_to_presets() {
        assert_eq!(preset_for_club_name("8 Iron"), Some("iron8"));
        assert_eq!(preset_for_club_name("Pitching Wedge"), Some("pw"));
        assert_eq!(preset_for_club_name(" Driver "), Some("driver"));
        assert_eq!(preset_for_club_name("Putter"), None);
    }
}
