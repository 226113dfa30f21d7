//! Launch conditions with TrackMan's definitions (ARCHITECTURE.md section 2).
//!
//! Launch angle (VLA) is the elevation of the ball velocity, up +; launch direction (HLA) its azimuth, right +.
//! Spin is split against the launch direction `u`: the horizontal axis `a = normalize(u x y)`, `up = a x u`;
//! `backspin = w . a`, `sidespin = -w . up` (+ = fade/slice, curves right), `spin_axis = atan2(sidespin,
//! backspin)` (+ = tilted right).

use crate::math::{Real, Vector3};
use crate::units::{mps_to_mph, radps_to_rpm};

/// TrackMan-style launch numbers.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct LaunchMetrics {
    /// Ball speed (m/s).
    pub ball_speed_mps: Real,
    /// Ball speed (mph).
    pub ball_speed_mph: Real,
    /// Launch angle above the horizontal (deg).
    pub launch_angle_deg: Real,
    /// Launch direction right (+) or left of the target line (deg).
    pub launch_direction_deg: Real,
    /// Backspin (rpm; negative: topspin).
    pub backspin_rpm: Real,
    /// Sidespin (rpm; + curves the ball right: fade or slice).
    pub sidespin_rpm: Real,
    /// Total spin (rpm).
    pub total_spin_rpm: Real,
    /// Spin axis tilt `atan2(sidespin, backspin)` (deg; + curves right).
    pub spin_axis_deg: Real,
}

impl LaunchMetrics {
    /// Launch numbers from the ball's velocity and spin (world frame).
    pub fn from_ball(velocity_mps: &Vector3, spin_radps: &Vector3) -> Self {
        let speed = velocity_mps.norm();
        let horizontal = velocity_mps.x.hypot(velocity_mps.z);
        let u = if speed > 0.0 { velocity_mps / speed } else { Vector3::x() };
        let a = u.cross(&Vector3::y());
        let a = if a.norm() > 1e-12 { a.normalize() } else { Vector3::z() };
        let up = a.cross(&u);
        let backspin = spin_radps.dot(&a);
        let sidespin = -spin_radps.dot(&up);
        LaunchMetrics {
            ball_speed_mps: speed,
            ball_speed_mph: mps_to_mph(speed),
            launch_angle_deg: velocity_mps.y.atan2(horizontal).to_degrees(),
            launch_direction_deg: velocity_mps.z.atan2(velocity_mps.x).to_degrees(),
            backspin_rpm: radps_to_rpm(backspin),
            sidespin_rpm: radps_to_rpm(sidespin),
            total_spin_rpm: radps_to_rpm(spin_radps.norm()),
            spin_axis_deg: sidespin.atan2(backspin).to_degrees(),
        }
    }

    /// The ball's spin vector (rad/s, world) for the given launch numbers: backspin about the horizontal axis,
    /// sidespin about the up axis; spin along the flight direction (rifle spin) is not represented.
    pub fn spin_vector_radps(&self) -> Vector3 {
        let (_, a, up) = self.axes();
        crate::units::rpm_to_radps(self.backspin_rpm) * a - crate::units::rpm_to_radps(self.sidespin_rpm) * up
    }

    /// The ball velocity (m/s, world).
    pub fn velocity_mps(&self) -> Vector3 {
        self.axes().0 * self.ball_speed_mps
    }

    fn axes(&self) -> (Vector3, Vector3, Vector3) {
        let (la, ld) = (self.launch_angle_deg.to_radians(), self.launch_direction_deg.to_radians());
        let u = Vector3::new(la.cos() * ld.cos(), la.sin(), la.cos() * ld.sin());
        let a = u.cross(&Vector3::y()).normalize();
        let up = a.cross(&u);
        (u, a, up)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pure backspin on a ball going straight: w = +z (top moving back toward the golfer).
    #[test]
    fn backspin_and_fade_signs() {
        let m = LaunchMetrics::from_ball(&Vector3::new(60.0, 10.0, 0.0), &Vector3::new(0.0, 0.0, 300.0));
        assert!(m.backspin_rpm > 0.0);
        assert!(m.sidespin_rpm.abs() < 1e-9);
        // Spin about -y (seen from above, clockwise) curves a ball going +x toward +z: fade, + sidespin.
        let m = LaunchMetrics::from_ball(&Vector3::new(60.0, 0.0, 0.0), &Vector3::new(0.0, -50.0, 300.0));
        assert!(m.sidespin_rpm > 0.0 && m.spin_axis_deg > 0.0);
        // Magnus force w x v points right (+z) for that spin.
        assert!(Vector3::new(0.0, -50.0, 0.0).cross(&Vector3::new(60.0, 0.0, 0.0)).z > 0.0);
    }

    #[test]
    fn metrics_round_trip_to_vectors() {
        let v = Vector3::new(70.0, 12.0, -3.0);
        let w = Vector3::new(0.0, 0.0, 250.0);
        let m = LaunchMetrics::from_ball(&v, &w);
        assert!((m.velocity_mps() - v).norm() < 1e-9);
        let w2 = m.spin_vector_radps();
        let m2 = LaunchMetrics::from_ball(&v, &w2);
        assert!((m2.backspin_rpm - m.backspin_rpm).abs() < 1e-9);
        assert!((m2.sidespin_rpm - m.sidespin_rpm).abs() < 1e-9);
    }
}
