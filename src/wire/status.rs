//! The daemon's own messages: each rig's health, the payloads it set aside, and a synthetic rig's truth.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::PredictOutput;

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
    /// Time bases or frame counts the track moved onto (a publisher restart, a wrapped frame counter).
    #[serde(default)]
    pub resets: u64,
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
    /// Samples on keys of rigs this daemon does not serve (counted over all such keys).
    #[serde(default)]
    pub unknown_rig_samples: u64,
    /// Rejected payloads counted but not recorded: over the per-rig recording budget.
    #[serde(default)]
    pub rejected_not_recorded: u64,
    /// The recording's write error (a full disk...), once one happened: nothing is recorded after it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub recorder_error: Option<String>,
    /// The Open Connect client sending this rig's shots to a golf simulator, when configured.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub simulator: Option<super::SimulatorStatus>,
    /// The NatNet or QTM server feeding this rig directly (`[rig.input]`), when configured.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub input: Option<super::MocapInputStatus>,
    /// The Open Connect listener taking this rig's measured shots, when configured.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub launch_monitor: Option<super::LaunchMonitorStatus>,
    /// Measured launches received on `lm/<rig>/launch` and their pairing with predictions.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub comparison: Option<super::ComparisonStatus>,
    /// The daemon's Foxglove live view (`--foxglove`), when it serves one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub live_view: Option<super::LiveViewStatus>,
    /// The daemon's bay screen (`--web`), when it serves one: pages and file requests open, rejections by kind.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub web: Option<super::LiveViewStatus>,
    /// The rig's club now (a put on `golf/<rig>/club` or another tracked body changes it): its name, what
    /// loaded it and the SHA-256 of its club file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub club: Option<super::ClubRef>,
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
