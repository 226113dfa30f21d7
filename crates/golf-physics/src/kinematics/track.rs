//! A per-rig track: validates samples in arrival order, keeps the recent history, counts what it rejects.
//!
//! Capture times order the stream; frame numbers only count dropped frames. A sample far ahead of (or behind)
//! the current time base is held as a candidate, never adopted as "now": the next sample on the current base
//! discards it, and only `resync_frames` consecutive samples that agree with each other on a new base (a
//! publisher that restarted its clock, a long pause) move the track onto it, counted as a reset. Frame numbers
//! that go back or leap while time goes on (a restarted or wrapping counter, a hostile number) resynchronise
//! the frame count, also counted as a reset, without adding implausible drops. So one hostile sample costs at
//! most the swing it lands in.

use std::collections::VecDeque;

use super::sample::{unit_quaternion, Calibration, ClubPose, ClubheadSample};
use crate::math::{Isometry3, Real, Translation3Ext};

/// Why a sample was not accepted.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum Reject {
    /// A position or orientation component is NaN or infinite.
    #[error("non-finite field `{field}`")]
    NonFinite {
        /// The sample's field that holds it (`position_m` or `orientation`).
        field: &'static str,
    },
    /// The orientation's norm is further from 1 than [`TrackLimits::quaternion_tolerance`].
    #[error("orientation is not a unit quaternion (norm {norm:.4})")]
    NotUnitQuaternion {
        /// The quaternion's norm as sent.
        norm: Real,
    },
    /// The position is further from the lab origin than [`TrackLimits::max_distance_m`].
    #[error("position {distance_m:.1} m from the lab origin is implausible (millimetres sent as metres?)")]
    OutOfRange {
        /// The position's distance from the lab origin (m).
        distance_m: Real,
    },
    /// The sample has the same capture time as the previous frame.
    #[error("duplicate frame {frame} (t_ns {t_ns})")]
    Duplicate {
        /// The sample's frame number.
        frame: u64,
        /// The capture time it shares with the previous frame (ns, rig clock).
        t_ns: u64,
    },
    /// The sample's capture time is before the previous frame's (held as a candidate for a new time base).
    #[error("frame {frame} goes back in time ({back_ns} ns before the previous)")]
    Backwards {
        /// The sample's frame number.
        frame: u64,
        /// How far its capture time is before the previous frame's (ns).
        back_ns: u64,
    },
    /// The calibrated club position moved faster than [`TrackLimits::max_speed_mps`] since the newest pose.
    #[error("implausible jump: {speed_mps:.0} m/s since the previous frame")]
    Jump {
        /// The speed the move implies: the distance between the two club-frame origins (world) over the time
        /// between them (m/s).
        speed_mps: Real,
    },
    /// The sample is further ahead of the previous frame than [`TrackLimits::max_ahead_s`] (held as a candidate
    /// for a new time base).
    #[error("frame {frame} is {ahead_ns} ns ahead of the rig's time base (held as an outlier)")]
    Outlier {
        /// The sample's frame number.
        frame: u64,
        /// How far its capture time is after the previous frame's (ns).
        ahead_ns: u64,
    },
    /// The sample agrees with a held candidate for a new time base, which fewer than
    /// [`TrackLimits::resync_frames`] consecutive samples confirm so far.
    #[error("frame {frame} is on a new time base; waiting for it to be confirmed")]
    Resyncing {
        /// The sample's frame number.
        frame: u64,
    },
}

impl Reject {
    /// A short stable key for counters (`non_finite`, `jump`...).
    pub fn key(&self) -> &'static str {
        match self {
            Reject::NonFinite { .. } => "non_finite",
            Reject::NotUnitQuaternion { .. } => "not_unit_quaternion",
            Reject::OutOfRange { .. } => "out_of_range",
            Reject::Duplicate { .. } => "duplicate",
            Reject::Backwards { .. } => "backwards",
            Reject::Jump { .. } => "jump",
            Reject::Outlier { .. } => "outlier",
            Reject::Resyncing { .. } => "resyncing",
        }
    }
}

/// Limits of the track.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackLimits {
    /// Frames kept.
    pub history: usize,
    /// Largest plausible speed between consecutive frames (m/s).
    pub max_speed_mps: Real,
    /// Largest plausible distance from the lab origin (m).
    pub max_distance_m: Real,
    /// Allowed deviation of the quaternion norm from 1.
    pub quaternion_tolerance: Real,
    /// After this long without a frame, the history restarts (s).
    pub reset_gap_s: Real,
    /// A sample further ahead of the newest than this is held as an outlier until confirmed (s).
    pub max_ahead_s: Real,
    /// Consecutive samples on a new time base that move the track onto it.
    pub resync_frames: u32,
    /// The highest frame rate frame numbers are believed at: a larger jump in frame numbers than this rate
    /// explains is a new frame count, not dropped frames (Hz).
    pub max_rate_hz: Real,
}

impl Default for TrackLimits {
    fn default() -> Self {
        TrackLimits {
            history: 64,
            max_speed_mps: 150.0,
            max_distance_m: 50.0,
            quaternion_tolerance: 0.01,
            reset_gap_s: 0.25,
            max_ahead_s: 5.0,
            resync_frames: 3,
            max_rate_hz: 20_000.0,
        }
    }
}

/// What the track did with one sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Accepted {
    /// A new pose.
    Pose {
        /// Frames missing between it and the previous accepted or occluded sample, by their frame numbers.
        dropped_before: u64,
    },
    /// The rig flagged the frame occluded; nothing was added.
    Occluded,
}

/// Counts over the life of a track.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TrackCounts {
    /// Samples added as poses.
    pub accepted: u64,
    /// Samples the rig flagged occluded (counted, no pose added).
    pub occluded: u64,
    /// Frames missing between consecutive accepted or occluded samples, from the gaps in their frame numbers.
    pub dropped: u64,
    /// Samples refused with a [`Reject`].
    pub rejected: u64,
    /// Time bases or frame counts the track moved onto (publisher restarts, wrapped counters).
    pub resets: u64,
}

/// The recent accepted poses of one rig's clubhead.
#[derive(Debug, Clone)]
pub struct Track {
    limits: TrackLimits,
    calibration: Calibration,
    poses: VecDeque<ClubPose>,
    last_frame: Option<(u64, u64)>,
    /// A sample off the current time base, and how many consecutive samples agree with it.
    candidate: Option<(u64, u32)>,
    /// What the track has done with the samples pushed so far.
    pub counts: TrackCounts,
}

impl Track {
    /// An empty track whose samples `calibration` takes to club poses in the world, checked against `limits`.
    pub fn new(calibration: Calibration, limits: TrackLimits) -> Self {
        Track {
            limits,
            calibration,
            poses: VecDeque::with_capacity(limits.history + 1),
            last_frame: None,
            candidate: None,
            counts: TrackCounts::default(),
        }
    }

    /// Validates and adds a sample.
    pub fn push(&mut self, s: &ClubheadSample) -> Result<Accepted, Reject> {
        let r = self.check(s);
        if r.is_err() {
            self.counts.rejected += 1;
        }
        r
    }

    /// Where a sample stands against the time base: `Ok(dropped frames before it)` when it belongs to it.
    fn order(&mut self, s: &ClubheadSample) -> Result<u64, Reject> {
        let Some((frame, t_ns)) = self.last_frame else { return Ok(0) };
        if s.t_ns == t_ns {
            return Err(Reject::Duplicate { frame: s.frame, t_ns: s.t_ns });
        }
        let ahead_ns = s.t_ns.wrapping_sub(t_ns);
        let on_base = s.t_ns > t_ns && (ahead_ns as Real) * 1e-9 <= self.limits.max_ahead_s;
        if !on_base {
            // Off the base: a candidate for a new one, confirmed only by consecutive samples that follow it.
            let follows = self
                .candidate
                .is_some_and(|(t0, _)| s.t_ns > t0 && ((s.t_ns - t0) as Real) * 1e-9 <= self.limits.reset_gap_s);
            let n = if follows { self.candidate.map_or(1, |(_, n)| n + 1) } else { 1 };
            self.candidate = Some((s.t_ns, n));
            if n < self.limits.resync_frames.max(1) {
                return Err(if n > 1 {
                    Reject::Resyncing { frame: s.frame }
                } else if s.t_ns > t_ns {
                    Reject::Outlier { frame: s.frame, ahead_ns }
                } else {
                    Reject::Backwards { frame: s.frame, back_ns: t_ns - s.t_ns }
                });
            }
            self.resync();
            return Ok(0);
        }
        self.candidate = None;
        // Frame numbers: a gap the elapsed time explains is dropped frames; anything else a new count.
        let explained = (ahead_ns as Real) * 1e-9 * self.limits.max_rate_hz + 1.0;
        match s.frame.checked_sub(frame) {
            Some(gap) if gap >= 1 && (gap as Real) <= explained => Ok(gap - 1),
            _ => {
                self.counts.resets += 1;
                Ok(0)
            }
        }
    }

    /// Moves onto a new time base: the history is dropped, the reset counted.
    fn resync(&mut self) {
        self.candidate = None;
        self.last_frame = None;
        self.poses.clear();
        self.counts.resets += 1;
    }

    fn check(&mut self, s: &ClubheadSample) -> Result<Accepted, Reject> {
        let dropped_before = self.order(s)?;
        if s.occluded {
            self.last_frame = Some((s.frame, s.t_ns));
            self.counts.occluded += 1;
            self.counts.dropped += dropped_before;
            return Ok(Accepted::Occluded);
        }
        if s.position_m.iter().any(|v| !v.is_finite()) {
            return Err(Reject::NonFinite { field: "position_m" });
        }
        if s.orientation_xyzw.iter().any(|v| !v.is_finite()) {
            return Err(Reject::NonFinite { field: "orientation" });
        }
        let distance_m = s.position_m.norm();
        if distance_m > self.limits.max_distance_m {
            return Err(Reject::OutOfRange { distance_m });
        }
        let q = unit_quaternion(&s.orientation_xyzw, self.limits.quaternion_tolerance).ok_or_else(|| {
            Reject::NotUnitQuaternion { norm: s.orientation_xyzw.iter().map(|v| v * v).sum::<Real>().sqrt() }
        })?;
        let lab_from_body = Isometry3::from_parts(s.position_m.into_translation(), q);
        let world_from_club = self.calibration.world_from_club(&lab_from_body);
        if let Some(prev) = self.poses.back() {
            let dt = (s.t_ns - prev.t_ns) as Real * 1e-9;
            if dt > self.limits.reset_gap_s {
                self.poses.clear();
            } else {
                let d = (world_from_club.translation.vector - prev.world_from_club.translation.vector).norm();
                let speed_mps = d / dt;
                if speed_mps > self.limits.max_speed_mps {
                    return Err(Reject::Jump { speed_mps });
                }
            }
        }
        self.last_frame = Some((s.frame, s.t_ns));
        self.counts.accepted += 1;
        self.counts.dropped += dropped_before;
        if self.poses.len() == self.limits.history {
            self.poses.pop_front();
        }
        self.poses.push_back(ClubPose { frame: s.frame, t_ns: s.t_ns, world_from_club });
        Ok(Accepted::Pose { dropped_before })
    }

    /// The accepted poses, oldest first.
    pub fn poses(&self) -> &VecDeque<ClubPose> {
        &self.poses
    }

    /// The newest accepted pose.
    pub fn latest(&self) -> Option<&ClubPose> {
        self.poses.back()
    }
}
