//! A free rigid clubhead: Newton-Euler in its body frame with a unit-quaternion attitude.

use super::{ClubLoad, ClubPart, Head, SteppedClub};
use crate::equipment::ClubSpec;
use crate::impact::ImpactState;
use crate::math::{Matrix3, Real, UnitQuaternion, Vector3};

/// A free 6-DOF head of the club's mass and inertia.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeHead {
    /// The head's mass (kg).
    pub mass_kg: Real,
    /// Inertia about the CG, club frame, and its inverse.
    pub inertia_kg_m2: Matrix3,
    /// See `inertia_kg_m2` (1/(kg m²)).
    pub inertia_inv_kg_m2: Matrix3,
}

impl FreeHead {
    /// The club's head mass and inertia.
    pub fn new(club: &ClubSpec) -> Self {
        FreeHead { mass_kg: club.mass_kg, inertia_kg_m2: club.inertia_kg_m2, inertia_inv_kg_m2: club.inertia_inv_kg_m2 }
    }
}

/// Position, velocity, attitude and body rate of the head.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeHeadState {
    /// CG position (m, world).
    pub cg_m: Vector3,
    /// CG velocity (m/s, world).
    pub velocity_mps: Vector3,
    /// Attitude: the club frame in the world.
    pub world_from_body: UnitQuaternion,
    /// Angular velocity in the club frame (rad/s).
    pub body_rate_radps: Vector3,
}

#[derive(Debug, Clone, Copy)]
pub struct FreeHeadRate {
    velocity_mps: Vector3,
    accel_mps2: Vector3,
    attitude_rate_per_s: crate::math::Quaternion,
    body_angular_accel_radps2: Vector3,
}

impl ClubPart for FreeHead {
    type State = FreeHeadState;
    type Rate = FreeHeadRate;

    fn initial(&self, state: &ImpactState) -> FreeHeadState {
        let rot = state.world_from_club.rotation;
        FreeHeadState {
            cg_m: state.world_from_club.translation.vector,
            velocity_mps: state.cg_velocity_mps,
            world_from_body: rot,
            body_rate_radps: rot.inverse_transform_vector(&state.angular_velocity_radps),
        }
    }

    #[inline]
    fn head(&self, s: &FreeHeadState) -> Head {
        let world_from_club = s.world_from_body.to_rotation_matrix();
        Head {
            position_m: s.cg_m,
            angular_velocity_radps: world_from_club * s.body_rate_radps,
            world_from_club,
            velocity_mps: s.velocity_mps,
        }
    }

    #[inline(always)]
    fn rate(&self, s: &FreeHeadState, head: &Head, force_n: Vector3, torque_nm: Vector3) -> FreeHeadRate {
        let torque_body = head.world_from_club.inverse_transform_vector(&torque_nm);
        let w = s.body_rate_radps;
        FreeHeadRate {
            velocity_mps: s.velocity_mps,
            accel_mps2: force_n / self.mass_kg,
            attitude_rate_per_s: s.world_from_body.quaternion() * crate::math::Quaternion::from_imag(w) * 0.5,
            body_angular_accel_radps2: self.inertia_inv_kg_m2 * (torque_body - w.cross(&(self.inertia_kg_m2 * w))),
        }
    }

    #[inline]
    fn advance(s: &FreeHeadState, r: &FreeHeadRate, h: Real) -> FreeHeadState {
        FreeHeadState {
            cg_m: s.cg_m + r.velocity_mps * h,
            velocity_mps: s.velocity_mps + r.accel_mps2 * h,
            world_from_body: UnitQuaternion::new_unchecked(s.world_from_body.quaternion() + r.attitude_rate_per_s * h),
            body_rate_radps: s.body_rate_radps + r.body_angular_accel_radps2 * h,
        }
    }

    #[inline]
    fn advance_rk4(s: &FreeHeadState, k: [&FreeHeadRate; 4], h: Real) -> FreeHeadState {
        let c = |a: Vector3, b: Vector3, c: Vector3, d: Vector3| (a + 2.0 * b + 2.0 * c + d) / 6.0;
        let [k1, k2, k3, k4] = k;
        let mean = FreeHeadRate {
            velocity_mps: c(k1.velocity_mps, k2.velocity_mps, k3.velocity_mps, k4.velocity_mps),
            accel_mps2: c(k1.accel_mps2, k2.accel_mps2, k3.accel_mps2, k4.accel_mps2),
            attitude_rate_per_s: (k1.attitude_rate_per_s
                + k2.attitude_rate_per_s * 2.0
                + k3.attitude_rate_per_s * 2.0
                + k4.attitude_rate_per_s)
                / 6.0,
            body_angular_accel_radps2: c(
                k1.body_angular_accel_radps2,
                k2.body_angular_accel_radps2,
                k3.body_angular_accel_radps2,
                k4.body_angular_accel_radps2,
            ),
        };
        let mut next = Self::advance(s, &mean, h);
        next.world_from_body = UnitQuaternion::new_normalize(next.world_from_body.into_inner());
        next
    }

    fn momentum(&self, s: &FreeHeadState) -> (Vector3, Vector3) {
        let rot = s.world_from_body.to_rotation_matrix();
        (
            self.mass_kg * s.velocity_mps,
            self.mass_kg * s.cg_m.cross(&s.velocity_mps) + rot * (self.inertia_kg_m2 * s.body_rate_radps),
        )
    }

    fn energy_j(&self, s: &FreeHeadState) -> Real {
        0.5 * self.mass_kg * s.velocity_mps.norm_squared()
            + 0.5 * s.body_rate_radps.dot(&(self.inertia_kg_m2 * s.body_rate_radps))
    }
}

/// The free head on the multi-rate stepping: classical Runge-Kutta's own stages (a step needs only its size).
impl SteppedClub for FreeHead {
    type State = FreeHeadState;
    type Rate = FreeHeadRate;
    type Motion = Head;
    type Step = Real;
    type Half = ();

    fn step(&self, h_s: Real) -> Real {
        h_s
    }

    #[inline]
    fn step_s(step: &Real) -> Real {
        *step
    }

    #[inline]
    fn motion(&self, s: &FreeHeadState, _t_s: Real) -> Head {
        ClubPart::head(self, s)
    }

    #[inline]
    fn head(m: &Head) -> Head {
        *m
    }

    #[inline(always)]
    fn rate(&self, s: &FreeHeadState, m: &Head, load: &ClubLoad) -> FreeHeadRate {
        let force_n = load.ground_force_n + load.ball_force_n;
        let torque_nm = load.ground_torque_nm + load.ball_lever_m.cross(&load.ball_force_n);
        ClubPart::rate(self, s, m, force_n, torque_nm)
    }

    fn free_half(&self, _: &Real, _: &FreeHeadState) {}

    #[inline]
    fn half(&self, step: &Real, s: &FreeHeadState, _: &(), k: &FreeHeadRate) -> FreeHeadState {
        <Self as ClubPart>::advance(s, k, 0.5 * step)
    }

    #[inline]
    fn fourth(
        &self,
        step: &Real,
        s: &FreeHeadState,
        _: &FreeHeadState,
        _: &FreeHeadRate,
        k3: &FreeHeadRate,
    ) -> FreeHeadState {
        <Self as ClubPart>::advance(s, k3, *step)
    }

    fn finish(&self, step: &Real, s: &FreeHeadState, k: [&FreeHeadRate; 4]) -> FreeHeadState {
        <Self as ClubPart>::advance_rk4(s, k, *step)
    }
}
