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
    pub ground_impulse_before_ball_n_s: Vector3,
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

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(t_s: Real, sinkage_m: Real) -> GroundSample {
        GroundSample { t_s, sinkage_m, edge_depth_m: sinkage_m - 0.002, horizontal_speed_mps: 40.0 }
    }

    /// A sinkage that rises linearly through zero at 0.25 ms, stays, and falls through zero at 1.6 ms, sampled
    /// every 0.3 ms: the contact is 1.35 ms and starts at 0.25 ms exactly (linear ends are interpolated
    /// exactly), where whole steps from their start would give 1.5 ms starting at 0.3 ms.
    #[test]
    fn contact_ends_are_interpolated_between_samples() {
        let sinkage = |t: Real| (2.0 * (t - 0.25e-3)).min(1e-3).min(2.0 * (1.6e-3 - t));
        let mut m = Measures::default();
        for k in 0..8 {
            let t = k as Real * 0.3e-3;
            m.ground(sample(t, sinkage(t)), 10.0);
        }
        assert!((m.ground_time_s - 1.35e-3).abs() < 1e-12, "{}", m.ground_time_s);
        assert!((m.first_ground_s.unwrap_or(0.0) - 0.25e-3).abs() < 1e-12);
        // The leading edge, 2 mm above the deepest point, never reaches the surface: the sinkage peaks at 1 mm.
        assert_eq!(m.divot_length_m, 0.0);
        assert!((m.max_sinkage_m - 1e-3).abs() < 1e-12 && m.peak_ground_n == 10.0);
    }

    /// A leading edge below the surface for half of one interval at 40 m/s cuts 40 m/s x half the interval.
    #[test]
    fn divot_length_over_the_part_of_an_interval_in_the_soil() {
        let mut m = Measures::default();
        let at = |t_s: Real, edge_depth_m: Real| GroundSample {
            t_s,
            sinkage_m: 0.01,
            edge_depth_m,
            horizontal_speed_mps: 40.0,
        };
        m.ground(at(0.0, -1e-3), 0.0);
        m.ground(at(1e-4, 1e-3), 0.0);
        assert!((m.divot_length_m - 40.0 * 0.5e-4).abs() < 1e-15, "{}", m.divot_length_m);
        assert_eq!(positive_fraction(-1.0, -2.0), 0.0);
        assert_eq!(positive_fraction(1.0, 3.0), 1.0);
        assert!((positive_fraction(3.0, -1.0) - 0.75).abs() < 1e-15);
    }
}
