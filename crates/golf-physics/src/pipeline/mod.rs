//! The pure pipeline: samples in, events out. Live (zenoh) and replay (MCAP, JSONL) both drive it, so the same
//! samples in the same order give byte-identical predictions. No clocks, no IO: the caller measures latency.

mod counters;
pub use counters::{CounterKind, Counts, Failure, Rejection, Tally};
use std::collections::BTreeMap;

use crate::equipment::ClubSpec;
use std::sync::Arc;

use crate::impact::uncertainty::{linearised, LaunchJacobian};
use crate::impact::{DeliveryMetrics, Equipment, ImpactModel, ImpulseModel, ImpulseVariant};
use crate::kinematics::ball_tracker::{BallIgnored, BallTracker, BallTrackerConfig};
use crate::kinematics::track::Accepted;
use crate::kinematics::uncertainty::{estimate_uncertainty, CalibrationSigma};
use crate::kinematics::{
    Calibration, ClubheadSample, DetectorConfig, EstimatorSpec, ImpactDetector, Reject, Track, TrackLimits,
};
use crate::wire::{BallSource, BallUsed, ClubRef, ImpactMessage, LaunchPrediction, PredictOutput, ShotLabels};

/// Everything one rig's pipeline needs.
#[derive(Debug, Clone)]
pub struct RigSetup {
    /// The rig's name, as in its key expressions (`golf/<rig>/...`).
    pub name: String,
    /// The club swung (until a put or another tracked body changes it).
    pub club: ClubSpec,
    /// The models, in the order their predictions are published (built by `impact::registry`).
    pub models: Vec<Arc<dyn ImpactModel>>,
    /// How the state at impact is estimated from the frames around it.
    pub estimator: EstimatorSpec,
    /// The club frame's pose in the tracked body's frame.
    pub calibration: Calibration,
    /// Where the ball is and how an impact is recognised.
    pub detector: DetectorConfig,
    /// The track's limits: what a plausible next sample is.
    pub track: TrackLimits,
    /// The ball flight added to each prediction (`None`: no flight).
    pub flight: Option<crate::flight::Flight>,
    /// The labels of the rig's shots (from its configuration; [`Pipeline::set_labels`] replaces them).
    pub labels: ShotLabels,
    /// The club file of `club` (preset or path and its SHA-256), carried by every impact and launch.
    pub club_ref: Option<ClubRef>,
    /// Tracked bodies and the club each holds (`[rig.clubs]`): a sample of another body, once the current
    /// body has been out of view for [`BODY_SWITCH_AFTER_NS`], switches the club ([`Pipeline::on_body_sample_with`]).
    pub bodies: BTreeMap<String, ClubSwitch>,
    /// The calibration's residuals, carried into every prediction's uncertainty (zero: no calibration reports
    /// them yet).
    pub calibration_sigma: CalibrationSigma,
    /// Sample each prediction's flight every this many seconds (`Trajectory::points`, for a drawn line) when it
    /// is the flight of the launch as published (0: no points). The points come from the one flight that gives
    /// the carry, so whoever draws the line need not fly the ball again.
    pub flight_line_step_s: f64,
}

/// A club to switch to: the head, its models (built by `impact::registry`), its file, and for a tracked body
/// its calibration (the body's pose in the club frame).
#[derive(Debug, Clone)]
pub struct ClubSwitch {
    /// The clubhead.
    pub club: ClubSpec,
    /// Its models, in publication order.
    pub models: Vec<Arc<dyn ImpactModel>>,
    /// Its club file (preset or path and its SHA-256).
    pub club_ref: Option<ClubRef>,
    /// The body's pose in the club frame (`None`: the rig's calibration).
    pub calibration: Option<Calibration>,
}

/// How long the current body must have been out of view (no tracked sample, capture time) before another
/// body's tracked sample switches the club: a club set down or held aside, not a marker flicker (ns).
pub const BODY_SWITCH_AFTER_NS: u64 = 200_000_000;

impl RigSetup {
    /// A rig with the defaults: the slip model ([`crate::impact::registry::DEFAULT_MODEL`]) with the seed's
    /// parameters for the club, the `arc` estimator, identity calibration, ball at the origin.
    pub fn new(name: &str, club: ClubSpec) -> Self {
        RigSetup {
            name: name.to_string(),
            club,
            models: vec![Arc::new(ImpulseModel::new(ImpulseVariant::Slip))],
            estimator: EstimatorSpec::arc(),
            calibration: Calibration::default(),
            detector: DetectorConfig::default(),
            track: TrackLimits::default(),
            flight: Some(crate::flight::Flight::default()),
            labels: ShotLabels::default(),
            club_ref: None,
            bodies: BTreeMap::new(),
            calibration_sigma: CalibrationSigma::default(),
            flight_line_step_s: 0.0,
        }
    }
}

/// What one sample produced. A launch is the large variant; an event is made at most a few times per shot and
/// handed on by reference, so it is not boxed.
#[derive(Debug, Clone, PartialEq)]
#[allow(clippy::large_enum_variant)]
pub enum Event {
    /// The track refused the sample.
    Rejected {
        /// The sample's frame number.
        frame: u64,
        /// Why.
        reason: Reject,
    },
    /// An impact was found and estimated.
    Impact(ImpactMessage),
    /// ... and its launch predicted by one model (`latency_us` is 0 here; the caller fills it in). With two
    /// models there are two, in publication order.
    Launch(LaunchPrediction),
    /// An impact was found but no prediction could be made.
    Failed {
        /// The shot's number on this rig.
        shot: u64,
        /// The frame that revealed the impact.
        frame: u64,
        /// What refused it, said for a person.
        reason: String,
        /// The counter it is counted under ([`Counts::failed`]).
        key: &'static str,
    },
    /// Another tracked body came into view: the rig's club is now this body's.
    ClubChanged(crate::wire::ClubChange),
    /// A swing ended without an impact: how it missed the ball (`kinematics::miss_watch`).
    Missed(crate::kinematics::miss_watch::MissedSwing),
    /// The frames after an impact have come: the head's speed step against the instant the estimate used.
    ImpactTiming(timing::ImpactTimingReport),
}

/// One rig's pipeline: track -> detect -> estimate -> model.
#[derive(Debug, Clone)]
pub struct Pipeline {
    /// The rig, as configured (and its club as switched since).
    pub setup: RigSetup,
    equipment: Equipment,
    track: Track,
    detector: ImpactDetector,
    estimators: Vec<EstimatorSpec>,
    /// A tracked ball's rest position (the fixed `ball_position_m` until one has rested).
    ball: BallTracker,
    /// What the pipeline has seen and produced.
    pub counts: Counts,
    /// The tracked body holding the club (`[rig.clubs]`) and the capture time of its last tracked sample.
    body: Option<(String, u64)>,
    /// Swings, for those that find no impact.
    swings: crate::kinematics::miss_watch::SwingWatch,
    /// The latest impact's speed step, waiting for the frames after it.
    step: Option<timing::PendingStep>,
}

impl Pipeline {
    /// A pipeline for one rig, before its first sample.
    pub fn new(setup: RigSetup) -> Self {
        Pipeline {
            equipment: Equipment::new(setup.club.clone()),
            track: Track::new(setup.calibration, setup.track),
            detector: ImpactDetector::new(setup.detector.clone()),
            estimators: vec![setup.estimator.clone()],
            ball: BallTracker::new(BallTrackerConfig::new(setup.detector.ball_position_m)),
            setup,
            counts: Counts::default(),
            body: None,
            swings: Default::default(),
            step: None,
        }
    }

    /// The rig's club as it is now (its name, and its file and SHA-256 when it came from one).
    pub fn club_ref(&self) -> ClubRef {
        self.setup.club_ref.clone().unwrap_or_else(|| ClubRef {
            name: self.setup.club.name.clone(),
            file: String::new(),
            sha256: String::new(),
        })
    }

    /// The rig's club as it is now, as recorded on `golf/<rig>/club`.
    pub fn club_change(&self, source: crate::wire::ClubSource, body: Option<String>) -> crate::wire::ClubChange {
        let club = self.club_ref();
        let models = self.setup.models.iter().map(|m| m.name().to_string()).collect();
        crate::wire::ClubChange { rig: self.setup.name.clone(), club, source, body, models }
    }

    /// The club from now on (a put on `golf/<rig>/club`, or a body's club): the same track and detector carry
    /// on unless the switch brings a body's calibration.
    pub fn switch_club(&mut self, switch: ClubSwitch) {
        self.equipment = Equipment::new(switch.club.clone());
        self.setup.club = switch.club;
        self.setup.models = switch.models;
        self.setup.club_ref = switch.club_ref;
        if let Some(calibration) = switch.calibration {
            self.setup.calibration = calibration;
            self.track = Track::new(calibration, self.setup.track);
            self.detector = ImpactDetector::new(self.setup.detector.clone());
        }
    }

    /// Feeds one sample of a tracked body (`None`: the rig's only body). With `[rig.clubs]`, a body not mapped
    /// is refused (`unknown_body`); another mapped body's tracked samples are set aside (`other_body`; its
    /// untracked ones count as occluded) until the current body has been out of view for
    /// [`BODY_SWITCH_AFTER_NS`], when its first tracked sample switches
    /// the club (a fresh track and detector: another object) and [`Event::ClubChanged`] says so.
    pub fn on_body_sample_with(&mut self, body: Option<&str>, sample: &ClubheadSample, out: &mut dyn FnMut(Event)) {
        if let (Some(name), false) = (body, self.setup.bodies.is_empty()) {
            let current = self.body.as_ref().map(|(b, t)| (b.as_str() == name, *t));
            match current {
                Some((true, _)) => {}
                _ if !self.setup.bodies.contains_key(name) => {
                    self.counts.samples += 1;
                    self.counts.rejected.add(Rejection::UnknownBody);
                    return;
                }
                Some((false, last_t_ns))
                    if !sample.occluded && sample.t_ns.saturating_sub(last_t_ns) < BODY_SWITCH_AFTER_NS =>
                {
                    self.counts.samples += 1;
                    self.counts.rejected.add(Rejection::OtherBody);
                    return;
                }
                // Another club out of view (in the bag): an occluded sample, not a rejection.
                Some((false, _)) | None if sample.occluded => {
                    self.counts.samples += 1;
                    self.counts.occluded += 1;
                    return;
                }
                _ => {
                    if let Some(switch) = self.setup.bodies.get(name).cloned() {
                        let calibration = switch.calibration.unwrap_or(self.setup.calibration);
                        self.switch_club(ClubSwitch { calibration: Some(calibration), ..switch });
                        out(Event::ClubChanged(self.club_change(crate::wire::ClubSource::Body, Some(name.into()))));
                    }
                }
            }
            if !sample.occluded {
                self.body = Some((name.to_string(), sample.t_ns));
            }
        }
        self.on_sample_with(sample, out);
    }

    /// The labels of the shots from now on (a put on `golf/<rig>/session`).
    pub fn set_labels(&mut self, labels: ShotLabels) {
        self.setup.labels = labels;
    }

    /// Takes an observation of a tracked ball's centre (lab frame, m; `None` when occluded): a ball at rest sets
    /// the position of the next impact ([`BallTracker`]). `Ok(true)` when it moved that position.
    pub fn on_ball(&mut self, position_lab_m: Option<[f64; 3]>) -> Result<bool, BallIgnored> {
        let world_from_lab = &self.setup.calibration.world_from_lab;
        let world = position_lab_m.map(|p| (world_from_lab * crate::math::Point3::from(p)).coords);
        let moved = self.ball.observe(world)?;
        if moved {
            self.detector.config.ball_position_m = self.ball.position().0;
        }
        Ok(moved)
    }

    /// The ball position the next impact uses, and where it comes from.
    pub fn ball_used(&self) -> BallUsed {
        let (p, tracked) = self.ball.position();
        BallUsed { position_m: p.into(), source: if tracked { BallSource::Tracked } else { BallSource::Config } }
    }

    /// Feeds one sample; events are appended to `out`.
    pub fn on_sample(&mut self, sample: &ClubheadSample, out: &mut Vec<Event>) {
        self.on_sample_with(sample, &mut |e| out.push(e));
    }

    /// Feeds one sample; each event goes to `emit` as soon as it exists (a fast model's launch before a slow
    /// model has run).
    pub fn on_sample_with(&mut self, sample: &ClubheadSample, out: &mut dyn FnMut(Event)) {
        self.counts.samples += 1;
        let pushed = self.track.push(sample);
        self.counts.resets = self.track.counts.resets;
        match pushed {
            Err(reason) => {
                self.counts.rejected.add(Rejection::from(&reason));
                out(Event::Rejected { frame: sample.frame, reason });
            }
            Ok(Accepted::Occluded) => {
                self.counts.occluded += 1;
                self.counts.dropped = self.track.counts.dropped;
            }
            Ok(Accepted::Pose { .. }) => {
                self.counts.accepted += 1;
                self.counts.dropped = self.track.counts.dropped;
                if let Some(detections) = self.detector.on_pose(&self.track, &self.setup.club, &self.estimators) {
                    self.swings.note_impact();
                    self.resolve_step(out);
                    for d in detections {
                        self.counts.shots += 1;
                        let shot = self.counts.shots;
                        self.predict(shot, d, out);
                    }
                }
                self.watch_pose(out);
            }
        }
    }

    fn fail(&mut self, shot: u64, frame: u64, reason: String, failure: Failure, out: &mut dyn FnMut(Event)) {
        self.counts.failed.add(failure);
        out(Event::Failed { shot, frame, reason, key: failure.wire_name() });
    }

    fn predict(&mut self, shot: u64, d: crate::kinematics::Detection, out: &mut dyn FnMut(Event)) {
        let est = match d.result {
            Ok(e) => e,
            Err(e) => return self.fail(shot, d.reveal_frame, self.explain(&e), Failure::from(&e), out),
        };
        let given = self.detector.config.given_impact.is_some();
        let club = &self.setup.club;
        let mut delivery = DeliveryMetrics::from_state(&est.state, club);
        if let Some(why) = crate::kinematics::guards::head_speed_refusal(delivery.club_speed_mps) {
            return self.fail(shot, d.reveal_frame, why, Failure::HeadSpeedBeyondBound, out);
        }
        self.await_step(shot, d.reveal_frame, &est, given);
        let (frame_gap, far_address) = (Self::frame_gap(&est, given), self.far_address());
        let impact_timing = crate::wire::ImpactTimingMsg::of(given, frame_gap, far_address);
        let club = &self.setup.club;
        // Once per impact: the plane and low point of the path over the frames before it (docs/club-data.md).
        let config = &self.detector.config;
        let scene = crate::kinematics::Scene {
            face: &club.face,
            ball_position_m: config.ball_position_m,
            ball_radius_m: config.ball_radius_m,
            max_extrapolation_s: config.max_extrapolation_s,
        };
        // How sure the delivery is (kinematics::uncertainty) and, below, each launch (impact::uncertainty).
        let uncertainty = estimate_uncertainty(&est, &scene, club, &self.setup.calibration_sigma);
        delivery.uncertainty = uncertainty.map(|u| u.delivery.sigmas());
        delivery.swing_arc = crate::kinematics::club_data::swing_arc(
            self.detector.pre_impact(),
            d.reveal_t_ns,
            est.t_from_reveal_s,
            est.arc.as_ref(),
            &club.face.center_m,
            &config.ball_position_m,
            config.ball_radius_m,
        );
        out(Event::Impact(ImpactMessage {
            rig: self.setup.name.clone(),
            shot,
            frame: d.reveal_frame,
            t_impact_ns: est.t_impact_ns,
            club: club.name.clone(),
            club_file: self.setup.club_ref.clone(),
            estimator: self.setup.estimator.name.clone(),
            state: (&est.state).into(),
            delivery,
            quality: est.quality,
            labels: self.setup.labels.clone(),
            ball: Some(self.ball_used()),
        }));
        let (linear_delivery, lie_rad) = (delivery.to_delivery(), delivery.dynamic_lie_deg.to_radians());
        let mut shared_jacobian = None;
        for i in 0..self.setup.models.len() {
            let m = Arc::clone(&self.setup.models[i]);
            // Each model's report (the ground model's `ground`) is published beside its launch.
            match m.run(&est.state, &self.equipment, &crate::impact::RunOptions::default()) {
                Ok(crate::impact::ModelRun { launch, report, .. }) => {
                    self.counts.predictions += 1;
                    let mut output = PredictOutput::new(&launch, &delivery, Default::default(), &self.equipment);
                    output.uncertainty = uncertainty.and_then(|u| {
                        let jacobian = |model: &dyn ImpactModel| {
                            LaunchJacobian::of(model, &self.equipment, &linear_delivery, lie_rad).ok()
                        };
                        let j = if m.linearises_itself() {
                            jacobian(m.as_ref())
                        } else {
                            *shared_jacobian
                                .get_or_insert_with(|| jacobian(linearised(&m, &self.setup.models).as_ref()))
                        };
                        j.map(|j| j.uncertainty(&u.delivery))
                    });
                    if frame_gap.is_some() {
                        output.warnings.push(crate::impact::LaunchWarning::FrameGapBeforeImpact);
                    }
                    if far_address.is_some() {
                        output.warnings.push(crate::impact::LaunchWarning::BallFarFromAddress);
                    }
                    for w in &output.warnings {
                        self.counts.flagged.add(*w);
                    }
                    let ball = crate::flight::LaunchState {
                        velocity_mps: launch.ball_velocity_mps,
                        spin_radps: launch.ball_spin_radps,
                    };
                    // The line is of the launch as published (mirrored for a left-handed club): sampled here
                    // only when that is the launch flown.
                    let (v, w) = (&launch.ball_velocity_mps, &launch.ball_spin_radps);
                    let published =
                        output.ball_velocity_mps == [v.x, v.y, v.z] && output.ball_spin_radps == [w.x, w.y, w.z];
                    let line_step_s = if published { self.setup.flight_line_step_s } else { 0.0 };
                    let flight = self.setup.flight.as_ref().map(|f| f.fly(&ball, line_step_s));
                    out(Event::Launch(LaunchPrediction {
                        rig: self.setup.name.clone(),
                        shot,
                        frame: d.reveal_frame,
                        t_impact_ns: est.t_impact_ns,
                        club: self.setup.club.name.clone(),
                        club_file: self.setup.club_ref.clone(),
                        model: m.name().to_string(),
                        estimator: self.setup.estimator.name.clone(),
                        delivery,
                        launch: output,
                        frames_used: est.quality.frames_used,
                        quality: est.quality.score,
                        latency_us: 0.0,
                        flight,
                        reports: report.into(),
                        labels: self.setup.labels.clone(),
                        ball: Some(self.ball_used()),
                        impact_timing,
                    }))
                }
                Err(e) => self.fail(shot, d.reveal_frame, format!("{}: {e}", m.name()), Failure::ModelRefused, out),
            }
        }
    }
}

#[cfg(test)]
mod tests;
mod timing;

pub use timing::ImpactTimingReport;
