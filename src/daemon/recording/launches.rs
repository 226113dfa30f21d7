//! The predicted launches of MCAP recordings (`golf/<rig>/launch`), one per shot: the first model's (the one
//! published first), or the named model's; and the shots left out of the session by puts on
//! `golf/<rig>/exclude` (the last put for a shot wins).

use std::path::Path;

use super::reader::OnDamage;
use super::stream::read_messages;
use crate::daemon::DaemonError;
use crate::wire::{keys, LaunchPrediction};

/// The launches of one recording.
#[derive(Debug, Default)]
pub struct RecordedLaunches {
    /// One prediction per (rig, shot), in recording order.
    pub launches: Vec<LaunchPrediction>,
    /// Every model the recording holds predictions of, in order of first appearance.
    pub models: Vec<String>,
    /// The shots left out of the session by a put on `golf/<rig>/exclude`, as `(rig, shot)`, after the last put.
    pub excluded: std::collections::BTreeSet<(String, u64)>,
    /// What could not be read (a damaged tail, a prediction that does not parse).
    pub damage: Vec<String>,
}

/// Reads the launches of `path`; with `model`, only that model's (an error when the recording has none of it).
pub fn read(path: &Path, model: Option<&str>) -> Result<RecordedLaunches, DaemonError> {
    let mut out = RecordedLaunches::default();
    let mut seen = std::collections::HashSet::new();
    let mut damage = Vec::new();
    let scan = read_messages(path, OnDamage::Stop, |_, channel, m| {
        let Some(channel) = channel else { return };
        if let Some(rig) = keys::rig_of_golf(channel.topic.trim_start_matches('/'), "exclude") {
            match crate::wire::ShotExclusion::parse(&m.data) {
                Ok(x) if x.excluded => {
                    out.excluded.insert((rig.to_string(), x.shot));
                }
                Ok(x) => {
                    out.excluded.remove(&(rig.to_string(), x.shot));
                }
                Err(e) => damage.push(format!("an exclusion at log time {} does not parse: {e}", m.log_time)),
            }
            return;
        }
        if keys::rig_of_launch(channel.topic.trim_start_matches('/')).is_none() {
            return;
        }
        let p = match serde_json::from_slice::<LaunchPrediction>(&m.data) {
            Ok(p) => p,
            Err(e) => {
                damage.push(format!("a prediction at log time {} does not parse: {e}", m.log_time));
                return;
            }
        };
        if !out.models.contains(&p.model) {
            out.models.push(p.model.clone());
        }
        if model.is_some_and(|name| name != p.model) {
            return;
        }
        if seen.insert((p.rig.clone(), p.shot)) {
            out.launches.push(p);
        }
    })?;
    out.damage = scan.problems();
    out.damage.extend(damage);
    if let Some(name) = model {
        if out.launches.is_empty() && !out.models.is_empty() {
            return Err(DaemonError::Config {
                field: "--model".into(),
                reason: format!("{} holds predictions of {} only, not {name}", path.display(), out.models.join(", ")),
            });
        }
    }
    Ok(out)
}
