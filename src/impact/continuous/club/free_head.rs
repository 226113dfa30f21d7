//! A free rigid clubhead: Newton-Euler in its body frame with a unit-quaternion attitude.

use super::{ClubLoad, ClubPart, Head, SteppedClub};
use crate::equipment::ClubSpec;
use crate::impact::ImpactState;
use crate::math::{Matrix3, Real, UnitQuaternion, Vector3};

/// A free 6-DOF head of the club's mass and inertia.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeHead {
    pub mass_kg: Real,
    /// Inertia about the CG, club frame, and its inverse.
    pub inertia_kg_m2: Matrix3,
    pub inertia_inv_kg_m2: Matrix3,
}

impl FreeHead {
    pub fn new(club: &ClubSpec) -> Self {
        FreeHead { mass_kg: club.mass_kg, inertia_kg_m2: club.inertia_kg_m2, inertia_inv_kg_m2: club.inertia_inv_kg_m2 }
    }
}

/// Position, velocity, attitude and body rate of the head.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeHeadState {
    pub p: Vector3,
    pub v: Vector3,
    pub q: UnitQuaternion,
    pub w_body: Vector3,
}

#[derive(Debug, Clone, Copy)]
pub struct FreeHeadRate {
    v: Vector3,
    a: Vector3,
    q_dot: crate::math::Quaternion,
    alpha_body: Vector3,
}

impl ClubPart for FreeHead {
    type State = FreeHeadState;
    type Rate = FreeHeadRate;

    fn initial(&self, state: &ImpactState) -> FreeHeadState {
        let rot = state.world_from_club.rotation;
        FreeHeadState {
            p: state.world_from_club.translation.vector,
            v: state.cg_velocity_mps,
            q: rot,
            w_body: rot.inverse_transform_vector(&state.angular_velocity_radps),
        }
    }

    #[inline]
    fn head(&self, s: &FreeHeadState) -> Head {
        let world_from_club = s.q.to_rotation_matrix();
        Head { position_m: s.p, angular_velocity_radps: world_from_club * s.w_body, world_from_club, velocity_mps: s.v }
    }

    #[inline]
    fn rate(&self, s: &FreeHeadState, head: &Head, force_n: Vector3, torque_nm: Vector3) -> FreeHeadRate {
        let torque_body = head.world_from_club.inverse_transform_vector(&torque_nm);
        let w = s.w_body;
        FreeHeadRate {
            v: s.v,
            a: force_n / self.mass_kg,
            q_dot: s.q.quaternion() * crate::math::Quaternion::from_imag(w) * 0.5,
            alpha_body: self.inertia_inv_kg_m2 * (torque_body - w.cross(&(self.inertia_kg_m2 * w))),
        }
    }

    #[inline]
    fn advance(s: &FreeHeadState, r: &FreeHeadRate, h: Real) -> FreeHeadState {
        FreeHeadState {
            p: s.p + r.v * h,
            v: s.v + r.a * h,
            q: UnitQuaternion::new_unchecked(s.q.quaternion() + r.q_dot * h),
            w_body: s.w_body + r.alpha_body * h,
        }
    }

    #[inline]
    fn advance_rk4(s: &FreeHeadState, k: [&FreeHeadRate; 4], h: Real) -> FreeHeadState {
        let c = |a: Vector3, b: Vector3, c: Vector3, d: Vector3| (a + 2.0 * b + 2.0 * c + d) / 6.0;
        let [k1, k2, k3, k4] = k;
        let mean = FreeHeadRate {
            v: c(k1.v, k2.v, k3.v, k4.v),
            a: c(k1.a, k2.a, k3.a, k4.a),
            q_dot: (k1.q_dot + k2.q_dot * 2.0 + k3.q_dot * 2.0 + k4.q_dot) / 6.0,
            alpha_body: c(k1.alpha_body, k2.alpha_body, k3.alpha_body, k4.alpha_body),
        };
        let mut next = Self::advance(s, &mean, h);
        next.q = UnitQuaternion::new_normalize(next.q.into_inner());
        next
    }

    fn momentum(&self, s: &FreeHeadState) -> (Vector3, Vector3) {
        let rot = s.q.to_rotation_matrix();
        (self.mass_kg * s.v, self.mass_kg * s.p.cross(&s.v) + rot * (self.inertia_kg_m2 * s.w_body))
    }

    fn energy_j(&self, s: &FreeHeadState) -> Real {
        0.5 * self.mass_kg * s.v.norm_squared() + 0.5 * s.w_body.dot(&(self.inertia_kg_m2 * s.w_body))
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

    #[inline]
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
