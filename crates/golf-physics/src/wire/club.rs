//! Which club a shot used: the club's name, the preset or file it was loaded from, and the SHA-256 of that
//! file's bytes, in every impact and launch (`club_file`), and recorded on `golf/<rig>/club` each time a rig's
//! club changes (at start, by a put on `golf/<rig>/club`, or by another tracked body coming into view).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A club and the file it came from.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct ClubRef {
    /// The club's name (a preset's name, or the `name` field of a club file).
    pub name: String,
    /// What loaded it: a preset name (`sw`) or the club file's path as given.
    pub file: String,
    /// SHA-256 of the club file's bytes, lower-case hex (`sha256sum FILE`); a preset's is that of its file in
    /// `clubs/presets/`.
    pub sha256: String,
}

/// Why a rig's club changed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ClubSource {
    /// The rig's configuration (`club = ...`), at start.
    Config,
    /// A put on `golf/<rig>/club`.
    Put,
    /// Another tracked body (`[rig.clubs]`) came into view.
    Body,
}

/// A rig's club from now on: recorded on `golf/<rig>/club` at start and at every change.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct ClubChange {
    /// The rig whose club changed.
    pub rig: String,
    /// The club now in use: preset or path, and its SHA-256.
    pub club: ClubRef,
    /// What made the change.
    pub source: ClubSource,
    /// The tracked body that holds the club (`[rig.clubs]`), when bodies choose the club.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// The rig's models for this club, in publication order.
    #[serde(deserialize_with = "super::model_name::list")]
    pub models: Vec<String>,
}

/// The largest put on `golf/<rig>/club` (bytes): a preset name or a path.
pub const MAX_CLUB_PUT_BYTES: usize = 4096;

/// Why a put on `golf/<rig>/club` was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ClubPutError {
    /// Longer than [`MAX_CLUB_PUT_BYTES`] (the put's length in bytes).
    #[error("a club put is a preset name or a club file's path, at most {MAX_CLUB_PUT_BYTES} bytes; got {0} bytes")]
    TooLong(usize),
    /// Not UTF-8.
    #[error("a club put is UTF-8 text (a preset name or a club file's path)")]
    NotText,
    /// Nothing but white space.
    #[error("a club put is a preset name or a club file's path; it is empty")]
    Empty,
}

/// The preset name or path a put on `golf/<rig>/club` carries (plain UTF-8 text, surrounding space trimmed).
pub fn parse_club_put(payload: &[u8]) -> Result<String, ClubPutError> {
    if payload.len() > MAX_CLUB_PUT_BYTES {
        return Err(ClubPutError::TooLong(payload.len()));
    }
    let text = std::str::from_utf8(payload).map_err(|_| ClubPutError::NotText)?.trim();
    if text.is_empty() || text.contains(['\0', '\n']) {
        return Err(if text.is_empty() { ClubPutError::Empty } else { ClubPutError::NotText });
    }
    Ok(text.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_put_is_one_line_of_text() {
        assert_eq!(parse_club_put(b" iron7\n").unwrap(), "iron7");
        assert_eq!(parse_club_put(b"clubs/presets/sw.toml").unwrap(), "clubs/presets/sw.toml");
        assert_eq!(parse_club_put(b"  "), Err(ClubPutError::Empty));
        assert_eq!(parse_club_put(&[0xff, 0xfe]), Err(ClubPutError::NotText));
        assert_eq!(parse_club_put(b"a\nb"), Err(ClubPutError::NotText));
        assert!(matches!(parse_club_put(&[b'a'; 5000]), Err(ClubPutError::TooLong(5000))));
    }
}
