//! Measured launches from a launch monitor and their comparison with predictions.
//!
//! A [`MeasuredLaunch`] arrives on `lm/<rig>/launch` (from any publisher, or from the Open Connect listener); a
//! [`ComparisonMessage`] pairs it with the rig's prediction of the same swing on `golf/<rig>/comparison`. Signs are
//! TrackMan's, as everywhere on the wire (ARCHITECTURE.md section 2): launch direction (HLA) right +, sidespin + = fade,
//! spin axis + = tilted right.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::math::Real;

/// Club data a launch monitor may report beside the ball (every field optional).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MeasuredClubData {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub club_speed_mph: Option<Real>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub attack_angle_deg: Option<Real>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub club_path_deg: Option<Real>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub face_angle_deg: Option<Real>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dynamic_loft_deg: Option<Real>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub impact_h_mm: Option<Real>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub impact_v_mm: Option<Real>,
}

/// A launch as a launch monitor measured it, on `lm/<rig>/launch`. The spin is given either as backspin and
/// sidespin or as total spin and spin axis (both may be present; backspin and sidespin win).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MeasuredLaunch {
    pub rig: String,
    /// When the shot was measured (ns since the Unix epoch, the receiving host's clock).
    pub t_ns: u64,
    /// The device or connector that measured it (`"GC3"`, `"open_connect:Trackman"`, ...).
    pub device: String,
    /// The device's own shot number, when it gives one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shot_number: Option<u64>,
    pub ball_speed_mph: Real,
    /// Vertical launch angle (VLA), up +.
    pub launch_angle_deg: Real,
    /// Horizontal launch angle (HLA), right +.
    pub launch_direction_deg: Real,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub backspin_rpm: Option<Real>,
    /// + = fade/slice (curves right).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sidespin_rpm: Option<Real>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub total_spin_rpm: Option<Real>,
    /// + = tilted right (fade).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spin_axis_deg: Option<Real>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub carry_yd: Option<Real>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub club: Option<MeasuredClubData>,
}

impl MeasuredLaunch {
    /// Backspin and sidespin (rpm): given directly, or from total spin and spin axis
    /// (`back = total cos(axis)`, `side = total sin(axis)`). `None` when neither pair is complete.
    pub fn spin_components_rpm(&self) -> Option<(Real, Real)> {
        match (self.backspin_rpm, self.sidespin_rpm, self.total_spin_rpm, self.spin_axis_deg) {
            (Some(back), Some(side), _, _) => Some((back, side)),
            (_, _, Some(total), Some(axis)) => {
                let a = axis.to_radians();
                Some((total * a.cos(), total * a.sin()))
            }
            _ => None,
        }
    }
}

/// The launch numbers compared field by field (the seed's Tables 3.2-3.7 fields, plus carry when both have it).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct LaunchFields {
    pub ball_speed_mph: Real,
    pub launch_angle_deg: Real,
    pub launch_direction_deg: Real,
    pub backspin_rpm: Real,
    pub sidespin_rpm: Real,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub carry_yd: Option<Real>,
}

/// What a launch monitor can measure, per field of [`LaunchFields`]: (field, lowest, highest). The Open Connect
/// listener takes the same bounds.
pub const MEASURABLE: [(&str, Real, Real); 6] = [
    ("ball_speed_mph", 0.1, 300.0),
    ("launch_angle_deg", -90.0, 90.0),
    ("launch_direction_deg", -90.0, 90.0),
    ("backspin_rpm", -30_000.0, 30_000.0),
    ("sidespin_rpm", -30_000.0, 30_000.0),
    ("carry_yd", 0.0, 600.0),
];

impl LaunchFields {
    /// Refuses a value no launch monitor measures (not finite, a negative or absurd speed, ...), naming the
    /// field, its value and the bounds.
    pub fn check_measurable(&self) -> Result<(), String> {
        let values = [
            Some(self.ball_speed_mph),
            Some(self.launch_angle_deg),
            Some(self.launch_direction_deg),
            Some(self.backspin_rpm),
            Some(self.sidespin_rpm),
            self.carry_yd,
        ];
        for ((name, lo, hi), v) in MEASURABLE.iter().zip(values) {
            match v {
                Some(v) if !(v.is_finite() && (*lo..=*hi).contains(&v)) => {
                    return Err(format!("measured.{name} = {v} is not what a launch monitor measures ({lo} to {hi})"))
                }
                _ => {}
            }
        }
        Ok(())
    }
}

/// A prediction paired with its measurement, on `golf/<rig>/comparison`: `residual = predicted - measured`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ComparisonMessage {
    pub rig: String,
    /// The prediction's shot number and model.
    pub shot: u64,
    #[serde(deserialize_with = "super::model_name::one")]
    pub model: String,
    pub t_impact_ns: u64,
    /// The measurement's time and device.
    pub measured_t_ns: u64,
    pub device: String,
    pub predicted: LaunchFields,
    pub measured: LaunchFields,
    pub residual: LaunchFields,
    /// Seconds from impact to the measurement (`(measured_t_ns - t_impact_ns) / 1e9`).
    #[serde(default)]
    pub delay_s: Real,
    /// Time from the later of the pair arriving to this comparison being published (us), measured live.
    #[serde(default)]
    pub latency_us: Real,
}

/// The pairing's health in a rig's status: how many shots were paired, how many found no partner, and the
/// running mean absolute error per field of each model.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ComparisonStatus {
    /// Measured launches received (good or bad).
    pub measured: u64,
    /// Measured launches that could not be used (not JSON, wrong rig, no spin), by reason.
    pub rejected: std::collections::BTreeMap<String, u64>,
    /// Shots paired with a measurement.
    pub paired: u64,
    /// Predicted shots no measurement arrived for within the window.
    pub unpaired_predictions: u64,
    /// Measurements no prediction matched within the window.
    pub unpaired_measured: u64,
    /// Running mean absolute error per field, per model (over every paired shot since start).
    #[serde(deserialize_with = "super::model_name::keys")]
    pub mae: std::collections::BTreeMap<String, LaunchFields>,
}
