//! TRC: OpenSim's marker trajectory format (written by OpenSim, Vicon Nexus, Cortex, Mokka, OpenCap, ...). Five
//! tab-separated header lines, then one line a frame:
//!
//! ```text
//! PathFileType  4  (X/Y/Z)  swing.trc
//! DataRate  CameraRate  NumFrames  NumMarkers  Units  OrigDataRate  OrigDataStartFrame  OrigNumFrames
//! 240  240  480  9  mm  240  1  480
//! Frame#  Time  CROWN      TOE      ...
//!             X1  Y1  Z1  X2  Y2  Z2  ...
//! 1  0.000000  101.2  920.4  -12.0  ...
//! ```
//!
//! A marker not seen in a frame has empty cells (or `NaN`), and a line may end early when its last markers are
//! missing. `Units` is required: a TRC without it, or with a unit not known (`units::LENGTH_UNITS`), is an error
//! unless `--units` says what to read it in (reported as an override). The frame's time is its `Frame#` less the
//! first one's over `DataRate` (a skipped frame number is a gap, as in the live inputs); a `Time` column that
//! disagrees is reported once. Read a line at a time (each bounded), so a file of any length streams.

mod header;

use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::Path;

pub use header::{TrcHeader, MAX_MARKERS};

use super::lines::Lines;
use super::{CaptureError, Frame, MarkerFrames};
use crate::math::Vector3;

/// A TRC file being read: its header, then its frames one at a time.
pub struct TrcReader<R> {
    pub header: TrcHeader,
    lines: Lines<R>,
    metres_per_unit: f64,
    first_frame: u64,
    frames: u64,
    last_number: Option<u64>,
    first_time_s: Option<f64>,
    pub warnings: Vec<String>,
}

/// The registry's entry ([`super::FORMATS`]).
pub const FORMAT: super::Format = super::Format {
    name: "trc",
    extensions: &["trc"],
    what: "TRC file",
    sniff: Some(looks_like_trc),
    open: open_samples,
    markers: Some(open_frames),
};

/// Whether these are a TRC file's first bytes.
pub fn looks_like_trc(first_bytes: &[u8]) -> bool {
    first_bytes.starts_with(b"PathFileType")
}

/// Opens a TRC file: its header read (and its frames counted), positioned on the first frame. `units` overrides
/// (or supplies) the file's `Units`, with a warning saying so.
pub fn open(path: &Path, units: Option<&str>) -> Result<TrcReader<BufReader<File>>, CaptureError> {
    let reader = |p: &Path| -> Result<_, CaptureError> {
        Ok(BufReader::with_capacity(1 << 16, File::open(p).map_err(CaptureError::io("opening"))?))
    };
    // A first pass counts the frames (a line at a time), so a replay knows them as it does a C3D capture's.
    let mut counting = Lines::new(reader(path)?, "TRC");
    let header = header::read(&mut counting, units.is_some())?;
    let mut frames = 0u64;
    let mut first_frame = None;
    while let Some((_, text)) = counting.next_line()? {
        if !text.trim().is_empty() {
            frames += 1;
            if first_frame.is_none() {
                first_frame = text.split('\t').next().and_then(|c| c.trim().parse::<u64>().ok());
            }
        }
    }
    TrcReader::new(reader(path)?, units, frames, first_frame.unwrap_or(header.orig_data_start_frame.unwrap_or(1)))
}

impl<R: BufRead> TrcReader<R> {
    /// Reads the header of `source`, which holds `frames` frames numbered from `first_frame`.
    pub fn new(source: R, units: Option<&str>, frames: u64, first_frame: u64) -> Result<Self, CaptureError> {
        let mut lines = Lines::new(source, "TRC");
        let header = header::read(&mut lines, units.is_some())?;
        let mut warnings = Vec::new();
        let metres_per_unit = match units {
            Some(u) => {
                let m = super::units::metres_per(u)?;
                let stated =
                    if header.units.is_empty() { "no units".to_string() } else { format!("`{}`", header.units) };
                warnings.push(format!("units: the file states {stated}; read as {u} (--units)"));
                m
            }
            None => super::units::metres_per(&header.units)?,
        };
        if header.num_frames != frames {
            warnings
                .push(format!("NumFrames is {} but the file holds {frames} frames; those are read", header.num_frames));
        }
        Ok(TrcReader {
            header,
            lines,
            metres_per_unit,
            first_frame,
            frames,
            last_number: None,
            first_time_s: None,
            warnings,
        })
    }

    /// Reads the next frame into `frame`; `false` after the last.
    pub fn next_frame(&mut self, frame: &mut Frame) -> Result<bool, CaptureError> {
        let markers = self.header.labels.len();
        let (line, text) = loop {
            match self.lines.next_line()? {
                None => return Ok(false),
                Some((_, t)) if t.trim().is_empty() => continue,
                Some(found) => break found,
            }
        };
        let bad = |reason: String| CaptureError::Text { format: "TRC", line, reason };
        let mut cells = text.split('\t').map(str::trim);
        let number_cell = cells.next().unwrap_or("");
        let number: u64 =
            number_cell.parse().map_err(|_| bad(format!("Frame# `{number_cell}` is not a frame number")))?;
        let time_cell = cells.next().unwrap_or("");
        let time_s: f64 = time_cell.parse().map_err(|_| bad(format!("Time `{time_cell}` is not a number")))?;
        if let Some(last) = self.last_number {
            if number <= last {
                return Err(bad(format!("Frame# {number} after {last}: the frames go forward")));
            }
        }
        let index = number
            .checked_sub(self.first_frame)
            .ok_or_else(|| bad(format!("Frame# {number} before the first frame's {}", self.first_frame)))?;
        frame.index = index;
        frame.points_m.clear();
        frame.residual_m.clear();
        let mut coordinates = [0.0f64; 3];
        for k in 0..markers {
            let mut seen = 0;
            for (axis, c) in coordinates.iter_mut().enumerate() {
                let cell = cells.next().unwrap_or("");
                if cell.is_empty() || cell.eq_ignore_ascii_case("nan") {
                    continue;
                }
                *c = cell.parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| {
                    bad(format!(
                        "marker {} ({}) {}: `{cell}` is not a number",
                        k + 1,
                        self.header.labels[k],
                        ["X", "Y", "Z"][axis]
                    ))
                })?;
                seen += 1;
            }
            let valid = seen == 3;
            frame.points_m.push(valid.then(|| Vector3::from(coordinates) * self.metres_per_unit));
            frame.residual_m.push(if valid { 0.0 } else { -1.0 });
        }
        if let Some(extra) = cells.find(|c| !c.is_empty()) {
            return Err(bad(format!("`{extra}` after the {markers} markers' {} coordinates", 3 * markers)));
        }
        let expected = self.first_time_s.get_or_insert(time_s - index as f64 / self.header.data_rate_hz);
        let expected_s = *expected + index as f64 / self.header.data_rate_hz;
        if (time_s - expected_s).abs() > 0.5 / self.header.data_rate_hz
            && !self.warnings.iter().any(|w| w.starts_with("Time "))
        {
            self.warnings.push(format!(
                "Time {time_s} s at line {line} is not Frame# over DataRate ({expected_s:.6} s): the frame numbers are used"
            ));
        }
        self.last_number = Some(number);
        Ok(true)
    }
}

impl<R: BufRead + Send> MarkerFrames for TrcReader<R> {
    fn labels(&self) -> &[String] {
        &self.header.labels
    }

    fn rate_hz(&self) -> f64 {
        self.header.data_rate_hz
    }

    fn first_frame(&self) -> u64 {
        self.first_frame
    }

    fn frames(&self) -> u64 {
        self.frames
    }

    fn warnings(&self) -> &[String] {
        &self.warnings
    }

    fn next_frame(&mut self, frame: &mut Frame) -> Result<bool, CaptureError> {
        TrcReader::next_frame(self, frame)
    }
}

fn open_frames(path: &Path, units: Option<&str>) -> Result<Box<dyn MarkerFrames>, CaptureError> {
    Ok(Box::new(open(path, units)?))
}

fn open_samples(path: &Path, options: &super::CaptureOptions) -> Result<Box<dyn super::CaptureSource>, CaptureError> {
    super::marker_samples(open_frames(path, options.units.as_deref())?, options, &FORMAT)
}
