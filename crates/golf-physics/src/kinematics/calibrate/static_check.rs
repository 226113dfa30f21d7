//! A static trial's markers averaged over its frames, and refused when one moved: a trial in which the club or
//! the wand moved gives an average of the motion and a fit that looks perfect (the average of rigid poses is
//! nearly rigid), so the motion itself is measured.

use crate::math::{Real, Vector3};

use super::CalibrationError;

/// The most a marker of a static trial may move from its mean position over the frames averaged (m): 2 mm is
/// several times the noise of a marker (0.1-0.3 mm per axis) and under the motion of a hand-held club.
pub const DEFAULT_STATIC_LIMIT_M: Real = 0.002;

/// One marker of a static trial.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticMarker {
    /// The marker's label.
    pub label: String,
    /// Mean position over the frames where the marker is valid (lab, m).
    pub mean_m: Vector3,
    /// The frames it is valid in.
    pub frames: usize,
    /// The furthest it sits from its mean in any of them (m).
    pub moved_m: Real,
    /// The frame it sits furthest from its mean in, as its index in the capture.
    pub moved_at: u64,
}

/// Each marker's mean over its valid frames (`frames[marker][k]` is frame `first + k`), refused when one is never
/// valid or moves more than `limit_m` from its mean; the error names the marker that moved most.
pub fn static_markers(
    labels: &[String],
    frames: &[Vec<Option<Vector3>>],
    first: u64,
    limit_m: Real,
) -> Result<Vec<StaticMarker>, CalibrationError> {
    let mut out = Vec::with_capacity(labels.len());
    for (label, track) in labels.iter().zip(frames) {
        let seen: Vec<(u64, Vector3)> =
            track.iter().enumerate().filter_map(|(k, p)| p.map(|p| (first + k as u64, p))).collect();
        if seen.is_empty() {
            return Err(CalibrationError::NeverSeen(label.clone()));
        }
        let mean_m = seen.iter().map(|(_, p)| p).sum::<Vector3>() / seen.len() as Real;
        let (moved_at, moved_m) =
            seen.iter()
                .map(|(i, p)| (*i, (p - mean_m).norm()))
                .fold((first, 0.0), |b, x| if x.1 > b.1 { x } else { b });
        out.push(StaticMarker { label: label.clone(), mean_m, frames: seen.len(), moved_m, moved_at });
    }
    if let Some(worst) = out.iter().max_by(|a, b| a.moved_m.total_cmp(&b.moved_m)) {
        if worst.moved_m > limit_m {
            return Err(CalibrationError::NotStatic {
                label: worst.label.clone(),
                moved_mm: worst.moved_m * 1e3,
                frame: worst.moved_at,
                frames: frames.iter().map(Vec::len).max().unwrap_or(0),
                limit_mm: limit_m * 1e3,
            });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_moving_marker_is_named_with_its_motion() {
        let still = vec![Some(Vector3::zeros()); 10];
        // Still for nine frames, then 10 mm off: its mean is 1 mm off, the last frame 9 mm from it.
        let moving: Vec<Option<Vector3>> =
            (0..10).map(|k| Some(Vector3::new(if k == 9 { 1e-2 } else { 0.0 }, 0.0, 0.0))).collect();
        let labels = ["A".to_string(), "B".to_string()];
        let e = static_markers(&labels, &[still.clone(), moving], 100, 2e-3).unwrap_err();
        let CalibrationError::NotStatic { label, moved_mm, frame, .. } = e else { panic!("{e}") };
        assert_eq!((label.as_str(), frame), ("B", 109));
        assert!((moved_mm - 9.0).abs() < 1e-9);
        let ok = static_markers(&labels[..1], &[still], 0, 2e-3).unwrap();
        assert_eq!((ok[0].frames, ok[0].moved_m), (10, 0.0));
        assert_eq!(
            static_markers(&labels[..1], &[vec![None]], 0, 2e-3).unwrap_err(),
            CalibrationError::NeverSeen("A".into())
        );
    }
}
