//! C3D motion-capture files (c3d.org's format, written by Vicon Nexus and Shogun, Qualisys, Motion Analysis,
//! Codamotion, ...): what a capture holds (`impactd info`), and its marker trajectories frame by frame
//! (`impactd import`, `impactd replay`, `impactd calibrate`).
//!
//! A file is 512-byte blocks: a header block (the data layout: points, analog words per frame, first and last
//! frame, scale, data start, rate), the parameter section (`params`), then one record per frame: each point as
//! x, y, z and a residual word (16-bit integers times `POINT:SCALE`, or floats when the scale is negative),
//! then the analog samples. A point is valid when its residual word is not negative: writers leave the
//! coordinates of a lost marker stale or zero, so they are never looked at for validity. The low byte of the
//! word is the residual in units of |scale|, the high byte the mask of the cameras that saw it.
//!
//! Written here rather than with the `c3dio` crate (0.8): c3dio reads the whole data section into memory and
//! converts it into grids before returning, so a 2 GB capture needs more than 2 GB of memory and a damaged frame
//! loses the file. This reader holds one frame at a time (a 2 GB file streams through in constant memory), keeps
//! the frames before a truncation, and reads exactly what `import` needs: labels, units, rate and the residual
//! words. It handles the three processor formats (Intel, DEC, SGI/MIPS) and integer and float data; it is tested
//! on c3d.org's sample files of every vendor (`tests/inputs/c3d_files.rs`).

mod numbers;
pub mod params;
mod reader;
mod summary;

use std::fs::File;
use std::io::BufReader;
use std::path::Path;

pub use numbers::Processor;
pub use params::Parameters;
pub use reader::C3dReader;
pub use summary::C3dSummary;
// Where these were before captures had a folder of their own (`daemon::recording::c3d::...`).
pub use super::static_trial;
pub use super::{CaptureSamples, Frame, ImportCounts};

/// Why a C3D file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum C3dError {
    #[error("{what}: {source}")]
    Io {
        what: &'static str,
        #[source]
        source: std::io::Error,
    },
    #[error("not a C3D file: {0}")]
    NotC3d(String),
    #[error("the parameter section: {0}")]
    Parameters(String),
    #[error("the data layout: {0}")]
    Layout(String),
    #[error("marker `{label}` of the marker set is not in the capture (its markers: {available})")]
    MissingMarker { label: String, available: String },
    #[error("frame index {index} could not be read: {source}")]
    Frame {
        index: u64,
        #[source]
        source: std::io::Error,
    },
}

impl C3dError {
    fn io(what: &'static str) -> impl FnOnce(std::io::Error) -> C3dError {
        move |source| C3dError::Io { what, source }
    }
}

/// What a capture holds.
#[derive(Debug, Clone)]
pub struct C3dInfo {
    pub processor: Processor,
    /// Point frames per second.
    pub rate_hz: f64,
    /// The number of the first frame (C3D counts from 1).
    pub first_frame: u64,
    /// Frames in the file (after any truncation).
    pub frames: u64,
    /// Point labels, trailing spaces trimmed.
    pub labels: Vec<String>,
    /// `POINT:UNITS` as written.
    pub units: String,
    pub metres_per_unit: f64,
    /// `POINT:SCALE` from the header (negative: float data).
    pub scale: f32,
    pub float_data: bool,
    /// Analog samples per point frame (all channels).
    pub analog_words: usize,
    pub analog_labels: Vec<String>,
    pub analog_rate_hz: f64,
    pub data_start_byte: u64,
    pub frame_bytes: usize,
    /// What is odd about the file but did not stop it being read.
    pub warnings: Vec<String>,
    pub parameters: Parameters,
}

impl C3dInfo {
    /// The number of the last frame.
    pub fn last_frame(&self) -> u64 {
        (self.first_frame + self.frames).saturating_sub(1)
    }
}

/// Opens a C3D file for reading frame by frame.
pub fn open(path: &Path) -> Result<C3dReader<BufReader<File>>, C3dError> {
    let file = File::open(path).map_err(C3dError::io("opening"))?;
    C3dReader::new(BufReader::with_capacity(1 << 16, file))
}

/// Whether these are the first bytes of a C3D file (a header block names its parameter block and has 0x50 second).
pub fn looks_like_c3d(first_bytes: &[u8]) -> bool {
    first_bytes.len() >= 2 && first_bytes[1] == 0x50 && first_bytes[0] >= 2
}

/// The registry's entry ([`super::FORMATS`]).
pub const FORMAT: super::Format = super::Format {
    name: "c3d",
    extensions: &["c3d"],
    what: "C3D capture",
    sniff: Some(looks_like_c3d),
    open: open_samples,
    markers: Some(open_frames),
};

fn open_frames(path: &Path, units: Option<&str>) -> Result<Box<dyn super::MarkerFrames>, super::CaptureError> {
    let mut reader = open(path)?;
    if let Some(unit) = units {
        let metres = super::units::metres_per(unit)?;
        let stated = if reader.info.units.trim().is_empty() { "(none)".to_string() } else { reader.info.units.clone() };
        reader.info.warnings.push(format!("units: POINT:UNITS is {stated}; read as {unit} (--units)"));
        reader.info.metres_per_unit = metres;
    }
    Ok(Box::new(reader))
}

fn open_samples(
    path: &Path,
    options: &super::CaptureOptions,
) -> Result<Box<dyn super::CaptureSource>, super::CaptureError> {
    super::marker_samples(open_frames(path, options.units.as_deref())?, options, &FORMAT)
}

impl<R: std::io::Read + std::io::Seek + Send> super::MarkerFrames for C3dReader<R> {
    fn labels(&self) -> &[String] {
        &self.info.labels
    }

    fn rate_hz(&self) -> f64 {
        self.info.rate_hz
    }

    fn first_frame(&self) -> u64 {
        self.info.first_frame
    }

    fn frames(&self) -> u64 {
        self.info.frames
    }

    fn warnings(&self) -> &[String] {
        &self.info.warnings
    }

    fn next_frame(&mut self, frame: &mut Frame) -> Result<bool, super::CaptureError> {
        Ok(C3dReader::next_frame(self, frame)?)
    }
}
