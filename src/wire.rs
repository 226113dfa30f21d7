//! Messages on the wire: serde types with units in their field names, their key expressions and encodings
//! (DESIGN.md section 4). Every key expression is built in [`keys`], with its payload documented beside it. Every
//! message type has a JSON Schema in `schemas/` generated from these types ([`schemas`]).
//!
//! This module holds the JSON forms only; it depends on no transport.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::kinematics::{ClubheadSample, Quality};

use crate::impact::{Delivery, DeliveryMetrics, Equipment, ImpactError, Launch, LaunchMetrics};
use crate::math::{mirror_z_axial, Real, Vector3};
use crate::units::{deg_to_rad, mm_to_m, mph_to_mps};

mod measured;
pub use measured::{ComparisonMessage, LaunchFields, MeasuredClubData, MeasuredLaunch};

/// Which hand the golfer plays. Left-handed deliveries are mirrored (z -> -z) into a right-handed world before
/// any model runs, and the launch is mirrored back.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Handedness {
    #[default]
    Right,
    Left,
}

/// A TrackMan-style delivery as read by `impactd predict`: flat fields with units in their names. Missing numbers
/// default to 0, except `dynamic_loft_deg`, which defaults to the club's static loft.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DeliveryInput {
    #[serde(default)]
    pub club_speed_mph: Real,
    #[serde(default)]
    pub attack_angle_deg: Real,
    #[serde(default)]
    pub club_path_deg: Real,
    #[serde(default)]
    pub face_angle_deg: Real,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dynamic_loft_deg: Option<Real>,
    #[serde(default)]
    pub impact_h_mm: Real,
    #[serde(default)]
    pub impact_v_mm: Real,
    /// Angular velocity of the head, rad/s, world frame.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub club_angular_velocity_radps: Option<[Real; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub handedness: Option<Handedness>,
}

impl DeliveryInput {
    /// The delivery in SI for a club of the given static loft, mirrored into the right-handed world for a
    /// left-handed golfer.
    pub fn to_delivery(&self, static_loft_deg: Real) -> Delivery {
        let w = self.club_angular_velocity_radps.map(Vector3::from).unwrap_or_else(Vector3::zeros);
        let left = self.handedness == Some(Handedness::Left);
        let s = if left { -1.0 } else { 1.0 };
        Delivery {
            club_speed_mps: mph_to_mps(self.club_speed_mph),
            attack_angle_rad: deg_to_rad(self.attack_angle_deg),
            club_path_rad: s * deg_to_rad(self.club_path_deg),
            face_angle_rad: s * deg_to_rad(self.face_angle_deg),
            dynamic_loft_rad: deg_to_rad(self.dynamic_loft_deg.unwrap_or(static_loft_deg)),
            impact_h_m: mm_to_m(self.impact_h_mm),
            impact_v_m: mm_to_m(self.impact_v_mm),
            club_angular_velocity_radps: if left { mirror_z_axial(&w) } else { w },
        }
    }

    /// The first non-finite field, named.
    pub fn check_finite(&self) -> Result<(), ImpactError> {
        let mut fields = vec![
            ("club_speed_mph", self.club_speed_mph),
            ("attack_angle_deg", self.attack_angle_deg),
            ("club_path_deg", self.club_path_deg),
            ("face_angle_deg", self.face_angle_deg),
            ("impact_h_mm", self.impact_h_mm),
            ("impact_v_mm", self.impact_v_mm),
        ];
        if let Some(l) = self.dynamic_loft_deg {
            fields.push(("dynamic_loft_deg", l));
        }
        if let Some(w) = self.club_angular_velocity_radps {
            fields.extend(w.iter().map(|v| ("club_angular_velocity_radps", *v)));
        }
        match fields.into_iter().find(|(_, v)| !v.is_finite()) {
            Some((field, _)) => Err(ImpactError::NotFinite { field }),
            None => Ok(()),
        }
    }
}

/// A launch as read by `impactd flight`: the fields `impactd predict` writes. The vectors, when present, are used
/// as they are; otherwise speed, angles and spins (backspin and sidespin, or total spin and spin axis).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FlightInput {
    pub ball_speed_mps: Option<Real>,
    pub ball_speed_mph: Option<Real>,
    #[serde(default)]
    pub launch_angle_deg: Real,
    #[serde(default)]
    pub launch_direction_deg: Real,
    pub backspin_rpm: Option<Real>,
    pub sidespin_rpm: Option<Real>,
    pub total_spin_rpm: Option<Real>,
    pub spin_axis_deg: Option<Real>,
    pub smash_factor: Option<Real>,
    pub spin_loft_deg: Option<Real>,
    pub face_to_path_deg: Option<Real>,
    pub ball_velocity_mps: Option<[Real; 3]>,
    pub ball_spin_radps: Option<[Real; 3]>,
}

impl FlightInput {
    /// The launch state, or the reason it cannot be made.
    pub fn to_launch(&self) -> Result<crate::flight::LaunchState, String> {
        let finite =
            |name: &str, v: Real| if v.is_finite() { Ok(v) } else { Err(format!("field `{name}` must be finite")) };
        if let (Some(v), Some(w)) = (self.ball_velocity_mps, self.ball_spin_radps) {
            for x in v.iter() {
                finite("ball_velocity_mps", *x)?;
            }
            for x in w.iter() {
                finite("ball_spin_radps", *x)?;
            }
            let speed = Vector3::from(v).norm();
            if !(1.0..=150.0).contains(&speed) {
                return Err(format!("field `ball_velocity_mps`: speed {speed:.1} m/s is outside 1-150 m/s"));
            }
            return Ok(crate::flight::LaunchState { velocity_mps: Vector3::from(v), spin_radps: Vector3::from(w) });
        }
        let speed = match (self.ball_speed_mps, self.ball_speed_mph) {
            (Some(v), _) => finite("ball_speed_mps", v)?,
            (None, Some(v)) => crate::units::mph_to_mps(finite("ball_speed_mph", v)?),
            (None, None) => return Err("field `ball_speed_mps` (or `ball_speed_mph`) is missing".into()),
        };
        if !(1.0..=150.0).contains(&speed) {
            return Err(format!("field `ball_speed_mps`: {speed:.1} m/s is outside 1-150 m/s"));
        }
        let launch = finite("launch_angle_deg", self.launch_angle_deg)?;
        if !(-30.0..=80.0).contains(&launch) {
            return Err(format!("field `launch_angle_deg`: {launch} is outside -30 to 80 deg"));
        }
        let direction = finite("launch_direction_deg", self.launch_direction_deg)?;
        let (back, side) = match (self.backspin_rpm, self.sidespin_rpm, self.total_spin_rpm, self.spin_axis_deg) {
            (Some(b), s, _, _) => (finite("backspin_rpm", b)?, finite("sidespin_rpm", s.unwrap_or(0.0))?),
            (None, _, Some(t), axis) => {
                let a = finite("spin_axis_deg", axis.unwrap_or(0.0))?.to_radians();
                let t = finite("total_spin_rpm", t)?;
                (t * a.cos(), t * a.sin())
            }
            (None, s, None, _) => (0.0, finite("sidespin_rpm", s.unwrap_or(0.0))?),
        };
        if back.hypot(side) > 20_000.0 {
            return Err("spin above 20000 rpm".into());
        }
        Ok(crate::flight::LaunchState::from_metrics(speed, launch, direction, back, side))
    }
}

/// One answer of `impactd predict`: the launch (TrackMan names) and the delivery numbers that explain it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PredictOutput {
    #[serde(flatten)]
    pub launch: LaunchMetrics,
    pub smash_factor: Real,
    pub spin_loft_deg: Real,
    pub face_to_path_deg: Real,
    pub ball_velocity_mps: [Real; 3],
    pub ball_spin_radps: [Real; 3],
    /// Sanity flags (`impact::sanity`): empty for a shot a golfer could hit.
    #[serde(default)]
    pub warnings: Vec<crate::impact::LaunchWarning>,
}

impl PredictOutput {
    /// Builds the answer with its sanity flags, mirroring back into the golfer's world for a left-hander.
    pub fn new(launch: &Launch, delivery: &DeliveryMetrics, handedness: Handedness, equipment: &Equipment) -> Self {
        let (v, w) = match handedness {
            Handedness::Right => (launch.ball_velocity_mps, launch.ball_spin_radps),
            Handedness::Left => {
                (crate::math::mirror_z(&launch.ball_velocity_mps), mirror_z_axial(&launch.ball_spin_radps))
            }
        };
        let metrics = LaunchMetrics::from_ball(&v, &w);
        let sign = if handedness == Handedness::Left { -1.0 } else { 1.0 };
        let smash_factor = metrics.ball_speed_mps / delivery.club_speed_mps;
        PredictOutput {
            warnings: crate::impact::sanity::warnings(&metrics, smash_factor, equipment),
            smash_factor,
            launch: metrics,
            spin_loft_deg: delivery.spin_loft_deg,
            face_to_path_deg: sign * delivery.face_to_path_deg,
            ball_velocity_mps: [v.x, v.y, v.z],
            ball_spin_radps: [w.x, w.y, w.z],
        }
    }
}

/// Version of every message type below; part of the encoding `application/json;impactd.<Type>/<version>`.
pub const WIRE_VERSION: u32 = 1;

/// Largest accepted payload (bytes): a clubhead sample is about 200.
pub const MAX_PAYLOAD_BYTES: usize = 64 * 1024;

/// The encoding string of a message type: `application/json;impactd.LaunchPrediction/1`.
pub fn encoding(type_name: &str) -> String {
    format!("application/json;impactd.{type_name}/{WIRE_VERSION}")
}

/// Key expressions (no leading `/`), each with its payload.
pub mod keys {
    /// In: [`ClubheadSampleMsg`](super::ClubheadSampleMsg) from the rig, `mocap/<rig>/clubhead`.
    pub fn clubhead(rig: &str) -> String {
        format!("mocap/{rig}/clubhead")
    }
    /// Every rig's clubhead samples.
    pub const CLUBHEAD_ALL: &str = "mocap/*/clubhead";
    /// Out: [`ImpactMessage`](super::ImpactMessage), the estimated state at impact.
    pub fn impact(rig: &str) -> String {
        format!("golf/{rig}/impact")
    }
    /// Out: [`LaunchPrediction`](super::LaunchPrediction).
    pub fn launch(rig: &str) -> String {
        format!("golf/{rig}/launch")
    }
    /// Out, once a second: [`StatusMessage`](super::StatusMessage).
    pub fn status(rig: &str) -> String {
        format!("golf/{rig}/status")
    }
    /// Liveliness token of the daemon serving a rig.
    pub fn alive(rig: &str) -> String {
        format!("golf/{rig}/impactd/alive")
    }
    /// Queryable: the daemon's configuration for the rig (JSON, read-only).
    pub fn config(rig: &str) -> String {
        format!("golf/{rig}/impactd/config")
    }
    /// Out of `impactd sim`: [`TruthMessage`](super::TruthMessage), what the synthetic rig really swung.
    pub fn truth(rig: &str) -> String {
        format!("sim/{rig}/truth")
    }
    /// In: [`MeasuredLaunch`](super::MeasuredLaunch) from a launch monitor (or the Open Connect listener).
    pub fn measured_launch(rig: &str) -> String {
        format!("lm/{rig}/launch")
    }
    /// Out: [`ComparisonMessage`](super::ComparisonMessage), a prediction paired with its measurement.
    pub fn comparison(rig: &str) -> String {
        format!("golf/{rig}/comparison")
    }
    /// The rig name of a `mocap/<rig>/clubhead` key.
    pub fn rig_of_clubhead(key: &str) -> Option<&str> {
        let rest = key.strip_prefix("mocap/")?;
        let rig = rest.strip_suffix("/clubhead")?;
        (!rig.is_empty() && !rig.contains('/')).then_some(rig)
    }
    /// Whether a rig name can stand in a key expression.
    pub fn valid_rig_name(rig: &str) -> bool {
        !rig.is_empty() && rig.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    }
}

/// A unit quaternion `{x, y, z, w}` (Vicon and Foxglove order).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct QuaternionMsg {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub w: f64,
}

impl From<crate::math::UnitQuaternion> for QuaternionMsg {
    fn from(q: crate::math::UnitQuaternion) -> Self {
        QuaternionMsg { x: q.i, y: q.j, z: q.k, w: q.w }
    }
}

/// One motion-capture frame of the tracked body, lab frame, on `mocap/<rig>/clubhead`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ClubheadSampleMsg {
    pub rig: String,
    pub frame: u64,
    /// Capture time on the rig's clock (ns).
    pub t_ns: u64,
    pub position_m: [f64; 3],
    pub orientation: QuaternionMsg,
    #[serde(default)]
    pub occluded: bool,
}

impl ClubheadSampleMsg {
    pub fn to_sample(&self) -> ClubheadSample {
        let q = &self.orientation;
        ClubheadSample {
            frame: self.frame,
            t_ns: self.t_ns,
            position_m: crate::math::Vector3::from(self.position_m),
            orientation_xyzw: [q.x, q.y, q.z, q.w],
            occluded: self.occluded,
        }
    }

    pub fn from_sample(rig: &str, s: &ClubheadSample) -> Self {
        let [x, y, z, w] = s.orientation_xyzw;
        ClubheadSampleMsg {
            rig: rig.to_string(),
            frame: s.frame,
            t_ns: s.t_ns,
            position_m: [s.position_m.x, s.position_m.y, s.position_m.z],
            orientation: QuaternionMsg { x, y, z, w },
            occluded: s.occluded,
        }
    }
}

/// Why an incoming payload was not a usable sample.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InputError {
    #[error("payload of {bytes} bytes is over the {MAX_PAYLOAD_BYTES}-byte limit")]
    Oversized { bytes: usize },
    #[error("encoding `{encoding}` is not {expected}")]
    WrongVersion { encoding: String, expected: String },
    #[error("malformed sample: {0}")]
    Malformed(String),
    #[error("sample names rig `{payload}` but arrived on the key of rig `{key}`")]
    RigMismatch { payload: String, key: String },
}

impl InputError {
    pub fn key(&self) -> &'static str {
        match self {
            InputError::Oversized { .. } => "oversized",
            InputError::WrongVersion { .. } => "wrong_version",
            InputError::Malformed(_) => "malformed",
            InputError::RigMismatch { .. } => "rig_mismatch",
        }
    }
}

/// Parses a sample arriving on the key of `key_rig` with the given encoding (empty or plain
/// `application/json` is accepted; an `impactd.ClubheadSample/<v>` schema must name this version).
pub fn parse_sample(key_rig: &str, payload: &[u8], encoding: &str) -> Result<ClubheadSampleMsg, InputError> {
    if payload.len() > MAX_PAYLOAD_BYTES {
        return Err(InputError::Oversized { bytes: payload.len() });
    }
    if let Some(schema) = encoding.split_once(';').map(|(_, s)| s) {
        if schema.starts_with("impactd.ClubheadSample/") && schema != format!("impactd.ClubheadSample/{WIRE_VERSION}") {
            return Err(InputError::WrongVersion {
                encoding: encoding.to_string(),
                expected: self::encoding("ClubheadSample"),
            });
        }
    }
    let msg: ClubheadSampleMsg = serde_json::from_slice(payload).map_err(|e| InputError::Malformed(e.to_string()))?;
    if msg.rig != key_rig {
        return Err(InputError::RigMismatch { payload: msg.rig, key: key_rig.to_string() });
    }
    Ok(msg)
}

/// The estimated club state at impact (world frame), in an [`ImpactMessage`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ImpactStateMsg {
    pub cg_position_m: [f64; 3],
    pub orientation: QuaternionMsg,
    pub cg_velocity_mps: [f64; 3],
    pub angular_velocity_radps: [f64; 3],
    pub impact_h_mm: f64,
    pub impact_v_mm: f64,
}

impl From<&crate::impact::ImpactState> for ImpactStateMsg {
    fn from(s: &crate::impact::ImpactState) -> Self {
        let p = s.world_from_club.translation.vector;
        let (v, w) = (s.cg_velocity_mps, s.angular_velocity_radps);
        ImpactStateMsg {
            cg_position_m: [p.x, p.y, p.z],
            orientation: s.world_from_club.rotation.into(),
            cg_velocity_mps: [v.x, v.y, v.z],
            angular_velocity_radps: [w.x, w.y, w.z],
            impact_h_mm: s.impact_h_m * 1e3,
            impact_v_mm: s.impact_v_m * 1e3,
        }
    }
}

/// The impact as estimated from the frames, on `golf/<rig>/impact`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ImpactMessage {
    pub rig: String,
    pub shot: u64,
    /// The frame that revealed the impact.
    pub frame: u64,
    pub t_impact_ns: u64,
    pub club: String,
    pub estimator: String,
    pub state: ImpactStateMsg,
    pub delivery: crate::impact::DeliveryMetrics,
    pub quality: Quality,
}

/// A predicted launch, on `golf/<rig>/launch`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct LaunchPrediction {
    pub rig: String,
    pub shot: u64,
    /// The frame that revealed the impact.
    pub frame: u64,
    pub t_impact_ns: u64,
    pub club: String,
    pub model: String,
    pub estimator: String,
    pub delivery: crate::impact::DeliveryMetrics,
    pub launch: PredictOutput,
    pub frames_used: usize,
    /// The estimate's quality score in (0, 1] (see `Quality`).
    pub quality: f64,
    /// Time from receiving the revealing frame to publishing this prediction (us), measured live; a replay
    /// carries the recorded value.
    pub latency_us: f64,
    /// Carry, apex, landing and offline of this launch (absent when the rig's `flight = false`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flight: Option<crate::flight::Trajectory>,
}

/// Health of one rig, once a second on `golf/<rig>/status`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct StatusMessage {
    pub rig: String,
    /// Wall-clock time of this status (ns since the Unix epoch).
    pub t_ns: u64,
    pub uptime_s: f64,
    /// Samples received for this rig (good or bad).
    pub samples: u64,
    pub accepted: u64,
    pub occluded: u64,
    /// Frames missing from the rig's frame numbering.
    pub dropped: u64,
    /// Samples rejected, by reason.
    pub rejected: BTreeMap<String, u64>,
    pub shots: u64,
    pub predictions: u64,
    /// Impacts without a prediction, by reason.
    pub failed: BTreeMap<String, u64>,
    /// Predictions that raised each sanity flag (`impact::sanity`), by flag.
    #[serde(default)]
    pub flagged: BTreeMap<String, u64>,
    pub latency_p50_us: f64,
    pub latency_p99_us: f64,
    /// Messages the recorder could not keep up with (never silently lost: counted here).
    pub recorder_dropped: u64,
}

/// A payload that was not a usable sample, kept in a recording beside the reason (nothing is lost).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct RejectedInput {
    pub reason: String,
    pub bytes: usize,
    /// The payload as text (invalid UTF-8 replaced), at most `MAX_PAYLOAD_BYTES`.
    pub payload: String,
}

/// What a synthetic rig really swung, on `sim/<rig>/truth`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct TruthMessage {
    pub rig: String,
    pub shot: u64,
    pub t_impact_ns: u64,
    pub club: String,
    pub delivery: crate::impact::DeliveryMetrics,
    /// The adjusted impulse-momentum launch of the true state.
    pub launch: PredictOutput,
}

/// Every message type with its JSON Schema, as written to `schemas/<Type>.json`.
pub fn schemas() -> Vec<(&'static str, String)> {
    fn one<T: JsonSchema>() -> String {
        let mut s = serde_json::to_string_pretty(&schemars::schema_for!(T)).unwrap_or_default();
        s.push('\n');
        s
    }
    vec![
        ("ClubheadSample", one::<ClubheadSampleMsg>()),
        ("ImpactMessage", one::<ImpactMessage>()),
        ("LaunchPrediction", one::<LaunchPrediction>()),
        ("StatusMessage", one::<StatusMessage>()),
        ("TruthMessage", one::<TruthMessage>()),
        ("RejectedInput", one::<RejectedInput>()),
        ("DeliveryInput", one::<DeliveryInput>()),
        ("PredictOutput", one::<PredictOutput>()),
        ("FlightInput", one::<FlightInput>()),
        ("Trajectory", one::<crate::flight::Trajectory>()),
        ("MeasuredLaunch", one::<MeasuredLaunch>()),
        ("ComparisonMessage", one::<ComparisonMessage>()),
    ]
}
