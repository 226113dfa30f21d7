//! A marker set: the markers of one tracked body and where each sits in the body's frame (m).
//!
//! The file is TOML with one table, `[markers]`, mapping each label to its body-frame position in metres:
//!
//! ```toml
//! [markers]
//! CH1 = [0.03, 0.0, 0.01]
//! CH2 = [-0.03, 0.0, 0.01]
//! CH3 = [0.0, 0.02, -0.01]
//! ```
//!
//! A set may also state where its body's face is, for `calibrate club` (the daemon and `import` read only
//! `[markers]`): the face centre (m) and the face's outward normal in the body frame,
//!
//! ```toml
//! [face]
//! centre_m = [0.041, -0.012, 0.0]
//! normal = [0.985, 0.17, 0.0]
//! ```
//!
//! and which capture markers are on the shaft, for `calibrate club` (the two it reads the address lean and lie
//! from, as `--shaft A,B` would) and for `calibrate club` and `replay` (the grip markers whose distance from the
//! head's markers must be a club's length, `guards::CLUB_LENGTH_M`):
//!
//! ```toml
//! [shaft]
//! markers = ["SHAFT_LO", "SHAFT_HI"]
//! grip = ["BUTT_CAP"]
//! ```
//!
//! Labels are compared after trimming spaces (C3D pads labels with trailing spaces). A set needs at least three
//! markers that are not all on one line, or no pose can be fitted from them.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::math::{Real, Vector3};

/// Why a marker set could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MarkerSetError {
    /// The text is not TOML of the set's form (`[markers]`, optional `[face]` and `[shaft]`, nothing else).
    #[error("not a marker set: {0}")]
    Toml(#[source] Box<toml::de::Error>),
    /// Fewer than 3 markers (the count given).
    #[error("a marker set needs at least 3 markers, this one has {0}")]
    TooFew(usize),
    /// More than [`MAX_MARKERS`] markers (the count given).
    #[error("a marker set has at most {MAX_MARKERS} markers, this one has {0}")]
    TooMany(usize),
    /// One marker (or the `[face]` or `[shaft]` table) is unusable.
    #[error("marker `{label}`: {reason}")]
    Marker {
        /// The marker's label, or `[face]`, or `[shaft]`.
        label: String,
        /// What is wrong with it: an empty label, a position (or face centre) that is not finite metres within
        /// 2 m of the body's origin, or a face normal that is not finite or is zero.
        reason: String,
    },
    /// The markers are too near one line (under 1 mm off it) to give an orientation.
    #[error("the markers lie on one line (spread {spread_mm:.2} mm off it): no orientation can be fitted")]
    Collinear {
        /// The largest distance of a marker from the line through the two markers furthest apart (mm).
        spread_mm: Real,
    },
    /// Two labels are the same once trimmed: the earlier one (trimmed) and the later one as given.
    #[error("marker labels `{0}` and `{1}` are the same once trailing spaces are trimmed")]
    Duplicate(String, String),
}

/// The markers of one body, in the order of the file's labels (sorted).
#[derive(Debug, Clone, PartialEq)]
pub struct MarkerSet {
    /// Trimmed labels.
    pub labels: Vec<String>,
    /// Body-frame positions (m), one per label.
    pub body_m: Vec<Vector3>,
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct MarkerSetFile {
    markers: BTreeMap<String, [Real; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    face: Option<FaceFile>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    shaft: Option<ShaftFile>,
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ShaftFile {
    #[serde(default)]
    markers: Vec<String>,
    #[serde(default)]
    grip: Vec<String>,
}

/// The shaft's markers as a marker set's `[shaft]` names them (capture labels, trimmed; not of the head's set).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct StatedShaft {
    /// Two markers on the shaft, on one side of it (either order), or none.
    pub markers: Vec<String>,
    /// The markers at the grip end (at least one when the table names any).
    pub grip: Vec<String>,
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FaceFile {
    centre_m: [Real; 3],
    normal: [Real; 3],
}

/// The face as a marker set's `[face]` states it, in the body frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StatedFace {
    /// The face centre in the body frame (m).
    pub centre_m: Vector3,
    /// Unit outward normal.
    pub normal: Vector3,
}

/// The most markers one body can have (the fit keeps its visible markers in a 64-bit mask).
pub const MAX_MARKERS: usize = 64;
/// The most grip markers a `[shaft]` names.
pub const MAX_GRIP_MARKERS: usize = 8;
/// Markers further than this from the body's origin are a unit mistake (mm typed as m), not a clubhead.
const MAX_OFFSET_M: Real = 2.0;
/// The markers must span at least this far off their best line to give an orientation.
const MIN_SPREAD_M: Real = 1e-3;

impl MarkerSet {
    /// A set from labels and body-frame positions, checked like a file.
    pub fn new(markers: impl IntoIterator<Item = (String, Vector3)>) -> Result<Self, MarkerSetError> {
        let mut labels: Vec<String> = Vec::new();
        let mut body_m = Vec::new();
        for (label, p) in markers {
            let trimmed = label.trim().to_string();
            if trimmed.is_empty() {
                return Err(MarkerSetError::Marker { label, reason: "empty label".into() });
            }
            if !p.iter().all(|v| v.is_finite()) || p.norm() > MAX_OFFSET_M {
                return Err(MarkerSetError::Marker {
                    label: trimmed,
                    reason: format!("position must be finite metres within {MAX_OFFSET_M} m of the origin"),
                });
            }
            if let Some(other) = labels.iter().find(|l| **l == trimmed) {
                return Err(MarkerSetError::Duplicate(other.clone(), label));
            }
            labels.push(trimmed);
            body_m.push(p);
        }
        if labels.len() < 3 {
            return Err(MarkerSetError::TooFew(labels.len()));
        }
        if labels.len() > MAX_MARKERS {
            return Err(MarkerSetError::TooMany(labels.len()));
        }
        let spread = off_line_spread_m(&body_m);
        if spread < MIN_SPREAD_M {
            return Err(MarkerSetError::Collinear { spread_mm: spread * 1e3 });
        }
        Ok(MarkerSet { labels, body_m })
    }

    /// Reads the TOML text of a marker set.
    pub fn from_toml(text: &str) -> Result<Self, MarkerSetError> {
        let file: MarkerSetFile = toml::from_str(text).map_err(|e| MarkerSetError::Toml(Box::new(e)))?;
        Self::new(file.markers.into_iter().map(|(l, p)| (l, Vector3::from(p))))
    }

    /// The `[face]` a marker set's TOML text states, if any (checked: the centre within the set's reach of its
    /// origin, the normal finite and not zero).
    pub fn face_from_toml(text: &str) -> Result<Option<StatedFace>, MarkerSetError> {
        let file: MarkerSetFile = toml::from_str(text).map_err(|e| MarkerSetError::Toml(Box::new(e)))?;
        let Some(face) = file.face else { return Ok(None) };
        let (centre_m, normal) = (Vector3::from(face.centre_m), Vector3::from(face.normal));
        let bad = |reason: &str| MarkerSetError::Marker { label: "[face]".into(), reason: reason.into() };
        if !centre_m.iter().all(|v| v.is_finite()) || centre_m.norm() > MAX_OFFSET_M {
            return Err(bad(&format!("centre_m must be finite metres within {MAX_OFFSET_M} m of the origin")));
        }
        if !normal.iter().all(|v| v.is_finite()) || normal.norm() < 1e-6 {
            return Err(bad("normal must be a finite direction, not zero"));
        }
        Ok(Some(StatedFace { centre_m, normal: normal.normalize() }))
    }

    /// The `[shaft]` a marker set's TOML text states (empty when none; checked: two distinct shaft markers, grip
    /// markers distinct and at most [`MAX_GRIP_MARKERS`], none empty or one of the head's `[markers]`).
    pub fn shaft_from_toml(text: &str) -> Result<StatedShaft, MarkerSetError> {
        let file: MarkerSetFile = toml::from_str(text).map_err(|e| MarkerSetError::Toml(Box::new(e)))?;
        let Some(shaft) = file.shaft else { return Ok(StatedShaft::default()) };
        let bad = |reason: String| MarkerSetError::Marker { label: "[shaft]".into(), reason };
        let trim = |v: Vec<String>| v.into_iter().map(|l| l.trim().to_string()).collect::<Vec<_>>();
        let (markers, grip) = (trim(shaft.markers), trim(shaft.grip));
        if !matches!(markers.len(), 0 | 2) {
            return Err(bad(format!(
                "markers names {} labels: it takes the two markers on the shaft, [\"A\", \"B\"]",
                markers.len()
            )));
        }
        if markers.len() == 2 && markers[0] == markers[1] {
            return Err(bad(format!("markers names `{}` twice: the shaft's two markers are two", markers[0])));
        }
        if grip.len() > MAX_GRIP_MARKERS {
            return Err(bad(format!("grip names {} markers, at most {MAX_GRIP_MARKERS}", grip.len())));
        }
        if let Some((i, g)) = grip.iter().enumerate().find(|(i, g)| grip[..*i].contains(g)) {
            return Err(bad(format!("grip names `{g}` twice (entry {})", i + 1)));
        }
        if markers.is_empty() && grip.is_empty() {
            return Err(bad("names no markers: give `markers = [\"A\", \"B\"]`, `grip = [\"G\"]` or both".into()));
        }
        for label in markers.iter().chain(&grip) {
            if label.is_empty() {
                return Err(bad("an empty label".into()));
            }
            if file.markers.keys().any(|k| k.trim() == label) {
                return Err(bad(format!(
                    "`{label}` is one of the head's [markers] too: a shaft or grip marker is not on the head"
                )));
            }
        }
        Ok(StatedShaft { markers, grip })
    }

    /// The TOML text of this set (0.1 um resolution).
    pub fn to_toml(&self) -> String {
        let mut out = String::from("[markers]\n");
        for (label, p) in self.labels.iter().zip(&self.body_m) {
            let key = if label.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
                label.clone()
            } else {
                format!("{label:?}")
            };
            out.push_str(&format!("{key} = [{:.7}, {:.7}, {:.7}]\n", p.x, p.y, p.z));
        }
        out
    }

    /// The number of markers.
    pub fn len(&self) -> usize {
        self.labels.len()
    }

    /// Whether the set has no markers (never true of a set built by [`new`](Self::new)).
    pub fn is_empty(&self) -> bool {
        self.labels.is_empty()
    }

    /// For each marker of the set, its index among `labels` (compared trimmed), or the first label missing.
    pub fn indices_in<S: AsRef<str>>(&self, labels: &[S]) -> Result<Vec<usize>, String> {
        self.labels
            .iter()
            .map(|want| labels.iter().position(|l| l.as_ref().trim() == want).ok_or_else(|| want.clone()))
            .collect()
    }
}

/// The largest distance of a marker from the line through the two markers furthest apart (m).
fn off_line_spread_m(points: &[Vector3]) -> Real {
    let mut best = (0, 0, 0.0);
    for i in 0..points.len() {
        for j in i + 1..points.len() {
            let d = (points[i] - points[j]).norm();
            if d > best.2 {
                best = (i, j, d);
            }
        }
    }
    if best.2 == 0.0 {
        return 0.0;
    }
    let axis = (points[best.1] - points[best.0]) / best.2;
    points.iter().map(|p| (p - points[best.0]).cross(&axis).norm()).fold(0.0, Real::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_and_writes_a_set() {
        let text = "[markers]\nCH1 = [0.03, 0.0, 0.01]\nCH2 = [-0.03, 0.0, 0.01]\nCH3 = [0.0, 0.02, -0.01]\n";
        let set = MarkerSet::from_toml(text).unwrap();
        assert_eq!(set.labels, ["CH1", "CH2", "CH3"]);
        assert_eq!(set.body_m[2], Vector3::new(0.0, 0.02, -0.01));
        assert_eq!(MarkerSet::from_toml(&set.to_toml()).unwrap(), set);
        assert_eq!(set.indices_in(&["X", "CH3  ", "CH1", "CH2 "]).unwrap(), vec![2, 3, 1]);
        assert_eq!(set.indices_in(&["CH1", "CH2"]).unwrap_err(), "CH3");
    }

    #[test]
    fn refuses_sets_no_pose_can_come_from() {
        let two = "[markers]\nA = [0.0, 0.0, 0.0]\nB = [0.1, 0.0, 0.0]\n";
        assert_eq!(MarkerSet::from_toml(two).unwrap_err(), MarkerSetError::TooFew(2));
        let line = "[markers]\nA = [0.0, 0.0, 0.0]\nB = [0.1, 0.0, 0.0]\nC = [0.05, 0.0, 0.0]\n";
        assert!(matches!(MarkerSet::from_toml(line).unwrap_err(), MarkerSetError::Collinear { .. }));
        let mm = "[markers]\nA = [30.0, 0.0, 0.0]\nB = [0.1, 0.0, 0.0]\nC = [0.05, 0.1, 0.0]\n";
        assert!(matches!(MarkerSet::from_toml(mm).unwrap_err(), MarkerSetError::Marker { .. }));
        let dup = "[markers]\n\"A \" = [0.0, 0.0, 0.0]\nA = [0.1, 0.0, 0.0]\nC = [0.05, 0.1, 0.0]\n";
        assert!(matches!(MarkerSet::from_toml(dup).unwrap_err(), MarkerSetError::Duplicate(..)));
        assert!(matches!(MarkerSet::from_toml("[marker]\n").unwrap_err(), MarkerSetError::Toml(_)));
    }

    #[test]
    fn reads_a_stated_face() {
        let base = "[markers]\nCH1 = [0.03, 0.0, 0.01]\nCH2 = [-0.03, 0.0, 0.01]\nCH3 = [0.0, 0.02, -0.01]\n";
        assert_eq!(MarkerSet::face_from_toml(base).unwrap(), None);
        let text = format!("{base}[face]\ncentre_m = [0.04, -0.01, 0.0]\nnormal = [2.0, 0.0, 0.0]\n");
        let face = MarkerSet::face_from_toml(&text).unwrap().unwrap();
        assert_eq!((face.centre_m, face.normal), (Vector3::new(0.04, -0.01, 0.0), Vector3::x()));
        assert_eq!(MarkerSet::from_toml(&text).unwrap(), MarkerSet::from_toml(base).unwrap());
        let zero = format!("{base}[face]\ncentre_m = [0.04, -0.01, 0.0]\nnormal = [0.0, 0.0, 0.0]\n");
        assert!(MarkerSet::face_from_toml(&zero).is_err());
    }

    #[test]
    fn reads_a_stated_shaft() {
        let base = "[markers]\nCH1 = [0.03, 0.0, 0.01]\nCH2 = [-0.03, 0.0, 0.01]\nCH3 = [0.0, 0.02, -0.01]\n";
        assert_eq!(MarkerSet::shaft_from_toml(base).unwrap(), StatedShaft::default());
        let text = format!("{base}[shaft]\nmarkers = [\"S1\", \"S2 \"]\ngrip = [\"BUTT\"]\n");
        let shaft = MarkerSet::shaft_from_toml(&text).unwrap();
        assert_eq!((shaft.markers, shaft.grip), (vec!["S1".to_string(), "S2".into()], vec!["BUTT".to_string()]));
        assert_eq!(MarkerSet::from_toml(&text).unwrap(), MarkerSet::from_toml(base).unwrap());
        let grip_only = MarkerSet::shaft_from_toml(&format!("{base}[shaft]\ngrip = [\"G1\", \"G2\"]\n")).unwrap();
        assert!(grip_only.markers.is_empty() && grip_only.grip.len() == 2);
        for bad in [
            "markers = [\"S1\"]",
            "markers = [\"S1\", \"S1\"]",
            "grip = [\"G\", \"G\"]",
            "grip = [\"CH1\"]",
            "markers = [\"S1\", \"\"]",
            "",
            "lean = 3",
        ] {
            assert!(MarkerSet::shaft_from_toml(&format!("{base}[shaft]\n{bad}\n")).is_err(), "{bad}");
        }
    }
}
