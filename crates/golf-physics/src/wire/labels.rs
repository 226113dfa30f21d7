//! Labels of a shot: who hit it, with which club (the fitter's name for it), tags and free text. They come from
//! the rig's configuration (`[rig.labels]`), a put on `golf/<rig>/session` (the labels of the shots that follow),
//! or the input line of `impactd predict`; impacts and launches carry them, so recordings are grouped by them
//! (`impactd session --by club|player|tag`).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The labels of a shot (every field optional; empty labels are left out of messages).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ShotLabels {
    /// The golfer.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub player: Option<String>,
    /// The fitter's name of the club in the golfer's hands (`"7i"`, `"G430 driver 9°"`); the club file the
    /// models use is the message's `club`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub club: Option<String>,
    /// Free tags (`"fitting"`, `"shaft B"`), at most [`MAX_TAGS`].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tags: Vec<String>,
    /// Free text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// The longest label text accepted (bytes); a put beyond it is refused.
pub const MAX_LABEL_BYTES: usize = 256;
/// The most tags of one shot.
pub const MAX_TAGS: usize = 32;

/// Why a put on `golf/<rig>/session` was refused.
#[derive(Debug, thiserror::Error)]
pub enum LabelsError {
    /// Not JSON of the labels' fields.
    #[error("session labels are not valid: {0}")]
    Parse(#[source] serde_json::Error),
    /// A label longer than [`MAX_LABEL_BYTES`].
    #[error("field `{field}`: longer than {MAX_LABEL_BYTES} bytes")]
    TooLong {
        /// The label (`player`, `club`, `note`, a tag).
        field: &'static str,
    },
    /// More than [`MAX_TAGS`] tags.
    #[error("field `tags`: more than {MAX_TAGS} tags")]
    TooManyTags,
}

impl ShotLabels {
    /// No label at all.
    pub fn is_empty(&self) -> bool {
        self.player.is_none() && self.club.is_none() && self.tags.is_empty() && self.note.is_none()
    }

    /// Labels from a put's payload (JSON), within the bounds above.
    pub fn parse(payload: &[u8]) -> Result<Self, LabelsError> {
        let labels: ShotLabels = serde_json::from_slice(payload).map_err(LabelsError::Parse)?;
        labels.check()?;
        Ok(labels)
    }

    /// Every text within [`MAX_LABEL_BYTES`] and at most [`MAX_TAGS`] tags.
    pub fn check(&self) -> Result<(), LabelsError> {
        let long = |s: &Option<String>| s.as_ref().is_some_and(|s| s.len() > MAX_LABEL_BYTES);
        if long(&self.player) {
            return Err(LabelsError::TooLong { field: "player" });
        }
        if long(&self.club) {
            return Err(LabelsError::TooLong { field: "club" });
        }
        if long(&self.note) {
            return Err(LabelsError::TooLong { field: "note" });
        }
        if self.tags.len() > MAX_TAGS {
            return Err(LabelsError::TooManyTags);
        }
        if self.tags.iter().any(|t| t.len() > MAX_LABEL_BYTES) {
            return Err(LabelsError::TooLong { field: "tags" });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_put_is_parsed_and_bounded() {
        let l = ShotLabels::parse(br#"{"player":"ann","club":"7i","tags":["fit"],"note":"new shaft"}"#).unwrap();
        assert_eq!(l.player.as_deref(), Some("ann"));
        assert_eq!(l.tags, ["fit"]);
        assert!(ShotLabels::parse(b"{}").unwrap().is_empty());
        let long = format!(r#"{{"player":"{}"}}"#, "x".repeat(MAX_LABEL_BYTES + 1));
        assert!(matches!(ShotLabels::parse(long.as_bytes()), Err(LabelsError::TooLong { field: "player" })));
        assert!(
            matches!(ShotLabels::parse(br#"{"plyer":"ann"}"#), Err(LabelsError::Parse(e)) if e.to_string().contains("plyer"))
        );
    }
}
