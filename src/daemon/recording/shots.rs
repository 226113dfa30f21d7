//! The measured shots of a recording: each comparison on `golf/<rig>/comparison` (a prediction paired live with
//! a launch monitor's measurement) and the delivery of its prediction on `golf/<rig>/launch`, as the JSONL
//! dataset lines `compare` and `fit` read.

use std::collections::BTreeMap;
use std::path::Path;

use super::reader::OnDamage;
use super::stream::read_messages;
use crate::daemon::DaemonError;
use crate::pairing::DatasetLine;
use crate::wire::{ComparisonMessage, DeliveryInput, LaunchPrediction};

/// What a recording holds of measured shots.
#[derive(Debug, Default)]
pub struct RecordedShots {
    /// One line per measured shot (the delivery of its prediction, the measurement), in shot order.
    pub lines: Vec<DatasetLine>,
    /// Every recorded comparison, in recording order.
    pub comparisons: Vec<ComparisonMessage>,
    /// The club the predictions were made with (the first prediction's).
    pub club: Option<String>,
    /// How many of `lines` are measured by a synthetic rig's recorded truth (`sim/<rig>/truth`).
    pub truths: usize,
    /// What could not be read.
    pub damage: Vec<String>,
}

/// The delivery numbers of a prediction as `predict`'s input (right-handed world, as the rig predicts).
pub fn delivery_input(p: &LaunchPrediction) -> DeliveryInput {
    let d = &p.delivery;
    DeliveryInput {
        club_speed_mph: d.club_speed_mph,
        attack_angle_deg: d.attack_angle_deg,
        club_path_deg: d.club_path_deg,
        face_angle_deg: d.face_angle_deg,
        dynamic_loft_deg: Some(d.dynamic_loft_deg),
        impact_h_mm: d.impact_h_mm,
        impact_v_mm: d.impact_v_mm,
        club_angular_velocity_radps: Some(d.club_angular_velocity_radps),
        handedness: None,
        dynamic_lie_deg: Some(d.dynamic_lie_deg),
    }
}

/// The widest gap between a prediction's impact time and the synthetic truth it is paired with (ns).
pub const TRUTH_WINDOW_NS: u64 = 5_000_000;

/// Reads the comparisons and predictions of an MCAP recording.
pub fn read(path: &Path) -> Result<RecordedShots, DaemonError> {
    let mut out = RecordedShots::default();
    let mut predictions: BTreeMap<(String, u64), LaunchPrediction> = BTreeMap::new();
    let mut truths: Vec<crate::wire::TruthMessage> = Vec::new();
    let scan = read_messages(path, OnDamage::Stop, |_, channel, m| {
        let Some(channel) = channel else { return };
        let topic = channel.topic.as_str();
        if crate::wire::keys::rig_of_truth(topic.trim_start_matches('/')).is_some() {
            if let Ok(t) = serde_json::from_slice::<crate::wire::TruthMessage>(&m.data) {
                truths.push(t);
            }
            return;
        }
        if !topic.starts_with("/golf/") {
            return;
        }
        if topic.ends_with("/comparison") {
            if let Ok(c) = serde_json::from_slice::<ComparisonMessage>(&m.data) {
                out.comparisons.push(c);
            }
        } else if topic.ends_with("/launch") {
            if let Ok(p) = serde_json::from_slice::<LaunchPrediction>(&m.data) {
                out.club.get_or_insert_with(|| p.club.clone());
                predictions.entry((p.rig.clone(), p.shot)).or_insert(p);
            }
        }
    })?;
    out.damage = scan.problems();
    let mut seen = BTreeMap::new();
    for c in &out.comparisons {
        let key = (c.rig.clone(), c.shot);
        if seen.contains_key(&key) {
            continue;
        }
        if let Some(p) = predictions.get(&key) {
            let mut measured = c.measured.clone();
            measured.carry_yd = None;
            seen.insert(key, DatasetLine { delivery: delivery_input(p), measured });
        }
    }
    // A synthetic rig's shots: each prediction measured against the truth of its impact (the same rig, impact
    // times within TRUTH_WINDOW_NS), when no launch monitor measured it.
    for (key, p) in &predictions {
        if seen.contains_key(key) {
            continue;
        }
        let truth = truths
            .iter()
            .filter(|t| t.rig == p.rig && t.t_impact_ns.abs_diff(p.t_impact_ns) <= TRUTH_WINDOW_NS)
            .min_by_key(|t| t.t_impact_ns.abs_diff(p.t_impact_ns));
        if let Some(t) = truth {
            let m = &t.launch.launch;
            let measured = crate::wire::LaunchFields {
                ball_speed_mph: m.ball_speed_mph,
                launch_angle_deg: m.launch_angle_deg,
                launch_direction_deg: m.launch_direction_deg,
                backspin_rpm: m.backspin_rpm,
                sidespin_rpm: m.sidespin_rpm,
                carry_yd: None,
            };
            seen.insert(key.clone(), DatasetLine { delivery: delivery_input(p), measured });
            out.truths += 1;
        }
    }
    out.lines = seen.into_values().collect();
    Ok(out)
}
