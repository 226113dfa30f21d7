//! Gaps in the frames an estimate bridged: frames missing (dropped, occluded or refused) between the fitted
//! frames or between the newest of them and the frame that revealed the impact. A fit bridges such a gap by
//! interpolating or extrapolating the motion, so the launch says how long it was (`frame_gap_before_impact`).

use super::guards::GAP_INTERVALS;
use crate::math::Real;

/// The longest gap in the frames before an impact.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct FrameGap {
    /// Frames missing in it (its length over the frame interval, less one).
    pub frames: u32,
    /// Its length, from the frame before it to the frame after it (ms).
    pub gap_ms: Real,
    /// How long before the revealing frame it ended (ms; 0: the revealing frame followed the gap).
    pub ends_before_reveal_ms: Real,
}

impl FrameGap {
    /// The longest gap among frames at `t_s` (oldest first, times from the revealing frame, all negative) and
    /// the revealing frame (at 0) that is at least [`GAP_INTERVALS`] frame intervals long; the interval is the
    /// median spacing of the frames.
    pub fn longest(t_s: &[Real]) -> Option<FrameGap> {
        if t_s.len() < 2 {
            return None;
        }
        let mut spacing: Vec<Real> = t_s.windows(2).map(|w| w[1] - w[0]).chain([-t_s[t_s.len() - 1]]).collect();
        let gaps = spacing.clone();
        spacing.sort_by(|a, b| a.total_cmp(b));
        let interval = spacing[spacing.len() / 2];
        if interval.is_nan() || interval <= 0.0 {
            return None;
        }
        let (i, longest) = gaps.iter().copied().enumerate().max_by(|a, b| a.1.total_cmp(&b.1))?;
        if longest < GAP_INTERVALS * interval {
            return None;
        }
        let ends = t_s.get(i + 1).map_or(0.0, |t| -t);
        Some(FrameGap {
            frames: ((longest / interval).round() as u32).saturating_sub(1),
            gap_ms: longest * 1e3,
            ends_before_reveal_ms: ends * 1e3,
        })
    }
}

impl std::fmt::Display for FrameGap {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} frames missing before the impact ({:.1} ms without a frame, ending {:.1} ms before the revealing \
             frame), bridged by the fit",
            self.frames, self.gap_ms, self.ends_before_reveal_ms
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn times(rate_hz: Real, missing: &[i32]) -> Vec<Real> {
        (1..=20).rev().filter(|k| !missing.contains(k)).map(|k| -(k as Real) / rate_hz).collect()
    }

    #[test]
    fn three_missing_frames_before_impact_are_a_gap_of_three() {
        let g = FrameGap::longest(&times(360.0, &[1, 2, 3])).unwrap();
        assert_eq!(g.frames, 3);
        assert!((g.gap_ms - 4.0 / 0.360).abs() < 1e-9 && g.ends_before_reveal_ms == 0.0, "{g:?}");
        let mid = FrameGap::longest(&times(720.0, &[6, 7])).unwrap();
        assert_eq!(mid.frames, 2);
        assert!((mid.ends_before_reveal_ms - 5.0 / 0.72).abs() < 1e-9, "{mid:?}");
        assert!(FrameGap::longest(&times(720.0, &[])).is_none());
    }
}
