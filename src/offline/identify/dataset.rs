//! Shots for comparison and identification: one JSON object per line,
//! `{"delivery": {predict's input fields}, "measured": {"ball_speed_mph", "launch_angle_deg",
//! "launch_direction_deg", "backspin_rpm", "sidespin_rpm"}}` (TrackMan signs; `carry_yd` optional), resolved to
//! an impact state on a club once, since no identified parameter changes the state at first contact.

use super::IdentifyError;
use crate::impact::{Equipment, ImpactState};
use crate::math::Real;
pub use crate::pairing::DatasetLine;
use crate::wire::Handedness;

/// A shot ready for the models: the state at first contact (right-handed world) and the measured launch fields
/// in the order of [`super::FIELDS`], mirrored into the right-handed world for a left-hander.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shot {
    pub state: ImpactState,
    pub measured: [Real; 5],
}

pub use crate::pairing::fields::{fields_of, fields_of_launch, fields_of_measured, launch_fields};

impl DatasetLine {
    /// The shot on `equipment`: the delivery's state, the measurement mirrored for a left-hander.
    pub fn to_shot(&self, equipment: &Equipment) -> Result<Shot, crate::impact::ImpactError> {
        self.delivery.check_finite()?;
        let state = self.delivery.to_state(equipment)?;
        let mut measured = fields_of_launch(&self.measured);
        if self.delivery.handedness == Some(Handedness::Left) {
            measured[2] = -measured[2];
            measured[4] = -measured[4];
        }
        Ok(Shot { state, measured })
    }
}

/// Parses a JSONL dataset (blank lines and lines starting with `#` are skipped); a bad line is an error naming
/// its number (1-based) and the reason.
pub fn parse_jsonl(text: &str) -> Result<Vec<DatasetLine>, IdentifyError> {
    read_jsonl(text.as_bytes())
}

/// [`parse_jsonl`] over a stream, a line at a time: a line over [`crate::jsonl::MAX_LINE_BYTES`] is an error, so
/// no input (`/dev/zero`, a huge file) is read whole.
pub fn read_jsonl(mut input: impl std::io::BufRead) -> Result<Vec<DatasetLine>, IdentifyError> {
    let mut out = Vec::new();
    let mut buf = Vec::new();
    for n in 1.. {
        let err = |reason: String| IdentifyError::Line { line: n, reason };
        match crate::jsonl::read_line(&mut input, &mut buf, crate::jsonl::MAX_LINE_BYTES) {
            Ok(false) => break,
            Ok(true) => {}
            Err(e) => return Err(err(e.to_string())),
        }
        let Ok(line) = std::str::from_utf8(&buf) else { return Err(err("not UTF-8 text".into())) };
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let parsed: DatasetLine =
            serde_json::from_str(t).map_err(|e| err(crate::capped::quote(&e.to_string()).into()))?;
        parsed.measured.check_measurable().map_err(err)?;
        out.push(parsed);
    }
    Ok(out)
}

/// Resolves every line on `equipment`; a line whose delivery the club cannot take is an error naming it.
pub fn resolve(lines: &[DatasetLine], equipment: &Equipment) -> Result<Vec<Shot>, IdentifyError> {
    lines
        .iter()
        .enumerate()
        .map(|(i, l)| l.to_shot(equipment).map_err(|e| IdentifyError::Line { line: i + 1, reason: e.to_string() }))
        .collect()
}

/// Writes lines as JSONL.
pub fn to_jsonl(lines: &[DatasetLine]) -> String {
    let mut s = String::new();
    for l in lines {
        s.push_str(&serde_json::to_string(l).unwrap_or_default());
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::ClubSpec;

    #[test]
    fn a_line_round_trips_and_a_bad_one_is_named() {
        let text = r#"{"delivery": {"club_speed_mph": 110, "dynamic_loft_deg": 12}, "measured": {"ball_speed_mph": 160, "launch_angle_deg": 12, "launch_direction_deg": 1, "backspin_rpm": 2500, "sidespin_rpm": -200}}
# a comment

{"delivery": {"club_speed_mph": 110}, "measured": {"ball_speed_mph": 160}}"#;
        let err = parse_jsonl(text).unwrap_err().to_string();
        assert!(err.starts_with("line 4:"), "{err}");
        let first = parse_jsonl(text.lines().next().unwrap()).unwrap();
        assert_eq!(parse_jsonl(&to_jsonl(&first)).unwrap(), first);
        let shot = first[0].to_shot(&Equipment::new(ClubSpec::driver())).unwrap();
        assert_eq!(shot.measured, [160.0, 12.0, 1.0, 2500.0, -200.0]);
    }
}
