//! One thing to record: what the live loop, replay and the bridges hand the writer, and what the Foxglove
//! encoder turns into a channel message.

use crate::math::Isometry3;
use crate::wire::{ImpactStateMsg, MessageType};

/// A flight line's points: sampled by the prediction's own flight, or to be flown by whoever encodes it (on
/// its thread, off the prediction path).
#[derive(Debug, Clone)]
pub enum FlightLine {
    /// `[t_s, x_m, y_m, z_m]` every `FLIGHT_LINE_STEP_S` (the channels' step), world frame,
    /// shared by the recording and the live view.
    Flown(std::sync::Arc<Vec<[f64; 4]>>),
    /// The launch and the flight model that flies it.
    ToFly { flight: Box<crate::flight::Flight>, launch: crate::flight::LaunchState },
}

/// One thing to record.
#[derive(Debug, Clone)]
pub enum Record {
    /// A zenoh message: its key (without the leading `/`), its wire type, and its JSON bytes.
    Message { key: String, message_type: MessageType, log_time_ns: u64, publish_time_ns: u64, data: Vec<u8> },
    /// The club's pose in the world at a sample (Foxglove `PoseInFrame` on `/foxglove/<rig>/club_pose`).
    ClubPose { rig: String, t_ns: u64, log_time_ns: u64, world_from_club: Isometry3 },
    /// Ball and club at an impact (Foxglove `SceneUpdate` on `/foxglove/<rig>/impact_scene`).
    ImpactScene {
        rig: String,
        t_ns: u64,
        log_time_ns: u64,
        ball_position_m: [f64; 3],
        ball_radius_m: f64,
        club: ImpactStateMsg,
    },
    /// The predicted ball flight as a line (Foxglove `SceneUpdate` on `/foxglove/<rig>/ball_flight`).
    Flight { rig: String, t_ns: u64, log_time_ns: u64, line: FlightLine },
    /// Close the current chunk and push it to the file.
    Flush,
}
