//! The two-layer ball (seed section 3.2.1, Table 3.5; McNally et al.): a core and a cover of uniform density
//! (cover thickness `t`) sharing translation; their relative rotation `θ` is resisted by a 3D rotary
//! spring-damper, torque `k_ball θ + c_ball (ω_cover − ω_core)`. The contact acts on the cover.

use super::{rk4_mean, BallPart};
use crate::equipment::BallSpec;
use crate::math::{Real, Vector3};

/// The two-layer ball's split of mass and inertia (uniform density) and its core-cover coupling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoLayerBall {
    /// Mass of the whole ball (kg).
    pub mass_kg: Real,
    /// Radius of the whole ball (m).
    pub radius_m: Real,
    /// The core's moment of inertia (kg m²).
    pub core_inertia_kg_m2: Real,
    /// The cover's moment of inertia (kg m²).
    pub cover_inertia_kg_m2: Real,
    /// Rotary spring between core and cover (N m/rad).
    pub k_ball_nm_per_rad: Real,
    /// Rotary damper between core and cover (N m s/rad).
    pub c_ball_nms_per_rad: Real,
}

impl TwoLayerBall {
    /// Core of radius `R − t` and cover shell, of one density, with the ball's total inertia split in proportion
    /// to `r⁵` (a uniform sphere's inertia is `(8/15) π ρ r⁵`); the total is the ball's given inertia.
    pub fn new(ball: &BallSpec, cover_thickness_m: Real, k_ball_nm_per_rad: Real, c_ball_nms_per_rad: Real) -> Self {
        let r_core = ball.radius_m - cover_thickness_m;
        let core_fraction = (r_core / ball.radius_m).powi(5);
        TwoLayerBall {
            mass_kg: ball.mass_kg,
            radius_m: ball.radius_m,
            core_inertia_kg_m2: ball.inertia_kg_m2 * core_fraction,
            cover_inertia_kg_m2: ball.inertia_kg_m2 * (1.0 - core_fraction),
            k_ball_nm_per_rad,
            c_ball_nms_per_rad,
        }
    }
}

/// Centre position and velocity, core and cover spins and their relative rotation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoLayerBallState {
    /// Centre (m, world).
    pub centre_m: Vector3,
    /// Centre velocity (m/s, world).
    pub velocity_mps: Vector3,
    /// The core's angular velocity (rad/s, world).
    pub core_spin_radps: Vector3,
    /// The cover's angular velocity (rad/s, world).
    pub cover_spin_radps: Vector3,
    /// The cover's rotation relative to the core (rotation vector, rad).
    pub cover_twist_rad: Vector3,
}

#[derive(Debug, Clone, Copy)]
pub struct TwoLayerBallRate {
    velocity_mps: Vector3,
    accel_mps2: Vector3,
    core_angular_accel_radps2: Vector3,
    cover_angular_accel_radps2: Vector3,
    twist_rate_radps: Vector3,
}

impl BallPart for TwoLayerBall {
    type State = TwoLayerBallState;
    type Rate = TwoLayerBallRate;

    fn mass_kg(&self) -> Real {
        self.mass_kg
    }

    fn radius_m(&self) -> Real {
        self.radius_m
    }

    fn at_rest(&self, centre_m: Vector3) -> TwoLayerBallState {
        TwoLayerBallState {
            centre_m,
            velocity_mps: Vector3::zeros(),
            core_spin_radps: Vector3::zeros(),
            cover_spin_radps: Vector3::zeros(),
            cover_twist_rad: Vector3::zeros(),
        }
    }

    #[inline]
    fn centre(s: &TwoLayerBallState) -> (Vector3, Vector3) {
        (s.centre_m, s.velocity_mps)
    }

    #[inline]
    fn surface_spin(s: &TwoLayerBallState) -> Vector3 {
        s.cover_spin_radps
    }

    fn spin(&self, s: &TwoLayerBallState) -> Vector3 {
        (self.core_inertia_kg_m2 * s.core_spin_radps + self.cover_inertia_kg_m2 * s.cover_spin_radps)
            / (self.core_inertia_kg_m2 + self.cover_inertia_kg_m2)
    }

    #[inline]
    fn rate(&self, s: &TwoLayerBallState, force_n: Vector3, r_m: Vector3) -> TwoLayerBallRate {
        let w_rel = s.cover_spin_radps - s.core_spin_radps;
        let spring = self.k_ball_nm_per_rad * s.cover_twist_rad + self.c_ball_nms_per_rad * w_rel;
        TwoLayerBallRate {
            velocity_mps: s.velocity_mps,
            accel_mps2: force_n / self.mass_kg,
            core_angular_accel_radps2: spring / self.core_inertia_kg_m2,
            cover_angular_accel_radps2: (r_m.cross(&force_n) - spring) / self.cover_inertia_kg_m2,
            twist_rate_radps: w_rel,
        }
    }

    #[inline]
    fn advance(s: &TwoLayerBallState, r: &TwoLayerBallRate, h: Real) -> TwoLayerBallState {
        TwoLayerBallState {
            centre_m: s.centre_m + r.velocity_mps * h,
            velocity_mps: s.velocity_mps + r.accel_mps2 * h,
            core_spin_radps: s.core_spin_radps + r.core_angular_accel_radps2 * h,
            cover_spin_radps: s.cover_spin_radps + r.cover_angular_accel_radps2 * h,
            cover_twist_rad: s.cover_twist_rad + r.twist_rate_radps * h,
        }
    }

    #[inline]
    fn advance_rk4(s: &TwoLayerBallState, k: [&TwoLayerBallRate; 4], h: Real) -> TwoLayerBallState {
        let [k1, k2, k3, k4] = k;
        let mean = TwoLayerBallRate {
            velocity_mps: rk4_mean(k1.velocity_mps, k2.velocity_mps, k3.velocity_mps, k4.velocity_mps),
            accel_mps2: rk4_mean(k1.accel_mps2, k2.accel_mps2, k3.accel_mps2, k4.accel_mps2),
            core_angular_accel_radps2: rk4_mean(
                k1.core_angular_accel_radps2,
                k2.core_angular_accel_radps2,
                k3.core_angular_accel_radps2,
                k4.core_angular_accel_radps2,
            ),
            cover_angular_accel_radps2: rk4_mean(
                k1.cover_angular_accel_radps2,
                k2.cover_angular_accel_radps2,
                k3.cover_angular_accel_radps2,
                k4.cover_angular_accel_radps2,
            ),
            twist_rate_radps: rk4_mean(
                k1.twist_rate_radps,
                k2.twist_rate_radps,
                k3.twist_rate_radps,
                k4.twist_rate_radps,
            ),
        };
        Self::advance(s, &mean, h)
    }

    #[inline]
    fn advance_rk4_scaled(s: &TwoLayerBallState, k: [&TwoLayerBallRate; 4], h: Real) -> TwoLayerBallState {
        let [k1, k2, k3, k4] = k;
        let c = |a: Vector3, b: Vector3, c: Vector3, d: Vector3| (a + 2.0 * b + 2.0 * c + d) * (h / 6.0);
        TwoLayerBallState {
            centre_m: s.centre_m + c(k1.velocity_mps, k2.velocity_mps, k3.velocity_mps, k4.velocity_mps),
            velocity_mps: s.velocity_mps + c(k1.accel_mps2, k2.accel_mps2, k3.accel_mps2, k4.accel_mps2),
            core_spin_radps: s.core_spin_radps
                + c(
                    k1.core_angular_accel_radps2,
                    k2.core_angular_accel_radps2,
                    k3.core_angular_accel_radps2,
                    k4.core_angular_accel_radps2,
                ),
            cover_spin_radps: s.cover_spin_radps
                + c(
                    k1.cover_angular_accel_radps2,
                    k2.cover_angular_accel_radps2,
                    k3.cover_angular_accel_radps2,
                    k4.cover_angular_accel_radps2,
                ),
            cover_twist_rad: s.cover_twist_rad
                + c(k1.twist_rate_radps, k2.twist_rate_radps, k3.twist_rate_radps, k4.twist_rate_radps),
        }
    }

    fn momentum(&self, s: &TwoLayerBallState) -> (Vector3, Vector3) {
        (
            self.mass_kg * s.velocity_mps,
            self.mass_kg * s.centre_m.cross(&s.velocity_mps)
                + self.core_inertia_kg_m2 * s.core_spin_radps
                + self.cover_inertia_kg_m2 * s.cover_spin_radps,
        )
    }

    fn energy_j(&self, s: &TwoLayerBallState) -> Real {
        0.5 * self.mass_kg * s.velocity_mps.norm_squared()
            + 0.5 * self.core_inertia_kg_m2 * s.core_spin_radps.norm_squared()
            + 0.5 * self.cover_inertia_kg_m2 * s.cover_spin_radps.norm_squared()
            + 0.5 * self.k_ball_nm_per_rad * s.cover_twist_rad.norm_squared()
    }
}
