//! Captures: the motion-capture files a lab already has, read as clubhead samples the way a live input's frames
//! are (`impactd import`, `impactd replay`, `impactd calibrate`). Each format is a folder of its own and one entry
//! of [`FORMATS`], found by `--format NAME` or by the file's extension:
//!
//! - [`c3d`]: C3D (c3d.org's binary marker format: Vicon, Qualisys, Motion Analysis, ...), marker trajectories.
//! - [`trc`]: TRC (OpenSim's tab-separated marker trajectories, which every biomechanics tool exports).
//! - [`pose_table`]: a pose table (CSV or TSV of time, position and orientation of the tracked body), with a
//!   column spec saying which column is what and in which units.
//!
//! A marker capture's frames go through one fit ([`CaptureSamples`]: the marker set fitted to each frame, as a
//! live marker input's are); a pose table's rows are the body's poses already. Every reader holds one frame at a
//! time, so a capture of any size streams. Units are stated, never guessed: a unit the user overrides
//! (`--units`) is reported as an override.

pub mod c3d;
mod lines;
mod markers;
pub mod pose_table;
pub mod static_trial;
pub mod trc;
pub mod units;

use std::path::Path;

pub use markers::{CaptureSamples, ImportCounts};

use crate::kinematics::MarkerFitter;
use crate::math::Vector3;
use crate::wire::{BallSampleMsg, ClubheadSampleMsg};

/// Why a capture could not be read.
#[derive(Debug, thiserror::Error)]
pub enum CaptureError {
    #[error(transparent)]
    C3d(#[from] c3d::C3dError),
    /// A text capture (TRC, a pose table) that is not what its format says, at a line (1-based).
    #[error("{format} line {line}: {reason}")]
    Text { format: &'static str, line: u64, reason: String },
    #[error("{what}: {source}")]
    Io {
        what: &'static str,
        #[source]
        source: std::io::Error,
    },
    #[error("marker `{label}` of the marker set is not in the capture (its markers: {available})")]
    MissingMarker { label: String, available: String },
    /// What the capture needs from the command line and did not get (a marker set, a column spec, ...).
    #[error("{0}")]
    Usage(String),
}

impl CaptureError {
    pub(crate) fn io(what: &'static str) -> impl FnOnce(std::io::Error) -> CaptureError {
        move |source| CaptureError::Io { what, source }
    }
}

/// One frame's markers.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Frame {
    /// 0-based index in the file.
    pub index: u64,
    /// Each point's lab-frame position (m), `None` when the capture marks it missing or invalid.
    pub points_m: Vec<Option<Vector3>>,
    /// Each point's residual (m), -1 when invalid; 0 when the format has no residuals.
    pub residual_m: Vec<f32>,
}

/// A marker capture read frame by frame (C3D, TRC).
pub trait MarkerFrames: Send {
    /// The markers' labels, in the order of a frame's points.
    fn labels(&self) -> &[String];
    /// Frames per second.
    fn rate_hz(&self) -> f64;
    /// The number of the first frame.
    fn first_frame(&self) -> u64;
    /// The frames the file holds.
    fn frames(&self) -> u64;
    /// What is odd about the file but did not stop it being read (and the units, when overridden).
    fn warnings(&self) -> &[String];
    /// Reads the next frame into `frame` (its vectors are reused); `false` after the last.
    fn next_frame(&mut self, frame: &mut Frame) -> Result<bool, CaptureError>;
}

/// A capture as the samples of one rig: what `import` writes and `replay` replays.
pub trait CaptureSource: Send {
    /// The next frame's sample, `None` after the last frame.
    fn next_sample(&mut self) -> Result<Option<ClubheadSampleMsg>, CaptureError>;
    /// The ball's sample of the frame [`CaptureSource::next_sample`] read last, when the capture tracks a ball.
    fn ball(&self) -> Option<BallSampleMsg>;
    /// What the frames read so far held.
    fn counts(&self) -> &ImportCounts;
    /// The frames the file holds.
    fn frames(&self) -> u64;
    /// What is odd about the file but did not stop it being read, and every unit overridden.
    fn warnings(&self) -> &[String];
}

/// What reading a capture as samples takes besides the file.
#[derive(Debug, Clone, Default)]
pub struct CaptureOptions {
    /// The rig the samples belong to.
    pub rig: String,
    /// A marker capture's marker set, fitted to each frame.
    pub fitter: Option<MarkerFitter>,
    /// A marker on the ball and the offset from it to the ball's centre (lab frame, m).
    pub ball_marker: Option<(String, Vector3)>,
    /// A pose table's column spec (`pose_table::ColumnSpec`), or a file holding one; without it the table's
    /// sidecar (`TABLE.columns`) is read.
    pub columns: Option<String>,
    /// The capture's length unit, overriding (or supplying) the file's own: reported as a warning.
    pub units: Option<String>,
    /// The face centre in the club frame (m, the club file's `face.center_m`): a pose table whose body has its
    /// origin at the face centre (`origin=face-centre`) is moved to the club frame with it.
    pub face_centre_club_m: Option<Vector3>,
}

/// A format's reader of a capture as samples of one rig.
pub type OpenSamples = fn(&Path, &CaptureOptions) -> Result<Box<dyn CaptureSource>, CaptureError>;

/// A marker format's reader of its frames (the units override as in [`OpenSamples`]).
pub type OpenMarkers = fn(&Path, Option<&str>) -> Result<Box<dyn MarkerFrames>, CaptureError>;

/// One capture format: its name (`--format`), the extensions it is found by, and its readers.
pub struct Format {
    pub name: &'static str,
    /// Lower-case, without the dot.
    pub extensions: &'static [&'static str],
    /// What the format is, for `--help` and errors.
    pub what: &'static str,
    /// Whether the file's first bytes are this format's (`None`: the format is known by its name only).
    pub sniff: Option<fn(&[u8]) -> bool>,
    /// The capture as samples of one rig.
    pub open: OpenSamples,
    /// The capture's marker frames, for a marker format (static trials); the units override as in `open`.
    pub markers: Option<OpenMarkers>,
}

/// Every capture format: a new one is a folder beside these and one entry here.
pub const FORMATS: [Format; 3] = [c3d::FORMAT, trc::FORMAT, pose_table::FORMAT];

/// The format named `name` (`--format`), or an error naming the formats.
pub fn format_named(name: &str) -> Result<&'static Format, CaptureError> {
    FORMATS
        .iter()
        .find(|f| f.name.eq_ignore_ascii_case(name.trim()))
        .ok_or_else(|| CaptureError::Usage(format!("--format {name}: the capture formats are {}", format_names())))
}

/// The formats' names, comma-separated.
pub fn format_names() -> String {
    FORMATS.iter().map(|f| f.name).collect::<Vec<_>>().join(", ")
}

/// The capture format of `path`: the one named by `forced`, else by the file's first bytes, else by its
/// extension; `None` for a file that is no capture (a recording, JSONL). A file named for a format whose first
/// bytes it does not have is an error.
pub fn format_of(path: &Path, forced: Option<&str>) -> Result<Option<&'static Format>, CaptureError> {
    if let Some(name) = forced {
        return format_named(name).map(Some);
    }
    let mut first = [0u8; 64];
    let n = {
        use std::io::Read;
        let mut file = std::fs::File::open(path).map_err(CaptureError::io("opening"))?;
        let mut n = 0;
        while n < first.len() {
            match file.read(&mut first[n..]).map_err(CaptureError::io("reading"))? {
                0 => break,
                k => n += k,
            }
        }
        n
    };
    let head = &first[..n];
    if head.starts_with(b"\x89MCAP") {
        return Ok(None);
    }
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    match FORMATS.iter().find(|f| f.extensions.contains(&extension.as_str())) {
        Some(f) if f.sniff.is_some_and(|looks| !looks(head)) => Err(CaptureError::Usage(format!(
            "{} is named .{extension} but does not start as a {} does",
            path.display(),
            f.what
        ))),
        Some(f) => Ok(Some(f)),
        None => Ok(FORMATS.iter().find(|f| f.sniff.is_some_and(|looks| looks(head)))),
    }
}

/// A marker capture's frames (C3D, TRC), by its format.
pub fn open_markers(path: &Path, units: Option<&str>) -> Result<Box<dyn MarkerFrames>, CaptureError> {
    let format = format_of(path, None)?
        .ok_or_else(|| CaptureError::Usage(format!("{} is not a capture ({})", path.display(), format_names())))?;
    let open = format.markers.ok_or_else(|| {
        CaptureError::Usage(format!(
            "{} is a {}: it holds poses, not the markers a static trial averages",
            path.display(),
            format.what
        ))
    })?;
    open(path, units)
}

/// Opens a marker capture as samples: the marker set fitted to each frame, and the ball marker if any.
pub(crate) fn marker_samples(
    frames: Box<dyn MarkerFrames>,
    options: &CaptureOptions,
    format: &Format,
) -> Result<Box<dyn CaptureSource>, CaptureError> {
    let fitter = options.fitter.clone().ok_or_else(|| {
        CaptureError::Usage(format!(
            "a {} holds markers: --markers SET.toml says which markers are the club",
            format.what
        ))
    })?;
    if options.columns.is_some() {
        return Err(CaptureError::Usage(format!("--columns is for pose tables; a {} holds markers", format.what)));
    }
    let mut samples = CaptureSamples::from_frames(frames, fitter, &options.rig)?;
    if let Some((label, offset)) = &options.ball_marker {
        samples = samples.with_ball_marker(label, *offset)?;
    }
    Ok(Box::new(samples))
}
