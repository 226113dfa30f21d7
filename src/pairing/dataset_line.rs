//! One shot of a dataset as it is stored: a delivery and the launch measured for it, one JSON object per line
//! (`{"delivery": {predict's input fields}, "measured": {"ball_speed_mph", "launch_angle_deg",
//! "launch_direction_deg", "backspin_rpm", "sidespin_rpm"}}`, TrackMan signs; `carry_yd` optional). Written by
//! `session` (TrackMan's CSV in) and the recording (its shots), read by the identification tools.

use serde::{Deserialize, Serialize};

use crate::wire::{DeliveryInput, LaunchFields};

/// One line of a dataset. Other fields (labels, notes) are not read.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DatasetLine {
    pub delivery: DeliveryInput,
    pub measured: LaunchFields,
}
