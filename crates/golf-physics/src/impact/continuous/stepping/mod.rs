//! The assembly's multi-rate, event-driven stepping: the same parts as the plain fixed step (a ball, a contact
//! law, a ground), with a club that advances each step its own way ([`SteppedClub`]: a shaft's modes by
//! exponential time differencing) and a policy that chooses each step ([`StepPolicy`]).
//!
//! Each step is classical Runge-Kutta's four stages (`step.rs`): the ball by Runge-Kutta, the club by its own
//! scheme on the same stages. What the policy decides:
//!
//! - the step's size, from a ladder of sizes whose coefficients are built once ([`StepLadder`]): long while
//!   slow forces act alone, short in the ball's contact; or shortened by the ball's contact at the step's start
//!   ([`StepPolicy::contact_step_s`]; [`StiffnessStep`]: as far as the friction's stiffness allows);
//! - events: instants a step must end at (a first touch, the end of a follow-through); a step that would pass
//!   one ends there, with coefficients built for that one step;
//! - the ground's clock: whether its forces are evaluated once at a step's start and held over the step and
//!   the steps that follow, for how long (they change over milliseconds, the ball's over microseconds);
//! - when to stop: after each step it sees the step's start, its state and what acted then ([`StepStart`]), and
//!   the contact law's history then ([`StepPolicy::law_state`]);
//! - a finer step where the contact law flags a step's start near one of its switches
//!   ([`StepPolicy::refined_step`], [`ContactLaw::refine`]);
//! - whether the step in which the ball leaves ends where the overlap closes, found by secant, and the run there
//!   ([`StepPolicy::end_at_separation`]).
//!
//! The contact law's history ([`ContactLaw::State`]) starts as the law says ([`ContactLaw::initial_state`]) and
//! is committed after each step with the contact at its end; the contact found there is the next step's start.
//! A law that reads the slip since a step's start ([`ContactLaw::TRACKS_SLIP`]) has it integrated beside the
//! parts by the same stages.
//!
//! Every model of the shared parts runs here. [`FixedStep`] is the plain policy (one step, stop when the ball
//! leaves); [`StiffnessStep`] the two-layer model's, measuring what a
//! [`ContinuousResult`](super::assembly::ContinuousResult) reports.

mod fixed;
#[cfg(test)]
mod hook_tests;
mod ladder;
mod step;
mod stiffness;
#[cfg(test)]
mod tests;

pub use fixed::FixedStep;
pub use ladder::StepLadder;
pub use step::StepStart;
pub use stiffness::{StiffnessBound, StiffnessStep};

use super::assembly::{Assembly, State};
use super::ball::BallPart;
use super::club::{Head, SteppedClub};
use super::ground::SampledGround;
use super::law::{Contact, ContactForce, ContactLaw};
use crate::impact::ImpactError;
use crate::math::{Real, Vector3};

/// The state of an assembly of ball `B` and club `C` on this stepping.
pub type SteppedState<B, C> = State<<C as SteppedClub>::State, <B as BallPart>::State>;

/// Whether to go on after a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    /// Take the next step.
    Continue,
    /// Stop at the step's start: the run ends in that state.
    Stop,
}

/// How a run on the multi-rate stepping proceeds: the steps, the events, the ground's clock and when to stop.
pub trait StepPolicy<L, B: BallPart, C: SteppedClub, G: SampledGround> {
    /// The step from state `s` at `t_s` with the head at `head` (before any event shortens it).
    fn step(&self, t_s: Real, s: &State<C::State, B::State>, head: &Head) -> &C::Step;
    /// The instants a step of `h_s` from `t_s` must end at if it would pass them (the first inside ends it).
    fn events(&self, _t_s: Real, _h_s: Real) -> impl IntoIterator<Item = Real> {
        []
    }
    /// `Some(hold_s)`: during a step of `h_s` the ground's forces are those of the step's start, and a start
    /// within `hold_s` of the last evaluation reuses it. `None` (the default): evaluated at every stage.
    fn ground_hold_s(&self, _h_s: Real) -> Option<Real> {
        None
    }
    /// The step to take instead of [`Self::step`]'s when the contact law flags the step's start as near one of its
    /// switches ([`ContactLaw::refine`]); `None` (the default): the law is not asked.
    fn refined_step(&self) -> Option<&C::Step> {
        None
    }
    /// Whether a step that starts in the ball's contact and ends out of it is shortened to end where the overlap
    /// closes (a secant on the signed overlap), the run then ending there: for a law whose forces jump at the
    /// separation (Arakawa's `ẋ` term). `false` (the default): the step stands and the run goes on.
    fn end_at_separation(&self) -> bool {
        false
    }
    /// A step shorter than the one chosen, from the ball's contact at its start and the law's force there: the
    /// step ends after `Some(h_s)` when that is shorter (its coefficients built for it; the ground's hold as
    /// chosen for the longer one). `None` (the default): the step as chosen.
    fn contact_step_s(&self, _asm: &Assembly<L, B, C, G>, _contact: &Contact, _force: &ContactForce) -> Option<Real> {
        None
    }
    /// The contact law's state at the step's start, just before [`Self::observe`] (a trace of the law's history).
    fn law_state(&mut self, _law: &L, _state: &L::State)
    where
        L: ContactLaw,
    {
    }
    /// After the step of `h_s` from `s` at `t_s`, with what acted at its start.
    fn observe(
        &mut self,
        asm: &Assembly<L, B, C, G>,
        t_s: Real,
        h_s: Real,
        s: &State<C::State, B::State>,
        start: &StepStart<C::Motion, G::Forces>,
    ) -> Result<Flow, ImpactError>;
}

impl<L: ContactLaw, B: BallPart, C: SteppedClub, G: SampledGround> Assembly<L, B, C, G> {
    /// Runs from state `s` at `t_s` until the policy stops (it sees every step, so it bounds the run: a step
    /// count, a time) or, with [`StepPolicy::end_at_separation`], the ball leaves; returns the state and time it
    /// stopped at.
    pub fn run_stepped<P: StepPolicy<L, B, C, G>>(
        &self,
        mut s: SteppedState<B, C>,
        mut t_s: Real,
        policy: &mut P,
    ) -> Result<(SteppedState<B, C>, Real), ImpactError> {
        let mut law_state = self.law.initial_state();
        // The contact's integrated slip (laws that track it).
        let mut slip_m = Vector3::zeros();
        // The ground's forces held, and when they were evaluated.
        let mut held: Option<(G::Forces, Real)> = None;
        let stateful = std::mem::size_of::<L::State>() > 0;
        // The ball's contact at the step's start when the last step found it at its end (a stateful law's commit).
        let mut known: Option<Option<Contact>> = None;
        loop {
            let motion = self.club.motion(&s.club, t_s);
            let head = C::head(&motion);
            let mut nominal = policy.step(t_s, &s, &head);
            let mut first = known.take();
            if let Some(fine) = policy.refined_step() {
                let c = *first.get_or_insert_with(|| self.contact(&head, &s.ball));
                if c.is_some_and(|c| self.law.refine(&c, &law_state)) {
                    nominal = fine;
                }
            }
            let h_nominal = C::step_s(nominal);
            let event = policy
                .events(t_s, h_nominal)
                .into_iter()
                .filter(|t| *t > t_s + 1e-9 && *t < t_s + h_nominal - 1e-9)
                .reduce(Real::min);
            let one_off;
            let step = match event {
                Some(t) => {
                    one_off = self.club.step(t - t_s);
                    &one_off
                }
                None => nominal,
            };
            let mut h = C::step_s(step);
            let hold_s = policy.ground_hold_s(h);
            let reuse = held.filter(|(_, t)| hold_s.is_some_and(|hold_s| t_s - t < hold_s - 0.5 * h)).map(|(g, _)| g);
            let hold = hold_s.is_some();
            let bound = |c: &Contact, f: &ContactForce| policy.contact_step_s(self, c, f);
            let (mut next, start, mut slip_next, h_taken) =
                self.step_stepped(&s, t_s, motion, step, &law_state, hold, reuse.as_ref(), slip_m, first, bound);
            h = h_taken;
            if reuse.is_none() {
                held = hold_s.map(|_| (start.ground, t_s));
            }
            let separation = policy.end_at_separation();
            let mut c_next = if stateful || separation {
                self.contact(&C::head(&self.club.motion(&next.club, t_s + h)), &next.ball)
            } else {
                None
            };
            let ended = match (&start.ball, &c_next) {
                (Some(c0), None) if separation => {
                    let redo = |t: Real| {
                        let step = self.club.step(t);
                        let no_bound = |_: &Contact, _: &ContactForce| None;
                        self.step_stepped(
                            &s,
                            t_s,
                            motion,
                            &step,
                            &law_state,
                            hold,
                            reuse.as_ref(),
                            slip_m,
                            first,
                            no_bound,
                        )
                    };
                    let t = self.separation_s(c0.depth_m, h, &next, t_s, |t| redo(t).0);
                    (next, _, slip_next, _) = redo(t);
                    h = t;
                    c_next = None;
                    true
                }
                _ => false,
            };
            policy.law_state(&self.law, &law_state);
            if policy.observe(self, t_s, h, &s, &start)? == Flow::Stop {
                return Ok((s, t_s));
            }
            if stateful {
                let c = c_next.map(|mut c| {
                    let ds = slip_next - slip_m;
                    c.slip_since_step_m = ds - ds.dot(&c.normal) * c.normal;
                    c
                });
                self.law.commit(c.as_ref(), &mut law_state, h);
                known = Some(c_next);
            }
            s = next;
            slip_m = slip_next;
            t_s += h;
            if ended {
                return Ok((s, t_s));
            }
        }
    }

    /// Where in a step of `h_s` from `t_s` (the overlap `depth0_m` at its start, none at its end `end`) the ball
    /// leaves the face: a secant on the signed overlap, four refinements, each a step of the trial length from
    /// the start (`step_to`).
    fn separation_s(
        &self,
        depth0_m: Real,
        h_s: Real,
        end: &SteppedState<B, C>,
        t_s: Real,
        step_to: impl Fn(Real) -> SteppedState<B, C>,
    ) -> Real {
        let gap = |st: &SteppedState<B, C>, t: Real| {
            let head = C::head(&self.club.motion(&st.club, t));
            let (centre_m, _) = B::centre(&st.ball);
            let ball_club = head.world_from_club.inverse_transform_vector(&(centre_m - head.position_m));
            self.surface.signed_depth_m(&ball_club, self.ball.radius_m())
        };
        let (mut lo, mut x_lo, mut hi, mut x_hi) = (0.0, depth0_m, h_s, gap(end, t_s + h_s));
        let mut t = lo + (hi - lo) * x_lo / (x_lo - x_hi);
        for _ in 0..4 {
            let x = gap(&step_to(t), t_s + t);
            if x.abs() < 1e-15 {
                break;
            }
            if x > 0.0 {
                (lo, x_lo) = (t, x);
            } else {
                (hi, x_hi) = (t, x);
            }
            t = lo + (hi - lo) * x_lo / (x_lo - x_hi);
        }
        t
    }
}
