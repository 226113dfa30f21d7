//! Foxglove's well-known message forms, shared by the MCAP recording and the live WebSocket view: a [`Record`]
//! becomes a channel message (topic, schema, times, JSON) in one place, so a recording and the live view show
//! the same channels with the same bytes.
//!
//! Beside every zenoh message (`/` + its key, schema `impactd.<Type>`), three channels are for looking at:
//! `/foxglove/<rig>/club_pose` (`foxglove.PoseInFrame`, the club in the world at each sample),
//! `/foxglove/<rig>/impact_scene` (`foxglove.SceneUpdate`, ball and club at impact) and
//! `/foxglove/<rig>/ball_flight` (`foxglove.SceneUpdate`, the predicted flight as a line strip, sampled every
//! 50 ms). Positions are in the world frame (ARCHITECTURE.md section 2: x to the target, y up, z right), `frame_id`
//! `world`.

use crate::daemon::recording::record::{FlightLine, Record};
use crate::wire::{
    keys, ClubheadSampleMsg, ImpactMessage, LaunchPrediction, MeasuredLaunch, Message, MessageType, StatusMessage,
};

/// Sampling period of the ball-flight line (s).
pub const FLIGHT_LINE_STEP_S: f64 = 0.05;

/// The schema of a channel: a wire message type or one of Foxglove's well-known ones. Typed, so a channel
/// cannot name a schema that does not exist.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Schema {
    Wire(MessageType),
    PoseInFrame,
    SceneUpdate,
}

impl Schema {
    /// The schema of a wire message type.
    pub fn of<M: Message>() -> Self {
        Schema::Wire(M::TYPE)
    }

    /// The schema's name: `impactd.LaunchPrediction`, `foxglove.SceneUpdate`.
    pub fn name(self) -> String {
        match self {
            Schema::Wire(t) => t.schema_name(),
            Schema::PoseInFrame => "foxglove.PoseInFrame".to_string(),
            Schema::SceneUpdate => "foxglove.SceneUpdate".to_string(),
        }
    }

    /// The schema's JSON Schema text.
    pub fn text(self) -> String {
        match self {
            Schema::Wire(t) => t.schema(),
            Schema::PoseInFrame => POSE_IN_FRAME.to_string(),
            Schema::SceneUpdate => SCENE_UPDATE.to_string(),
        }
    }
}

/// A record as a channel message.
#[derive(Debug, Clone, PartialEq)]
pub struct Encoded {
    pub topic: String,
    pub schema: Schema,
    pub log_time_ns: u64,
    pub publish_time_ns: u64,
    pub data: Vec<u8>,
}

/// The topics of a rig's channels with their schema, in the order the live view advertises them.
pub fn rig_channels(rig: &str) -> Vec<(String, Schema)> {
    vec![
        (format!("/{}", keys::clubhead(rig)), Schema::of::<ClubheadSampleMsg>()),
        (format!("/{}", keys::impact(rig)), Schema::of::<ImpactMessage>()),
        (format!("/{}", keys::launch(rig)), Schema::of::<LaunchPrediction>()),
        (format!("/{}", keys::status(rig)), Schema::of::<StatusMessage>()),
        (format!("/{}", keys::measured_launch(rig)), Schema::of::<MeasuredLaunch>()),
        (format!("/{}", keys::foxglove_club_pose(rig)), Schema::PoseInFrame),
        (format!("/{}", keys::foxglove_impact_scene(rig)), Schema::SceneUpdate),
        (format!("/{}", keys::foxglove_ball_flight(rig)), Schema::SceneUpdate),
    ]
}

fn timestamp(t_ns: u64) -> serde_json::Value {
    serde_json::json!({ "sec": t_ns / 1_000_000_000, "nsec": t_ns % 1_000_000_000 })
}

fn pose_json(p: [f64; 3], q: crate::wire::QuaternionMsg) -> serde_json::Value {
    serde_json::json!({
        "position": { "x": p[0], "y": p[1], "z": p[2] },
        "orientation": { "x": q.x, "y": q.y, "z": q.z, "w": q.w },
    })
}

const IDENTITY: crate::wire::QuaternionMsg = crate::wire::QuaternionMsg { x: 0.0, y: 0.0, z: 0.0, w: 1.0 };

/// A `SceneEntity` with only the given primitives.
fn entity(t_ns: u64, id: &str, kind: &str, primitives: serde_json::Value) -> serde_json::Value {
    let mut e = serde_json::json!({
        "timestamp": timestamp(t_ns), "frame_id": "world", "id": id,
        "lifetime": { "sec": 0, "nsec": 0 }, "frame_locked": false, "metadata": [],
        "arrows": [], "cubes": [], "spheres": [], "cylinders": [], "lines": [],
        "triangles": [], "texts": [], "models": [],
    });
    e[kind] = primitives;
    e
}

/// The flight-line record of a prediction: its flight's points when the prediction's flight was sampled
/// ([`crate::pipeline::RigSetup::flight_line_step_s`]), else flown later by whoever encodes it.
pub fn flight_record(
    l: &LaunchPrediction,
    flight: crate::flight::Flight,
    points: Option<std::sync::Arc<Vec<[f64; 4]>>>,
    log_time_ns: u64,
) -> Record {
    let line = match points {
        Some(points) => FlightLine::Flown(points),
        None => FlightLine::ToFly {
            flight: Box::new(flight),
            launch: crate::flight::LaunchState {
                velocity_mps: l.launch.ball_velocity_mps.into(),
                spin_radps: l.launch.ball_spin_radps.into(),
            },
        },
    };
    Record::Flight { rig: l.rig.clone(), t_ns: l.t_impact_ns, log_time_ns, line }
}

/// The channel message of a record (`None` for [`Record::Flush`]).
pub fn encode(record: Record) -> Option<Encoded> {
    let scene = |entities: Vec<serde_json::Value>| {
        serde_json::to_vec(&serde_json::json!({ "deletions": [], "entities": entities })).unwrap_or_default()
    };
    Some(match record {
        Record::Message { key, message_type, log_time_ns, publish_time_ns, data } => {
            Encoded { topic: format!("/{key}"), schema: Schema::Wire(message_type), log_time_ns, publish_time_ns, data }
        }
        Record::ClubPose { rig, t_ns, log_time_ns, world_from_club } => {
            let p = world_from_club.translation.vector;
            let msg = serde_json::json!({
                "timestamp": timestamp(t_ns),
                "frame_id": "world",
                "pose": pose_json([p.x, p.y, p.z], world_from_club.rotation.into()),
            });
            Encoded {
                topic: format!("/{}", keys::foxglove_club_pose(&rig)),
                schema: Schema::PoseInFrame,
                log_time_ns,
                publish_time_ns: t_ns,
                data: serde_json::to_vec(&msg).unwrap_or_default(),
            }
        }
        Record::ImpactScene { rig, t_ns, log_time_ns, ball_position_m, ball_radius_m, club } => {
            let d = 2.0 * ball_radius_m;
            let ball = serde_json::json!([{ "pose": pose_json(ball_position_m, IDENTITY), "size": { "x": d, "y": d, "z": d }, "color": { "r": 1.0, "g": 1.0, "b": 1.0, "a": 1.0 } }]);
            let head = serde_json::json!([{ "pose": pose_json(club.cg_position_m, club.orientation), "size": { "x": 0.10, "y": 0.05, "z": 0.11 }, "color": { "r": 0.2, "g": 0.4, "b": 0.9, "a": 0.8 } }]);
            Encoded {
                topic: format!("/{}", keys::foxglove_impact_scene(&rig)),
                schema: Schema::SceneUpdate,
                log_time_ns,
                publish_time_ns: t_ns,
                data: scene(vec![entity(t_ns, "ball", "spheres", ball), entity(t_ns, "club", "cubes", head)]),
            }
        }
        Record::Flight { rig, t_ns, log_time_ns, line } => {
            let flown = match line {
                FlightLine::Flown(points) => points,
                FlightLine::ToFly { flight, launch } => flight.fly(&launch, FLIGHT_LINE_STEP_S).points.into(),
            };
            let points: Vec<_> = flown.iter().map(|p| serde_json::json!({ "x": p[1], "y": p[2], "z": p[3] })).collect();
            // LINE_STRIP (type 0), 2 cm wide, orange.
            let line = serde_json::json!([{
                "type": 0, "pose": pose_json([0.0; 3], IDENTITY), "thickness": 0.02, "scale_invariant": false,
                "points": points, "color": { "r": 1.0, "g": 0.55, "b": 0.1, "a": 1.0 }, "colors": [], "indices": [],
            }]);
            Encoded {
                topic: format!("/{}", keys::foxglove_ball_flight(&rig)),
                schema: Schema::SceneUpdate,
                log_time_ns,
                publish_time_ns: t_ns,
                data: scene(vec![entity(t_ns, "flight", "lines", line)]),
            }
        }
        Record::Flush => return None,
    })
}

const POSE_IN_FRAME: &str = concat!(
    r#"{"title":"foxglove.PoseInFrame","description":"A timestamped pose for an object or reference frame in 3D space","type":"object","properties":{"timestamp":"#,
    r#"{"type":"object","properties":{"sec":{"type":"integer","minimum":0},"nsec":{"type":"integer","minimum":0,"maximum":999999999}}}"#,
    r#","frame_id":{"type":"string"},"pose":{"type":"object","properties":{"position":{"type":"object","properties":{"x":{"type":"number"},"y":{"type":"number"},"z":{"type":"number"}}},"orientation":{"type":"object","properties":{"x":{"type":"number"},"y":{"type":"number"},"z":{"type":"number"},"w":{"type":"number"}}}}}}}"#
);

const SCENE_UPDATE: &str = r#"{"title":"foxglove.SceneUpdate","description":"An update to the entities displayed in a 3D scene","type":"object","properties":{"deletions":{"type":"array","items":{"type":"object"}},"entities":{"type":"array","items":{"type":"object","properties":{"timestamp":{"type":"object"},"frame_id":{"type":"string"},"id":{"type":"string"},"lifetime":{"type":"object"},"frame_locked":{"type":"boolean"},"metadata":{"type":"array"},"arrows":{"type":"array"},"cubes":{"type":"array"},"spheres":{"type":"array"},"cylinders":{"type":"array"},"lines":{"type":"array"},"triangles":{"type":"array"},"texts":{"type":"array"},"models":{"type":"array"}}}}}}"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_flight_line_follows_the_predicted_flight() {
        // A 7-iron-like launch: 54 m/s, 17 deg up, 7000 rpm of backspin (about +z: ARCHITECTURE.md's spin axis
        // a = u x y for u along x). The line starts at the ball and ends where the flight model stops the same
        // launch through its bounce and roll.
        let flight = crate::flight::Flight::default();
        let (speed, angle) = (54.0_f64, 17.0_f64.to_radians());
        let launch = crate::flight::LaunchState {
            velocity_mps: crate::math::Vector3::new(speed * angle.cos(), speed * angle.sin(), 0.0),
            spin_radps: crate::math::Vector3::new(0.0, 0.0, 7000.0 * std::f64::consts::TAU / 60.0),
        };
        // The line runs through the bounce and roll to where the ball stops (straight here: x is the total).
        let total_m = flight.fly(&launch, 0.0).total_m;
        let line = FlightLine::ToFly { flight: Box::new(flight), launch };
        let e = encode(Record::Flight { rig: "r".into(), t_ns: 5, log_time_ns: 6, line }).unwrap();
        assert_eq!(
            (e.topic.as_str(), e.schema, e.publish_time_ns),
            ("/foxglove/r/ball_flight", Schema::SceneUpdate, 5)
        );
        let v: serde_json::Value = serde_json::from_slice(&e.data).unwrap();
        let points = v["entities"][0]["lines"][0]["points"].as_array().unwrap().clone();
        assert!(points.len() > 20, "{} points", points.len());
        assert_eq!(points[0]["x"].as_f64(), Some(0.0));
        let last_x = points.last().unwrap()["x"].as_f64().unwrap();
        assert!((last_x - total_m).abs() < 1e-9, "{last_x} vs total {total_m}");
        assert!(encode(Record::Flush).is_none());
        // The prediction's own sampled flight gives the same bytes.
        let flown = FlightLine::Flown(flight.fly(&launch, FLIGHT_LINE_STEP_S).points.into());
        let shared = encode(Record::Flight { rig: "r".into(), t_ns: 5, log_time_ns: 6, line: flown }).unwrap();
        assert_eq!(shared, e);
    }
}
