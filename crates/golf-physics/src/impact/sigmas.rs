//! How sure a prediction is, as published: one-sigma standard deviations under the delivery's and the launch's
//! own field names (computed by `impact::uncertainty`).

use crate::math::Real;

/// One-sigma standard deviations of a delivery's numbers, under the delivery's own field names.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct DeliveryUncertainty {
    pub club_speed_mph: Real,
    pub attack_angle_deg: Real,
    pub club_path_deg: Real,
    pub face_angle_deg: Real,
    pub dynamic_loft_deg: Real,
    pub face_to_path_deg: Real,
    pub impact_h_mm: Real,
    pub impact_v_mm: Real,
}

/// One-sigma standard deviations of a launch's numbers, under the launch's own field names.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct LaunchUncertainty {
    pub ball_speed_mph: Real,
    pub launch_angle_deg: Real,
    pub launch_direction_deg: Real,
    pub total_spin_rpm: Real,
    pub spin_axis_deg: Real,
}
