//! The plain policy: one step size, no events, the ground evaluated at every stage, stopping when the ball leaves
//! the face. A model of the shared parts runs on the multi-rate stepping with it and nothing of its own.

use super::{Flow, StepPolicy, StepStart, SteppedState};
use crate::impact::continuous::assembly::Assembly;
use crate::impact::continuous::ball::BallPart;
use crate::impact::continuous::club::{Head, SteppedClub};
use crate::impact::continuous::ground::SampledGround;
use crate::impact::ImpactError;
use crate::math::Real;

/// One step size; stops at the first step's start out of contact after a contact (or, never touched, after ten
/// steps: the face moves off); more than `max_steps` steps is an error naming `model`.
#[derive(Debug, Clone)]
pub struct FixedStep<S> {
    /// The one step (its size and coefficients).
    pub step: S,
    /// The most steps before the run is an error.
    pub max_steps: usize,
    /// The name errors carry.
    pub model: &'static str,
    touched: bool,
    steps: usize,
}

impl<S> FixedStep<S> {
    /// Steps of `step`, at most `max_steps`, errors naming `model`.
    pub fn new(step: S, max_steps: usize, model: &'static str) -> Self {
        FixedStep { step, max_steps, model, touched: false, steps: 0 }
    }

    /// Whether the ball was ever in contact (a run that stops without one is a miss).
    pub fn touched(&self) -> bool {
        self.touched
    }

    /// Steps taken before the one it stopped at.
    pub fn steps(&self) -> usize {
        self.steps
    }
}

impl<L, B: BallPart, C: SteppedClub, G: SampledGround> StepPolicy<L, B, C, G> for FixedStep<C::Step> {
    fn step(&self, _: Real, _: &SteppedState<B, C>, _: &Head) -> &C::Step {
        &self.step
    }

    fn observe(
        &mut self,
        _: &Assembly<L, B, C, G>,
        _: Real,
        _: Real,
        _: &SteppedState<B, C>,
        start: &StepStart<C::Motion, G::Forces>,
    ) -> Result<Flow, ImpactError> {
        if start.ball.is_some() {
            self.touched = true;
        } else if self.touched || self.steps > 10 {
            return Ok(Flow::Stop);
        }
        if self.steps >= self.max_steps {
            return Err(ImpactError::NotConverged {
                model: self.model,
                reason: format!("still in contact after {} steps", self.max_steps),
            });
        }
        self.steps += 1;
        Ok(Flow::Continue)
    }
}
