//! A pose table: a CSV (or TSV) of the tracked body's poses, one row a frame, as a tracker or a model exports them
//! (a rigid body's poses from Motive or QTM, a club-face-centre trajectory from a swing model). A header line names
//! the columns; a column spec ([`ColumnSpec`], `--columns` or the sidecar `TABLE.columns`) says which column is
//! the time, the position (with its unit) and the orientation (quaternion, rotation matrix or a named Euler
//! sequence). Lines starting with `#` before the header are comments. A row whose position or orientation cells
//! are empty is a frame the body was not seen in (`occluded`). Each row is the body's pose in the lab
//! (`lab_from_body`); with `origin=face-centre` the body is the face centre and the pose is moved to the club frame
//! by the club's `face.center_m`, so the configuration's `club_from_body` stays the identity.

pub mod columns;
pub mod orientation;

use std::fs::File;
use std::io::BufReader;
use std::path::{Path, PathBuf};

pub use columns::{ColumnSpec, Origin, Time};

use super::lines::Lines;
use super::{CaptureError, CaptureOptions, CaptureSource, ImportCounts};
use crate::math::{Isometry3, Translation3, UnitQuaternion, Vector3};
use crate::wire::{BallSampleMsg, ClubheadSampleMsg, QuaternionMsg};

/// The registry's entry ([`super::FORMATS`]).
pub const FORMAT: super::Format = super::Format {
    name: "pose-table",
    extensions: &["csv", "tsv"],
    what: "pose table",
    sniff: None,
    open: open_samples,
    markers: None,
};

/// Where a table's sidecar column spec is: `TABLE.columns` beside it (`swings.csv.columns`).
pub fn sidecar(path: &Path) -> PathBuf {
    let mut name = path.as_os_str().to_owned();
    name.push(".columns");
    PathBuf::from(name)
}

/// The column spec of `path`: `given` (a spec, or a file holding one), else the sidecar.
pub fn spec_for(path: &Path, given: Option<&str>) -> Result<ColumnSpec, CaptureError> {
    let text = match given {
        Some(g) if Path::new(g).is_file() => {
            std::fs::read_to_string(g).map_err(CaptureError::io("reading the column spec"))?
        }
        Some(g) => g.to_string(),
        None => {
            let side = sidecar(path);
            if !side.is_file() {
                return Err(CaptureError::Usage(format!(
                    "{} is a pose table: say what its columns are with --columns 'time=Time:s; position=X,Y,Z:mm; \
                     quaternion-xyzw=QX,QY,QZ,QW' (or the same in {}); docs/captures.md",
                    path.display(),
                    side.display()
                )));
            }
            std::fs::read_to_string(&side).map_err(CaptureError::io("reading the sidecar column spec"))?
        }
    };
    ColumnSpec::parse(&text)
}

/// The column indices of a spec in a table's header.
struct Layout {
    time: Option<usize>,
    frame: Option<usize>,
    position: [usize; 3],
    orientation: Vec<usize>,
    ball: Option<[usize; 3]>,
}

/// A pose table read as samples of one rig, a row at a time.
pub struct PoseSamples {
    spec: ColumnSpec,
    layout: Layout,
    lines: Lines<BufReader<File>>,
    delimiter: char,
    rig: String,
    /// `body_from_club` for `origin=face-centre`.
    body_from_club: Isometry3,
    metres_per_unit: f64,
    frames: u64,
    rows: u64,
    first_time_s: Option<f64>,
    last_t_ns: Option<u64>,
    last_pose: Isometry3,
    ball: Option<BallSampleMsg>,
    counts: ImportCounts,
    warnings: Vec<String>,
}

fn reader(path: &Path) -> Result<Lines<BufReader<File>>, CaptureError> {
    let file = File::open(path).map_err(CaptureError::io("opening"))?;
    Ok(Lines::new(BufReader::with_capacity(1 << 16, file), "pose table"))
}

/// Reads up to the header line: its number, its cells and the delimiter.
fn header(lines: &mut Lines<BufReader<File>>, given: Option<char>) -> Result<(Vec<String>, char), CaptureError> {
    loop {
        let Some((_, text)) = lines.next_line()? else {
            return Err(lines.error("the table ends before its header line (the columns' names)".into()));
        };
        let text = text.trim_start_matches('\u{feff}');
        if text.trim().is_empty() || text.starts_with('#') {
            continue;
        }
        let delimiter = given.unwrap_or(if text.contains('\t') {
            '\t'
        } else if text.contains(';') && !text.contains(',') {
            ';'
        } else {
            ','
        });
        return Ok((text.split(delimiter).map(|c| c.trim().trim_matches('"').to_string()).collect(), delimiter));
    }
}

impl PoseSamples {
    pub fn open(path: &Path, options: &CaptureOptions) -> Result<Self, CaptureError> {
        if options.fitter.is_some() || options.ball_marker.is_some() {
            return Err(CaptureError::Usage(
                "--markers and --ball-marker are for marker captures; a pose table's columns say what it holds".into(),
            ));
        }
        let spec = spec_for(path, options.columns.as_deref())?;
        let mut warnings = Vec::new();
        let metres_per_unit = match &options.units {
            Some(u) => {
                warnings.push(format!("units: the column spec states {}; read as {u} (--units)", spec.units));
                super::units::metres_per(u)?
            }
            None => spec.metres_per_unit,
        };
        let body_from_club = match (spec.origin, options.face_centre_club_m) {
            (Origin::Body, _) => Isometry3::identity(),
            (Origin::FaceCentre, Some(c)) => Isometry3::from_parts(Translation3::from(-c), UnitQuaternion::identity()),
            (Origin::FaceCentre, None) => {
                return Err(CaptureError::Usage(
                    "origin=face-centre: the club's face centre places the club frame; give the club (--club)".into(),
                ))
            }
        };
        // A first pass counts the rows, so a replay knows them as it does a C3D capture's.
        let mut counting = reader(path)?;
        let (names, delimiter) = header(&mut counting, spec.delimiter)?;
        let header_line = counting.line();
        let mut frames = 0;
        while let Some((_, text)) = counting.next_line()? {
            frames += u64::from(!text.trim().is_empty());
        }
        let find = |name: &str| {
            names.iter().position(|n| n == name).ok_or_else(|| CaptureError::Text {
                format: "pose table",
                line: header_line,
                reason: format!(
                    "the column spec names column `{name}`, which the header does not ({})",
                    names.join(", ")
                ),
            })
        };
        let three =
            |n: &[String; 3]| -> Result<[usize; 3], CaptureError> { Ok([find(&n[0])?, find(&n[1])?, find(&n[2])?]) };
        let layout = Layout {
            time: match &spec.time {
                Time::Column { name, .. } => Some(find(name)?),
                Time::Rate(_) => None,
            },
            frame: spec.frame.as_deref().map(find).transpose()?,
            position: three(&spec.position)?,
            orientation: spec.orientation_columns.iter().map(|n| find(n)).collect::<Result<_, _>>()?,
            ball: spec.ball.as_ref().map(three).transpose()?,
        };
        let mut lines = reader(path)?;
        header(&mut lines, Some(delimiter))?;
        Ok(PoseSamples {
            spec,
            layout,
            lines,
            delimiter,
            rig: options.rig.clone(),
            body_from_club,
            metres_per_unit,
            frames,
            rows: 0,
            first_time_s: None,
            last_t_ns: None,
            last_pose: Isometry3::identity(),
            ball: None,
            counts: ImportCounts::default(),
            warnings,
        })
    }

    /// The next row's sample, `None` after the last row.
    pub fn next_sample(&mut self) -> Result<Option<ClubheadSampleMsg>, CaptureError> {
        let (line, text) = loop {
            match self.lines.next_line()? {
                None => return Ok(None),
                Some((_, t)) if t.trim().is_empty() => continue,
                Some(found) => break found,
            }
        };
        let bad = |reason: String| CaptureError::Text { format: "pose table", line, reason };
        let cells: Vec<&str> = text.split(self.delimiter).map(|c| c.trim().trim_matches('"')).collect();
        // A cell's number: `None` when empty (or NaN), an error when not a number.
        let number = |i: usize| -> Result<Option<f64>, CaptureError> {
            let cell = cells.get(i).copied().unwrap_or("");
            if cell.is_empty() || cell.eq_ignore_ascii_case("nan") {
                return Ok(None);
            }
            cell.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .map(Some)
                .ok_or_else(|| bad(format!("column {} (`{cell}`) is not a number", i + 1)))
        };
        let t_ns = match (&self.spec.time, self.layout.time) {
            (Time::Column { seconds_per_unit, .. }, Some(i)) => {
                let t =
                    number(i)?.ok_or_else(|| bad(format!("the time (column {}) is empty", i + 1)))? * seconds_per_unit;
                let t0 = *self.first_time_s.get_or_insert(t);
                let t_ns = ((t - t0) * 1e9).round();
                if t_ns < 0.0 || self.last_t_ns.is_some_and(|last| t_ns as u64 <= last) {
                    return Err(bad(format!("time {t} s does not come after the row before's")));
                }
                t_ns as u64
            }
            (Time::Rate(hz), _) => (self.rows as f64 * 1e9 / hz).round() as u64,
            (Time::Column { .. }, None) => 0,
        };
        let frame = match self.layout.frame {
            Some(i) => {
                let f = number(i)?.ok_or_else(|| bad(format!("the frame number (column {}) is empty", i + 1)))?;
                if f < 0.0 || f.fract() != 0.0 {
                    return Err(bad(format!("frame number {f} is not a count")));
                }
                f as u64
            }
            None => self.rows + 1,
        };
        let position: Vec<Option<f64>> = self.layout.position.iter().map(|&i| number(i)).collect::<Result<_, _>>()?;
        let angles: Vec<Option<f64>> = self.layout.orientation.iter().map(|&i| number(i)).collect::<Result<_, _>>()?;
        let seen = position.iter().chain(&angles).all(Option::is_some);
        let pose = if seen {
            let p: Vec<f64> = position.iter().flatten().map(|v| v * self.metres_per_unit).collect();
            let values: Vec<f64> = angles.iter().flatten().copied().collect();
            let q = self.spec.orientation.rotation(&values).map_err(bad)?;
            let pose = Isometry3::from_parts(Translation3::new(p[0], p[1], p[2]), q) * self.body_from_club;
            self.last_pose = pose;
            pose
        } else {
            self.counts.occluded += 1;
            self.last_pose
        };
        if let Some(ball) = self.layout.ball {
            let b: Vec<Option<f64>> = ball.iter().map(|&i| number(i)).collect::<Result<_, _>>()?;
            let at = b
                .iter()
                .all(Option::is_some)
                .then(|| b.iter().flatten().map(|v| v * self.metres_per_unit).collect::<Vec<_>>());
            self.ball = Some(BallSampleMsg {
                rig: self.rig.clone(),
                frame,
                t_ns,
                position_m: at.as_ref().map_or([0.0; 3], |p| [p[0], p[1], p[2]]),
                occluded: at.is_none(),
            });
        }
        self.rows += 1;
        self.counts.frames += 1;
        self.last_t_ns = Some(t_ns);
        let p: Vector3 = pose.translation.vector;
        Ok(Some(ClubheadSampleMsg {
            rig: self.rig.clone(),
            frame,
            t_ns,
            position_m: [p.x, p.y, p.z],
            orientation: QuaternionMsg::from(pose.rotation),
            occluded: !seen,
            fit_residual_m: None,
            exposure_t_ns: None,
            system_latency_us: None,
            body: None,
        }))
    }
}

impl CaptureSource for PoseSamples {
    fn next_sample(&mut self) -> Result<Option<ClubheadSampleMsg>, CaptureError> {
        PoseSamples::next_sample(self)
    }

    fn ball(&self) -> Option<BallSampleMsg> {
        self.ball.clone()
    }

    fn counts(&self) -> &ImportCounts {
        &self.counts
    }

    fn frames(&self) -> u64 {
        self.frames
    }

    fn warnings(&self) -> &[String] {
        &self.warnings
    }
}

fn open_samples(path: &Path, options: &CaptureOptions) -> Result<Box<dyn CaptureSource>, CaptureError> {
    Ok(Box::new(PoseSamples::open(path, options)?))
}
