//! The head on a flexible shaft (seed section 4.1, eq. 4.1-4.2) riding on the grip's undisturbed motion: a club
//! part for the assembly's multi-rate stepping ([`SteppedClub`]).
//!
//! The head's pose is the rigid club's undisturbed pose (the grip's constant twist, [`ConstantTwist`]) plus the
//! shaft's elastic offset ([`ModalClub::head_offset`]). The elastic motion is computed in the club's frame at the
//! start, which does not turn with the swing (a few tenths of a radian during the ground contact): the shaft's
//! modes are those of the club at its initial attitude. With that, the club's linear momentum is the rigid
//! club's plus the modes', and it changes exactly by the impulses of the ball, the ground and the grip (the
//! clamp's reaction plus the force the rigid swing needs), which the state carries.
//!
//! Stepping: the modes by exponential time differencing ([`ModalStepper`]: each mode's free motion exact, so the
//! step is not bounded by the stiffest mode) on classical Runge-Kutta's four stages, the impulses by Runge-Kutta's
//! quadrature of the same stages. The grip's impulse is the rigid swing's force by that quadrature plus the
//! clamp's reaction `K_cf ∫η + M_cf Δη̇` with each mode's `∫η` from its own equation.

use super::{ClubLoad, Head, SteppedClub};
use crate::impact::continuous::shaft::exponential::ModalStepper;
use crate::impact::continuous::shaft::grip::{ConstantTwist, PreparedTwist};
use crate::impact::continuous::shaft::modal::{ModalClub, ModalState, ModalVec};
use crate::math::{Real, Rotation3, Vector3};

/// The club on its shaft, fixed during a run.
#[derive(Debug, Clone)]
pub struct ShaftClub<'a> {
    /// The flexible club's modes (seed section 4.1, eq. 4.1-4.2).
    pub modal: &'a ModalClub,
    /// The grip's drive: the rigid club's undisturbed motion.
    pub motion: ConstantTwist,
    /// `motion` prepared for its evaluations ([`ConstantTwist::prepared`]).
    pub twist: PreparedTwist,
    /// The club frame at the start (world from club), in which the elastic motion is computed.
    pub elastic_frame: Rotation3,
    /// The head's mass (kg).
    pub head_mass_kg: Real,
    /// The shaft's mass (kg).
    pub shaft_mass_kg: Real,
    /// The undeformed shaft's CG, club frame (m).
    pub shaft_cg_m: Vector3,
}

/// The shaft's modes and the impulses on the club (N s, world) from the ball, the ground and the grip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShaftClubState {
    /// The shaft's modal coordinates and velocities.
    pub shaft: ModalState,
    /// The ball's impulse on the club so far (N s, world).
    pub j_ball_n_s: Vector3,
    /// The ground's impulse on the club so far (N s, world).
    pub j_ground_n_s: Vector3,
    /// The grip's impulse on the club so far (N s, world).
    pub j_grip_n_s: Vector3,
}

impl Default for ShaftClubState {
    fn default() -> Self {
        let zero = Vector3::zeros();
        ShaftClubState { shaft: ModalState::default(), j_ball_n_s: zero, j_ground_n_s: zero, j_grip_n_s: zero }
    }
}

/// The modal loads and the forces on the club the impulses integrate.
#[derive(Debug, Clone, Copy)]
pub struct ShaftClubRate {
    /// The modal loads `Φ_tipᵀ f_tip` ([`ModalClub::load`]).
    pub modal_load: ModalVec,
    /// Forces on the club (world); at the grip, the force the rigid swing needs (the clamp's elastic reaction is
    /// integrated per step).
    pub f_ball_n: Vector3,
    /// The ground's force on the head (N, world).
    pub f_ground_n: Vector3,
    /// The force at the grip the rigid swing needs (N, world).
    pub f_grip_rigid_n: Vector3,
}

/// The head's motion and the rigid club's it rides on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShaftMotion {
    /// The head, the shaft's deflection included.
    pub head: Head,
    /// The rigid club's head on the undisturbed swing.
    pub rigid: Head,
}

impl ShaftClub<'_> {
    /// The rigid swing's club momentum (N s, world) and the grip force it needs (N).
    fn rigid_momentum_and_force(&self, rigid: &Head) -> (Vector3, Vector3) {
        let (w, v) = (rigid.angular_velocity_radps, rigid.velocity_mps);
        let r = rigid.world_from_club * self.shaft_cg_m;
        let m = self.head_mass_kg + self.shaft_mass_kg;
        (m * v + self.shaft_mass_kg * w.cross(&r), m * w.cross(&v) + self.shaft_mass_kg * w.cross(&w.cross(&r)))
    }

    /// The club's linear momentum (N s, world) in state `s` at `t_s`.
    pub fn momentum_n_s(&self, s: &ShaftClubState, t_s: Real) -> Vector3 {
        let rigid = self.motion(s, t_s).rigid;
        self.rigid_momentum_and_force(&rigid).0 + self.elastic_frame * self.modal.momentum(&s.shaft)
    }

    /// The head of the undisturbed swing at `t_s`: the shaft at rest.
    pub fn undisturbed_head(&self, s: &ShaftClubState, t_s: Real) -> Head {
        self.motion(&ShaftClubState { shaft: ModalState::default(), ..*s }, t_s).head
    }

    /// `s` with its modes `shaft` (a stage: the impulses are integrated over the whole step only).
    fn with_shaft(s: &ShaftClubState, shaft: ModalState) -> ShaftClubState {
        ShaftClubState { shaft, ..*s }
    }
}

impl SteppedClub for ShaftClub<'_> {
    type State = ShaftClubState;
    type Rate = ShaftClubRate;
    type Motion = ShaftMotion;
    type Step = ModalStepper;
    type Half = ModalState;

    fn step(&self, h_s: Real) -> ModalStepper {
        ModalStepper::new(self.modal, h_s)
    }

    #[inline]
    fn step_s(step: &ModalStepper) -> Real {
        step.h_s
    }

    #[inline]
    fn motion(&self, s: &ShaftClubState, t_s: Real) -> ShaftMotion {
        let (rotation, position_m, velocity_mps) = self.twist.at(t_s);
        let rigid = Head {
            position_m,
            world_from_club: rotation,
            velocity_mps,
            angular_velocity_radps: self.motion.angular_velocity_radps,
        };
        let o = self.modal.head_offset(&s.shaft);
        let f = &self.elastic_frame;
        let head = Head {
            position_m: rigid.position_m + f * o.cg_m,
            world_from_club: crate::math::small_rotation(&(f * o.rotation_rad)) * rigid.world_from_club,
            velocity_mps: rigid.velocity_mps + f * o.cg_velocity_mps,
            angular_velocity_radps: rigid.angular_velocity_radps + f * o.angular_velocity_radps,
        };
        ShaftMotion { head, rigid }
    }

    #[inline]
    fn head(m: &ShaftMotion) -> Head {
        m.head
    }

    #[inline]
    fn rate(&self, _: &ShaftClubState, m: &ShaftMotion, load: &ClubLoad) -> ShaftClubRate {
        let force = load.ground_force_n + load.ball_force_n;
        let torque = load.ground_torque_nm + load.ball_lever_m.cross(&load.ball_force_n);
        let fi = self.elastic_frame.inverse();
        ShaftClubRate {
            modal_load: self.modal.load(&(fi * force), &(fi * torque)),
            f_ball_n: load.ball_force_n,
            f_ground_n: load.ground_force_n,
            f_grip_rigid_n: self.rigid_momentum_and_force(&m.rigid).1,
        }
    }

    #[inline]
    fn free_half(&self, step: &ModalStepper, s: &ShaftClubState) -> ModalState {
        step.free_half(&s.shaft)
    }

    #[inline]
    fn half(&self, step: &ModalStepper, s: &ShaftClubState, free: &ModalState, k: &ShaftClubRate) -> ShaftClubState {
        Self::with_shaft(s, step.add_half_load(free, &k.modal_load))
    }

    #[inline]
    fn fourth(
        &self,
        step: &ModalStepper,
        s: &ShaftClubState,
        s2: &ShaftClubState,
        k1: &ShaftClubRate,
        k3: &ShaftClubRate,
    ) -> ShaftClubState {
        Self::with_shaft(s, step.third(&s2.shaft, &k1.modal_load, &k3.modal_load))
    }

    fn finish(&self, step: &ModalStepper, s: &ShaftClubState, k: [&ShaftClubRate; 4]) -> ShaftClubState {
        let h = step.h_s;
        let [r1, r2, r3, r4] = k;
        let c = |a: Vector3, b: Vector3, c: Vector3, d: Vector3| (a + 2.0 * b + 2.0 * c + d) * (h / 6.0);
        let loads = [&r1.modal_load, &r2.modal_load, &r3.modal_load, &r4.modal_load];
        let shaft = step.finish(&s.shaft, loads);
        let eta_integral = step.eta_integral(&s.shaft, &shaft, loads);
        let clamp = self.modal.grip_force(
            &ModalState { eta: eta_integral, eta_dot: ModalVec::zeros() },
            &(shaft.eta_dot - s.shaft.eta_dot),
        );
        ShaftClubState {
            shaft,
            j_ball_n_s: s.j_ball_n_s + c(r1.f_ball_n, r2.f_ball_n, r3.f_ball_n, r4.f_ball_n),
            j_ground_n_s: s.j_ground_n_s + c(r1.f_ground_n, r2.f_ground_n, r3.f_ground_n, r4.f_ground_n),
            j_grip_n_s: s.j_grip_n_s
                + (c(r1.f_grip_rigid_n, r2.f_grip_rigid_n, r3.f_grip_rigid_n, r4.f_grip_rigid_n)
                    + self.elastic_frame * clamp),
        }
    }
}
