//! The configuration's poses (`[rig.world_from_lab]`, `[rig.club_from_body]`) and the clubs of a rig's tracked
//! bodies (`[rig.clubs]`: a club, or a club and where the body sits on it).

use serde::{Deserialize, Serialize};

use crate::daemon::DaemonError;
use crate::math::{Isometry3, Translation3Ext, Vector3};

/// A `[rig.clubs]` entry: a club (preset or file), or a club with the body's own pose in the club frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum BodyClub {
    Club(String),
    Mounted(MountedClub),
}

/// A club and where its tracked body sits on it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MountedClub {
    pub club: String,
    /// The body's pose in the club frame (default: the rig's `club_from_body`).
    #[serde(default)]
    pub club_from_body: Option<PoseConfig>,
}

impl BodyClub {
    pub(super) fn club(&self) -> &str {
        match self {
            BodyClub::Club(c) | BodyClub::Mounted(MountedClub { club: c, .. }) => c,
        }
    }
}

/// A rigid transform: rotation quaternion `[x, y, z, w]` and translation (m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoseConfig {
    #[serde(default = "identity_xyzw")]
    pub rotation_xyzw: [f64; 4],
    #[serde(default)]
    pub translation_m: [f64; 3],
}

fn identity_xyzw() -> [f64; 4] {
    [0.0, 0.0, 0.0, 1.0]
}

impl PoseConfig {
    pub(super) fn to_isometry(self, field: String) -> Result<Isometry3, DaemonError> {
        if self.rotation_xyzw.iter().chain(self.translation_m.iter()).any(|v| !v.is_finite()) {
            return Err(DaemonError::Config { field, reason: "must be finite numbers".into() });
        }
        let q = crate::kinematics::sample::unit_quaternion(&self.rotation_xyzw, 1e-3).ok_or_else(|| {
            DaemonError::Config {
                field: format!("{field}.rotation_xyzw"),
                reason: "must be a unit quaternion [x, y, z, w]".into(),
            }
        })?;
        Ok(Isometry3::from_parts(Vector3::from(self.translation_m).into_translation(), q))
    }
}
