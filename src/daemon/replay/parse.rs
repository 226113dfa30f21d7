//! A recorded message or a JSONL line as a replay reads it: an [`Item`], a recorded prediction, nothing of
//! interest, or the reason it cannot be read. The index pass and the replay itself read through these same two
//! functions, so they agree on every message.

use super::items::{contains, Item};
use crate::wire::{keys, ClubheadSampleMsg, LaunchPrediction};

/// Which pass reads a recorded message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pass {
    /// The index: a sample is counted from its topic (its rig) and its publish time (its capture time, as the
    /// daemon records it) without being parsed; recorded predictions are read.
    Index,
    /// The index, each sample parsed for its own rig and capture time (what `--start-offset` counts from).
    IndexParsed,
    /// The replay: samples are parsed, recorded predictions passed over.
    Replay,
}

/// What a message or a line is to a replay.
pub enum Parsed {
    Item(Item),
    /// A recorded sample, seen by the index pass: its topic's rig, capture and receive times.
    SampleAt {
        rig: String,
        t_ns: u64,
        log_time_ns: u64,
    },
    /// A recorded prediction's bytes (under the current model name), its (rig, shot, model) and latency, and the
    /// former model name it was recorded under, if any (`(former, current)`).
    Launch {
        data: Vec<u8>,
        key: Option<((String, u64, String), f64)>,
        renamed: Option<(String, String)>,
    },
    /// Neither a sample nor anything a replay uses.
    Other,
    /// Cannot be read: why.
    Bad(String),
}

/// A recorded message on `topic` (its key with the leading `/`), received at `log_time_ns` and published (a
/// sample: captured) at `publish_time_ns`, as `pass` reads it.
pub fn recorded(topic: &str, data: Vec<u8>, log_time_ns: u64, publish_time_ns: u64, pass: Pass) -> Parsed {
    let topic = topic.trim_start_matches('/');
    let at = log_time_ns;
    if let Some(rig) = keys::rig_of_clubhead(topic) {
        if pass == Pass::Index {
            return Parsed::SampleAt { rig: rig.to_string(), t_ns: publish_time_ns, log_time_ns };
        }
        let why = |e| format!("a recorded sample at log time {at} does not parse: {e}");
        match (serde_json::from_slice::<ClubheadSampleMsg>(&data), pass) {
            (Ok(msg), Pass::IndexParsed) => Parsed::SampleAt { rig: msg.rig, t_ns: msg.t_ns, log_time_ns },
            (Ok(msg), _) => Parsed::Item(Item::Sample { msg, log_time_ns: Some(at) }),
            // Damage the replay finds again (as an item) and reports.
            (Err(_), Pass::IndexParsed) => Parsed::Other,
            (Err(e), _) => Parsed::Item(Item::Unreadable(why(e))),
        }
    } else if keys::rig_of_ball(topic).is_some() {
        match crate::wire::BallSampleMsg::parse(&data) {
            Ok(ball) => Parsed::Item(Item::Ball { ball, payload: data }),
            Err(e) => Parsed::Bad(format!("a recorded ball sample at log time {at} does not parse: {e}")),
        }
    } else if let Some(rig) = keys::rig_of_truth(topic) {
        match serde_json::from_slice::<crate::wire::TruthMessage>(&data) {
            Ok(t) => Parsed::Item(Item::Truth { rig: rig.to_string(), t_impact_ns: t.t_impact_ns, payload: data }),
            Err(e) => Parsed::Bad(format!("a recorded truth at log time {at} does not parse: {e}")),
        }
    } else if let Some(rig) = keys::rig_of_session(topic) {
        match crate::wire::ShotLabels::parse(&data) {
            Ok(labels) => Parsed::Item(Item::Labels { rig: rig.to_string(), labels }),
            Err(e) => Parsed::Bad(format!("recorded labels at log time {at} do not parse: {e}")),
        }
    } else if let Some(rig) = keys::rig_of_club(topic) {
        match serde_json::from_slice::<crate::wire::ClubChange>(&data) {
            Ok(change) if change.source == crate::wire::ClubSource::Put => {
                Parsed::Item(Item::ClubPut { rig: rig.to_string(), change })
            }
            Ok(_) => Parsed::Other,
            Err(e) => Parsed::Bad(format!("a recorded club change at log time {at} does not parse: {e}")),
        }
    } else if pass != Pass::Replay && keys::rig_of_launch(topic).is_some() {
        let mut data = data;
        let mut key = None;
        let mut renamed = None;
        if let Ok(l) = serde_json::from_slice::<LaunchPrediction>(&data) {
            if let Some((bytes, names)) = under_current_name(&data, &l.model) {
                data = bytes;
                renamed = Some(names);
            }
            key = Some(((l.rig.clone(), l.shot, l.model.clone()), l.latency_us));
        }
        Parsed::Launch { data, key, renamed }
    } else {
        Parsed::Other
    }
}

/// A line of a JSONL file of samples: a sample (received at its `t_ns`), a ball line (`impactd import
/// --ball-marker`), nothing (a blank line), or why it is neither.
pub fn jsonl_line(line: &[u8]) -> Parsed {
    let text = match std::str::from_utf8(line) {
        Err(e) => return Parsed::Bad(format!("not UTF-8 ({e})")),
        Ok(text) if text.trim().is_empty() => return Parsed::Other,
        Ok(text) => text,
    };
    match serde_json::from_str::<ClubheadSampleMsg>(text) {
        Ok(msg) => {
            let t_ns = msg.t_ns;
            Parsed::Item(Item::Sample { msg, log_time_ns: Some(t_ns) })
        }
        Err(e) => match crate::wire::BallSampleMsg::parse(text.as_bytes()) {
            Ok(ball) => Parsed::Item(Item::Ball { ball, payload: text.as_bytes().to_vec() }),
            Err(_) => Parsed::Bad(crate::capped::quote(&e.to_string()).into_owned()),
        },
    }
}

/// A recorded prediction published under a former name of its model (`model`, as read, is the current name), as
/// it is published today: the same bytes with the name replaced, and `(former, current)`. `None` when it carries
/// the current name. The bytes are compared as they were written, so the name is replaced in them, not
/// re-serialized.
fn under_current_name(data: &[u8], model: &str) -> Option<(Vec<u8>, (String, String))> {
    let current = format!("\"model\":\"{model}\"");
    if contains(data, current.as_bytes()) {
        return None;
    }
    crate::impact::registry::FORMER_NAMES.iter().filter(|(_, c)| *c == model).find_map(|(former, _)| {
        let field = format!("\"model\":\"{former}\"");
        let at = data.windows(field.len()).position(|w| w == field.as_bytes())?;
        let mut out = Vec::with_capacity(data.len());
        out.extend_from_slice(&data[..at]);
        out.extend_from_slice(current.as_bytes());
        out.extend_from_slice(&data[at + field.len()..]);
        Some((out, (former.to_string(), model.to_string())))
    })
}
