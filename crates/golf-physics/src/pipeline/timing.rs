//! What the pipeline says beside its launches: swings that found no impact ([`Event::Missed`]), and, once the
//! frames after an impact have come, where the head's speed stepped down against the instant the estimate used
//! ([`Event::ImpactTiming`]; `kinematics::contact_step`). A launch is published at the revealing frame, before
//! those frames exist, so this comes as an event of its own.

use super::{Event, Pipeline};
use crate::kinematics::contact_step::{self, SpeedStep, StepUnresolved, MAX_FRAMES_PER_SIDE, WINDOW_S};
use crate::kinematics::frame_gap::FrameGap;
use crate::kinematics::guards::MAX_BALL_FROM_FACE_AT_ADDRESS_M;
use crate::kinematics::{ClubPose, ImpactEstimate};
use crate::math::{Point3, Real, Vector3};

/// The impact instant an estimate used, and the head's speed step measured from the frames around it.
#[derive(Debug, Clone, PartialEq)]
pub struct ImpactTimingReport {
    /// The shot's number on its rig.
    pub shot: u64,
    /// The frame that revealed the impact.
    pub frame: u64,
    /// The instant the estimate used (ns, the rig's clock): the geometric contact, or the given instant.
    pub impact_t_ns: u64,
    /// The instant was the user's (`--impact-frame`, `--impact-time`).
    pub given: bool,
    /// The step, or why none was placed.
    pub step: Result<SpeedStep, StepUnresolved>,
}

impl ImpactTimingReport {
    /// The step's instant (ns), when placed.
    pub fn step_t_ns(&self) -> Option<u64> {
        let s = self.step.as_ref().ok()?;
        Some((self.impact_t_ns as i128 + (s.t_from_contact_s * 1e9).round() as i128).max(0) as u64)
    }

    /// The two instants disagree by more than the frame interval.
    pub fn disagrees(&self) -> bool {
        self.step.as_ref().is_ok_and(|s| s.disagrees())
    }
}

impl std::fmt::Display for ImpactTimingReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let what = if self.given { "the given instant" } else { "the geometric contact" };
        write!(f, "shot {}: impact at {what} {:.6} s", self.shot, self.impact_t_ns as Real * 1e-9)?;
        match &self.step {
            Ok(s) => {
                write!(
                    f,
                    "; the head's speed steps down at {:.6} s (+-{:.2} ms; {:.1} -> {:.1} m/s, {:.1} %): {:+.2} ms \
                     apart, ",
                    self.step_t_ns().unwrap_or(0) as Real * 1e-9,
                    s.sigma_s * 1e3,
                    s.speed_before_mps,
                    s.speed_after_mps,
                    s.drop_pct(),
                    s.t_from_contact_s * 1e3
                )?;
                if s.disagrees() {
                    write!(
                        f,
                        "warning: more than the frame interval ({:.2} ms): the ball position or the calibration \
                         puts the contact elsewhere (--impact-time {:.6} makes the estimate at the step)",
                        s.interval_s * 1e3,
                        self.step_t_ns().unwrap_or(0) as Real * 1e-9
                    )
                } else {
                    write!(f, "within the frame interval ({:.2} ms)", s.interval_s * 1e3)
                }
            }
            Err(e) => write!(f, "; no speed step placed: {e}"),
        }
    }
}

/// A step waiting for the frames after its impact.
#[derive(Debug, Clone)]
pub(super) struct PendingStep {
    report: ImpactTimingReport,
    /// (time from the impact instant (s), face centre (world, m)).
    frames: Vec<(Real, Vector3)>,
    after: usize,
    noise_floor_m: Real,
}

impl Pipeline {
    /// The face centre of a pose (world, m).
    pub(super) fn face_centre(&self, pose: &ClubPose) -> Vector3 {
        (pose.world_from_club * Point3::from(self.setup.club.face.center_m)).coords
    }

    /// Watches the swing and the pending step with the pose the track accepted last.
    pub(super) fn watch_pose(&mut self, out: &mut dyn FnMut(Event)) {
        let Some(pose) = self.track.latest().copied() else { return };
        let centre = self.face_centre(&pose);
        let config = &self.detector.config;
        let ball = config.ball_position_m;
        let ball_club = pose.world_from_club.inverse_transform_point(&Point3::from(ball)).coords;
        let seen = crate::kinematics::miss_watch::SeenPose {
            frame: pose.frame,
            t_ns: pose.t_ns,
            centre_m: centre,
            ball_club_m: ball_club,
            ball_world_m: ball,
        };
        if let Some(m) = self.swings.on_pose(&seen, &self.setup.club, config.ball_radius_m) {
            self.counts.missed_swings += 1;
            out(Event::Missed(m));
        }
        self.feed_step(&pose, centre, out);
    }

    fn feed_step(&mut self, pose: &ClubPose, centre: Vector3, out: &mut dyn FnMut(Event)) {
        let Some(p) = &mut self.step else { return };
        let t = (pose.t_ns as i128 - p.report.impact_t_ns as i128) as Real * 1e-9;
        if t > 0.0 {
            if t <= WINDOW_S {
                p.frames.push((t, centre));
                p.after += 1;
            }
            if t > WINDOW_S || p.after >= MAX_FRAMES_PER_SIDE {
                self.resolve_step(out);
            }
        }
    }

    /// Places the pending step with the frames it has.
    pub(super) fn resolve_step(&mut self, out: &mut dyn FnMut(Event)) {
        if let Some(mut p) = self.step.take() {
            p.report.step = contact_step::find(&p.frames, p.noise_floor_m);
            out(Event::ImpactTiming(p.report));
        }
    }

    /// After an estimate: its step waits for the frames after it, from the frames before it.
    pub(super) fn await_step(&mut self, shot: u64, frame: u64, est: &ImpactEstimate, given: bool) {
        let impact = est.t_impact_ns;
        let frames = self
            .detector
            .pre_impact()
            .iter()
            .map(|p| ((p.t_ns as i128 - impact as i128) as Real * 1e-9, p))
            .filter(|(t, _)| *t < 0.0 && -*t <= WINDOW_S)
            .map(|(t, p)| (t, self.face_centre(p)))
            .collect();
        self.step = Some(PendingStep {
            report: ImpactTimingReport {
                shot,
                frame,
                impact_t_ns: impact,
                given,
                step: Err(StepUnresolved::TooFewFrames { before: 0, after: 0 }),
            },
            frames,
            after: 0,
            noise_floor_m: est.quality.residual_rms_mm * 1e-3,
        });
    }

    /// The longest gap in the frames the estimate fitted, up to its impact instant.
    pub(super) fn frame_gap(est: &ImpactEstimate, given: bool) -> Option<FrameGap> {
        let shift = if given { est.t_from_reveal_s } else { 0.0 };
        let t: Vec<Real> = est.fits.frame_t_s[..est.fits.frames].iter().map(|t| t - shift).collect();
        FrameGap::longest(&t)
    }

    /// The face centre's distance from the ball at the swing's address, when beyond the bound.
    pub(super) fn far_address(&self) -> Option<Real> {
        self.swings.address().map(|a| a.1).filter(|d| *d > MAX_BALL_FROM_FACE_AT_ADDRESS_M)
    }

    /// The input ended: the swing in progress and the pending step are reported.
    pub fn finish(&mut self, out: &mut dyn FnMut(Event)) {
        self.resolve_step(out);
        if let Some(m) = self.swings.end() {
            self.counts.missed_swings += 1;
            out(Event::Missed(m));
        }
    }
}

impl Pipeline {
    /// An estimator's refusal for a person: a contact not reached also says on which side of the face the ball
    /// was and by how much.
    pub(super) fn explain(&self, e: &crate::kinematics::EstimateError) -> String {
        match *e {
            crate::kinematics::EstimateError::NoContact { gap_mm, h_mm, v_mm, past: false } => {
                let club = &self.setup.club;
                let r = self.detector.config.ball_radius_m;
                let gap = crate::face::FaceGap { distance_m: gap_mm * 1e-3 + r, h_m: h_mm * 1e-3, v_m: v_mm * 1e-3 };
                let miss =
                    crate::kinematics::guards::Miss::of(&gap, r, club.face_half_width_m, club.face_half_height_m);
                format!("{e}: {miss}")
            }
            _ => e.to_string(),
        }
    }
}
