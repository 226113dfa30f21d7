//! A C3D capture as the input of a replay: its frames fitted to samples of one rig (`recording::c3d`), read a
//! frame at a time as the replay goes (as `impactd import` reads it), so a capture of any size replays in
//! bounded memory. Its samples are in capture order, numbered from the first frame at `t_ns` 0.

use std::io::BufReader;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use super::items::{Item, Items, ReplayIndex, ReplaySource, RigSpan};
use crate::daemon::recording::c3d::{self, C3dError, CaptureSamples, ImportCounts};
use crate::daemon::DaemonError;
use crate::kinematics::MarkerFitter;

/// A capture's marker on the ball: its label and the offset from it to the ball's centre (lab frame, m).
pub type BallMarker<'a> = (&'a str, crate::math::Vector3);

/// A C3D capture, checked and ready to replay as samples of one rig.
pub struct ReplayCapture {
    path: PathBuf,
    fitter: MarkerFitter,
    rig: String,
    ball: Option<(String, crate::math::Vector3)>,
    index: ReplayIndex,
    /// The file's warnings (its header and parameters).
    pub warnings: Vec<String>,
    /// What the last replay of it saw, once it has read every frame.
    counts: Arc<Mutex<Option<ImportCounts>>>,
}

impl ReplayCapture {
    /// Opens the capture and checks that its markers hold the set (and the ball marker); every frame announced
    /// is a sample of `rig`.
    pub fn open(path: &Path, fitter: MarkerFitter, rig: &str, ball: Option<BallMarker>) -> Result<Self, C3dError> {
        let capture = ReplayCapture {
            path: path.to_path_buf(),
            fitter,
            rig: rig.to_string(),
            ball: ball.map(|(label, offset)| (label.to_string(), offset)),
            index: ReplayIndex::default(),
            warnings: Vec::new(),
            counts: Arc::default(),
        };
        let samples = capture.samples()?;
        let frames = samples.info().frames;
        let warnings = samples.info().warnings.clone();
        let mut index = ReplayIndex::default();
        if frames > 0 {
            index.rigs.insert(rig.to_string(), RigSpan { samples: frames, first_t_ns: 0 });
        }
        Ok(ReplayCapture { index, warnings, ..capture })
    }

    fn samples(&self) -> Result<CaptureSamples<BufReader<std::fs::File>>, C3dError> {
        let mut samples = CaptureSamples::new(c3d::open(&self.path)?, self.fitter.clone(), &self.rig)?;
        if let Some((label, offset_m)) = &self.ball {
            samples = samples.with_ball_marker(label, *offset_m)?;
        }
        Ok(samples)
    }

    /// What the last replay saw of the capture's frames (once it read them all).
    pub fn counts(&self) -> Option<ImportCounts> {
        self.counts.lock().ok().and_then(|c| c.clone())
    }
}

/// A capture's samples, each frame's ball sample before it.
struct CaptureItems {
    samples: CaptureSamples<BufReader<std::fs::File>>,
    path: String,
    ball_next: Option<Item>,
    counts: Arc<Mutex<Option<ImportCounts>>>,
    done: bool,
}

impl Iterator for CaptureItems {
    type Item = Result<Item, DaemonError>;

    fn next(&mut self) -> Option<Self::Item> {
        if let Some(sample) = self.ball_next.take() {
            return Some(Ok(sample));
        }
        if self.done {
            return None;
        }
        match self.samples.next_sample() {
            Ok(Some(msg)) => {
                let sample = Item::Sample { msg, log_time_ns: None };
                match self.samples.ball() {
                    Some(ball) => {
                        self.ball_next = Some(sample);
                        let payload = serde_json::to_vec(&ball).unwrap_or_default();
                        Some(Ok(Item::Ball { ball, payload }))
                    }
                    None => Some(Ok(sample)),
                }
            }
            Ok(None) => {
                self.done = true;
                if let Ok(mut c) = self.counts.lock() {
                    *c = Some(self.samples.counts.clone());
                }
                None
            }
            Err(source) => {
                self.done = true;
                Some(Err(DaemonError::Capture { path: self.path.clone(), source }))
            }
        }
    }
}

impl ReplaySource for ReplayCapture {
    fn index(&self) -> std::borrow::Cow<'_, ReplayIndex> {
        std::borrow::Cow::Borrowed(&self.index)
    }

    fn items(&self) -> Result<Items<'_>, DaemonError> {
        let path = self.path.display().to_string();
        let samples = self.samples().map_err(|source| DaemonError::Capture { path: path.clone(), source })?;
        let counts = self.counts.clone();
        Ok(Box::new(CaptureItems { samples, path, ball_next: None, counts, done: false }))
    }
}
