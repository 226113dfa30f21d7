//! A rigid ball: one sphere of the ball's mass and inertia (the contact laws of seed sections 3.2.2-3.2.3 act on
//! it directly).

use super::{rk4_mean, BallPart};
use crate::equipment::BallSpec;
use crate::math::{Real, Vector3};

/// A rigid sphere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBall {
    /// Mass (kg).
    pub mass_kg: Real,
    /// Radius (m).
    pub radius_m: Real,
    /// Moment of inertia about a diameter (kg m²).
    pub inertia_kg_m2: Real,
}

impl RigidBall {
    /// The ball's mass, radius and inertia.
    pub fn new(ball: &BallSpec) -> Self {
        RigidBall { mass_kg: ball.mass_kg, radius_m: ball.radius_m, inertia_kg_m2: ball.inertia_kg_m2 }
    }
}

/// Centre position and velocity and spin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBallState {
    /// Centre (m, world).
    pub centre_m: Vector3,
    /// Centre velocity (m/s, world).
    pub velocity_mps: Vector3,
    /// Angular velocity (rad/s, world).
    pub spin_radps: Vector3,
}

#[derive(Debug, Clone, Copy)]
pub struct RigidBallRate {
    velocity_mps: Vector3,
    accel_mps2: Vector3,
    angular_accel_radps2: Vector3,
}

impl BallPart for RigidBall {
    type State = RigidBallState;
    type Rate = RigidBallRate;

    fn mass_kg(&self) -> Real {
        self.mass_kg
    }

    fn radius_m(&self) -> Real {
        self.radius_m
    }

    fn at_rest(&self, centre_m: Vector3) -> RigidBallState {
        RigidBallState { centre_m, velocity_mps: Vector3::zeros(), spin_radps: Vector3::zeros() }
    }

    #[inline]
    fn centre(s: &RigidBallState) -> (Vector3, Vector3) {
        (s.centre_m, s.velocity_mps)
    }

    #[inline]
    fn surface_spin(s: &RigidBallState) -> Vector3 {
        s.spin_radps
    }

    fn spin(&self, s: &RigidBallState) -> Vector3 {
        s.spin_radps
    }

    #[inline]
    fn rate(&self, s: &RigidBallState, force_n: Vector3, r_m: Vector3) -> RigidBallRate {
        RigidBallRate {
            velocity_mps: s.velocity_mps,
            accel_mps2: force_n / self.mass_kg,
            angular_accel_radps2: r_m.cross(&force_n) / self.inertia_kg_m2,
        }
    }

    #[inline]
    fn advance(s: &RigidBallState, r: &RigidBallRate, h: Real) -> RigidBallState {
        RigidBallState {
            centre_m: s.centre_m + r.velocity_mps * h,
            velocity_mps: s.velocity_mps + r.accel_mps2 * h,
            spin_radps: s.spin_radps + r.angular_accel_radps2 * h,
        }
    }

    #[inline]
    fn advance_rk4(s: &RigidBallState, k: [&RigidBallRate; 4], h: Real) -> RigidBallState {
        let [k1, k2, k3, k4] = k;
        let mean = RigidBallRate {
            velocity_mps: rk4_mean(k1.velocity_mps, k2.velocity_mps, k3.velocity_mps, k4.velocity_mps),
            accel_mps2: rk4_mean(k1.accel_mps2, k2.accel_mps2, k3.accel_mps2, k4.accel_mps2),
            angular_accel_radps2: rk4_mean(
                k1.angular_accel_radps2,
                k2.angular_accel_radps2,
                k3.angular_accel_radps2,
                k4.angular_accel_radps2,
            ),
        };
        Self::advance(s, &mean, h)
    }

    fn momentum(&self, s: &RigidBallState) -> (Vector3, Vector3) {
        (
            self.mass_kg * s.velocity_mps,
            self.mass_kg * s.centre_m.cross(&s.velocity_mps) + self.inertia_kg_m2 * s.spin_radps,
        )
    }

    fn energy_j(&self, s: &RigidBallState) -> Real {
        0.5 * self.mass_kg * s.velocity_mps.norm_squared() + 0.5 * self.inertia_kg_m2 * s.spin_radps.norm_squared()
    }
}
