//! OpenGolfSim's developer API messages (help.opengolfsim.com, "Developer API" and "Shot Data API" pages).
//!
//! TCP, the simulator listens on port 3111; each message is one JSON object with a `type`, followed by a newline
//! (as the page's Python example writes them). Out: `{"type": "device", "status": "ready" | "busy"}` and
//! `{"type": "shot", "unit": "imperial" | "metric", "shot": {"ballSpeed", "verticalLaunchAngle",
//! "horizontalLaunchAngle", "spinSpeed", "spinAxis"}}`, ball speed in mph (`imperial`, the default) or m/s
//! (`metric`), angles in degrees, spin in rpm. The page gives the ranges: vertical launch 0 to 45 degrees,
//! horizontal launch and spin axis -45 to 45 degrees; a prediction outside them is refused, not clipped. Back:
//! `{"type": "result", "data": {"result": {"carry", "height", "roll", "total", "lateral"}, "club": {...},
//! "shot": {...}, "sessionId"}}` once the simulator has flown the shot, distances always in metres.
//! Signs: the page names no convention; its fields are those of Open Connect v1, whose signs are TrackMan's
//! (horizontal launch right +, spin axis + = tilted right, a fade), and they pass unchanged.

use serde::{Deserialize, Serialize};

use crate::daemon::bridges::open_connect::OpenConnectError;
use crate::wire::LaunchPrediction;

/// The unit of a shot's ball speed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Unit {
    /// Miles per hour (the API's default).
    Imperial,
    /// Metres per second.
    Metric,
}

/// The device's readiness.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DeviceStatus {
    Ready,
    Busy,
}

/// A message to the simulator.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum Outgoing {
    Device { status: DeviceStatus },
    Shot { unit: Unit, shot: Shot },
}

/// A shot's ball launch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct Shot {
    /// mph (`imperial`) or m/s (`metric`).
    pub ball_speed: f64,
    /// Degrees, up +, 0 to 45.
    pub vertical_launch_angle: f64,
    /// Degrees, right +, -45 to 45.
    pub horizontal_launch_angle: f64,
    /// Total spin, rpm.
    pub spin_speed: f64,
    /// Degrees, + = tilted right (fade), -45 to 45.
    pub spin_axis: f64,
}

/// The simulator's `result` of a shot it flew (metres).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ShotResult {
    #[serde(default)]
    pub carry: Option<f64>,
    #[serde(default)]
    pub height: Option<f64>,
    #[serde(default)]
    pub roll: Option<f64>,
    #[serde(default)]
    pub total: Option<f64>,
    #[serde(default)]
    pub lateral: Option<f64>,
}

/// The `data` of a `result` message; the rest of it (club, shot, session) is kept in the recording as sent.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ResultData {
    #[serde(default)]
    pub result: ShotResult,
}

/// A message from the simulator: a `result`, or any other `type` (kept by name).
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Incoming {
    #[serde(rename = "type")]
    pub kind: String,
    #[serde(default)]
    pub data: Option<ResultData>,
}

/// One message's bytes: the JSON object and its newline.
pub fn encode(message: &Outgoing) -> Result<Vec<u8>, OpenConnectError> {
    let mut bytes = serde_json::to_vec(message).map_err(OpenConnectError::Encode)?;
    bytes.push(b'\n');
    Ok(bytes)
}

impl Shot {
    /// A prediction as a shot in `unit`. Refuses a non-finite number, a ball speed under 1 mph, and a number
    /// outside the API's ranges (no ghost shots, nothing clipped).
    pub fn from_prediction(l: &LaunchPrediction, unit: Unit) -> Result<Self, OpenConnectError> {
        let m = &l.launch.launch;
        let refuse = |reason: String| OpenConnectError::Refused { shot: l.shot, reason };
        let numbers = [m.ball_speed_mph, m.launch_angle_deg, m.launch_direction_deg, m.total_spin_rpm, m.spin_axis_deg];
        if numbers.iter().any(|v| !v.is_finite()) {
            return Err(refuse("a launch number is not finite".into()));
        }
        if m.ball_speed_mph < 1.0 {
            return Err(refuse(format!("ball speed {:.3} mph is no shot", m.ball_speed_mph)));
        }
        for (name, v, lo, hi) in [
            ("vertical launch angle", m.launch_angle_deg, 0.0, 45.0),
            ("horizontal launch angle", m.launch_direction_deg, -45.0, 45.0),
            ("spin axis", m.spin_axis_deg, -45.0, 45.0),
        ] {
            if !(lo..=hi).contains(&v) {
                return Err(refuse(format!("{name} {v:.1} deg is outside OpenGolfSim's {lo} to {hi} deg")));
            }
        }
        Ok(Shot {
            ball_speed: match unit {
                Unit::Imperial => m.ball_speed_mph,
                Unit::Metric => m.ball_speed_mps,
            },
            vertical_launch_angle: m.launch_angle_deg,
            horizontal_launch_angle: m.launch_direction_deg,
            spin_speed: m.total_spin_rpm,
            spin_axis: m.spin_axis_deg,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Shot Data API page's examples, field for field (one in mph, one in m/s).
    #[test]
    fn the_pages_examples_read_and_write_back() {
        let metric = r#"{"type":"shot","unit":"metric","shot":{"ballSpeed":44.704,"verticalLaunchAngle":15.4,"horizontalLaunchAngle":-2.1,"spinSpeed":3021,"spinAxis":-0.5}}"#;
        let m: Outgoing = serde_json::from_str(metric).unwrap();
        let Outgoing::Shot { unit, shot } = &m else { panic!("{m:?}") };
        assert_eq!((*unit, shot.ball_speed, shot.spin_axis), (Unit::Metric, 44.704, -0.5));
        let bytes = encode(&m).unwrap();
        assert_eq!(bytes.last(), Some(&b'\n'), "one message a line");
        assert_eq!(serde_json::from_slice::<Outgoing>(&bytes).unwrap(), m);
        let text = String::from_utf8(bytes).unwrap();
        for name in [
            "\"type\":\"shot\"",
            "\"unit\":\"metric\"",
            "\"ballSpeed\"",
            "\"verticalLaunchAngle\"",
            "\"horizontalLaunchAngle\"",
            "\"spinSpeed\"",
            "\"spinAxis\"",
        ] {
            assert!(text.contains(name), "{name} in {text}");
        }
        let ready = encode(&Outgoing::Device { status: DeviceStatus::Ready }).unwrap();
        assert_eq!(ready, b"{\"type\":\"device\",\"status\":\"ready\"}\n");
        let busy = encode(&Outgoing::Device { status: DeviceStatus::Busy }).unwrap();
        assert_eq!(busy, b"{\"type\":\"device\",\"status\":\"busy\"}\n");
    }

    #[test]
    fn the_pages_result_reads() {
        let r = r#"{"type":"result","data":{"result":{"carry":196.06776428222656,"height":18.728025436401367,"roll":6.482479572296143,"total":202.54876708984375,"lateral":-0.07558325678110123},"club":{"name":"5W","id":"5W","distance":205},"shot":{"ballSpeed":135,"verticalLaunchAngle":11.100000381469727,"horizontalLaunchAngle":1.2000000476837158,"spinAxis":-2.5,"spinSpeed":4800},"sessionId":22}}"#;
        let m: Incoming = serde_json::from_str(r).unwrap();
        assert_eq!(m.kind, "result");
        let d = m.data.unwrap().result;
        assert_eq!(
            (d.carry, d.total, d.lateral),
            (Some(196.06776428222656), Some(202.54876708984375), Some(-0.07558325678110123))
        );
    }
}
