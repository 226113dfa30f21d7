//! A marker capture's frames (C3D, TRC) as clubhead samples: each frame's markers of the set fitted to a pose
//! (`MarkerFitter`), in the file's lab axes and metres. `t_ns` is the 0-based frame index over the rate, `frame`
//! the capture's frame number (first frame + index); a frame with fewer than 3 valid markers (seen, and not
//! rejected by its residual) is `occluded`.

use super::{CaptureError, Frame, MarkerFrames};
use crate::kinematics::{FitFailure, MarkerFitter};
use crate::math::{Isometry3, Vector3};
use crate::wire::{ClubheadSampleMsg, QuaternionMsg};

/// What an import saw.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ImportCounts {
    pub frames: u64,
    /// Frames with fewer than 3 valid markers of the set (seen, and not rejected by their residual).
    pub occluded: u64,
    /// Of the occluded frames, those with 3 or more markers seen, left with fewer than 3 by rejection.
    pub occluded_by_rejection: u64,
    /// Markers dropped by their residual (swaps, ghosts).
    pub rejected_markers: u64,
}

/// Samples from a capture, one per frame.
pub struct CaptureSamples {
    reader: Box<dyn MarkerFrames>,
    fitter: MarkerFitter,
    rig: String,
    /// For each marker of the set, its point index in the file.
    indices: Vec<usize>,
    frame: Frame,
    lab_m: Vec<Option<Vector3>>,
    last_pose: Isometry3,
    /// The ball marker's point index and the offset from it to the ball's centre (lab, m).
    ball: Option<(usize, Vector3)>,
    pub counts: ImportCounts,
}

impl CaptureSamples {
    /// The samples of a marker capture's frames (a C3D reader, a TRC reader).
    pub fn new(reader: impl MarkerFrames + 'static, fitter: MarkerFitter, rig: &str) -> Result<Self, CaptureError> {
        Self::from_frames(Box::new(reader), fitter, rig)
    }

    pub fn from_frames(reader: Box<dyn MarkerFrames>, fitter: MarkerFitter, rig: &str) -> Result<Self, CaptureError> {
        let indices = fitter
            .set
            .indices_in(reader.labels())
            .map_err(|label| CaptureError::MissingMarker { label, available: reader.labels().join(", ") })?;
        Ok(CaptureSamples {
            reader,
            lab_m: Vec::with_capacity(indices.len()),
            fitter,
            rig: rig.to_string(),
            indices,
            frame: Frame::default(),
            last_pose: Isometry3::identity(),
            ball: None,
            counts: ImportCounts::default(),
        })
    }

    /// Reads the marker `label` as the ball: its position plus `offset_m` (lab frame, m; from a marker on the
    /// ball's surface to the ball's centre) is the ball's centre of each frame ([`CaptureSamples::ball`]).
    pub fn with_ball_marker(mut self, label: &str, offset_m: Vector3) -> Result<Self, CaptureError> {
        let labels = self.reader.labels();
        let index = labels
            .iter()
            .position(|l| l.trim() == label.trim())
            .ok_or_else(|| CaptureError::MissingMarker { label: label.to_string(), available: labels.join(", ") })?;
        self.ball = Some((index, offset_m));
        Ok(self)
    }

    /// The ball's sample of the frame [`CaptureSamples::next_sample`] read last (with a ball marker; occluded when
    /// the marker is not valid in that frame).
    pub fn ball(&self) -> Option<crate::wire::BallSampleMsg> {
        let (index, offset) = self.ball?;
        let at = self.frame.points_m.get(index).copied().flatten();
        let p = at.map_or([0.0; 3], |p| (p + offset).into());
        Some(crate::wire::BallSampleMsg {
            rig: self.rig.clone(),
            frame: self.reader.first_frame() + self.frame.index,
            t_ns: (self.frame.index as f64 * 1e9 / self.reader.rate_hz()).round() as u64,
            position_m: p,
            occluded: at.is_none(),
        })
    }

    /// The capture's frames.
    pub fn frames(&self) -> &dyn MarkerFrames {
        self.reader.as_ref()
    }

    /// The next frame's sample, `None` after the last frame.
    pub fn next_sample(&mut self) -> Result<Option<ClubheadSampleMsg>, CaptureError> {
        if !self.reader.next_frame(&mut self.frame)? {
            return Ok(None);
        }
        self.counts.frames += 1;
        self.lab_m.clear();
        self.lab_m.extend(self.indices.iter().map(|&i| self.frame.points_m.get(i).copied().flatten()));
        let (pose, occluded, residual) = match self.fitter.fit(&self.lab_m) {
            Ok(fit) => {
                self.counts.rejected_markers += u64::from(fit.rejected);
                self.last_pose = fit.lab_from_body;
                (fit.lab_from_body, false, Some(fit.residual_m))
            }
            Err(FitFailure::TooFew { .. }) => {
                self.counts.occluded += 1;
                (self.last_pose, true, None)
            }
            Err(FitFailure::Rejected { rejected, .. }) => {
                self.counts.occluded += 1;
                self.counts.occluded_by_rejection += 1;
                self.counts.rejected_markers += u64::from(rejected);
                (self.last_pose, true, None)
            }
        };
        let index = self.frame.index;
        let t_ns = (index as f64 * 1e9 / self.reader.rate_hz()).round() as u64;
        let p = pose.translation.vector;
        Ok(Some(ClubheadSampleMsg {
            rig: self.rig.clone(),
            frame: self.reader.first_frame() + index,
            t_ns,
            position_m: [p.x, p.y, p.z],
            orientation: QuaternionMsg::from(pose.rotation),
            occluded,
            fit_residual_m: residual,
            exposure_t_ns: None,
            system_latency_us: None,
            body: None,
        }))
    }
}

impl super::CaptureSource for CaptureSamples {
    fn next_sample(&mut self) -> Result<Option<ClubheadSampleMsg>, CaptureError> {
        CaptureSamples::next_sample(self)
    }

    fn ball(&self) -> Option<crate::wire::BallSampleMsg> {
        CaptureSamples::ball(self)
    }

    fn counts(&self) -> &ImportCounts {
        &self.counts
    }

    fn frames(&self) -> u64 {
        self.reader.frames()
    }

    fn warnings(&self) -> &[String] {
        self.reader.warnings()
    }
}
