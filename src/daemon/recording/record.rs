//! One thing to record: what the live loop, replay and the bridges hand the writer, and what the Foxglove
//! encoder turns into a channel message.

use crate::math::Isometry3;
use crate::wire::{ImpactStateMsg, MessageType};

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
    /// The predicted ball flight as a line (Foxglove `SceneUpdate` on `/foxglove/<rig>/ball_flight`), flown
    /// from `launch` by `flight` on the consumer's thread, off the prediction path.
    Flight {
        rig: String,
        t_ns: u64,
        log_time_ns: u64,
        flight: crate::flight::Flight,
        launch: crate::flight::LaunchState,
    },
    /// Close the current chunk and push it to the file.
    Flush,
}
