//! A club's marker set fitted to Motive's labelled markers, so the club needs no rigid body in Motive.
//!
//! Motive describes each asset's markers as a marker set (`NAT_MODELDEF` data set type 0: the set's name, its
//! markers' names) named after the asset, and streams every labelled marker with the asset's id in the high 16
//! bits of its id and the marker's 1-based index in that set in the low 16. The asset's id comes from the
//! description of the model with the set's name: a Trained Markerset (NatNet 4.1's asset descriptions), a
//! skeleton, or a rigid body. So `[rig.input] body = "Club"` names the asset (as Motive's Assets pane shows it)
//! and the marker set file's labels are the marker names within it (`CH1`, as Motive's labels show them; a name
//! streamed with Motive's subject prefix, `Club_CH1` or `Club:CH1`, matches too).
//!
//! Each frame, a marker counts as seen when Motive measured it ([`LabeledMarker::measured`]: not occluded, not
//! only filled in by the model solver); the set is fitted to the seen ones by [`MarkerFitter`], which rejects a
//! swapped or ghost marker by its residual. Fewer than 3 valid markers: the sample is occluded.

use crate::kinematics::{MarkerFitter, MarkerSet};
use crate::math::Vector3;

use super::sample::natnet_sample;
use super::{Frame, ModelDef, RigidBody};
use crate::mocap::track::BodySample;

/// Where each marker of a set is among Motive's labelled markers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LabelMap {
    /// The asset's id (the labelled markers' model id).
    pub model_id: i32,
    /// Per marker of the set (in the set's order), its 1-based index in Motive's marker set.
    pub members: Vec<i32>,
}

/// Why a marker set cannot be found in Motive's descriptions.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LabelMapError {
    #[error("Motive describes no marker set `{set}` (it has {have:?})")]
    NoSet { set: String, have: Vec<String> },
    #[error("marker `{label}` is not in Motive's marker set `{set}` (it has {have:?})")]
    NoMarker { set: String, label: String, have: Vec<String> },
    #[error(
        "Motive's marker set `{set}` belongs to no asset with an id (a Trained Markerset, skeleton or rigid body \
         named `{set}`), so its labelled markers cannot be told apart"
    )]
    NoModelId { set: String },
}

/// Whether Motive's marker name `name` in set `set` is the label `label` (trimmed; Motive's subject prefix
/// `SET_` or `SET:` allowed).
fn same_marker(name: &str, set: &str, label: &str) -> bool {
    let name = name.trim();
    let bare = name.strip_prefix(set).and_then(|rest| rest.strip_prefix('_').or_else(|| rest.strip_prefix(':')));
    name == label || bare == Some(label)
}

/// Maps `set`'s labels to Motive's labelled markers of the marker set named `set_name`.
pub fn label_map(model: &ModelDef, set_name: &str, set: &MarkerSet) -> Result<LabelMap, LabelMapError> {
    let set_name = set_name.trim();
    let Some(described) = model.marker_sets.iter().find(|s| s.name.trim() == set_name) else {
        let have = model.marker_sets.iter().map(|s| s.name.clone()).collect();
        return Err(LabelMapError::NoSet { set: set_name.into(), have });
    };
    let members = set
        .labels
        .iter()
        .map(|label| {
            let at = described.markers.iter().position(|name| same_marker(name, set_name, label));
            at.map(|i| i as i32 + 1).ok_or_else(|| LabelMapError::NoMarker {
                set: set_name.into(),
                label: label.clone(),
                have: described.markers.clone(),
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let model_id = model.model_id(set_name).ok_or_else(|| LabelMapError::NoModelId { set: set_name.into() })?;
    Ok(LabelMap { model_id, members })
}

/// The pose of the set in `frame`: the fit of its measured labelled markers (lab frame, m), with the fit's
/// residual; occluded (origin, identity) when fewer than 3 are valid. `lab_m` is a reused buffer.
pub fn natnet_fitted_sample(
    fitter: &MarkerFitter,
    map: &LabelMap,
    frame: &Frame,
    clock_hz: Option<u64>,
    lab_m: &mut Vec<Option<Vector3>>,
) -> BodySample {
    let timing = RigidBody { orientation_xyzw: [0.0, 0.0, 0.0, 1.0], tracking_valid: true, ..RigidBody::default() };
    let (mut s, _) = natnet_sample(&timing, frame, clock_hz);
    lab_m.clear();
    lab_m.extend(map.members.iter().map(|&member| {
        let m = frame.labeled_markers.iter().find(|m| m.model_id() == map.model_id && m.member_id() == member)?;
        m.measured().then(|| Vector3::from(m.position_m.map(f64::from)))
    }));
    match fitter.fit(lab_m) {
        Ok(fit) => {
            let p = fit.lab_from_body.translation.vector;
            let q = fit.lab_from_body.rotation;
            s.position_m = [p.x, p.y, p.z];
            s.orientation_xyzw = [q.i, q.j, q.k, q.w];
            s.fit_residual_m = Some(fit.residual_m);
        }
        Err(_) => s.occluded = true,
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mocap::natnet::markers::{LabeledMarker, OCCLUDED, POINT_CLOUD_SOLVED};
    use crate::mocap::natnet::{MarkerSetDef, RigidBodyDef};

    fn set() -> MarkerSet {
        MarkerSet::from_toml(
            "[markers]\nCH1 = [0.04, 0.0, 0.01]\nCH2 = [-0.04, 0.005, 0.01]\nCH3 = [0.0, 0.03, -0.012]\nCH4 = [0.01, -0.02, -0.03]\n",
        )
        .unwrap()
    }

    fn model() -> ModelDef {
        ModelDef {
            marker_sets: vec![MarkerSetDef {
                name: "Club".into(),
                markers: ["Club_CH4", "Club_CH2", "Club_CH1", "Club_CH3"].map(String::from).to_vec(),
            }],
            assets: vec![RigidBodyDef { id: 5, name: "Club".into() }],
            ..ModelDef::default()
        }
    }

    #[test]
    fn labels_map_by_name_within_the_set_and_the_assets_id() {
        let map = label_map(&model(), "Club", &set()).unwrap();
        assert_eq!(map, LabelMap { model_id: 5, members: vec![3, 2, 4, 1] });
        assert!(matches!(label_map(&model(), "Putter", &set()), Err(LabelMapError::NoSet { .. })));
        let mut no_id = model();
        no_id.assets.clear();
        assert!(matches!(label_map(&no_id, "Club", &set()), Err(LabelMapError::NoModelId { .. })));
        let mut short = model();
        short.marker_sets[0].markers.pop();
        assert!(
            matches!(label_map(&short, "Club", &set()), Err(LabelMapError::NoMarker { label, .. }) if label == "CH3")
        );
    }

    /// Four markers, one a ghost 2 cm off: the pose comes from the other three, the ghost rejected by its residual
    /// (not averaged in). With one more flagged occluded, 2 valid markers are left: the sample is occluded.
    #[test]
    fn occluded_and_ghost_markers_are_not_averaged_in() {
        let set = set();
        let map = label_map(&model(), "Club", &set).unwrap();
        let pose = crate::math::Isometry3::new(Vector3::new(0.3, 1.1, -0.4), Vector3::new(0.7, -1.9, 0.4));
        let markers: Vec<LabeledMarker> = (0..4)
            .map(|k| {
                let p = pose * crate::math::Point3::from(set.body_m[k]);
                LabeledMarker {
                    id: LabeledMarker::pack_id(5, map.members[k]),
                    position_m: [p.x as f32, p.y as f32, p.z as f32],
                    size_m: 0.014,
                    params: POINT_CLOUD_SOLVED,
                    residual_m: 2e-4,
                }
            })
            .collect();
        let fitter = MarkerFitter::new(set.clone());
        let mut frame = Frame { frame_number: 9, labeled_markers: markers, ..Frame::default() };
        frame.labeled_markers[1].position_m[1] += 0.02; // CH2 a ghost
        let s = natnet_fitted_sample(&fitter, &map, &frame, None, &mut Vec::new());
        assert!(!s.occluded && s.fit_residual_m.is_some_and(|r| r < 1e-6), "{s:?}");
        let p = pose.translation.vector;
        assert!((Vector3::from(s.position_m) - p).norm() < 1e-6, "{s:?}");
        frame.labeled_markers[3].params |= OCCLUDED; // CH4 occluded: 2 valid once the ghost is rejected
        let s = natnet_fitted_sample(&fitter, &map, &frame, None, &mut Vec::new());
        assert!(s.occluded && s.frame == 9);
    }
}
