//! One step of the multi-rate stepping: classical Runge-Kutta's four stages, the ball by Runge-Kutta, the club by
//! its own scheme on the same stages, the ground's forces evaluated at every stage or held from the step's start.
//!
//! The ball's force acts at the contact point; the head gets the opposite there, its moment about the head's CG
//! taken with the lever from the CG to the point (ball centre + the ball's lever), so linear momentum is
//! conserved to rounding at every stage.

use super::SteppedState;
use crate::impact::continuous::assembly::{Assembly, ContactForces, State};
use crate::impact::continuous::ball::BallPart;
use crate::impact::continuous::club::{ClubLoad, SteppedClub};
use crate::impact::continuous::ground::SampledGround;
use crate::impact::continuous::law::{Contact, ContactForce, ContactLaw};
use crate::math::{Real, Vector3};

/// What acted at a step's start: the club's motion, the ball's contact (if any) and the ground's forces.
#[derive(Debug, Clone, Copy)]
pub struct StepStart<M, F> {
    pub motion: M,
    pub ball: Option<ContactForces>,
    pub ground: F,
}

/// The rates of one stage.
struct StageRate<CR, BR> {
    club: CR,
    ball: BR,
}

/// A stage's rates, the ball's contact (if any) and the step's bound made of it.
type StageOut<CR, BR> = (StageRate<CR, BR>, Option<ContactForces>, Option<Real>);

/// A step's end, what acted at its start and the step's size (s).
type StepEnd<B, C, G> = (SteppedState<B, C>, StepStart<<C as SteppedClub>::Motion, <G as SampledGround>::Forces>, Real);

impl<L: ContactLaw, B: BallPart, C: SteppedClub, G: SampledGround> Assembly<L, B, C, G> {
    /// The rates in `s` with the club's motion `motion` and the ground's forces `ground`, the ball's contact, and
    /// what `bound` makes of the contact and the law's force there (`None` out of contact).
    #[inline(always)]
    fn stage_rate(
        &self,
        s: &SteppedState<B, C>,
        motion: &C::Motion,
        law_state: &L::State,
        ground: &G::Forces,
        bound: impl FnOnce(&Contact, &ContactForce) -> Option<Real>,
    ) -> StageOut<C::Rate, B::Rate> {
        let head = C::head(motion);
        let mut bound_s = None;
        let contact = self.contact(&head, &s.ball).map(|c| {
            let force = self.law.force(&c, law_state);
            bound_s = bound(&c, &force);
            let ContactForce { normal_n, friction_n } = force;
            let forces = ContactForces { normal_n, friction_n, in_contact: true, depth_m: c.overlap.depth_m };
            (forces, normal_n * c.normal + friction_n, c.r_ball_m)
        });
        let (f_on_ball, r_ball) = contact.map_or((Vector3::zeros(), Vector3::zeros()), |(_, f, r)| (f, r));
        let wrench = G::wrench_of(ground);
        let (p_ball, _) = B::centre(&s.ball);
        let load = ClubLoad {
            ball_force_n: -f_on_ball,
            ball_lever_m: p_ball + r_ball - head.position_m,
            ground_force_n: wrench.force_n,
            ground_torque_nm: wrench.torque_nm,
        };
        let rate = StageRate {
            club: self.club.rate(&s.club, motion, &load),
            ball: self.ball.rate(&s.ball, f_on_ball, r_ball),
        };
        (rate, contact.map(|c| c.0), bound_s)
    }

    /// The rates of a later stage in `s` at `t_s`: the ground's forces `held`, or evaluated there.
    #[inline]
    fn later_stage_rate(
        &self,
        s: &SteppedState<B, C>,
        t_s: Real,
        law_state: &L::State,
        held: Option<&G::Forces>,
    ) -> StageRate<C::Rate, B::Rate> {
        let motion = self.club.motion(&s.club, t_s);
        match held {
            Some(g) => self.stage_rate(s, &motion, law_state, g, |_, _| None).0,
            None => self.stage_rate(s, &motion, law_state, &self.ground.forces_on(&C::head(&motion)), |_, _| None).0,
        }
    }

    /// One step from `s` at `t_s` (the club's motion there `motion`) with `step`'s coefficients, or shorter where
    /// `bound` of the ball's contact at the start says (a step built for it). With `hold_ground` the ground's
    /// forces of the step's start (`ground` when given, else evaluated) act over the whole step. Returns the
    /// step's end, what acted at its start and the step's size (s).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn step_stepped(
        &self,
        s: &SteppedState<B, C>,
        t_s: Real,
        motion: C::Motion,
        step: &C::Step,
        law_state: &L::State,
        hold_ground: bool,
        ground: Option<&G::Forces>,
        bound: impl FnOnce(&Contact, &ContactForce) -> Option<Real>,
    ) -> StepEnd<B, C, G> {
        let g1 = match ground {
            Some(g) => *g,
            None => self.ground.forces_on(&C::head(&motion)),
        };
        let (k1, contact, bound_s) = self.stage_rate(s, &motion, law_state, &g1, bound);
        let shorter;
        let step = match bound_s {
            Some(h_s) if h_s < C::step_s(step) => {
                shorter = self.club.step(h_s);
                &shorter
            }
            _ => step,
        };
        let h = C::step_s(step);
        let held = hold_ground.then_some(&g1);
        let club = &self.club;
        // Stages two and three share the club's free motion over the half step.
        let free = club.free_half(step, &s.club);
        let s2 =
            State { club: club.half(step, &s.club, &free, &k1.club), ball: B::advance(&s.ball, &k1.ball, 0.5 * h) };
        let k2 = self.later_stage_rate(&s2, t_s + 0.5 * h, law_state, held);
        let s3 =
            State { club: club.half(step, &s.club, &free, &k2.club), ball: B::advance(&s.ball, &k2.ball, 0.5 * h) };
        let k3 = self.later_stage_rate(&s3, t_s + 0.5 * h, law_state, held);
        let s4 = State {
            club: club.fourth(step, &s.club, &s2.club, &k1.club, &k3.club),
            ball: B::advance(&s.ball, &k3.ball, h),
        };
        let k4 = self.later_stage_rate(&s4, t_s + h, law_state, held);
        let next = State {
            club: club.finish(step, &s.club, [&k1.club, &k2.club, &k3.club, &k4.club]),
            ball: B::advance_rk4_scaled(&s.ball, [&k1.ball, &k2.ball, &k3.ball, &k4.ball], h),
        };
        (next, StepStart { motion, ball: contact, ground: g1 }, h)
    }
}
