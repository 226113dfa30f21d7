//! A static trial: each named marker's mean position over a run of frames (lab frame, m), for calibration, from
//! any marker capture (C3D, TRC).

use std::path::Path;

use super::{CaptureError, Frame};
use crate::math::Vector3;

/// The mean position of each of `labels` over the frames `first..first + count` (0-based indices), each over
/// the frames where it is valid; an error names a marker never valid there.
pub fn mean_positions(path: &Path, labels: &[String], first: u64, count: u64) -> Result<Vec<Vector3>, CaptureError> {
    let mut reader = super::open_markers(path, None)?;
    let frames = reader.frames();
    if first >= frames || count == 0 {
        return Err(CaptureError::Usage(format!(
            "frames {first}..{} asked for, the capture has frame indices 0..{frames}",
            first.saturating_add(count),
        )));
    }
    let all = reader.labels();
    let indices: Vec<usize> = labels
        .iter()
        .map(|want| {
            all.iter()
                .position(|l| l == want.trim())
                .ok_or_else(|| CaptureError::MissingMarker { label: want.clone(), available: all.join(", ") })
        })
        .collect::<Result<_, _>>()?;
    let mut sums = vec![(Vector3::zeros(), 0u64); labels.len()];
    let mut frame = Frame::default();
    while reader.next_frame(&mut frame)? && frame.index < first.saturating_add(count) {
        if frame.index < first {
            continue;
        }
        for (sum, &i) in sums.iter_mut().zip(&indices) {
            if let Some(p) = frame.points_m.get(i).copied().flatten() {
                sum.0 += p;
                sum.1 += 1;
            }
        }
    }
    sums.iter()
        .zip(labels)
        .map(|((sum, n), label)| match n {
            0 => Err(CaptureError::Usage(format!("marker `{label}` is not valid in any of the frames asked for"))),
            n => Ok(sum / *n as f64),
        })
        .collect()
}

/// Per marker, its position in each frame (`None` where invalid).
pub type MarkerTracks = Vec<Vec<Option<Vector3>>>;

/// Every marker of the capture over the frames `first..first + count` (0-based indices): the labels (trimmed)
/// and, per marker, its position in each of those frames (`None` where invalid), for a static trial's check.
pub fn marker_frames(path: &Path, first: u64, count: u64) -> Result<(Vec<String>, MarkerTracks), CaptureError> {
    let mut reader = super::open_markers(path, None)?;
    let frames = reader.frames();
    if first >= frames || count == 0 {
        return Err(CaptureError::Usage(format!(
            "frames {first}..{} asked for, the capture has frame indices 0..{frames}",
            first.saturating_add(count),
        )));
    }
    let labels: Vec<String> = reader.labels().iter().map(|l| l.trim().to_string()).collect();
    let mut tracks = vec![Vec::new(); labels.len()];
    let mut frame = Frame::default();
    while reader.next_frame(&mut frame)? && frame.index < first.saturating_add(count) {
        if frame.index < first {
            continue;
        }
        for (i, track) in tracks.iter_mut().enumerate() {
            track.push(frame.points_m.get(i).copied().flatten());
        }
    }
    Ok((labels, tracks))
}
