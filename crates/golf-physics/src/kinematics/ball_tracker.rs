//! The ball's position for the next impact from a tracked ball: observations that agree with the one before
//! (the ball at rest on the tee or the turf) set it; a ball in flight (observations that move), one outside the
//! hitting area (a ghost, a ball rolled away) or an occluded one change nothing, so the position at the impact
//! is where the ball rested before the club reached it. Until a tracked ball has rested, the rig's fixed
//! `ball_position_m` is used.

use crate::math::{Real, Vector3};

/// How the tracker accepts observations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallTrackerConfig {
    /// The fixed position (world, m): the fallback, and the centre of the hitting area.
    pub fallback_m: Vector3,
    /// Observations farther than this from the fallback are not the ball at address (m).
    pub max_distance_m: Real,
    /// Two consecutive observations within this distance are a ball at rest (m). A ball struck at 1 m/s moves
    /// 2.8 mm between frames at 360 Hz, so 1 mm separates rest from flight at every rate labs use.
    pub at_rest_m: Real,
}

impl BallTrackerConfig {
    /// The rig's fixed ball position (world, m) with a hitting area of 0.5 m around it and 1 mm between
    /// consecutive observations for a ball at rest.
    pub fn new(fallback_m: Vector3) -> Self {
        BallTrackerConfig { fallback_m, max_distance_m: 0.5, at_rest_m: 0.001 }
    }
}

/// Why an observation changed nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BallIgnored {
    /// No position, or a non-finite one.
    Occluded,
    /// Further than [`BallTrackerConfig::max_distance_m`] from the fixed position.
    OutsideHittingArea,
    /// Moving (or the first observation after a gap): it sets nothing until the next one agrees with it.
    Moving,
}

impl BallIgnored {
    /// The counting key.
    pub fn key(self) -> &'static str {
        match self {
            BallIgnored::Occluded => "ball_occluded",
            BallIgnored::OutsideHittingArea => "ball_outside_hitting_area",
            BallIgnored::Moving => "ball_moving",
        }
    }
}

/// The tracked ball's state.
#[derive(Debug, Clone, PartialEq)]
pub struct BallTracker {
    /// How observations are accepted.
    pub config: BallTrackerConfig,
    previous: Option<Vector3>,
    at_rest: Option<Vector3>,
}

impl BallTracker {
    /// A tracker that has seen no ball yet: [`position`](Self::position) gives the fallback.
    pub fn new(config: BallTrackerConfig) -> Self {
        BallTracker { config, previous: None, at_rest: None }
    }

    /// Takes one observation of the ball's centre (world, m); `Ok(true)` when it moved the ball's rest position.
    pub fn observe(&mut self, position_m: Option<Vector3>) -> Result<bool, BallIgnored> {
        let Some(p) = position_m.filter(|p| p.iter().all(|v| v.is_finite())) else {
            self.previous = None;
            return Err(BallIgnored::Occluded);
        };
        if (p - self.config.fallback_m).norm() > self.config.max_distance_m {
            self.previous = None;
            return Err(BallIgnored::OutsideHittingArea);
        }
        let agrees = self.previous.is_some_and(|q| (p - q).norm() <= self.config.at_rest_m);
        self.previous = Some(p);
        if !agrees {
            return Err(BallIgnored::Moving);
        }
        let moved = self.at_rest != Some(p);
        self.at_rest = Some(p);
        Ok(moved)
    }

    /// The ball's position for the next impact and whether it is tracked (else the fallback).
    pub fn position(&self) -> (Vector3, bool) {
        match self.at_rest {
            Some(p) => (p, true),
            None => (self.config.fallback_m, false),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ball_at_rest_sets_the_position_and_a_ball_in_flight_does_not() {
        let mut t = BallTracker::new(BallTrackerConfig::new(Vector3::zeros()));
        assert_eq!(t.position(), (Vector3::zeros(), false));
        let rest = Vector3::new(0.004, -0.002, 0.0);
        assert_eq!(t.observe(Some(rest)), Err(BallIgnored::Moving), "one observation is not yet a rest");
        assert_eq!(t.observe(Some(rest + Vector3::new(0.0002, 0.0, 0.0))), Ok(true));
        assert!((t.position().0 - rest).norm() < 0.00021 && t.position().1);
        // Struck at 60 m/s, observed at 720 Hz: 83 mm a frame, then out of the hitting area.
        for k in 1..10 {
            let r = t.observe(Some(rest + Vector3::new(0.083 * k as Real, 0.0, 0.01 * k as Real)));
            assert!(r.is_err());
        }
        assert!((t.position().0 - rest).norm() < 0.00021, "the position at the impact is where the ball rested");
        assert_eq!(t.observe(None), Err(BallIgnored::Occluded));
        assert_eq!(t.observe(Some(Vector3::new(2.0, 0.0, 0.0))), Err(BallIgnored::OutsideHittingArea));
        let next = Vector3::new(-0.01, 0.003, 0.0);
        assert!(t.observe(Some(next)).is_err());
        assert_eq!(t.observe(Some(next)), Ok(true), "the next ball teed up");
        assert_eq!(t.position(), (next, true));
        assert_eq!(t.observe(Some(next)), Ok(false), "still at rest: nothing moved");
    }
}
