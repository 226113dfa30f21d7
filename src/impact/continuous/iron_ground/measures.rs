//! What a run measures of the strike as it steps: the ground's contact time, first touch, divot length, peaks,
//! and the ball's contact.
//!
//! The ground's contact and the divot are integrated over each interval between two evaluated states, the
//! part in contact found by interpolating the sole's sinkage (and the leading edge's depth) linearly between the
//! ends: second order in the step where counting whole steps from their start would be first order (a
//! contact ending mid-step counted the whole step).

use crate::math::{Real, Vector3};

/// The ground's state at one evaluated instant.
#[derive(Debug, Clone, Copy)]
pub(super) struct GroundSample {
    pub t_s: Real,
    /// The sole's deepest sinkage (m; ≤ 0 when clear).
    pub sinkage_m: Real,
    /// The leading edge's depth below the surface (m; negative above); the sole's sinkage when the sole is
    /// clear (the leading edge is on the sole, so no deeper).
    pub edge_depth_m: Real,
    /// The head's horizontal speed (m/s).
    pub horizontal_speed_mps: Real,
}

#[derive(Debug, Default)]
pub(super) struct Measures {
    pub ball_touched: bool,
    pub t_ball_s: Real,
    pub t_separation_s: Real,
    pub first_ground_s: Option<Real>,
    pub ground_time_s: Real,
    pub ball_time_s: Real,
    pub peak_ground_n: Real,
    pub peak_ball_n: Real,
    pub max_sinkage_m: Real,
    pub divot_length_m: Real,
    pub speed_loss_mps: Real,
    pub face_change_deg: Real,
    pub loft_change_deg: Real,
    pub ground_impulse_before_ball: Vector3,
    last: Option<GroundSample>,
}

/// The fraction of an interval where a quantity interpolated linearly from `a` to `b` is positive.
fn positive_fraction(a: Real, b: Real) -> Real {
    match (a > 0.0, b > 0.0) {
        (true, true) => 1.0,
        (false, false) => 0.0,
        (true, false) => a / (a - b),
        (false, true) => b / (b - a),
    }
}

impl Measures {
    /// The ground at the next evaluated instant, with the resultant force on the head then (N).
    pub fn ground(&mut self, now: GroundSample, force_n: Real) {
        if now.sinkage_m > 0.0 {
            self.peak_ground_n = self.peak_ground_n.max(force_n);
            self.max_sinkage_m = self.max_sinkage_m.max(now.sinkage_m);
        }
        let Some(last) = self.last.replace(now) else {
            if now.sinkage_m > 0.0 {
                self.first_ground_s = Some(now.t_s);
            }
            return;
        };
        let h = now.t_s - last.t_s;
        let f = positive_fraction(last.sinkage_m, now.sinkage_m);
        if f > 0.0 {
            self.ground_time_s += f * h;
            // Entering during the interval: the touch is where the sinkage crosses zero.
            let touch = if last.sinkage_m > 0.0 { last.t_s } else { now.t_s - f * h };
            self.first_ground_s.get_or_insert(touch);
        }
        let divot = positive_fraction(last.edge_depth_m, now.edge_depth_m);
        self.divot_length_m += divot * h * 0.5 * (last.horizontal_speed_mps + now.horizontal_speed_mps);
    }
}
