//! One step of the multi-rate stepping: classical Runge-Kutta's four stages, the ball by Runge-Kutta, the club by
//! its own scheme on the same stages, the ground's forces evaluated at every stage or held from the step's start.
//!
//! The ball's force acts at the contact point; the head gets the opposite there, its moment about the head's CG
//! taken with the lever from the CG to the point (ball centre + the ball's lever), so linear momentum is
//! conserved to rounding at every stage.
//!
//! For a law that asks for it ([`ContactLaw::TRACKS_SLIP`]) the contact's slip is integrated by the same stages
//! beside the parts (absolute, from the run's start): each stage's contact gets the slip since the step's start
//! in its tangent plane.

use super::SteppedState;
use crate::impact::continuous::assembly::{Assembly, ContactForces, State};
use crate::impact::continuous::ball::{rk4_mean, BallPart};
use crate::impact::continuous::club::{ClubLoad, SteppedClub};
use crate::impact::continuous::ground::SampledGround;
use crate::impact::continuous::law::{Contact, ContactForce, ContactLaw};
use crate::math::{Real, Vector3};

/// What acted at a step's start: the club's motion, the ball's contact (if any) and the ground's forces.
#[derive(Debug, Clone, Copy)]
pub struct StepStart<M, F> {
    /// The club's motion.
    pub motion: M,
    /// The ball's contact forces, if it touches.
    pub ball: Option<ContactForces>,
    /// The ground's forces (held over several steps near the ball).
    pub ground: F,
}

/// A step's end, what acted at its start, the contact's integrated slip at its end and the step's size (s).
pub(super) type Stepped<B, C, F> = (SteppedState<B, C>, StepStart<<C as SteppedClub>::Motion, F>, Vector3, Real);

/// A stage's rates, the ball's contact (if any) and the step's bound made of it.
type StageOut<CR, BR> = (StageRate<CR, BR>, Option<ContactForces>, Option<Real>);

/// The rates of one stage.
struct StageRate<CR, BR> {
    club: CR,
    ball: BR,
    /// The contact's slip velocity (m/s; zero apart or when the law does not track it).
    slip_mps: Vector3,
}

impl<L: ContactLaw, B: BallPart, C: SteppedClub, G: SampledGround> Assembly<L, B, C, G> {
    /// The rates in `s` with the club's motion `motion` and the ground's forces `ground`, and the ball's contact
    /// (`known`: already found there); `slip_since_m` is the contact's slip since the step's start (tracked laws
    /// only), `FIRST` the step's first stage ([`ContactLaw::start_force`]); with what `bound` makes of the contact
    /// and the law's force there (`None` out of contact).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn stage_rate<const FIRST: bool>(
        &self,
        s: &SteppedState<B, C>,
        motion: &C::Motion,
        law_state: &L::State,
        ground: &G::Forces,
        slip_since_m: Vector3,
        known: Option<Option<Contact>>,
        bound: impl FnOnce(&Contact, &ContactForce) -> Option<Real>,
    ) -> StageOut<C::Rate, B::Rate> {
        let head = C::head(motion);
        let mut slip_mps = Vector3::zeros();
        let mut bound_s = None;
        let contact = known.unwrap_or_else(|| self.contact(&head, &s.ball));
        let contact = contact.map(|mut c| {
            if L::TRACKS_SLIP {
                c.slip_since_step_m = slip_since_m - slip_since_m.dot(&c.normal) * c.normal;
                slip_mps = c.slip_mps;
            }
            let force = if FIRST { self.law.start_force(&c, law_state) } else { self.law.force(&c, law_state) };
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
            slip_mps,
        };
        (rate, contact.map(|c| c.0), bound_s)
    }

    /// The rates of a later stage in `s` at `t_s`: the ground's forces `held`, or evaluated there.
    #[inline(always)]
    fn later_stage_rate(
        &self,
        s: &SteppedState<B, C>,
        t_s: Real,
        law_state: &L::State,
        held: Option<&G::Forces>,
        slip_since_m: Vector3,
    ) -> StageRate<C::Rate, B::Rate> {
        let motion = self.club.motion(&s.club, t_s);
        match held {
            Some(g) => self.stage_rate::<false>(s, &motion, law_state, g, slip_since_m, None, |_, _| None).0,
            None => {
                let g = self.ground.forces_on(&C::head(&motion));
                self.stage_rate::<false>(s, &motion, law_state, &g, slip_since_m, None, |_, _| None).0
            }
        }
    }

    /// One step from `s` at `t_s` (the club's motion there `motion`) with `step`'s coefficients. With
    /// `hold_ground` the ground's forces of the step's start (`ground` when given, else evaluated) act over the
    /// whole step. `slip_m` is the contact's integrated slip at the start (tracked laws only); `first`, the
    /// ball's contact at the start when already found. The step is shorter where `bound` of the ball's contact at
    /// the start says (a step built for it). Returns the step's end, what acted at its start, the integrated slip
    /// at its end and the step's size (s).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn step_stepped(
        &self,
        s: &SteppedState<B, C>,
        t_s: Real,
        motion: C::Motion,
        step: &C::Step,
        law_state: &L::State,
        hold_ground: bool,
        ground: Option<&G::Forces>,
        slip_m: Vector3,
        first: Option<Option<Contact>>,
        bound: impl FnOnce(&Contact, &ContactForce) -> Option<Real>,
    ) -> Stepped<B, C, G::Forces> {
        let g1 = match ground {
            Some(g) => *g,
            None => self.ground.forces_on(&C::head(&motion)),
        };
        // The slip since the step's start at a stage whose integrated slip is `at` (as the stage's state holds
        // it, so the rounding is the integrated slip's).
        let since = |at: Vector3| if L::TRACKS_SLIP { at - slip_m } else { Vector3::zeros() };
        let (k1, contact, bound_s) = self.stage_rate::<true>(s, &motion, law_state, &g1, since(slip_m), first, bound);
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
        let k2 = self.later_stage_rate(&s2, t_s + 0.5 * h, law_state, held, since(slip_m + k1.slip_mps * (0.5 * h)));
        let s3 =
            State { club: club.half(step, &s.club, &free, &k2.club), ball: B::advance(&s.ball, &k2.ball, 0.5 * h) };
        let k3 = self.later_stage_rate(&s3, t_s + 0.5 * h, law_state, held, since(slip_m + k2.slip_mps * (0.5 * h)));
        let s4 = State {
            club: club.fourth(step, &s.club, &s2.club, &k1.club, &k3.club),
            ball: B::advance(&s.ball, &k3.ball, h),
        };
        let k4 = self.later_stage_rate(&s4, t_s + h, law_state, held, since(slip_m + k3.slip_mps * h));
        let next = State {
            club: club.finish(step, &s.club, [&k1.club, &k2.club, &k3.club, &k4.club]),
            ball: B::advance_rk4_scaled(&s.ball, [&k1.ball, &k2.ball, &k3.ball, &k4.ball], h),
        };
        let slip_end_m = if L::TRACKS_SLIP {
            slip_m + rk4_mean(k1.slip_mps, k2.slip_mps, k3.slip_mps, k4.slip_mps) * h
        } else {
            slip_m
        };
        (next, StepStart { motion, ball: contact, ground: g1 }, slip_end_m, h)
    }
}
