//! What an impact-state estimator fits ([`EstimatorSpec`]): the named estimators (`linear2`, `poly`, `arc`) and
//! custom ones, and the checks on their numbers.

use super::fit::MAX_DEGREE;
use crate::math::Real;

/// Why an estimator's numbers are unusable.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum EstimatorSpecError {
    /// A fit's polynomial degree is above [`MAX_DEGREE`].
    #[error("{what} degree {degree} is above the maximum {max}")]
    DegreeTooHigh {
        /// Which fit: `position` or `rotation`.
        what: &'static str,
        /// The degree asked for.
        degree: usize,
        /// The highest degree a fit supports ([`MAX_DEGREE`]).
        max: usize,
    },
    /// A fit's frame count is not above its degree, or is above 64.
    #[error("{what} frames must be within {min} and 64 for degree {degree}, got {frames}")]
    FrameCount {
        /// Which fit: `position` or `rotation`.
        what: &'static str,
        /// The frame count asked for.
        frames: usize,
        /// The fit's degree.
        degree: usize,
        /// The fewest frames that degree needs (`degree + 1`).
        min: usize,
    },
    /// `rotation_frames` is above `frames`.
    #[error("rotation frames must not exceed position frames")]
    RotationFrames,
}

/// How an estimator fits: how many pre-impact frames and which polynomial degrees.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct EstimatorSpec {
    /// The estimator's name as [`by_name`](Self::by_name) reads it (`linear2`, `poly`, `arc` or a custom
    /// `poly:...`, `poly@...`, `arc@...`), reported with each estimate.
    pub name: String,
    /// Frames of the position fit (the newest pre-impact ones).
    pub frames: usize,
    /// Degree of the position polynomial in time (at most [`MAX_DEGREE`]; 1 for `linear2`).
    pub position_degree: usize,
    /// Frames of the orientation fit (at most `frames`).
    pub rotation_frames: usize,
    /// Degree of the orientation's polynomial: the rotation vector relative to the newest frame, in time (at most
    /// [`MAX_DEGREE`]).
    pub rotation_degree: usize,
    /// When set, the fits use the pre-impact frames within this time span instead of a fixed count (at most
    /// `frames` / `rotation_frames`), and each degree is capped at half the frames minus one, so one spec
    /// serves every capture rate (ms).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub window_ms: Option<Real>,
    /// With `window_ms` set, the orientation fit's own time span (ms); unset, it uses `window_ms`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation_window_ms: Option<Real>,
    /// When set, the club speed comes from a fit of the path length over this span ([`PathSpeedFit`](super::path_speed::PathSpeedFit)) and the
    /// velocity's direction from the position fit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub path_speed: Option<PathSpeedSpec>,
    /// When set, the face centre's position and velocity come from an arc ([`ArcFit`](super::arc::ArcFit)) fitted to the frames
    /// within this span (ms); the polynomial position fit stands in when the arc fit fails or fits the frames
    /// worse than it (`ARC_LACK_OF_FIT_RATIO`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arc_window_ms: Option<Real>,
}

/// The span and degree of the path-length fit that gives the club speed.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PathSpeedSpec {
    /// The span of the newest pre-impact frames whose path length is fitted (ms).
    pub window_ms: Real,
    /// Degree of the path length's polynomial in time (capped at half the span's frames minus one).
    pub degree: usize,
}

impl EstimatorSpec {
    /// The seed's two-point linear extrapolation.
    pub fn linear2() -> Self {
        EstimatorSpec {
            name: "linear2".into(),
            frames: 2,
            position_degree: 1,
            rotation_frames: 2,
            rotation_degree: 1,
            window_ms: None,
            rotation_window_ms: None,
            path_speed: None,
            arc_window_ms: None,
        }
    }

    /// Least squares over the last 44 ms of the face centre's path (degree up to 5), the
    /// last 39 ms of the orientation (degree up to 3) and, for the club speed, the last 40 ms of the path length
    /// (cubic, [`PathSpeedFit`](super::path_speed::PathSpeedFit)). The spans were chosen with
    /// `impactd eval extrapolation` at 240, 720 and 1000 Hz (README).
    pub fn poly() -> Self {
        EstimatorSpec {
            name: "poly".into(),
            frames: 64,
            position_degree: 5,
            rotation_frames: 64,
            rotation_degree: 3,
            window_ms: Some(44.0),
            rotation_window_ms: Some(39.0),
            path_speed: Some(PathSpeedSpec { window_ms: 40.0, degree: 3 }),
            arc_window_ms: None,
        }
    }

    /// The default estimator: `poly` with the face centre's path as an arc over the last `ARC_WINDOW_MS`
    /// ([`ArcFit`](super::arc::ArcFit)), a cubic angle and a quadratic radius in the swing's plane instead of a degree-5 polynomial in
    /// space, while the arc fits the frames about as well as the polynomial does (`ARC_LACK_OF_FIT_RATIO`), and
    /// `poly`'s path otherwise. The club speed stays the path-length fit's: the arc's own is twice as precise on
    /// an exact arc but biased on other paths.
    pub fn arc() -> Self {
        Self::arc_over(Self::ARC_WINDOW_MS, "arc")
    }

    fn arc_over(window_ms: Real, name: &str) -> Self {
        EstimatorSpec { name: name.into(), arc_window_ms: Some(window_ms), ..Self::poly() }
    }

    /// The span of the arc fit (ms).
    pub const ARC_WINDOW_MS: Real = 60.0;

    /// The fewest frames a windowed fit accepts (a quadratic with two frames per coefficient).
    pub const MIN_WINDOW_FRAMES: usize = 6;

    /// The estimators by name: `linear2`, `poly`,
    /// `poly:POSITION_FRAMES:POSITION_DEGREE:ROTATION_FRAMES:ROTATION_DEGREE` (fixed frame counts) or
    /// `poly@POSITION_MS:POSITION_DEGREE:ROTATION_MS:ROTATION_DEGREE` (time spans).
    pub fn by_name(name: &str) -> Option<Self> {
        match name {
            "linear2" => Some(Self::linear2()),
            "poly" => Some(Self::poly()),
            "arc" => Some(Self::arc()),
            custom if custom.starts_with("arc@") => {
                let ms: Real = custom["arc@".len()..].parse().ok()?;
                (ms > 0.0 && ms <= 90.0).then(|| Self::arc_over(ms, custom))
            }
            custom if custom.starts_with("poly@") => {
                let parts: Vec<Real> =
                    custom["poly@".len()..].split(':').map(|p| p.parse().ok()).collect::<Option<_>>()?;
                let (pos_ms, pos_deg, rot_ms, rot_deg, path_speed) = match parts[..] {
                    [a, b, c, d] => (a, b, c, d, None),
                    [a, b, c, d, e, f] if e > 0.0 && (1.0..=3.0).contains(&f) => {
                        (a, b, c, d, Some(PathSpeedSpec { window_ms: e, degree: f as usize }))
                    }
                    _ => return None,
                };
                let spec = EstimatorSpec {
                    name: custom.to_string(),
                    window_ms: Some(pos_ms),
                    rotation_window_ms: Some(rot_ms),
                    position_degree: pos_deg as usize,
                    rotation_degree: rot_deg as usize,
                    path_speed,
                    ..Self::poly()
                };
                (pos_ms > 0.0
                    && rot_ms > 0.0
                    && spec.position_degree <= super::fit::MAX_DEGREE
                    && spec.rotation_degree <= super::fit::MAX_DEGREE)
                    .then_some(spec)
            }
            custom => {
                let mut parts = custom.strip_prefix("poly:")?.split(':').map(|p| p.parse::<usize>().ok());
                let spec = EstimatorSpec {
                    name: custom.to_string(),
                    frames: parts.next()??,
                    position_degree: parts.next()??,
                    rotation_frames: parts.next()??,
                    rotation_degree: parts.next()??,
                    window_ms: None,
                    rotation_window_ms: None,
                    path_speed: None,
                    arc_window_ms: None,
                };
                (parts.next().is_none() && spec.validate().is_ok()).then_some(spec)
            }
        }
    }

    /// The named estimators [`by_name`](Self::by_name) knows besides the custom `poly:`, `poly@` and `arc@` forms.
    pub const NAMES: [&'static str; 3] = ["linear2", "poly", "arc"];

    /// Checks the numbers are usable.
    pub fn validate(&self) -> Result<(), EstimatorSpecError> {
        for (what, frames, degree) in
            [("position", self.frames, self.position_degree), ("rotation", self.rotation_frames, self.rotation_degree)]
        {
            if degree > MAX_DEGREE {
                return Err(EstimatorSpecError::DegreeTooHigh { what, degree, max: MAX_DEGREE });
            }
            if frames <= degree || frames > 64 {
                return Err(EstimatorSpecError::FrameCount { what, frames, degree, min: degree + 1 });
            }
        }
        if self.rotation_frames > self.frames {
            return Err(EstimatorSpecError::RotationFrames);
        }
        Ok(())
    }
}
