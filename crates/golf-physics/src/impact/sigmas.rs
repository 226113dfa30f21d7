//! How sure a prediction is, as published: one-sigma standard deviations under the delivery's and the launch's
//! own field names (computed by `impact::uncertainty`).

use crate::math::Real;

/// One-sigma standard deviations of a delivery's numbers, under the delivery's own field names.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct DeliveryUncertainty {
    /// Club speed (mph).
    pub club_speed_mph: Real,
    /// Attack angle (deg).
    pub attack_angle_deg: Real,
    /// Club path (deg).
    pub club_path_deg: Real,
    /// Face angle (deg).
    pub face_angle_deg: Real,
    /// Dynamic loft (deg).
    pub dynamic_loft_deg: Real,
    /// Face to path (deg).
    pub face_to_path_deg: Real,
    /// Impact location across the face (mm).
    pub impact_h_mm: Real,
    /// Impact location up the face (mm).
    pub impact_v_mm: Real,
}

/// One-sigma standard deviations of a launch's numbers, under the launch's own field names.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct LaunchUncertainty {
    /// Ball speed (mph).
    pub ball_speed_mph: Real,
    /// Launch angle (deg).
    pub launch_angle_deg: Real,
    /// Launch direction (deg).
    pub launch_direction_deg: Real,
    /// Total spin (rpm).
    pub total_spin_rpm: Real,
    /// Spin axis (deg).
    pub spin_axis_deg: Real,
}
