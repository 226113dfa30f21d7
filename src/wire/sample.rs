//! Checking an incoming clubhead sample: size, encoding version, JSON and rig.

use super::{ClubheadSampleMsg, MessageType, MAX_PAYLOAD_BYTES};

/// Why an incoming payload was not a usable sample.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InputError {
    #[error("payload of {bytes} bytes is over the {MAX_PAYLOAD_BYTES}-byte limit")]
    Oversized { bytes: usize },
    #[error("encoding `{encoding}` is not {expected}")]
    WrongVersion { encoding: String, expected: String },
    #[error("malformed sample: {0}")]
    Malformed(String),
    #[error("sample names rig `{payload}` but arrived on the key of rig `{key}`")]
    RigMismatch { payload: String, key: String },
}

impl InputError {
    /// The count it is filed under in a rig's status (`rejected`).
    pub fn rejection(&self) -> crate::pipeline::Rejection {
        use crate::pipeline::Rejection;
        match self {
            InputError::Oversized { .. } => Rejection::Oversized,
            InputError::WrongVersion { .. } => Rejection::WrongVersion,
            InputError::Malformed(_) => Rejection::Malformed,
            InputError::RigMismatch { .. } => Rejection::RigMismatch,
        }
    }

    pub fn key(&self) -> &'static str {
        match self {
            InputError::Oversized { .. } => "oversized",
            InputError::WrongVersion { .. } => "wrong_version",
            InputError::Malformed(_) => "malformed",
            InputError::RigMismatch { .. } => "rig_mismatch",
        }
    }
}

/// Parses a sample arriving on the key of `key_rig` with the given encoding (empty or plain
/// `application/json` is accepted; an `impactd.ClubheadSample/<v>` schema must name this version).
pub fn parse_sample(key_rig: &str, payload: &[u8], encoding: &str) -> Result<ClubheadSampleMsg, InputError> {
    if payload.len() > MAX_PAYLOAD_BYTES {
        return Err(InputError::Oversized { bytes: payload.len() });
    }
    if let Some(schema) = encoding.split_once(';').map(|(_, s)| s) {
        let expected = MessageType::ClubheadSample.encoding();
        let name = MessageType::ClubheadSample.schema_name();
        if schema.starts_with(&format!("{name}/")) && !expected.ends_with(&format!(";{schema}")) {
            return Err(InputError::WrongVersion { encoding: encoding.to_string(), expected });
        }
    }
    let msg: ClubheadSampleMsg = serde_json::from_slice(payload).map_err(|e| InputError::Malformed(e.to_string()))?;
    if msg.rig != key_rig {
        return Err(InputError::RigMismatch { payload: msg.rig, key: key_rig.to_string() });
    }
    Ok(msg)
}
