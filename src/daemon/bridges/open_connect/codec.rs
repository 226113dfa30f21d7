//! The Open Connect v1 messages, both ways (GSPro's "Open Connect v1" page; OpenGolfSim accepts the same).
//!
//! A launch monitor sends one JSON object per shot: `DeviceID`, `Units`, `ShotNumber`, `APIversion` "1",
//! `BallData`, `ClubData` and `ShotDataOptions`; a heartbeat is the same object with `IsHeartBeat` true and no
//! ball data. The simulator answers with `{"Code": 200, "Message": ...}` (shot received), 201 with `Player`
//! (handedness and club) when the player changes, and 5xx on failure. Units and signs are the specification's,
//! which are TrackMan's (ARCHITECTURE.md section 2), so no sign flips at this boundary: speeds in mph, angles in
//! degrees, spin in rpm, HLA right +, spin axis and side spin + = tilted right (fade), VLA up +, carry in yards.
//! The face impact location (no unit in the specification) goes out in mm, toe + and up +.

use serde::{Deserialize, Serialize};

use super::OpenConnectError;
use crate::wire::{LaunchPrediction, MeasuredClubData, MeasuredLaunch};

/// The only API version there is.
pub const API_VERSION: &str = "1";

/// A shot or a heartbeat, launch monitor -> simulator.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ShotMessage {
    #[serde(rename = "DeviceID", default)]
    pub device_id: String,
    #[serde(rename = "Units", default = "yards")]
    pub units: String,
    #[serde(rename = "ShotNumber", default)]
    pub shot_number: u64,
    #[serde(rename = "APIversion", default = "api_version")]
    pub api_version: String,
    #[serde(rename = "BallData", default, skip_serializing_if = "Option::is_none")]
    pub ball_data: Option<BallData>,
    #[serde(rename = "ClubData", default, skip_serializing_if = "Option::is_none")]
    pub club_data: Option<ClubData>,
    #[serde(rename = "ShotDataOptions", default)]
    pub shot_data_options: ShotDataOptions,
}

fn yards() -> String {
    "Yards".into()
}

fn api_version() -> String {
    API_VERSION.into()
}

/// Ball launch: mph, degrees, rpm, yards.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct BallData {
    #[serde(rename = "Speed")]
    pub speed_mph: f64,
    /// + = tilted right (fade).
    #[serde(rename = "SpinAxis", default, skip_serializing_if = "Option::is_none")]
    pub spin_axis_deg: Option<f64>,
    #[serde(rename = "TotalSpin", default, skip_serializing_if = "Option::is_none")]
    pub total_spin_rpm: Option<f64>,
    #[serde(rename = "BackSpin", default, skip_serializing_if = "Option::is_none")]
    pub back_spin_rpm: Option<f64>,
    /// + = fade (curves right).
    #[serde(rename = "SideSpin", default, skip_serializing_if = "Option::is_none")]
    pub side_spin_rpm: Option<f64>,
    /// Horizontal launch angle, right +.
    #[serde(rename = "HLA")]
    pub hla_deg: f64,
    /// Vertical launch angle, up +.
    #[serde(rename = "VLA")]
    pub vla_deg: f64,
    #[serde(rename = "CarryDistance", default, skip_serializing_if = "Option::is_none")]
    pub carry_yd: Option<f64>,
}

/// Club delivery: mph and degrees (TrackMan's definitions); face impact in mm.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ClubData {
    #[serde(rename = "Speed", default, skip_serializing_if = "Option::is_none")]
    pub speed_mph: Option<f64>,
    #[serde(rename = "AngleOfAttack", default, skip_serializing_if = "Option::is_none")]
    pub angle_of_attack_deg: Option<f64>,
    #[serde(rename = "FaceToTarget", default, skip_serializing_if = "Option::is_none")]
    pub face_to_target_deg: Option<f64>,
    #[serde(rename = "Lie", default, skip_serializing_if = "Option::is_none")]
    pub lie_deg: Option<f64>,
    #[serde(rename = "Loft", default, skip_serializing_if = "Option::is_none")]
    pub loft_deg: Option<f64>,
    #[serde(rename = "Path", default, skip_serializing_if = "Option::is_none")]
    pub path_deg: Option<f64>,
    #[serde(rename = "SpeedAtImpact", default, skip_serializing_if = "Option::is_none")]
    pub speed_at_impact_mph: Option<f64>,
    #[serde(rename = "VerticalFaceImpact", default, skip_serializing_if = "Option::is_none")]
    pub vertical_face_impact_mm: Option<f64>,
    #[serde(rename = "HorizontalFaceImpact", default, skip_serializing_if = "Option::is_none")]
    pub horizontal_face_impact_mm: Option<f64>,
    /// Deg/s, closing + (`closure_rate_degps` of the delivery, docs/club-data.md); `Lie` is the dynamic lie (deg).
    #[serde(rename = "ClosureRate", default, skip_serializing_if = "Option::is_none")]
    pub closure_rate: Option<f64>,
}

/// What the message carries and the launch monitor's readiness.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ShotDataOptions {
    /// Left out by some connectors: then a nonzero ball speed makes the message a shot ([`ShotMessage::is_heartbeat`]).
    #[serde(rename = "ContainsBallData", default, skip_serializing_if = "Option::is_none")]
    pub contains_ball_data: Option<bool>,
    #[serde(rename = "ContainsClubData", default)]
    pub contains_club_data: bool,
    #[serde(rename = "LaunchMonitorIsReady", default, skip_serializing_if = "Option::is_none")]
    pub launch_monitor_is_ready: Option<bool>,
    #[serde(rename = "LaunchMonitorBallDetected", default, skip_serializing_if = "Option::is_none")]
    pub launch_monitor_ball_detected: Option<bool>,
    #[serde(rename = "IsHeartBeat", default, skip_serializing_if = "Option::is_none")]
    pub is_heart_beat: Option<bool>,
}

/// Simulator -> launch monitor.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Reply {
    #[serde(rename = "Code")]
    pub code: u16,
    #[serde(rename = "Message", default)]
    pub message: String,
    #[serde(rename = "Player", default, skip_serializing_if = "Option::is_none")]
    pub player: Option<Player>,
}

/// The player's handedness and club, sent with code 201.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Player {
    /// "RH" or "LH".
    #[serde(rename = "Handed", default, skip_serializing_if = "Option::is_none")]
    pub handed: Option<String>,
    /// "DR", "7I", ...
    #[serde(rename = "Club", default, skip_serializing_if = "Option::is_none")]
    pub club: Option<String>,
    #[serde(rename = "DistanceToTarget", default, skip_serializing_if = "Option::is_none")]
    pub distance_to_target: Option<f64>,
}

impl ShotMessage {
    /// A heartbeat: shot number 0, no ball data, with the readiness flags.
    pub fn heartbeat(device_id: &str, ready: bool) -> Self {
        ShotMessage {
            device_id: device_id.into(),
            units: yards(),
            shot_number: 0,
            api_version: api_version(),
            ball_data: None,
            club_data: None,
            shot_data_options: ShotDataOptions {
                contains_ball_data: Some(false),
                contains_club_data: false,
                launch_monitor_is_ready: Some(ready),
                launch_monitor_ball_detected: Some(ready),
                is_heart_beat: Some(true),
            },
        }
    }

    /// Whether this is a heartbeat: flagged, or carrying no ball data. A message with a nonzero ball speed is a
    /// shot when `ContainsBallData` is left out, so a connector that omits the flag is answered (200, or 501 with
    /// the reason) rather than silently ignored; an explicit `ContainsBallData: false` is never a shot.
    pub fn is_heartbeat(&self) -> bool {
        let carries_ball = self.ball_data.as_ref().is_some_and(|b| b.speed_mph != 0.0);
        self.shot_data_options.is_heart_beat == Some(true)
            || !self.shot_data_options.contains_ball_data.unwrap_or(carries_ball)
    }

    /// A prediction as shot `shot_number`. Refuses a launch with a zero, negative or non-finite number where
    /// the simulator needs one (no ghost shots).
    pub fn from_prediction(l: &LaunchPrediction, device_id: &str, shot_number: u64) -> Result<Self, OpenConnectError> {
        let m = &l.launch.launch;
        let ball = [m.ball_speed_mph, m.launch_angle_deg, m.launch_direction_deg, m.backspin_rpm, m.sidespin_rpm];
        let spin = [m.total_spin_rpm, m.spin_axis_deg];
        if ball.iter().chain(spin.iter()).any(|v| !v.is_finite()) {
            return Err(OpenConnectError::Refused { shot: l.shot, reason: "a launch number is not finite".into() });
        }
        if m.ball_speed_mph < 1.0 {
            return Err(OpenConnectError::Refused {
                shot: l.shot,
                reason: format!("ball speed {:.3} mph is no shot", m.ball_speed_mph),
            });
        }
        let d = &l.delivery;
        let finite = |v: f64| v.is_finite().then_some(v);
        let carry = l.flight.as_ref().map(|f| f.carry_yd).filter(|c| c.is_finite() && *c >= 0.0);
        Ok(ShotMessage {
            device_id: device_id.into(),
            units: yards(),
            shot_number,
            api_version: api_version(),
            ball_data: Some(BallData {
                speed_mph: m.ball_speed_mph,
                spin_axis_deg: Some(m.spin_axis_deg),
                total_spin_rpm: Some(m.total_spin_rpm),
                back_spin_rpm: Some(m.backspin_rpm),
                side_spin_rpm: Some(m.sidespin_rpm),
                hla_deg: m.launch_direction_deg,
                vla_deg: m.launch_angle_deg,
                carry_yd: carry,
            }),
            club_data: Some(ClubData {
                speed_mph: finite(d.club_speed_mph),
                angle_of_attack_deg: finite(d.attack_angle_deg),
                face_to_target_deg: finite(d.face_angle_deg),
                lie_deg: finite(d.dynamic_lie_deg),
                loft_deg: finite(d.dynamic_loft_deg),
                path_deg: finite(d.club_path_deg),
                speed_at_impact_mph: finite(d.club_speed_mph),
                vertical_face_impact_mm: finite(d.impact_v_mm),
                horizontal_face_impact_mm: finite(d.impact_h_mm),
                closure_rate: finite(d.closure_rate_degps),
            }),
            shot_data_options: ShotDataOptions {
                contains_ball_data: Some(true),
                contains_club_data: true,
                launch_monitor_is_ready: Some(true),
                launch_monitor_ball_detected: Some(true),
                is_heart_beat: Some(false),
            },
        })
    }

    /// A received shot as a [`MeasuredLaunch`] of `rig`, checking the numbers a launch needs.
    pub fn to_measured(&self, rig: &str, t_ns: u64) -> Result<MeasuredLaunch, OpenConnectError> {
        let bad = |reason: String| OpenConnectError::Invalid(reason);
        let b = self.ball_data.as_ref().ok_or_else(|| bad("no BallData".into()))?;
        if self.api_version != API_VERSION {
            return Err(bad(format!("APIversion `{}` is not \"1\"", self.api_version)));
        }
        let check = |name: &str, v: f64, lo: f64, hi: f64| {
            if v.is_finite() && (lo..=hi).contains(&v) {
                Ok(v)
            } else {
                Err(bad(format!("BallData.{name} = {v} is not within {lo} and {hi}")))
            }
        };
        let speed_mph = check("Speed", b.speed_mph, 0.1, 300.0)?;
        let vla = check("VLA", b.vla_deg, -90.0, 90.0)?;
        let hla = check("HLA", b.hla_deg, -90.0, 90.0)?;
        let spin = |name: &str, v: Option<f64>| v.map(|v| check(name, v, -30_000.0, 30_000.0)).transpose();
        let back = spin("BackSpin", b.back_spin_rpm)?;
        let side = spin("SideSpin", b.side_spin_rpm)?;
        let total = spin("TotalSpin", b.total_spin_rpm)?;
        let axis = b.spin_axis_deg.map(|v| check("SpinAxis", v, -90.0, 90.0)).transpose()?;
        if (back.is_none() || side.is_none()) && (total.is_none() || axis.is_none()) {
            return Err(bad("BallData needs TotalSpin and SpinAxis, or BackSpin and SideSpin".into()));
        }
        let yards_per_unit = if self.units.eq_ignore_ascii_case("meters") { 1.0 / 0.9144 } else { 1.0 };
        let carry = b.carry_yd.filter(|c| c.is_finite() && *c > 0.0).map(|c| c * yards_per_unit);
        let club = self.club_data.as_ref().filter(|_| self.shot_data_options.contains_club_data).map(|c| {
            let f = |v: Option<f64>| v.filter(|v| v.is_finite());
            MeasuredClubData {
                club_speed_mph: f(c.speed_mph),
                attack_angle_deg: f(c.angle_of_attack_deg),
                club_path_deg: f(c.path_deg),
                face_angle_deg: f(c.face_to_target_deg),
                dynamic_loft_deg: f(c.loft_deg),
                impact_h_mm: f(c.horizontal_face_impact_mm),
                impact_v_mm: f(c.vertical_face_impact_mm),
            }
        });
        Ok(MeasuredLaunch {
            rig: rig.into(),
            t_ns,
            device: format!("open_connect:{}", self.device_id),
            shot_number: Some(self.shot_number),
            ball_speed_mph: speed_mph,
            launch_angle_deg: vla,
            launch_direction_deg: hla,
            backspin_rpm: back,
            sidespin_rpm: side,
            total_spin_rpm: total,
            spin_axis_deg: axis,
            carry_yd: carry,
            club,
        })
    }
}

impl Reply {
    pub fn new(code: u16, message: impl Into<String>) -> Self {
        Reply { code, message: message.into(), player: None }
    }

    /// 2xx.
    pub fn is_success(&self) -> bool {
        (200..300).contains(&self.code)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The example shot of GSPro's Open Connect v1 page, field for field.
    const SPEC_EXAMPLE: &str = r#"{"DeviceID": "GSPro LM 1.1", "Units": "Yards", "ShotNumber": 13, "APIversion": "1",
        "BallData": {"Speed": 147.5, "SpinAxis": -13.2, "TotalSpin": 3250.0, "BackSpin": 2500.0, "SideSpin": -800.0,
                     "HLA": 2.3, "VLA": 14.3, "CarryDistance": 256.5},
        "ClubData": {"Speed": 0.0, "AngleOfAttack": 0.0, "FaceToTarget": 0.0, "Lie": 0.0, "Loft": 0.0, "Path": 0.0,
                     "SpeedAtImpact": 0.0, "VerticalFaceImpact": 0.0, "HorizontalFaceImpact": 0.0, "ClosureRate": 0.0},
        "ShotDataOptions": {"ContainsBallData": true, "ContainsClubData": false, "LaunchMonitorIsReady": true,
                            "LaunchMonitorBallDetected": true, "IsHeartBeat": false}}"#;

    #[test]
    fn ball_data_without_the_flag_is_a_shot_and_zero_ball_data_is_a_heartbeat() {
        let shot =
            r#"{"DeviceID":"LM","ShotNumber":3,"APIversion":"1","BallData":{"Speed":140.0,"HLA":0.0,"VLA":12.0}}"#;
        assert!(!serde_json::from_str::<ShotMessage>(shot).unwrap().is_heartbeat());
        let idle = r#"{"DeviceID":"LM","ShotNumber":0,"BallData":{"Speed":0.0,"HLA":0.0,"VLA":0.0}}"#;
        assert!(serde_json::from_str::<ShotMessage>(idle).unwrap().is_heartbeat());
        // An explicit "no ball data" wins over stale ball data (a club-only message).
        let club_only = r#"{"DeviceID":"LM","ShotNumber":4,"BallData":{"Speed":140.0,"HLA":0.0,"VLA":12.0},"ShotDataOptions":{"ContainsBallData":false,"ContainsClubData":true}}"#;
        assert!(serde_json::from_str::<ShotMessage>(club_only).unwrap().is_heartbeat());
    }

    #[test]
    fn the_specification_example_reads_as_a_measured_launch() {
        let m: ShotMessage = serde_json::from_str(SPEC_EXAMPLE).unwrap();
        assert!(!m.is_heartbeat());
        let l = m.to_measured("bay1", 7).unwrap();
        assert_eq!((l.ball_speed_mph, l.launch_angle_deg, l.launch_direction_deg), (147.5, 14.3, 2.3));
        // Back and side spin are given, so they win over total spin and axis.
        assert_eq!(l.spin_components_rpm(), Some((2500.0, -800.0)));
        assert_eq!((l.carry_yd, l.shot_number, l.club.is_none()), (Some(256.5), Some(13), true));
        assert_eq!(l.device, "open_connect:GSPro LM 1.1");
        // Written back, the names are the specification's.
        let text = serde_json::to_string(&m).unwrap();
        for name in ["\"DeviceID\"", "\"APIversion\"", "\"HLA\"", "\"VLA\"", "\"SpinAxis\"", "\"IsHeartBeat\""] {
            assert!(text.contains(name), "{name} in {text}");
        }
    }

    #[test]
    fn bad_shots_name_their_field() {
        let with = |ball: &str| {
            let t = format!(
                r#"{{"DeviceID":"x","ShotNumber":1,"APIversion":"1","BallData":{ball},"ShotDataOptions":{{"ContainsBallData":true,"ContainsClubData":false}}}}"#
            );
            let m: ShotMessage = serde_json::from_str(&t).unwrap();
            m.to_measured("r", 0).map(|_| ()).map_err(|e| e.to_string())
        };
        assert!(with(r#"{"Speed":0.0,"HLA":0,"VLA":10,"TotalSpin":3000,"SpinAxis":0}"#).unwrap_err().contains("Speed"));
        assert!(with(r#"{"Speed":100,"HLA":0,"VLA":143,"TotalSpin":3000,"SpinAxis":0}"#).unwrap_err().contains("VLA"));
        assert!(with(r#"{"Speed":100,"HLA":0,"VLA":14}"#).unwrap_err().contains("TotalSpin"));
        assert!(with(r#"{"Speed":100,"HLA":0,"VLA":14,"TotalSpin":3000,"SpinAxis":0}"#).is_ok());
        let hb = ShotMessage::heartbeat("impactd", true);
        assert!(hb.is_heartbeat() && hb.to_measured("r", 0).is_err());
    }

    #[test]
    fn replies_with_player_information() {
        let r: Reply = serde_json::from_str(r#"{"Code":201,"Message":"GSPro Player Information","Player":{"Handed":"LH","Club":"7I","DistanceToTarget":150}}"#).unwrap();
        assert!(r.is_success());
        let p = r.player.unwrap();
        assert_eq!((p.handed.as_deref(), p.club.as_deref()), (Some("LH"), Some("7I")));
        let r: Reply = serde_json::from_str(r#"{"Code":501,"Message":"failure"}"#).unwrap();
        assert!(!r.is_success());
    }
}
