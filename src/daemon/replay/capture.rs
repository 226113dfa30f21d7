//! A C3D capture as the input of a replay: its frames fitted to samples of one rig (`recording::c3d`).

use std::path::Path;

use super::ReplayInput;
use crate::daemon::recording::c3d::{self, C3dError, CaptureSamples, ImportCounts};
use crate::kinematics::MarkerFitter;

/// Every frame of the capture as a sample of `rig`, what the import saw, and the file's warnings.
pub fn load_capture(
    path: &Path,
    fitter: MarkerFitter,
    rig: &str,
) -> Result<(ReplayInput, ImportCounts, Vec<String>), C3dError> {
    let reader = c3d::open(path)?;
    let warnings = reader.info.warnings.clone();
    let mut samples = CaptureSamples::new(reader, fitter, rig)?;
    let mut input = ReplayInput::default();
    input.samples.reserve(usize::try_from(samples.info().frames).unwrap_or(0).min(1 << 24));
    while let Some(s) = samples.next_sample()? {
        input.samples.push(s);
    }
    Ok((input, samples.counts.clone(), warnings))
}
