//! The page's controls, each the put a program would make on zenoh: the club (`golf/<rig>/club`, plain text),
//! player and tags (`golf/<rig>/session`, [`ShotLabels`]), a shot left out (`golf/<rig>/exclude`) and the units
//! (`golf/<rig>/display`). A page's message is one JSON object with an `op`; anything else is refused with a
//! kind counted in the rig's status.

use crate::daemon::bridges::peer_rejection::PeerRejection;
use serde::Deserialize;

use crate::wire::{keys, DisplaySettings, DisplayUnits, ShotExclusion, ShotLabels};

/// A page's message.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "op", rename_all = "snake_case", deny_unknown_fields)]
pub enum Control {
    /// Switch the rig's club (a preset name or a club-file path).
    Club { rig: String, club: String },
    /// The player and tags of the next shots (the club label and note are kept).
    Labels {
        rig: String,
        #[serde(default)]
        player: Option<String>,
        #[serde(default)]
        tags: Vec<String>,
    },
    /// Leave a shot out of the session, or take it back.
    Exclude { rig: String, shot: u64, excluded: bool },
    /// The units of the rig's screens.
    Units { rig: String, units: DisplayUnits },
}

/// Why a page's message was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ControlReject {
    #[error("not a control: {0}")]
    Malformed(String),
    #[error("no rig `{0}` is served here")]
    UnknownRig(String),
    #[error("{0}")]
    Invalid(String),
}

impl ControlReject {
    pub fn kind(&self) -> PeerRejection {
        match self {
            ControlReject::Malformed(_) => PeerRejection::Malformed,
            ControlReject::UnknownRig(_) => PeerRejection::UnknownRig,
            ControlReject::Invalid(_) => PeerRejection::InvalidControl,
        }
    }
}

impl Control {
    pub fn rig(&self) -> &str {
        match self {
            Control::Club { rig, .. }
            | Control::Labels { rig, .. }
            | Control::Exclude { rig, .. }
            | Control::Units { rig, .. } => rig,
        }
    }

    /// Parses a page's message, for one of `rigs`.
    pub fn parse(text: &str, rigs: &[String]) -> Result<Self, ControlReject> {
        let c: Control = serde_json::from_str(text).map_err(|e| ControlReject::Malformed(e.to_string()))?;
        if !rigs.iter().any(|r| r == c.rig()) {
            return Err(ControlReject::UnknownRig(c.rig().chars().take(64).collect()));
        }
        Ok(c)
    }

    /// The key and payload of the put this control makes; `current` are the rig's labels now.
    pub fn put(&self, current: &ShotLabels) -> Result<(String, Vec<u8>), ControlReject> {
        let invalid = |e: &dyn std::fmt::Display| ControlReject::Invalid(e.to_string());
        Ok(match self {
            Control::Club { rig, club } => {
                let text = crate::wire::club_text(club.as_bytes()).map_err(|e| invalid(&e))?;
                (keys::club(rig), text.as_bytes().to_vec())
            }
            Control::Labels { rig, player, tags } => {
                let player = player.as_deref().map(str::trim).filter(|p| !p.is_empty()).map(String::from);
                let tags = tags.iter().map(|t| t.trim()).filter(|t| !t.is_empty()).map(String::from).collect();
                let labels = ShotLabels { player, tags, club: current.club.clone(), note: current.note.clone() };
                labels.check().map_err(|e| invalid(&e))?;
                (keys::session(rig), serde_json::to_vec(&labels).unwrap_or_default())
            }
            Control::Exclude { rig, shot, excluded } => {
                let x = ShotExclusion { shot: *shot, excluded: *excluded };
                (keys::exclude(rig), serde_json::to_vec(&x).unwrap_or_default())
            }
            Control::Units { rig, units } => {
                (keys::display(rig), serde_json::to_vec(&DisplaySettings { units: *units }).unwrap_or_default())
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_control_is_the_put_a_program_would_make() {
        let rigs = vec!["bay1".to_string()];
        let none = ShotLabels::default();
        let club = Control::parse(r#"{"op":"club","rig":"bay1","club":" iron7 "}"#, &rigs).unwrap();
        assert_eq!(club.put(&none).unwrap(), ("golf/bay1/club".to_string(), b"iron7".to_vec()));
        let kept = ShotLabels { club: Some("7i".into()), ..Default::default() };
        let labels =
            Control::parse(r#"{"op":"labels","rig":"bay1","player":"ann","tags":["fit"," "]}"#, &rigs).unwrap();
        let (key, payload) = labels.put(&kept).unwrap();
        assert_eq!(key, "golf/bay1/session");
        let sent = ShotLabels::parse(&payload).unwrap();
        assert_eq!(
            (sent.player.as_deref(), sent.tags.as_slice(), sent.club.as_deref()),
            (Some("ann"), &["fit".to_string()][..], Some("7i"))
        );
        let x = Control::parse(r#"{"op":"exclude","rig":"bay1","shot":4,"excluded":true}"#, &rigs).unwrap();
        assert_eq!(ShotExclusion::parse(&x.put(&none).unwrap().1), Ok(ShotExclusion { shot: 4, excluded: true }));
        let u = Control::parse(r#"{"op":"units","rig":"bay1","units":"metric"}"#, &rigs).unwrap();
        assert_eq!(u.put(&none).unwrap().0, "golf/bay1/display");

        let refused = |text: &str| Control::parse(text, &rigs).unwrap_err().kind();
        assert_eq!(refused(r#"{"op":"club","rig":"bay2","club":"iron7"}"#), PeerRejection::UnknownRig);
        assert_eq!(refused(r#"{"op":"reboot","rig":"bay1"}"#), PeerRejection::Malformed);
        assert_eq!(refused("not json"), PeerRejection::Malformed);
        let empty = Control::parse(r#"{"op":"club","rig":"bay1","club":"  "}"#, &rigs).unwrap();
        assert_eq!(empty.put(&none).unwrap_err().kind(), PeerRejection::InvalidControl);
        let long = format!(r#"{{"op":"labels","rig":"bay1","player":"{}"}}"#, "x".repeat(300));
        assert_eq!(Control::parse(&long, &rigs).unwrap().put(&none).unwrap_err().kind(), PeerRejection::InvalidControl);
    }
}
