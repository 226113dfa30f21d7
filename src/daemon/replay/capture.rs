//! A C3D capture as the input of a replay: its frames fitted to samples of one rig (`recording::c3d`).

use std::path::Path;

use super::ReplayInput;
use crate::daemon::recording::c3d::{self, C3dError, CaptureSamples, ImportCounts};
use crate::kinematics::MarkerFitter;

/// A capture's marker on the ball: its label and the offset from it to the ball's centre (lab frame, m).
pub type BallMarker<'a> = (&'a str, crate::math::Vector3);

/// Every frame of the capture as a sample of `rig` (and, with `ball`, the ball marker's position as the rig's
/// tracked ball before each sample), what the import saw, and the file's warnings.
pub fn load_capture(
    path: &Path,
    fitter: MarkerFitter,
    rig: &str,
    ball: Option<BallMarker>,
) -> Result<(ReplayInput, ImportCounts, Vec<String>), C3dError> {
    let reader = c3d::open(path)?;
    let warnings = reader.info.warnings.clone();
    let mut samples = CaptureSamples::new(reader, fitter, rig)?;
    if let Some((label, offset_m)) = ball {
        samples = samples.with_ball_marker(label, offset_m)?;
    }
    let mut input = ReplayInput::default();
    input.samples.reserve(usize::try_from(samples.info().frames).unwrap_or(0).min(1 << 24));
    while let Some(s) = samples.next_sample()? {
        if let Some(b) = samples.ball() {
            let payload = serde_json::to_vec(&b).unwrap_or_default();
            input.balls.push((input.samples.len(), b, payload));
        }
        input.samples.push(s);
    }
    Ok((input, samples.counts.clone(), warnings))
}
