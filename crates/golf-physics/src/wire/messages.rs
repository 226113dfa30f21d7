//! The messages of the pipeline: clubhead samples in; impacts and predictions out.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::PredictOutput;
use crate::kinematics::{ClubheadSample, Quality};

/// A unit quaternion `{x, y, z, w}` (Vicon and Foxglove order). Only the object form is read: an array is
/// refused with a reason, since rigs disagree on its order (`[x, y, z, w]` or `[w, x, y, z]`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct QuaternionMsg {
    /// The vector part's x.
    pub x: f64,
    /// The vector part's y.
    pub y: f64,
    /// The vector part's z.
    pub z: f64,
    /// The scalar part.
    pub w: f64,
}

impl<'de> Deserialize<'de> for QuaternionMsg {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Fields {
            x: f64,
            y: f64,
            z: f64,
            w: f64,
        }
        struct Object;
        impl<'de> serde::de::Visitor<'de> for Object {
            type Value = QuaternionMsg;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a quaternion object {x, y, z, w}")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(self, map: A) -> Result<QuaternionMsg, A::Error> {
                let q = Fields::deserialize(serde::de::value::MapAccessDeserializer::new(map))?;
                Ok(QuaternionMsg { x: q.x, y: q.y, z: q.z, w: q.w })
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(self, _: A) -> Result<QuaternionMsg, A::Error> {
                Err(serde::de::Error::custom(
                    "an orientation must be an object {x, y, z, w}: an array's order ([x, y, z, w] or \
                     [w, x, y, z]) is ambiguous",
                ))
            }
        }
        d.deserialize_any(Object)
    }
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
    /// The rig the sample is of.
    pub rig: String,
    /// The motion-capture frame number.
    pub frame: u64,
    /// Capture time on the rig's clock (ns).
    pub t_ns: u64,
    /// The tracked body's origin in the lab frame (m).
    pub position_m: [f64; 3],
    /// The tracked body's orientation in the lab frame.
    pub orientation: QuaternionMsg,
    /// The body was not seen in this frame (its pose is then not used).
    #[serde(default)]
    pub occluded: bool,
    /// The cameras' mid-exposure instant on the capture host's clock (ns), when the motion-capture system
    /// sends it (NatNet's `CameraMidExposureTimestamp`; QTM's timestamp is itself the capture time).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exposure_t_ns: Option<u64>,
    /// The RMS distance of the markers from their fitted places when the pose was fitted from markers (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fit_residual_m: Option<f64>,
    /// The motion-capture system's own latency for this frame, from capture to sending it, as the system reports
    /// it (us; Vicon: the sum of its `LatencyInfo` samples).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub system_latency_us: Option<f64>,
    /// The tracked body (rigid body, 6DOF body or marker set) the pose is of, when the rig tracks several clubs:
    /// `[rig.clubs]` maps each body to its club, so another body coming into view switches the club.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
}

impl ClubheadSampleMsg {
    /// The pipeline's sample (the rig's name and the optional timing fields left out).
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

    /// The message of `rig` for a pipeline sample (no optional fields).
    pub fn from_sample(rig: &str, s: &ClubheadSample) -> Self {
        let [x, y, z, w] = s.orientation_xyzw;
        ClubheadSampleMsg {
            rig: rig.to_string(),
            frame: s.frame,
            t_ns: s.t_ns,
            position_m: [s.position_m.x, s.position_m.y, s.position_m.z],
            orientation: QuaternionMsg { x, y, z, w },
            occluded: s.occluded,
            exposure_t_ns: None,
            fit_residual_m: None,
            system_latency_us: None,
            body: None,
        }
    }
}

/// The estimated club state at impact (world frame), in an [`ImpactMessage`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ImpactStateMsg {
    /// The head's CG (m, world).
    pub cg_position_m: [f64; 3],
    /// `world_from_club`'s rotation.
    pub orientation: QuaternionMsg,
    /// The CG's velocity (m/s, world).
    pub cg_velocity_mps: [f64; 3],
    /// The head's angular velocity (rad/s, world).
    pub angular_velocity_radps: [f64; 3],
    /// Impact location across the face from its centre (mm, toward the toe +).
    pub impact_h_mm: f64,
    /// Impact location up the face from its centre (mm, up +).
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
    /// The rig.
    pub rig: String,
    /// The rig's shot number.
    pub shot: u64,
    /// The frame that revealed the impact.
    pub frame: u64,
    /// The impact's time on the rig's clock (ns).
    pub t_impact_ns: u64,
    /// The club's name.
    pub club: String,
    /// The club file the models used: preset or path, and its SHA-256 (absent in recordings made before it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub club_file: Option<super::ClubRef>,
    /// The estimator that extrapolated the frames to impact (`arc`, `poly@44:5:39:3`, ...).
    pub estimator: String,
    /// The club at impact.
    pub state: ImpactStateMsg,
    /// The club data of that state (TrackMan's definitions).
    pub delivery: crate::impact::DeliveryMetrics,
    /// How good the estimate is.
    pub quality: Quality,
    /// The shot's labels (player, club, tags, note) when it has any.
    #[serde(default, skip_serializing_if = "super::ShotLabels::is_empty")]
    pub labels: super::ShotLabels,
    /// The ball position this impact used (world frame) and where it came from (absent in recordings made
    /// before it was reported: the rig's fixed `ball_position_m`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ball: Option<super::BallUsed>,
}

/// A predicted launch, on `golf/<rig>/launch`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct LaunchPrediction {
    /// The rig.
    pub rig: String,
    /// The rig's shot number (the impact's).
    pub shot: u64,
    /// The frame that revealed the impact.
    pub frame: u64,
    /// The impact's time on the rig's clock (ns).
    pub t_impact_ns: u64,
    /// The club's name.
    pub club: String,
    /// The club file the model used: preset or path, and its SHA-256 (absent in recordings made before it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub club_file: Option<super::ClubRef>,
    /// The impact model that predicted it (`impactd models`).
    #[serde(deserialize_with = "super::model_name::one")]
    pub model: String,
    /// The estimator that extrapolated the frames to impact.
    pub estimator: String,
    /// The club data at impact.
    pub delivery: crate::impact::DeliveryMetrics,
    /// The predicted launch.
    pub launch: PredictOutput,
    /// How many frames the estimate used.
    pub frames_used: usize,
    /// The estimate's quality score in (0, 1] (see `Quality`).
    pub quality: f64,
    /// Time from receiving the revealing frame to publishing this prediction (us), measured live; a replay
    /// carries the recorded value.
    pub latency_us: f64,
    /// Carry, apex, landing and offline of this launch (absent when the rig's `flight = false`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flight: Option<crate::flight::Trajectory>,
    /// The model's own numbers, each an object under its key: the ground model's `ground` (how the club met the
    /// turf, seed chapter 4); none for the other models.
    #[serde(default, flatten, skip_serializing_if = "crate::impact::report::WireReports::is_empty")]
    pub reports: crate::impact::report::WireReports,
    /// The shot's labels (player, club, tags, note) when it has any.
    #[serde(default, skip_serializing_if = "super::ShotLabels::is_empty")]
    pub labels: super::ShotLabels,
    /// The ball position this impact used (world frame) and where it came from (absent in recordings made
    /// before it was reported: the rig's fixed `ball_position_m`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ball: Option<super::BallUsed>,
    /// A given impact instant, a gap the fit bridged, a ball far from the face at address (absent: none of
    /// them; `LaunchPrediction` version 3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub impact_timing: Option<super::ImpactTimingMsg>,
}
