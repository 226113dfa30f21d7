//! The bay's controls that are not shot labels: leaving a shot out of the session's numbers
//! (`golf/<rig>/exclude`, recorded, so `impactd session` leaves it out too) and the units a bay screen shows
//! (`golf/<rig>/display`). Each is a put any program can make; the bay screen's controls make the same puts.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A shot left out of (or taken back into) the session's averages, on `golf/<rig>/exclude`; the last put for a
/// shot wins.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ShotExclusion {
    /// The shot number (as in `golf/<rig>/launch`).
    pub shot: u64,
    /// `true` leaves the shot out (a mishit), `false` takes it back.
    pub excluded: bool,
}

/// Units of a display.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum DisplayUnits {
    /// mph, yd, ft.
    #[default]
    Imperial,
    /// m/s, m.
    Metric,
}

/// What a rig's bay screens show, on `golf/<rig>/display`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DisplaySettings {
    pub units: DisplayUnits,
}

/// Why a control's put was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ControlError {
    #[error("not valid JSON for {what}: {reason}")]
    Parse { what: &'static str, reason: String },
    #[error("club name is empty or longer than {MAX_CLUB_BYTES} bytes")]
    BadClub,
}

/// The longest club name or club-file path a control sends (bytes).
pub const MAX_CLUB_BYTES: usize = 512;

impl ShotExclusion {
    pub fn parse(payload: &[u8]) -> Result<Self, ControlError> {
        serde_json::from_slice(payload)
            .map_err(|e| ControlError::Parse { what: "a shot exclusion", reason: e.to_string() })
    }
}

impl DisplaySettings {
    pub fn parse(payload: &[u8]) -> Result<Self, ControlError> {
        serde_json::from_slice(payload)
            .map_err(|e| ControlError::Parse { what: "display settings", reason: e.to_string() })
    }
}

/// A club put's text (`golf/<rig>/club`: a preset name or a club-file path), trimmed and bounded.
pub fn club_text(payload: &[u8]) -> Result<&str, ControlError> {
    let text = std::str::from_utf8(payload).map_err(|_| ControlError::BadClub)?.trim();
    if text.is_empty() || text.len() > MAX_CLUB_BYTES {
        return Err(ControlError::BadClub);
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn controls_parse_and_refuse_with_a_reason() {
        assert_eq!(
            ShotExclusion::parse(br#"{"shot":3,"excluded":true}"#),
            Ok(ShotExclusion { shot: 3, excluded: true })
        );
        assert!(matches!(ShotExclusion::parse(br#"{"shot":-1,"excluded":true}"#), Err(ControlError::Parse { .. })));
        assert_eq!(DisplaySettings::parse(br#"{"units":"metric"}"#).map(|d| d.units), Ok(DisplayUnits::Metric));
        assert!(DisplaySettings::parse(br#"{"units":"furlongs"}"#).is_err());
        assert_eq!(club_text(b" iron7\n"), Ok("iron7"));
        assert_eq!(club_text(b"  "), Err(ControlError::BadClub));
        assert_eq!(club_text(&[0xff, 0xfe]), Err(ControlError::BadClub));
    }
}
