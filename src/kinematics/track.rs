//! A per-rig track: validates samples in arrival order, keeps the recent history, counts what it rejects.

use std::collections::VecDeque;

use super::sample::{unit_quaternion, Calibration, ClubPose, ClubheadSample};
use crate::math::{Isometry3, Real, Translation3Ext};

/// Why a sample was not accepted.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum Reject {
    #[error("non-finite field `{field}`")]
    NonFinite { field: &'static str },
    #[error("orientation is not a unit quaternion (norm {norm:.4})")]
    NotUnitQuaternion { norm: Real },
    #[error("position {distance_m:.1} m from the lab origin is implausible (millimetres sent as metres?)")]
    OutOfRange { distance_m: Real },
    #[error("duplicate frame {frame} (t_ns {t_ns})")]
    Duplicate { frame: u64, t_ns: u64 },
    #[error("frame {frame} goes back in time ({back_ns} ns before the previous)")]
    Backwards { frame: u64, back_ns: u64 },
    #[error("implausible jump: {speed_mps:.0} m/s since the previous frame")]
    Jump { speed_mps: Real },
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
}

impl Default for TrackLimits {
    fn default() -> Self {
        TrackLimits {
            history: 64,
            max_speed_mps: 150.0,
            max_distance_m: 50.0,
            quaternion_tolerance: 0.01,
            reset_gap_s: 0.25,
        }
    }
}

/// What the track did with one sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Accepted {
    /// A new pose (with the number of frames missing before it).
    Pose { dropped_before: u64 },
    /// The rig flagged the frame occluded; nothing was added.
    Occluded,
}

/// Counts over the life of a track.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TrackCounts {
    pub accepted: u64,
    pub occluded: u64,
    pub dropped: u64,
    pub rejected: u64,
}

/// The recent accepted poses of one rig's clubhead.
#[derive(Debug, Clone)]
pub struct Track {
    limits: TrackLimits,
    calibration: Calibration,
    poses: VecDeque<ClubPose>,
    last_frame: Option<(u64, u64)>,
    pub counts: TrackCounts,
}

impl Track {
    pub fn new(calibration: Calibration, limits: TrackLimits) -> Self {
        Track {
            limits,
            calibration,
            poses: VecDeque::with_capacity(limits.history + 1),
            last_frame: None,
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

    fn check(&mut self, s: &ClubheadSample) -> Result<Accepted, Reject> {
        if let Some((frame, t_ns)) = self.last_frame {
            if s.t_ns == t_ns || s.frame == frame {
                return Err(Reject::Duplicate { frame: s.frame, t_ns: s.t_ns });
            }
            if s.t_ns < t_ns || s.frame < frame {
                return Err(Reject::Backwards { frame: s.frame, back_ns: t_ns.saturating_sub(s.t_ns) });
            }
        }
        let dropped_before = self.last_frame.map(|(f, _)| s.frame.saturating_sub(f + 1)).unwrap_or(0);
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
