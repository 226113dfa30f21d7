//! What a capture's markers say before its swings are replayed: the runs of frames in which each marker of the
//! head's set was lost (so a shot that fails or bridges a gap names the marker and the frames), and the club's
//! length from the head's markers to each grip marker (those the marker set's `[shaft] grip` names, else a capture
//! label that says grip or butt; `kinematics::guards`). Read in a
//! pass of its own over the file, a frame at a time: only the runs are kept.

use std::path::Path;

use crate::captures::{CaptureError, Frame};
use crate::kinematics::guards::club_length_refusal;
use crate::kinematics::MarkerFitter;
use crate::math::Vector3;

/// The most marker-loss runs kept; more are counted.
pub const MAX_LOSSES: usize = 4096;

/// A marker of the set not seen over a run of frames.
#[derive(Debug, Clone, PartialEq)]
pub struct MarkerLoss {
    pub label: String,
    /// The capture's frame numbers of the first and last frame without it.
    pub first_frame: u64,
    pub last_frame: u64,
}

impl MarkerLoss {
    pub fn frames(&self) -> u64 {
        self.last_frame - self.first_frame + 1
    }
}

/// What the scan found.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CaptureLayout {
    pub rate_hz: f64,
    pub losses: Vec<MarkerLoss>,
    /// Runs beyond [`MAX_LOSSES`].
    pub more_losses: u64,
    /// Each grip marker, the frame and the distance from the head's body origin to it (m), at the first frame
    /// both are seen (one entry a grip marker seen with the head).
    pub club_length: Vec<(String, u64, f64)>,
}

/// Whether a capture label is a marker at the grip end of the shaft.
pub fn is_grip_label(label: &str) -> bool {
    let l = label.trim().to_ascii_lowercase();
    l.contains("grip") || l.contains("butt")
}

impl CaptureLayout {
    /// Scans the marker capture (C3D, TRC) at `path` for the set `fitter` fits, its lengths read in `units` when
    /// given; `grip`: the grip markers the marker set names (each must be in the capture), else (empty) the
    /// capture's first label that says grip or butt.
    pub fn scan(
        path: &Path,
        fitter: &MarkerFitter,
        grip: &[String],
        units: Option<&str>,
    ) -> Result<CaptureLayout, CaptureError> {
        let mut reader = crate::captures::open_markers(path, units)?;
        let labels = reader.labels().to_vec();
        let first_frame = reader.first_frame();
        let indices = fitter
            .set
            .indices_in(&labels)
            .map_err(|label| CaptureError::MissingMarker { label, available: labels.join(", ") })?;
        let grip: Vec<usize> = if grip.is_empty() {
            labels.iter().position(|l| is_grip_label(l)).into_iter().collect()
        } else {
            grip.iter()
                .map(|g| {
                    labels.iter().position(|l| l.trim() == g.trim()).ok_or_else(|| CaptureError::MissingMarker {
                        label: g.trim().to_string(),
                        available: labels.join(", "),
                    })
                })
                .collect::<Result<_, _>>()?
        };
        let mut measured = vec![false; grip.len()];
        let mut layout = CaptureLayout { rate_hz: reader.rate_hz(), ..CaptureLayout::default() };
        let mut open: Vec<Option<u64>> = vec![None; indices.len()];
        let mut frame = Frame::default();
        let mut last_frame = first_frame;
        let mut lab: Vec<Option<Vector3>> = Vec::with_capacity(indices.len());
        while reader.next_frame(&mut frame)? {
            let number = first_frame + frame.index;
            last_frame = number;
            lab.clear();
            lab.extend(indices.iter().map(|&i| frame.points_m.get(i).copied().flatten()));
            for (k, p) in lab.iter().enumerate() {
                match (p, open[k]) {
                    (None, None) => open[k] = Some(number),
                    (Some(_), Some(first)) => {
                        open[k] = None;
                        layout.push(&fitter.set.labels[k], first, number - 1);
                    }
                    _ => {}
                }
            }
            if measured.iter().any(|m| !m) {
                if let Ok(fit) = fitter.fit(&lab) {
                    for (k, &g) in grip.iter().enumerate() {
                        if let (false, Some(p)) = (measured[k], frame.points_m.get(g).copied().flatten()) {
                            let d = (p - fit.lab_from_body.translation.vector).norm();
                            layout.club_length.push((labels[g].trim().to_string(), number, d));
                            measured[k] = true;
                        }
                    }
                }
            }
        }
        for (k, first) in open.iter().enumerate() {
            if let Some(first) = first {
                layout.push(&fitter.set.labels[k], *first, last_frame);
            }
        }
        Ok(layout)
    }

    fn push(&mut self, label: &str, first_frame: u64, last_frame: u64) {
        if self.losses.len() < MAX_LOSSES {
            self.losses.push(MarkerLoss { label: label.to_string(), first_frame, last_frame });
        } else {
            self.more_losses += 1;
        }
    }

    /// The club length's refusal: the first grip marker outside [`CLUB_LENGTH_M`] from the head's markers.
    ///
    /// [`CLUB_LENGTH_M`]: crate::kinematics::guards::CLUB_LENGTH_M
    pub fn club_length_refusal(&self) -> Option<String> {
        self.club_length.iter().find_map(|(label, frame, d)| club_length_refusal(label, *d, &format!("frame {frame}")))
    }

    /// The marker losses that end within `window` frames before `frame` (or span it), said for a person.
    pub fn losses_before(&self, frame: u64, window: u64) -> Vec<String> {
        let ms = |n: u64| n as f64 * 1e3 / self.rate_hz.max(1e-9);
        self.losses
            .iter()
            .filter(|l| l.first_frame <= frame && l.last_frame + window >= frame && l.frames() >= 2)
            .map(|l| {
                format!(
                    "marker {} lost in frames {}-{} ({} frames, {:.1} ms), {} before the revealing frame {frame}",
                    l.label,
                    l.first_frame,
                    l.last_frame,
                    l.frames(),
                    ms(l.frames()),
                    match frame.saturating_sub(l.last_frame) {
                        0 => "up to".to_string(),
                        n => format!("ending {n} frames"),
                    }
                )
            })
            .collect()
    }
}

/// The face centre's refusal: further than [`MAX_FACE_FROM_MARKERS_M`] from every marker of the head's set
/// (`face_centre_body_m`: the club's face centre in the tracked body's frame, through `club_from_body`).
///
/// [`MAX_FACE_FROM_MARKERS_M`]: crate::kinematics::guards::MAX_FACE_FROM_MARKERS_M
pub fn face_from_markers_refusal(set: &crate::kinematics::MarkerSet, face_centre_body_m: &Vector3) -> Option<String> {
    use crate::kinematics::guards::MAX_FACE_FROM_MARKERS_M;
    let (label, d) = set
        .labels
        .iter()
        .zip(&set.body_m)
        .map(|(l, p)| (l, (p - face_centre_body_m).norm()))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    (d > MAX_FACE_FROM_MARKERS_M).then(|| {
        format!(
            "the face centre is {d:.2} m from the nearest marker of the head's set ({label}), more than the \
             {MAX_FACE_FROM_MARKERS_M} m a face centre can be from markers on its head: the calibration's \
             club_from_body is wrong (`impactd calibrate club`, docs/c3d.md)"
        )
    })
}
