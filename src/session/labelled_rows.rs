//! The rows of a camera monitor's labelled-column CSV (Foresight's FSX export, Uneekor's shot CSV): one header row
//! naming each column, then one row per shot. [`read_labelled`] walks the rows (byte-order mark, blank rows, row
//! numbers, numbers parsed or refused by name) and turns each row's [`ShotCells`], already in impactd's units and
//! signs, into a measured shot or a skipped row; each reader says only which column is which and how it maps.

use crate::math::Real;
use crate::pairing::DatasetLine;
use crate::wire::{DeliveryInput, LaunchFields};

use super::labelled_header::split;
use super::trackman_rows::{RowLabels, SkippedRows};

/// Why a labelled-column export cannot be read; each names the row (1-based, the header is row 1) or column.
#[derive(Debug, thiserror::Error)]
pub enum LabelledCsvError {
    #[error("not a {export}: {detail}")]
    Layout { export: &'static str, detail: String },
    #[error("row {row}: {source}")]
    Csv {
        row: usize,
        #[source]
        source: csv::Error,
    },
    #[error("row {row}, column `{column}`: `{value}` is not a number")]
    Number { row: usize, column: String, value: String },
    #[error("column `{column}`: unit `{unit}` is not one impactd reads ({expected})")]
    Unit { column: String, unit: String, expected: &'static str },
    #[error(
        "column `{column}`: sign convention `{found}` where impactd reads `{expected}`; export with Foresight's \
         default (right-handed) conventions"
    )]
    Convention { column: String, found: String, expected: &'static str },
}

/// One row's numbers in impactd's units and sign conventions (`None`: empty or not captured).
#[derive(Debug, Clone, Copy, Default)]
pub struct ShotCells {
    pub club_speed_mph: Option<Real>,
    pub ball_speed_mph: Option<Real>,
    pub launch_angle_deg: Option<Real>,
    pub launch_direction_deg: Option<Real>,
    pub backspin_rpm: Option<Real>,
    pub sidespin_rpm: Option<Real>,
    pub attack_angle_deg: Option<Real>,
    pub club_path_deg: Option<Real>,
    pub face_angle_deg: Option<Real>,
    pub dynamic_loft_deg: Option<Real>,
    pub impact_h_mm: Option<Real>,
    pub impact_v_mm: Option<Real>,
    pub carry_yd: Option<Real>,
}

/// One data row as the reader sees it: its 1-based number and its cells.
pub struct Row<'a> {
    row: usize,
    header: &'a csv::StringRecord,
    record: &'a csv::StringRecord,
}

impl Row<'_> {
    /// Column `i`'s number as written (`None` when the cell is empty or missing), or an error naming the row,
    /// the column and the cell.
    pub fn number(&self, i: usize) -> Result<Option<Real>, LabelledCsvError> {
        let cell = self.record.get(i).unwrap_or("").trim();
        if cell.is_empty() {
            return Ok(None);
        }
        cell.parse().map(Some).map_err(|_| LabelledCsvError::Number {
            row: self.row,
            column: self.header.get(i).unwrap_or("").trim().to_string(),
            value: cell.to_string(),
        })
    }
}

/// The header's columns as a reader maps them: [`read_labelled`] asks once, from the header row.
pub trait Columns: Sized {
    /// The export's name in errors (`not a {export}: ...`).
    const EXPORT: &'static str;
    /// The reader's column map from the header, or why the header is not one it reads.
    fn from_header(header: &csv::StringRecord) -> Result<Self, LabelledCsvError>;
    /// Whether a header cell's name (before any bracket) is the club's column.
    fn is_club_column(name: &str) -> bool;
    /// One row's numbers in impactd's units and signs.
    fn cells(&self, row: &Row) -> Result<ShotCells, LabelledCsvError>;
}

/// A missing column named in the header's error.
pub fn missing_column<C: Columns>(detail: String) -> LabelledCsvError {
    LabelledCsvError::Layout { export: C::EXPORT, detail }
}

/// The measured shots of `text` read through `C` with each row's [`RowLabels`], and the rows skipped: without
/// ball speed, launch angle, launch direction, back or side spin, or club speed; with a club speed but not all of
/// attack angle, club path, face angle and dynamic loft. An impact location not read leaves the shot unlocated
/// (at the face centre).
pub fn read_labelled<C: Columns>(text: &str) -> Result<(Vec<(DatasetLine, RowLabels)>, SkippedRows), LabelledCsvError> {
    let text = text.trim_start_matches('\u{feff}');
    let mut reader = csv::ReaderBuilder::new().has_headers(false).flexible(true).from_reader(text.as_bytes());
    let mut records = reader.records();
    let header = match records.next() {
        Some(r) => r.map_err(|source| LabelledCsvError::Csv { row: 1, source })?,
        None => return Err(missing_column::<C>("no header row".into())),
    };
    let cols = C::from_header(&header)?;
    let club_col = header.iter().position(|h| C::is_club_column(split(h).0));
    let mut lines = Vec::new();
    let mut skipped = SkippedRows::default();
    for (k, rec) in records.enumerate() {
        let row = k + 2;
        let record = rec.map_err(|source| LabelledCsvError::Csv { row, source })?;
        if record.iter().all(|c| c.trim().is_empty()) {
            continue;
        }
        let c = cols.cells(&Row { row, header: &header, record: &record })?;
        let ball = [c.ball_speed_mph, c.launch_angle_deg, c.launch_direction_deg, c.backspin_rpm, c.sidespin_rpm];
        let (Some(club_speed), [Some(ball_speed), Some(launch), Some(direction), Some(back), Some(side)]) =
            (c.club_speed_mph, ball)
        else {
            skipped.without_club_or_ball += 1;
            continue;
        };
        let [Some(attack), Some(path), Some(face), Some(loft)] =
            [c.attack_angle_deg, c.club_path_deg, c.face_angle_deg, c.dynamic_loft_deg]
        else {
            skipped.incomplete_club_data += 1;
            continue;
        };
        let delivery = DeliveryInput {
            club_speed_mph: club_speed,
            attack_angle_deg: attack,
            club_path_deg: path,
            face_angle_deg: face,
            dynamic_loft_deg: Some(loft),
            impact_h_mm: c.impact_h_mm.unwrap_or(0.0),
            impact_v_mm: c.impact_v_mm.unwrap_or(0.0),
            club_angular_velocity_radps: None,
            handedness: None,
            dynamic_lie_deg: None,
        };
        let measured = LaunchFields {
            ball_speed_mph: ball_speed,
            launch_angle_deg: launch,
            launch_direction_deg: direction,
            backspin_rpm: back,
            sidespin_rpm: side,
            carry_yd: c.carry_yd,
        };
        let club = club_col.and_then(|i| record.get(i)).map(str::trim).filter(|c| !c.is_empty());
        let labels = RowLabels {
            club: club.map(str::to_string),
            spin_measured: true,
            axis_measured: true,
            impact_located: c.impact_h_mm.is_some() && c.impact_v_mm.is_some(),
        };
        lines.push((DatasetLine { delivery, measured }, labels));
    }
    Ok((lines, skipped))
}
