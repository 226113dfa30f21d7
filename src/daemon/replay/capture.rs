//! A capture (C3D, TRC, a pose table: `crate::captures`) as the input of a replay: its frames as samples of one
//! rig, read a frame at a time as the replay goes (as `impactd import` reads it), so a capture of any size replays
//! in bounded memory. Its samples are in capture order, numbered from the first frame at `t_ns` 0.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use super::items::{Item, Items, ReplayIndex, ReplaySource, RigSpan};
use crate::captures::{CaptureError, CaptureOptions, CaptureSource, Format, ImportCounts};
use crate::daemon::{DaemonError, ReadError};

/// A capture's marker on the ball: its label and the offset from it to the ball's centre (lab frame, m).
pub type BallMarker<'a> = (&'a str, crate::math::Vector3);

/// A capture, checked and ready to replay as samples of one rig.
pub struct ReplayCapture {
    path: PathBuf,
    format: &'static Format,
    options: CaptureOptions,
    index: ReplayIndex,
    /// The file's warnings (its header and parameters, the units overridden).
    pub warnings: Vec<String>,
    /// What the last replay of it saw, once it has read every frame.
    counts: Arc<Mutex<Option<ImportCounts>>>,
}

impl ReplayCapture {
    /// Opens the capture and checks that it holds what `options` name (the marker set's markers, the ball marker,
    /// a pose table's columns); every frame is a sample of `options.rig`.
    pub fn open(path: &Path, format: &'static Format, options: CaptureOptions) -> Result<Self, CaptureError> {
        let samples = (format.open)(path, &options)?;
        let frames = samples.frames();
        let warnings = samples.warnings().to_vec();
        let mut index = ReplayIndex::default();
        if frames > 0 {
            index.rigs.insert(options.rig.clone(), RigSpan { samples: frames, first_t_ns: 0 });
        }
        Ok(ReplayCapture { path: path.to_path_buf(), format, options, index, warnings, counts: Arc::default() })
    }

    /// What the last replay saw of the capture's frames (once it read them all).
    pub fn counts(&self) -> Option<ImportCounts> {
        self.counts.lock().ok().and_then(|c| c.clone())
    }

    /// The capture's format.
    pub fn format(&self) -> &'static Format {
        self.format
    }
}

/// A capture's samples, each frame's ball sample before it.
struct CaptureItems {
    samples: Box<dyn CaptureSource>,
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
                    *c = Some(self.samples.counts().clone());
                }
                None
            }
            Err(source) => {
                self.done = true;
                Some(Err(ReadError::Capture { path: self.path.clone(), source }.into()))
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
        let samples = (self.format.open)(&self.path, &self.options)
            .map_err(|source| ReadError::Capture { path: path.clone(), source })?;
        let counts = self.counts.clone();
        Ok(Box::new(CaptureItems { samples, path, ball_next: None, counts, done: false }))
    }
}
