//! The JSONL form of `impactd flight`: a launch in (the fields `impactd predict` writes).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::math::{Real, Vector3};

/// A launch as read by `impactd flight`: the fields `impactd predict` writes. The vectors, when present, are used
/// as they are; otherwise speed, angles and spins (backspin and sidespin, or total spin and spin axis). Other fields
/// (labels, `warnings`, an earlier flight's `apex_m`) are not read: `impactd flight` passes them through.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct FlightInput {
    /// Ball speed (m/s); or `ball_speed_mph`.
    pub ball_speed_mps: Option<Real>,
    /// Ball speed (mph), when `ball_speed_mps` is absent.
    pub ball_speed_mph: Option<Real>,
    /// Launch angle above the horizontal (deg).
    #[serde(default)]
    pub launch_angle_deg: Real,
    /// Launch direction right (+) or left (−) of the target line (deg).
    #[serde(default)]
    pub launch_direction_deg: Real,
    /// Backspin (rpm), with `sidespin_rpm`.
    pub backspin_rpm: Option<Real>,
    /// Sidespin (rpm; + curves the ball right: fade or slice).
    pub sidespin_rpm: Option<Real>,
    /// Total spin (rpm), with `spin_axis_deg`, when backspin and sidespin are absent.
    pub total_spin_rpm: Option<Real>,
    /// Spin axis tilt (deg; + curves the ball right).
    pub spin_axis_deg: Option<Real>,
    /// Club data `impactd predict` writes; read and not used.
    pub smash_factor: Option<Real>,
    /// Club data `impactd predict` writes; read and not used.
    pub spin_loft_deg: Option<Real>,
    /// Club data `impactd predict` writes; read and not used.
    pub face_to_path_deg: Option<Real>,
    /// Club data `impactd predict` writes (docs/club-data.md); read and not used.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dynamic_lie_deg: Option<Real>,
    /// Club data `impactd predict` writes; read and not used.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub closure_rate_degps: Option<Real>,
    /// The ball's velocity (m/s, world); used as it is when given.
    pub ball_velocity_mps: Option<[Real; 3]>,
    /// The ball's angular velocity (rad/s, world); used as it is when given.
    pub ball_spin_radps: Option<[Real; 3]>,
}

/// Why a line of `impactd flight` input is not a launch; each names its field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FlightInputError {
    /// A number that is not finite.
    #[error("field `{field}` must be finite")]
    NotFinite {
        /// The field.
        field: &'static str,
    },
    /// `ball_velocity_mps` too slow or too fast to fly.
    #[error("field `ball_velocity_mps`: speed {speed_mps:.1} m/s is outside 1-150 m/s")]
    VelocityOutOfRange {
        /// Its length (m/s).
        speed_mps: Real,
    },
    /// Neither `ball_speed_mps` nor `ball_speed_mph` (nor the vectors).
    #[error("field `ball_speed_mps` (or `ball_speed_mph`) is missing")]
    MissingSpeed,
    /// `ball_speed_mps` (or `ball_speed_mph`) too slow or too fast to fly.
    #[error("field `ball_speed_mps`: {speed_mps:.1} m/s is outside 1-150 m/s")]
    SpeedOutOfRange {
        /// The speed (m/s).
        speed_mps: Real,
    },
    /// `launch_angle_deg` outside -30 to 80 deg.
    #[error("field `launch_angle_deg`: {launch_angle_deg} is outside -30 to 80 deg")]
    LaunchAngleOutOfRange {
        /// The angle given (deg).
        launch_angle_deg: Real,
    },
    /// The spin from the spin fields above [`MAX_BALL_SPIN_RPM`].
    #[error("spin {spin_rpm:.0} rpm is above {MAX_BALL_SPIN_RPM} rpm")]
    SpinTooHigh {
        /// The total spin (rpm).
        spin_rpm: Real,
    },
    /// `ball_spin_radps` above [`MAX_BALL_SPIN_RPM`].
    #[error("field `ball_spin_radps`: {spin_rpm:.0} rpm is above {MAX_BALL_SPIN_RPM} rpm")]
    SpinVectorTooHigh {
        /// Its length (rpm).
        spin_rpm: Real,
    },
    /// A number given beside the vectors that disagrees with what they give.
    #[error(
        "field `{field}` = {given} disagrees with the vectors ({from_vectors:.3}): the vectors are what flies, so \
         give one or make them agree"
    )]
    Disagrees {
        /// The field.
        field: &'static str,
        /// Its value.
        given: Real,
        /// The value the vectors give.
        from_vectors: Real,
    },
}

/// The most spin a flight accepts: tour wedges reach about 12,000 rpm (TrackMan).
pub const MAX_BALL_SPIN_RPM: Real = 20_000.0;

impl FlightInput {
    /// With the vectors present, every scalar launch field given beside them must say the same (the line is
    /// echoed in the answer, so an ignored scalar that disagreed would be shown as if it had flown).
    fn agrees_with(&self, velocity_mps: &Vector3, spin_radps: &Vector3) -> Result<(), FlightInputError> {
        let m = crate::impact::LaunchMetrics::from_ball(velocity_mps, spin_radps);
        let speed_mph = crate::units::mps_to_mph(velocity_mps.norm());
        // (field, given, from the vectors, tolerance): rounding in a printed line, not a different launch.
        let checks = [
            ("ball_speed_mps", self.ball_speed_mps, velocity_mps.norm(), 0.05),
            ("ball_speed_mph", self.ball_speed_mph, speed_mph, 0.1),
            ("launch_angle_deg", Some(self.launch_angle_deg).filter(|a| *a != 0.0), m.launch_angle_deg, 0.1),
            (
                "launch_direction_deg",
                Some(self.launch_direction_deg).filter(|a| *a != 0.0),
                m.launch_direction_deg,
                0.1,
            ),
            ("backspin_rpm", self.backspin_rpm, m.backspin_rpm, 10.0),
            ("sidespin_rpm", self.sidespin_rpm, m.sidespin_rpm, 10.0),
            ("total_spin_rpm", self.total_spin_rpm, m.total_spin_rpm, 10.0),
        ];
        for (field, given, from_vectors, tolerance) in checks {
            if let Some(given) = given {
                if !(given.is_finite() && (given - from_vectors).abs() <= tolerance) {
                    return Err(FlightInputError::Disagrees { field, given, from_vectors });
                }
            }
        }
        Ok(())
    }

    /// The launch state, or the reason it cannot be made.
    pub fn to_launch(&self) -> Result<crate::flight::LaunchState, FlightInputError> {
        let finite = |field: &'static str, v: Real| {
            if v.is_finite() {
                Ok(v)
            } else {
                Err(FlightInputError::NotFinite { field })
            }
        };
        if let (Some(v), Some(w)) = (self.ball_velocity_mps, self.ball_spin_radps) {
            for x in v.iter() {
                finite("ball_velocity_mps", *x)?;
            }
            for x in w.iter() {
                finite("ball_spin_radps", *x)?;
            }
            let speed = Vector3::from(v).norm();
            if !(1.0..=150.0).contains(&speed) {
                return Err(FlightInputError::VelocityOutOfRange { speed_mps: speed });
            }
            let spin_rpm = crate::units::radps_to_rpm(Vector3::from(w).norm());
            if spin_rpm > MAX_BALL_SPIN_RPM {
                return Err(FlightInputError::SpinVectorTooHigh { spin_rpm });
            }
            self.agrees_with(&Vector3::from(v), &Vector3::from(w))?;
            return Ok(crate::flight::LaunchState { velocity_mps: Vector3::from(v), spin_radps: Vector3::from(w) });
        }
        let speed = match (self.ball_speed_mps, self.ball_speed_mph) {
            (Some(v), _) => finite("ball_speed_mps", v)?,
            (None, Some(v)) => crate::units::mph_to_mps(finite("ball_speed_mph", v)?),
            (None, None) => return Err(FlightInputError::MissingSpeed),
        };
        if !(1.0..=150.0).contains(&speed) {
            return Err(FlightInputError::SpeedOutOfRange { speed_mps: speed });
        }
        let launch = finite("launch_angle_deg", self.launch_angle_deg)?;
        if !(-30.0..=80.0).contains(&launch) {
            return Err(FlightInputError::LaunchAngleOutOfRange { launch_angle_deg: launch });
        }
        let direction = finite("launch_direction_deg", self.launch_direction_deg)?;
        let (back, side) = match (self.backspin_rpm, self.sidespin_rpm, self.total_spin_rpm, self.spin_axis_deg) {
            (Some(b), s, _, _) => (finite("backspin_rpm", b)?, finite("sidespin_rpm", s.unwrap_or(0.0))?),
            (None, _, Some(t), axis) => {
                let a = finite("spin_axis_deg", axis.unwrap_or(0.0))?.to_radians();
                let t = finite("total_spin_rpm", t)?;
                (t * a.cos(), t * a.sin())
            }
            (None, s, None, _) => (0.0, finite("sidespin_rpm", s.unwrap_or(0.0))?),
        };
        if back.hypot(side) > MAX_BALL_SPIN_RPM {
            return Err(FlightInputError::SpinTooHigh { spin_rpm: back.hypot(side) });
        }
        Ok(crate::flight::LaunchState::from_metrics(speed, launch, direction, back, side))
    }
}
