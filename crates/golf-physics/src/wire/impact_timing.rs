//! What a launch says of its impact instant: found at the geometric contact of the face with the ball or given
//! by the user, and what the fit of the frames before it had to bridge (docs/estimation.md).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::kinematics::frame_gap::FrameGap;

/// Where the impact instant came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ImpactInstant {
    /// The geometric contact of the fitted face with the configured or tracked ball.
    Contact,
    /// The user's `--impact-frame` or `--impact-time`.
    Given,
}

/// A launch's impact instant and the gaps the estimate bridged; on a launch only when there is something to say
/// (a given instant, a gap, a ball far from the face at address), absent otherwise.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ImpactTimingMsg {
    /// Where the impact instant came from: the geometric contact, or the user.
    pub instant: ImpactInstant,
    /// The longest gap in the frames before the impact that the fit bridged (warning `frame_gap_before_impact`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame_gap: Option<FrameGap>,
    /// The face centre's distance from the ball at the address before the swing, when beyond the 0.5 m of a ball
    /// addressed (m; warning `ball_far_from_address`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub address_ball_distance_m: Option<f64>,
}

impl ImpactTimingMsg {
    /// The message, when it has something to say.
    pub fn of(given: bool, frame_gap: Option<FrameGap>, address_ball_distance_m: Option<f64>) -> Option<Self> {
        (given || frame_gap.is_some() || address_ball_distance_m.is_some()).then_some(ImpactTimingMsg {
            instant: if given { ImpactInstant::Given } else { ImpactInstant::Contact },
            frame_gap,
            address_ball_distance_m,
        })
    }
}
