//! The five launch fields a measured shot is compared on (seed eq. 3.13: ball speed, launch angle, launch
//! direction, backspin, sidespin), as an array in that order, from each message that carries them.

use crate::impact::LaunchMetrics;
use crate::math::Real;
use crate::wire::{LaunchFields, MeasuredLaunch};

/// The five launch fields of eq. 3.13 (wire name, the seed's table label).
pub const FIELDS: [(&str, &str); 5] = [
    ("ball_speed_mph", "Speed (mph)"),
    ("launch_angle_deg", "Launch (deg)"),
    ("launch_direction_deg", "Azimuth (deg)"),
    ("backspin_rpm", "Backspin (rpm)"),
    ("sidespin_rpm", "Sidespin (rpm)"),
];

/// The five compared fields of a launch, in the order of eq. 3.13 (ball speed, launch angle, launch direction, backspin, sidespin).
pub fn fields_of(m: &LaunchMetrics) -> [Real; 5] {
    [m.ball_speed_mph, m.launch_angle_deg, m.launch_direction_deg, m.backspin_rpm, m.sidespin_rpm]
}

/// The five compared fields of [`LaunchFields`].
pub fn fields_of_launch(f: &LaunchFields) -> [Real; 5] {
    [f.ball_speed_mph, f.launch_angle_deg, f.launch_direction_deg, f.backspin_rpm, f.sidespin_rpm]
}

/// [`LaunchFields`] from the five fields (no carry).
pub fn launch_fields(x: &[Real; 5]) -> LaunchFields {
    LaunchFields {
        ball_speed_mph: x[0],
        launch_angle_deg: x[1],
        launch_direction_deg: x[2],
        backspin_rpm: x[3],
        sidespin_rpm: x[4],
        carry_yd: None,
    }
}

/// The five fields of a measured launch (spin from backspin and sidespin, or total spin and axis).
pub fn fields_of_measured(m: &MeasuredLaunch) -> Option<[Real; 5]> {
    let (back, side) = m.spin_components_rpm()?;
    Some([m.ball_speed_mph, m.launch_angle_deg, m.launch_direction_deg, back, side])
}
