//! The iron-plus-ground system's equations of motion: the two-layer ball (seed 3.2.1, eq. 3.14-3.15, reused as
//! is), the head on the flexible shaft (section 4.1) riding on the grip's undisturbed motion, and the ground's
//! forces on the head (section 4.2, eq. 4.3-4.13).
//!
//! The head's pose is the rigid club's undisturbed pose (the grip's constant twist) plus the shaft's elastic
//! offset. The elastic motion is computed in the club's frame at the start, which does not turn with the swing
//! (a few tenths of a radian during the ground contact): the shaft's modes are those of the club at its initial
//! attitude. With that, the club's linear momentum is the rigid club's plus the modes', and it changes exactly
//! by the impulses of the ball, the ground and the grip (the clamp's reaction plus the force the rigid swing
//! needs).
//!
//! Stepping: the shaft's modes by exponential time differencing ([`ModalStepper`]: each mode's free motion
//! exact, so the step is not bounded by the stiffest mode), the ball and the impulses by classical Runge-Kutta
//! on the same four stages. The grip's impulse is the rigid swing's force by Runge-Kutta's quadrature plus the
//! clamp's reaction `K_cf ∫η + M_cf Δη̇` with each mode's `∫η` from its own equation.

use crate::impact::continuous::ball::TwoLayerBall;
use crate::impact::continuous::club::Head as BodyMotion;
use crate::impact::continuous::ground::{GroundForces, SoilGround};
use crate::impact::continuous::law::volumetric::Volumetric;
use crate::impact::continuous::law::{Contact, ContactForce, ContactLaw};
use crate::impact::continuous::shaft::exponential::ModalStepper;
use crate::impact::continuous::shaft::grip::{ConstantTwist, PreparedTwist};
use crate::impact::continuous::shaft::modal::{ModalClub, ModalState, ModalVec};
use crate::impact::continuous::surface::FaceSurface;
use crate::impact::continuous::{ContactForces, TwoLayerParams};
use crate::math::{Real, Rotation3, Vector3};

/// The integrated state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    /// Time from the ball's first contact on the undisturbed swing (s).
    pub t_s: Real,
    pub shaft: ModalState,
    pub p_b_m: Vector3,
    pub v_b_mps: Vector3,
    pub w_core_radps: Vector3,
    pub w_cover_radps: Vector3,
    pub theta_rad: Vector3,
    /// Impulses on the club (N s, world): from the ball, the ground and the grip.
    pub j_ball_ns: Vector3,
    pub j_ground_ns: Vector3,
    pub j_grip_ns: Vector3,
}

/// Time derivatives.
#[derive(Debug, Clone, Copy)]
pub struct Rates {
    /// The modal loads `Φ_tipᵀ f_tip` ([`ModalClub::load`]).
    pub modal_load: ModalVec,
    pub a_b: Vector3,
    pub alpha_core: Vector3,
    pub alpha_cover: Vector3,
    /// Forces on the club (world); at the grip, the force the rigid swing needs (the clamp's elastic reaction is
    /// integrated per step).
    pub f_ball: Vector3,
    pub f_ground: Vector3,
    pub f_grip_rigid: Vector3,
}

/// One evaluation: the rates and what acted.
#[derive(Debug, Clone, Copy)]
pub struct Eval {
    pub rates: Rates,
    pub ball: Option<ContactForces>,
    pub ground: GroundForces,
    pub head: BodyMotion,
}

/// Everything fixed during a run.
pub struct System<'a> {
    pub params: TwoLayerParams,
    pub ball: TwoLayerBall,
    pub surface: FaceSurface,
    pub modal: &'a ModalClub,
    pub ground: &'a SoilGround,
    pub motion: ConstantTwist,
    /// `motion` prepared for its evaluations ([`ConstantTwist::prepared`]).
    pub twist: PreparedTwist,
    /// The club frame at the start (world from club), in which the elastic motion is computed.
    pub elastic_frame: Rotation3,
    pub head_mass_kg: Real,
    pub shaft_mass_kg: Real,
    /// The undeformed shaft's CG, club frame (m).
    pub shaft_cg_m: Vector3,
}

impl System<'_> {
    /// The head's pose and velocity.
    pub fn head(&self, s: &State) -> BodyMotion {
        self.head_and_rigid(s).0
    }

    /// The head's pose and velocity, and the rigid club's.
    pub fn head_and_rigid(&self, s: &State) -> (BodyMotion, BodyMotion) {
        let (rotation, position_m, velocity_mps) = self.twist.at(s.t_s);
        let rigid = BodyMotion {
            position_m,
            world_from_club: rotation,
            velocity_mps,
            angular_velocity_radps: self.motion.angular_velocity_radps,
        };
        let o = self.modal.head_offset(&s.shaft);
        let f = &self.elastic_frame;
        let head = BodyMotion {
            position_m: rigid.position_m + f * o.cg_m,
            world_from_club: crate::math::small_rotation(&(f * o.rotation_rad)) * rigid.world_from_club,
            velocity_mps: rigid.velocity_mps + f * o.cg_velocity_mps,
            angular_velocity_radps: rigid.angular_velocity_radps + f * o.angular_velocity_radps,
        };
        (head, rigid)
    }

    /// The rigid swing's club momentum (N s, world) and the grip force it needs (N).
    fn rigid_momentum_and_force(&self, rigid: &BodyMotion) -> (Vector3, Vector3) {
        let (w, v) = (rigid.angular_velocity_radps, rigid.velocity_mps);
        let r = rigid.world_from_club * self.shaft_cg_m;
        let m = self.head_mass_kg + self.shaft_mass_kg;
        (m * v + self.shaft_mass_kg * w.cross(&r), m * w.cross(&v) + self.shaft_mass_kg * w.cross(&w.cross(&r)))
    }

    /// The club's linear momentum (N s, world).
    pub fn club_momentum(&self, s: &State) -> Vector3 {
        let (_, rigid) = self.head_and_rigid(s);
        self.rigid_momentum_and_force(&rigid).0 + self.elastic_frame * self.modal.momentum(&s.shaft)
    }

    /// The ground's forces on the head as it is in `s`.
    pub fn ground_forces(&self, s: &State) -> GroundForces {
        self.ground_forces_on(&self.head(s))
    }

    fn ground_forces_on(&self, h: &BodyMotion) -> GroundForces {
        self.ground.forces_at(&h.world_from_club, &h.position_m, &h.velocity_mps, &h.angular_velocity_radps)
    }

    /// The rates; `ground` given holds the ground's forces (sub-cycled during the ball's contact).
    pub fn eval(&self, s: &State, ground: Option<&GroundForces>) -> Eval {
        self.eval_at(s, self.head_and_rigid(s), ground)
    }

    /// [`Self::eval`] with the head's and the rigid club's motion given ([`Self::head_and_rigid`] of `s`).
    fn eval_at(&self, s: &State, (head, rigid): (BodyMotion, BodyMotion), ground: Option<&GroundForces>) -> Eval {
        let ball_motion = BodyMotion {
            position_m: s.p_b_m,
            world_from_club: Rotation3::identity(),
            velocity_mps: s.v_b_mps,
            angular_velocity_radps: s.w_cover_radps,
        };
        let contact = two_layer_contact(&self.params, self.ball.radius_m, &self.surface, &head, &ball_motion);
        let (f_on_ball, r_b) = contact.map_or((Vector3::zeros(), Vector3::zeros()), |(_, f, r)| (f, r));
        let ground = ground.copied().unwrap_or_else(|| self.ground_forces_on(&head));
        let lever = s.p_b_m + r_b - head.position_m;
        let force = ground.force_n() - f_on_ball;
        let torque = ground.torque_nm() + lever.cross(&(-f_on_ball));
        let fi = self.elastic_frame.inverse();
        let modal_load = self.modal.load(&(fi * force), &(fi * torque));
        let w_rel = s.w_cover_radps - s.w_core_radps;
        let spring = self.ball.k_ball_nm_per_rad * s.theta_rad + self.ball.c_ball_nms_per_rad * w_rel;
        Eval {
            rates: Rates {
                modal_load,
                a_b: f_on_ball / self.ball.mass_kg,
                alpha_core: spring / self.ball.core_inertia_kg_m2,
                alpha_cover: (r_b.cross(&f_on_ball) - spring) / self.ball.cover_inertia_kg_m2,
                f_ball: -f_on_ball,
                f_ground: ground.force_n(),
                f_grip_rigid: self.rigid_momentum_and_force(&rigid).1,
            },
            ball: contact.map(|c| c.0),
            ground,
            head,
        }
    }

    /// One step of `stepper.h_s` (Runge-Kutta's stages, the modes by exponential time differencing); with
    /// `hold_ground` the ground's forces are evaluated once, at the step's start, and held over it.
    pub fn step(&self, s: &State, stepper: &ModalStepper, hold_ground: bool) -> (State, Eval) {
        self.step_held(s, self.head_and_rigid(s), stepper, hold_ground, None)
    }

    /// [`Self::step`] from the head's and rigid club's motion at `s` ([`Self::head_and_rigid`]) with the
    /// ground's forces `ground` given (held from an earlier step) or, when `None`, evaluated at the step's start.
    pub fn step_held(
        &self,
        s: &State,
        head_and_rigid: (BodyMotion, BodyMotion),
        stepper: &ModalStepper,
        hold_ground: bool,
        ground: Option<&GroundForces>,
    ) -> (State, Eval) {
        let h = stepper.h_s;
        let e1 = self.eval_at(s, head_and_rigid, ground);
        let held = hold_ground.then_some(e1.ground);
        // Stages a and b share the modes' free motion over the half step.
        let free_half = stepper.free_half(&s.shaft);
        let s2 = advance(s, s, &e1.rates, 0.5 * h, stepper.add_half_load(&free_half, &e1.rates.modal_load));
        let e2 = self.eval(&s2, held.as_ref());
        let s3 = advance(s, &s2, &e2.rates, 0.5 * h, stepper.add_half_load(&free_half, &e2.rates.modal_load));
        let e3 = self.eval(&s3, held.as_ref());
        let s4 = advance(s, &s3, &e3.rates, h, stepper.third(&s2.shaft, &e1.rates.modal_load, &e3.rates.modal_load));
        let e4 = self.eval(&s4, held.as_ref());
        let (r1, r2, r3, r4) = (&e1.rates, &e2.rates, &e3.rates, &e4.rates);
        let c = |a: Vector3, b: Vector3, c: Vector3, d: Vector3| (a + 2.0 * b + 2.0 * c + d) * (h / 6.0);
        let mut next = *s;
        next.t_s = s.t_s + h;
        let loads = [&r1.modal_load, &r2.modal_load, &r3.modal_load, &r4.modal_load];
        next.shaft = stepper.finish(&s.shaft, loads);
        let eta_integral = stepper.eta_integral(&s.shaft, &next.shaft, loads);
        let clamp = self.modal.grip_force(
            &ModalState { eta: eta_integral, eta_dot: ModalVec::zeros() },
            &(next.shaft.eta_dot - s.shaft.eta_dot),
        );
        next.p_b_m += c(s.v_b_mps, s2.v_b_mps, s3.v_b_mps, s4.v_b_mps);
        next.v_b_mps += c(r1.a_b, r2.a_b, r3.a_b, r4.a_b);
        next.w_core_radps += c(r1.alpha_core, r2.alpha_core, r3.alpha_core, r4.alpha_core);
        next.w_cover_radps += c(r1.alpha_cover, r2.alpha_cover, r3.alpha_cover, r4.alpha_cover);
        next.theta_rad += c(
            s.w_cover_radps - s.w_core_radps,
            s2.w_cover_radps - s2.w_core_radps,
            s3.w_cover_radps - s3.w_core_radps,
            s4.w_cover_radps - s4.w_core_radps,
        );
        next.j_ball_ns += c(r1.f_ball, r2.f_ball, r3.f_ball, r4.f_ball);
        next.j_ground_ns += c(r1.f_ground, r2.f_ground, r3.f_ground, r4.f_ground);
        next.j_grip_ns +=
            c(r1.f_grip_rigid, r2.f_grip_rigid, r3.f_grip_rigid, r4.f_grip_rigid) + self.elastic_frame * clamp;
        (next, e1)
    }
}

/// The face's contact with the two-layer ball's cover through the continuous model's law (eq. 3.14-3.15,
/// [`Volumetric`]): the forces, the force on the ball (world) and the ball centre -> contact lever.
fn two_layer_contact(
    params: &TwoLayerParams,
    ball_radius_m: Real,
    surface: &FaceSurface,
    club: &BodyMotion,
    ball: &BodyMotion,
) -> Option<(ContactForces, Vector3, Vector3)> {
    let rot = &club.world_from_club;
    let overlap =
        surface.overlap(&rot.inverse_transform_vector(&(ball.position_m - club.position_m)), ball_radius_m)?;
    let normal = rot * overlap.normal;
    let r_club_m = rot * overlap.centroid_m;
    let r_ball_m = club.position_m + r_club_m - ball.position_m;
    let v_club = club.velocity_mps + club.angular_velocity_radps.cross(&r_club_m);
    let v_ball = ball.velocity_mps + ball.angular_velocity_radps.cross(&r_ball_m);
    let v_rel = v_ball - v_club;
    let contact = Contact {
        overlap,
        normal,
        r_club_m,
        r_ball_m,
        approach_mps: -v_rel.dot(&normal),
        slip_mps: v_rel - v_rel.dot(&normal) * normal,
    };
    let law = Volumetric {
        k_v_n_per_m3: params.k_v_n_per_m3,
        d_s_per_m: params.d_s_per_m,
        mu: params.mu,
        v_tr_mps: params.v_tr_mps,
    };
    let ContactForce { normal_n, friction_n } = law.force(&contact, &());
    Some((
        ContactForces { normal_n, friction_n, in_contact: true, depth_m: overlap.depth_m },
        normal_n * normal + friction_n,
        r_ball_m,
    ))
}

/// `base` advanced by `h` along the rates `r` evaluated at `at`, with the shaft's modes `shaft`.
fn advance(base: &State, at: &State, r: &Rates, h: Real, shaft: ModalState) -> State {
    State {
        t_s: base.t_s + h,
        shaft,
        p_b_m: base.p_b_m + at.v_b_mps * h,
        v_b_mps: base.v_b_mps + r.a_b * h,
        w_core_radps: base.w_core_radps + r.alpha_core * h,
        w_cover_radps: base.w_cover_radps + r.alpha_cover * h,
        theta_rad: base.theta_rad + (at.w_cover_radps - at.w_core_radps) * h,
        j_ball_ns: base.j_ball_ns,
        j_ground_ns: base.j_ground_ns,
        j_grip_ns: base.j_grip_ns,
    }
}
