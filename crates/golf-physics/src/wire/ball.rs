//! The ball where it is: a tracked ball's position on `mocap/<rig>/ball` (a marker on the ball, a rigid body, or
//! any tracker), and the ball position each impact and launch used. A few millimetres of ball position move the
//! impact point on the face, so the spin axis by degrees: every impact says which position it used and where
//! that came from.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// One observation of the ball's centre, lab frame, on `mocap/<rig>/ball`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BallSampleMsg {
    /// The rig the sample is of.
    pub rig: String,
    /// The motion-capture frame number.
    #[serde(default)]
    pub frame: u64,
    /// Capture time on the rig's clock (ns).
    pub t_ns: u64,
    /// The ball's centre in the rig's lab frame (m); a marker on the ball's surface is the centre to within
    /// its radius, so a ball marker is best placed on top and `ball_marker_offset_m` given in the config.
    pub position_m: [f64; 3],
    /// The ball was not seen in this frame (`position_m` is then not read).
    #[serde(default)]
    pub occluded: bool,
}

impl BallSampleMsg {
    /// A ball sample from its payload (JSON), with finite coordinates within 50 m of the lab's origin.
    pub fn parse(payload: &[u8]) -> Result<Self, String> {
        let msg: BallSampleMsg = serde_json::from_slice(payload).map_err(|e| e.to_string())?;
        msg.checked()
    }

    /// The sample when its coordinates are finite and within 50 m of the lab's origin (or it is occluded).
    pub fn checked(self) -> Result<Self, String> {
        if !self.occluded && self.position_m.iter().any(|v| !v.is_finite() || v.abs() > 50.0) {
            return Err("position_m must be finite and within 50 m".into());
        }
        Ok(self)
    }
}

/// Where an impact's ball position came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BallSource {
    /// The rig's fixed `ball_position_m` (no tracked ball at rest yet).
    Config,
    /// A tracked ball at rest before the impact (`mocap/<rig>/ball`, a ball body or marker).
    Tracked,
}

/// The ball position an impact used (world frame).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct BallUsed {
    /// The ball's centre (m, world).
    pub position_m: [f64; 3],
    /// Where it came from.
    pub source: BallSource,
}
