//! The one 7-iron swing the seed's findings over the face are measured on (seed section 4.3: "the same swing
//! kinematics were used for all shots"): 90 mph at the face centre, 4.3° down, square path and face, 25° dynamic
//! loft (TrackMan's 7-iron averages), the club turning at 27 rad/s (club speed over a 1.5 m swing radius) about
//! the normal of a 60° swing plane. docs/ground.md, research/ground-parts.md and the ground tests use it.

use crate::impact::Delivery;
use crate::math::{Real, Vector3};
use crate::units::MPS_PER_MPH;

/// The reference swing struck `h_mm` toward the toe and `v_mm` up the face from its centre.
pub fn reference_swing(h_mm: Real, v_mm: Real) -> Delivery {
    let plane = 60f64.to_radians();
    Delivery {
        club_speed_mps: 90.0 * MPS_PER_MPH,
        attack_angle_rad: (-4.3f64).to_radians(),
        club_path_rad: 0.0,
        face_angle_rad: 0.0,
        dynamic_loft_rad: 25f64.to_radians(),
        impact_h_m: h_mm * 1e-3,
        impact_v_m: v_mm * 1e-3,
        club_angular_velocity_radps: 27.0 * Vector3::new(0.0, plane.cos(), plane.sin()),
    }
}
