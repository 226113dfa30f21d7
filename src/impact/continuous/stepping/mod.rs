//! The assembly's multi-rate, event-driven stepping: the same parts as the plain fixed step (a ball, a contact
//! law, a ground), with a club that advances each step its own way ([`SteppedClub`]: a shaft's modes by
//! exponential time differencing) and a policy that chooses each step ([`StepPolicy`]).
//!
//! Each step is classical Runge-Kutta's four stages (`step.rs`): the ball by Runge-Kutta, the club by its own
//! scheme on the same stages. What the policy decides:
//!
//! - the step's size, from a ladder of sizes whose coefficients are built once ([`StepLadder`]): long while
//!   slow forces act alone, short in the ball's contact; or shortened by the ball's contact at the step's start
//!   ([`StiffnessStep`]: as far as the friction's stiffness allows);
//! - events: instants a step must end at (a first touch, the end of a follow-through); a step that would pass
//!   one ends there, with coefficients built for that one step;
//! - the ground's clock: whether its forces are evaluated once at a step's start and held over the step and
//!   the steps that follow, for how long (they change over milliseconds, the ball's over microseconds);
//! - when to stop: after each step it sees the step's start, its state and what acted then ([`StepStart`]).
//!
//! Every model of the shared parts runs here. [`FixedStep`] is the plain policy (one step, stop when the ball
//! leaves); [`StiffnessStep`] the two-layer model's, measuring what a
//! [`ContinuousResult`](super::assembly::ContinuousResult) reports.

mod fixed;
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
use crate::math::Real;

/// The state of an assembly of ball `B` and club `C` on this stepping.
pub type SteppedState<B, C> = State<<C as SteppedClub>::State, <B as BallPart>::State>;

/// Whether to go on after a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
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
    /// A step shorter than the one chosen, from the ball's contact at its start and the law's force there: the
    /// step ends after `Some(h_s)` when that is shorter (its coefficients built for it; the ground's hold as
    /// chosen for the longer one). `None` (the default): the step as chosen.
    fn contact_step_s(&self, _asm: &Assembly<L, B, C, G>, _contact: &Contact, _force: &ContactForce) -> Option<Real> {
        None
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
    /// count, a time); returns the state and time it stopped at.
    pub fn run_stepped<P: StepPolicy<L, B, C, G>>(
        &self,
        mut s: SteppedState<B, C>,
        mut t_s: Real,
        policy: &mut P,
    ) -> Result<(SteppedState<B, C>, Real), ImpactError> {
        let mut law_state = L::State::default();
        // The ground's forces held, and when they were evaluated.
        let mut held: Option<(G::Forces, Real)> = None;
        loop {
            let motion = self.club.motion(&s.club, t_s);
            let nominal = policy.step(t_s, &s, &C::head(&motion));
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
            let h = C::step_s(step);
            let hold_s = policy.ground_hold_s(h);
            let reuse = held.filter(|(_, t)| hold_s.is_some_and(|hold_s| t_s - t < hold_s - 0.5 * h)).map(|(g, _)| g);
            let bound = |c: &Contact, f: &ContactForce| policy.contact_step_s(self, c, f);
            let (next, start, h) =
                self.step_stepped(&s, t_s, motion, step, &law_state, hold_s.is_some(), reuse.as_ref(), bound);
            if reuse.is_none() {
                held = hold_s.map(|_| (start.ground, t_s));
            }
            if policy.observe(self, t_s, h, &s, &start)? == Flow::Stop {
                return Ok((s, t_s));
            }
            if std::mem::size_of::<L::State>() > 0 {
                let head = C::head(&self.club.motion(&next.club, t_s + h));
                let c = self.contact(&head, &next.ball);
                self.law.commit(c.as_ref(), &mut law_state, h);
            }
            s = next;
            t_s += h;
        }
    }
}
