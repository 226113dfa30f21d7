//! The line of a launch's predicted flight (`golf/<rig>/flight`): the points the daemon's flight model sampled
//! while it flew the launch, published right after the launch so the bay screens (and any other program) draw
//! the flight without flying the ball again.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The flight of one prediction, from the launch point to where the ball stops, on `golf/<rig>/flight` right
/// after its `golf/<rig>/launch` (off the latency path).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct FlightLine {
    pub rig: String,
    /// The shot number, as in its `golf/<rig>/launch`.
    pub shot: u64,
    /// The model whose launch was flown (a rig running several publishes a line for each).
    pub model: String,
    pub t_impact_ns: u64,
    /// The time between points (s); the last point is where the ball stops.
    pub step_s: f64,
    /// `[t_s, x_m, y_m, z_m]`: time since launch and the ball's centre in the world frame (x to the target, y
    /// up, z right), from the launch point through the flight, the bounces and the roll.
    pub points: Vec<[f64; 4]>,
}

impl FlightLine {
    /// Reads a `golf/<rig>/flight` payload.
    pub fn parse(payload: &[u8]) -> Result<Self, serde_json::Error> {
        serde_json::from_slice(payload)
    }
}
