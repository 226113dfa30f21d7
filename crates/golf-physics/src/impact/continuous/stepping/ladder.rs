//! A run's step sizes, each with its club's coefficients built once per prepared club (building a shaft's costs
//! about a hundred steps' worth of the modes' arithmetic).

use crate::math::Real;

/// A long step, and a short one times powers of two below it (an approach from the one to the other).
#[derive(Debug, Clone)]
pub struct StepLadder<S> {
    long: S,
    /// `short_s · 2ᵏ` at index k, all below the long step but the first.
    rungs: Vec<S>,
    long_s: Real,
    short_s: Real,
}

impl<S> StepLadder<S> {
    /// The steps from `short_s` up to `long_s` (at least `short_s`), each built by `step` from its size (a
    /// club's `SteppedClub::step`).
    pub fn new(step: impl Fn(Real) -> S, short_s: Real, long_s: Real) -> Self {
        let long_s = long_s.max(short_s);
        let mut rungs = vec![step(short_s)];
        let mut h = 2.0 * short_s;
        while h < long_s && rungs.len() < 40 {
            rungs.push(step(h));
            h *= 2.0;
        }
        StepLadder { long: step(long_s), rungs, long_s, short_s }
    }

    /// The long step (`long_s`).
    pub fn long(&self) -> &S {
        &self.long
    }

    /// The short step (`short_s`).
    pub fn short(&self) -> &S {
        &self.rungs[0]
    }

    /// The largest step not above `h_s`: the long one, or the short one times the largest power of two that fits
    /// (the short one at least).
    pub fn at_most(&self, h_s: Real) -> &S {
        if h_s >= self.long_s {
            return &self.long;
        }
        let k = (h_s / self.short_s).log2().floor().max(0.0) as usize;
        &self.rungs[k.min(self.rungs.len() - 1)]
    }
}
