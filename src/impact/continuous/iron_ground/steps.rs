//! The run's step sizes, each with its modal stepper built once per prepared club (building one costs about a
//! hundred steps' worth of the modes' arithmetic).

use crate::impact::continuous::shaft::exponential::ModalStepper;
use crate::impact::continuous::shaft::modal::ModalClub;
use crate::math::Real;

/// The ground's step, and the ball's step times powers of two below it (the approach to the ball).
#[derive(Debug, Clone)]
pub struct StepLadder {
    ground: ModalStepper,
    /// `ball_step_s · 2ᵏ` at index k, all below the ground's step but the first.
    rungs: Vec<ModalStepper>,
}

impl StepLadder {
    pub fn new(modal: &ModalClub, ball_step_s: Real, ground_step_s: Real) -> Self {
        let ground_step_s = ground_step_s.max(ball_step_s);
        let mut rungs = vec![ModalStepper::new(modal, ball_step_s)];
        let mut h = 2.0 * ball_step_s;
        while h < ground_step_s && rungs.len() < 40 {
            rungs.push(ModalStepper::new(modal, h));
            h *= 2.0;
        }
        StepLadder { ground: ModalStepper::new(modal, ground_step_s), rungs }
    }

    pub fn ground(&self) -> &ModalStepper {
        &self.ground
    }

    pub fn ball(&self) -> &ModalStepper {
        &self.rungs[0]
    }

    /// The largest step not above `h_s`: the ground's, or the ball's times the largest power of two that fits
    /// (the ball's at least).
    pub fn at_most(&self, h_s: Real) -> &ModalStepper {
        if h_s >= self.ground.h_s {
            return &self.ground;
        }
        let k = (h_s / self.ball().h_s).log2().floor().max(0.0) as usize;
        &self.rungs[k.min(self.rungs.len() - 1)]
    }
}
