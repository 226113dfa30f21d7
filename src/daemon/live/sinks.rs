//! Where one rig's messages go: its zenoh publishers (when publishing) and the recording (when recording). The
//! live daemon and `impactd replay --publish -o` both write through [`RigSinks`], so a replay publishes and
//! records what the daemon does, on the same keys with the same schemas.

use std::collections::BTreeMap;

use zenoh::Wait;

use crate::daemon::recording::record::Record;
use crate::daemon::recording::writer::RecorderHandle;
use crate::daemon::stats::LatencyWindow;
use crate::daemon::DaemonError;
use crate::kinematics::ClubheadSample;
use crate::math::Isometry3;
use crate::pipeline::{CounterKind, Counts, Pipeline, Rejection};
use crate::wire::{
    keys, ClubheadSampleMsg, ComparisonMessage, FlightLine, ImpactMessage, LaunchPrediction, MeasuredLaunch, Message,
    MessageType, RejectedInput, StatusMessage,
};

/// Takes the points of a prediction's flight out of it (its sampled line is for the recording, the live view and
/// `golf/<rig>/flight`, never the prediction's own message); `None` when its flight sampled none.
pub fn take_line(l: &mut LaunchPrediction) -> Option<Vec<[f64; 4]>> {
    l.flight.as_mut().map(|f| std::mem::take(&mut f.points)).filter(|p| !p.is_empty())
}

/// A rig's key expressions, built once.
struct RigKeys {
    clubhead: String,
    rejected: String,
    impact: String,
    launch: String,
    status: String,
    measured: String,
    measured_rejected: String,
    comparison: String,
}

impl RigKeys {
    fn new(rig: &str) -> Self {
        RigKeys {
            clubhead: keys::clubhead(rig),
            rejected: keys::rejected(rig),
            impact: keys::impact(rig),
            launch: keys::launch(rig),
            status: keys::status(rig),
            measured: keys::measured_launch(rig),
            measured_rejected: format!("{}/rejected", keys::measured_launch(rig)),
            comparison: keys::comparison(rig),
        }
    }
}

/// The zenoh publishers of one rig's outputs.
pub struct RigPublishers {
    impact: zenoh::pubsub::Publisher<'static>,
    launch: zenoh::pubsub::Publisher<'static>,
    flight: zenoh::pubsub::Publisher<'static>,
    status: zenoh::pubsub::Publisher<'static>,
    comparison: zenoh::pubsub::Publisher<'static>,
}

impl RigPublishers {
    /// Declares the publishers of `golf/<rig>/impact`, `.../launch`, `.../flight`, `.../status` and
    /// `.../comparison` with their encodings.
    pub async fn declare(session: &zenoh::Session, rig: &str) -> Result<Self, DaemonError> {
        async fn one<M: Message>(
            session: &zenoh::Session,
            key: String,
        ) -> Result<zenoh::pubsub::Publisher<'static>, DaemonError> {
            session.declare_publisher(key).encoding(M::TYPE.encoding()).await.map_err(DaemonError::zenoh)
        }
        Ok(RigPublishers {
            impact: one::<ImpactMessage>(session, keys::impact(rig)).await?,
            launch: one::<LaunchPrediction>(session, keys::launch(rig)).await?,
            flight: one::<FlightLine>(session, keys::flight(rig)).await?,
            status: one::<StatusMessage>(session, keys::status(rig)).await?,
            comparison: one::<ComparisonMessage>(session, keys::comparison(rig)).await?,
        })
    }
}

/// One rig's outputs: zenoh (when `publishers` is given) and the recording (when the recorder is enabled).
pub struct RigSinks {
    rig: String,
    keys: RigKeys,
    publishers: Option<RigPublishers>,
    recorder: RecorderHandle,
    ball_position_m: [f64; 3],
    ball_radius_m: f64,
    /// The rig's flight model, for the predicted flight's line (Foxglove).
    flight: Option<crate::flight::Flight>,
    /// The time between the points of a prediction's own flight line (`RigSetup::flight_line_step_s`).
    line_step_s: f64,
}

impl RigSinks {
    /// The sinks of the rig of `pipeline` (its ball position and radius go into the impact scene, its flight
    /// model draws the predicted flight).
    pub fn new(pipeline: &Pipeline, publishers: Option<RigPublishers>, recorder: RecorderHandle) -> Self {
        let setup = &pipeline.setup;
        RigSinks {
            rig: setup.name.clone(),
            keys: RigKeys::new(&setup.name),
            publishers,
            recorder,
            ball_position_m: setup.detector.ball_position_m.into(),
            ball_radius_m: setup.detector.ball_radius_m,
            flight: setup.flight,
            line_step_s: setup.flight_line_step_s,
        }
    }

    pub fn recorder(&self) -> &RecorderHandle {
        &self.recorder
    }

    fn record<M: Message>(&self, key: &str, log_time_ns: u64, publish_time_ns: u64, data: Vec<u8>) {
        if self.recorder.enabled() {
            let message_type: MessageType = M::TYPE;
            self.recorder.send(Record::Message {
                key: key.to_string(),
                message_type,
                log_time_ns,
                publish_time_ns,
                data,
            });
        }
    }

    fn publish(
        &self,
        publisher: impl Fn(&RigPublishers) -> &zenoh::pubsub::Publisher<'static>,
        what: &str,
        data: &[u8],
    ) {
        if let Some(p) = &self.publishers {
            if let Err(e) = publisher(p).put(data.to_vec()).wait() {
                tracing::error!("rig {}: publishing the {what}: {e}", self.rig);
            }
        }
    }

    /// Records an accepted sample's payload as it arrived.
    pub fn sample(&self, log_time_ns: u64, t_ns: u64, payload: Vec<u8>) {
        self.record::<ClubheadSampleMsg>(&self.keys.clubhead, log_time_ns, t_ns, payload);
    }

    /// Records a payload that was not a usable sample, beside the reason (nothing is lost).
    pub fn rejected(&self, log_time_ns: u64, rejected: &RejectedInput) {
        let data = serde_json::to_vec(rejected).unwrap_or_default();
        self.record::<RejectedInput>(&self.keys.rejected, log_time_ns, log_time_ns, data);
    }

    /// Records the club's pose in the world at a sample (for Foxglove).
    pub fn club_pose(&self, t_ns: u64, log_time_ns: u64, world_from_club: Isometry3) {
        if self.recorder.enabled() {
            self.recorder.send(Record::ClubPose { rig: self.rig.clone(), t_ns, log_time_ns, world_from_club });
        }
    }

    /// Publishes and records an impact, and records the scene of ball and club.
    pub fn impact(&self, m: &ImpactMessage, now_ns: u64) {
        let data = serde_json::to_vec(m).unwrap_or_default();
        self.publish(|p| &p.impact, "impact", &data);
        self.record::<ImpactMessage>(&self.keys.impact, now_ns, now_ns, data);
        if self.recorder.enabled() {
            self.recorder.send(Record::ImpactScene {
                rig: self.rig.clone(),
                t_ns: m.t_impact_ns,
                log_time_ns: now_ns,
                ball_position_m: m.ball.map_or(self.ball_position_m, |b| b.position_m),
                ball_radius_m: self.ball_radius_m,
                club: m.state,
            });
        }
    }

    /// Publishes and records a prediction and the line of its flight (`line`: the points of the prediction's
    /// own flight, taken out of it, also published on `golf/<rig>/flight`; without them flown by the recorder
    /// or the live view, off the prediction path), and closes the recording's chunk (a shot is never
    /// half-written).
    pub fn launch_with_line(&self, l: &LaunchPrediction, line: Option<Vec<[f64; 4]>>, now_ns: u64) -> Vec<u8> {
        let data = self.publish_launch(l);
        self.publish_flight(l, line.as_deref());
        self.record_launch(l, data, line, now_ns)
    }

    /// Publishes a prediction on `golf/<rig>/launch` (nothing else: the latency ends here); returns its JSON
    /// for [`RigSinks::record_launch`].
    pub fn publish_launch(&self, l: &LaunchPrediction) -> Vec<u8> {
        let data = serde_json::to_vec(l).unwrap_or_default();
        self.publish(|p| &p.launch, "launch", &data);
        data
    }

    /// Publishes the line of a published prediction's flight on `golf/<rig>/flight` (`points`: the prediction's
    /// own, sampled while it was flown; nothing without them).
    pub fn publish_flight(&self, l: &LaunchPrediction, points: Option<&[[f64; 4]]>) {
        let (Some(points), Some(_)) = (points, &self.publishers) else { return };
        let line = FlightLine {
            rig: l.rig.clone(),
            shot: l.shot,
            model: l.model.clone(),
            t_impact_ns: l.t_impact_ns,
            step_s: self.line_step_s,
            points: points.to_vec(),
        };
        let data = serde_json::to_vec(&line).unwrap_or_default();
        self.publish(|p| &p.flight, "flight line", &data);
    }

    /// Records a published prediction (`data`, from [`RigSinks::publish_launch`]) and the line of its flight,
    /// and closes the recording's chunk (a shot is never half-written). Returns `data`.
    pub fn record_launch(
        &self,
        l: &LaunchPrediction,
        data: Vec<u8>,
        line: Option<Vec<[f64; 4]>>,
        now_ns: u64,
    ) -> Vec<u8> {
        self.record::<LaunchPrediction>(&self.keys.launch, now_ns, now_ns, data.clone());
        if let (true, Some(flight)) = (self.recorder.enabled(), self.flight) {
            let points = line.map(std::sync::Arc::new);
            self.recorder.send(crate::daemon::recording::channels::flight_record(l, flight, points, now_ns));
        }
        self.recorder.send(Record::Flush);
        data
    }

    /// An impact without a prediction: closes the recording's chunk.
    pub fn failed(&self) {
        self.recorder.send(Record::Flush);
    }

    /// Publishes and records a status.
    pub fn status(&self, status: &StatusMessage) {
        let data = serde_json::to_vec(status).unwrap_or_default();
        self.publish(|p| &p.status, "status", &data);
        self.record::<StatusMessage>(&self.keys.status, status.t_ns, status.t_ns, data);
    }

    /// Records a measured launch's payload as it arrived on `lm/<rig>/launch` (whatever its source).
    pub fn measured(&self, log_time_ns: u64, t_ns: u64, payload: Vec<u8>) {
        self.record::<MeasuredLaunch>(&self.keys.measured, log_time_ns, t_ns, payload);
    }

    /// Records a synthetic rig's truth as it arrived (`sim/<rig>/truth`).
    pub fn truth(&self, log_time_ns: u64, t_impact_ns: u64, payload: Vec<u8>) {
        self.record::<crate::wire::TruthMessage>(
            &crate::wire::keys::truth(&self.rig),
            log_time_ns,
            t_impact_ns,
            payload,
        );
    }

    /// Records the rig's club from now on (`golf/<rig>/club`).
    pub fn club_change(&self, log_time_ns: u64, change: &crate::wire::ClubChange) {
        let data = serde_json::to_vec(change).unwrap_or_default();
        self.record::<crate::wire::ClubChange>(&crate::wire::keys::club(&self.rig), log_time_ns, log_time_ns, data);
    }

    /// Records a tracked ball's sample as it arrived (`mocap/<rig>/ball`).
    pub fn ball(&self, log_time_ns: u64, t_ns: u64, payload: Vec<u8>) {
        self.record::<crate::wire::BallSampleMsg>(&crate::wire::keys::ball(&self.rig), log_time_ns, t_ns, payload);
    }

    /// Records the session labels a put set (`golf/<rig>/session`).
    pub fn labels(&self, log_time_ns: u64, labels: &crate::wire::ShotLabels) {
        let data = serde_json::to_vec(labels).unwrap_or_default();
        self.record::<crate::wire::ShotLabels>(&crate::wire::keys::session(&self.rig), log_time_ns, log_time_ns, data);
    }

    /// Records a shot's exclusion from the session (`golf/<rig>/exclude`).
    pub fn exclusion(&self, log_time_ns: u64, x: &crate::wire::ShotExclusion) {
        let data = serde_json::to_vec(x).unwrap_or_default();
        let key = crate::wire::keys::exclude(&self.rig);
        self.record::<crate::wire::ShotExclusion>(&key, log_time_ns, log_time_ns, data);
        self.recorder.send(Record::Flush);
    }

    /// Records a measured-launch payload that could not be used, beside the reason.
    pub fn measured_rejected(&self, log_time_ns: u64, rejected: &RejectedInput) {
        let data = serde_json::to_vec(rejected).unwrap_or_default();
        self.record::<RejectedInput>(&self.keys.measured_rejected, log_time_ns, log_time_ns, data);
    }

    /// Publishes and records a comparison of a prediction with its measurement, and closes the chunk.
    pub fn comparison(&self, c: &ComparisonMessage, now_ns: u64) {
        let data = serde_json::to_vec(c).unwrap_or_default();
        self.publish(|p| &p.comparison, "comparison", &data);
        self.record::<ComparisonMessage>(&self.keys.comparison, now_ns, now_ns, data);
        self.recorder.send(Record::Flush);
    }
}

/// What a rig's status reports besides its pipeline's counts.
pub struct StatusInputs<'a> {
    pub counts: &'a Counts,
    /// Samples dropped before the pipeline (a full queue).
    pub queue_dropped: u64,
    pub latency: &'a LatencyWindow,
    pub uptime_s: f64,
    pub t_ns: u64,
    pub unknown_rig_samples: u64,
    pub rejected_not_recorded: u64,
    pub recorder_error: Option<String>,
}

/// A rig's status message.
pub fn status_message(rig: &str, s: StatusInputs<'_>, recorder_dropped: u64) -> StatusMessage {
    let c = s.counts;
    let mut rejected: BTreeMap<String, u64> = c.rejected.to_wire();
    if s.queue_dropped > 0 {
        rejected.insert(Rejection::QueueFull.wire_name().into(), s.queue_dropped);
    }
    StatusMessage {
        rig: rig.to_string(),
        t_ns: s.t_ns,
        uptime_s: s.uptime_s,
        samples: c.samples + s.queue_dropped,
        accepted: c.accepted,
        occluded: c.occluded,
        dropped: c.dropped,
        resets: c.resets,
        rejected,
        shots: c.shots,
        predictions: c.predictions,
        failed: c.failed.to_wire(),
        flagged: c.flagged.to_wire(),
        latency_p50_us: s.latency.quantile(0.5),
        latency_p99_us: s.latency.quantile(0.99),
        recorder_dropped,
        unknown_rig_samples: s.unknown_rig_samples,
        rejected_not_recorded: s.rejected_not_recorded,
        recorder_error: s.recorder_error,
        simulator: None,
        input: None,
        launch_monitor: None,
        comparison: None,
        live_view: None,
        web: None,
        club: None,
    }
}

/// The club in the world at a sample, if its orientation is usable.
pub fn world_from_club(pipeline: &Pipeline, sample: &ClubheadSample) -> Option<Isometry3> {
    let q = crate::kinematics::sample::unit_quaternion(&sample.orientation_xyzw, 0.01)?;
    let lab = Isometry3::from_parts(sample.position_m.into(), q);
    Some(pipeline.setup.calibration.world_from_club(&lab))
}
