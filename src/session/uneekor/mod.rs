//! Uneekor's shot data (EYE XO, QED, EYE MINI: the shots of a my.uneekor.com Power U report, as its report API
//! names them) in, as measured shots for `compare` and `fit`: a CSV whose header row names the API's fields
//! (`ball_speed`, `club_face_angle`, `impact_x`, ...) and one row per shot. Uneekor writes 99999 for a number its
//! cameras did not capture (a club without markers, a ball the cameras lost); it is read as not measured, never as
//! a value.
//!
//! Units are the API's: speeds in m/s and distances in m, angles in degrees, spins in rpm, impact in mm. A header
//! may name its unit in brackets instead (`ball_speed (mph)`, `carry_distance (yd)`); one impactd does not read is
//! an error naming the column. Conventions (a right-handed player; the field meanings as public readers of the API
//! document them, e.g. github.com/Redeemedduck/GolfDataApp's impact guide: `impact_x` + toe, `impact_y` + high):
//!
//! | Uneekor field | impactd field | mapping |
//! |---|---|---|
//! | `club_speed` | `club_speed_mph` | m/s to mph |
//! | `attack_angle` | `attack_angle_deg` | as is (up +) |
//! | `club_path` | `club_path_deg` | as is: in-to-out is right + |
//! | `club_face_angle` | `face_angle_deg` | as is: open is right + |
//! | `dynamic_loft` | `dynamic_loft_deg` | as is |
//! | `impact_x` | `impact_h_mm` | as is: toward the toe + |
//! | `impact_y` | `impact_v_mm` | as is: up the face + |
//! | `ball_speed` | `ball_speed_mph` | m/s to mph |
//! | `launch_angle` | `launch_angle_deg` | as is |
//! | `side_angle` | `launch_direction_deg` | as is: right + |
//! | `back_spin` | `backspin_rpm` | as is |
//! | `side_spin` | `sidespin_rpm` | as is: right (fade for a right-hander) + |
//! | `carry_distance` | `carry_yd` | m to yd |

#[cfg(test)]
mod tests;

use crate::math::Real;
use crate::pairing::DatasetLine;
use crate::wire::{DeliveryInput, LaunchFields};

use super::labelled_header::{length_to_yd, speed_to_mph, split};
use super::trackman_rows::{RowLabels, SkippedRows};

/// Uneekor's "not captured".
pub const NOT_CAPTURED: Real = 99999.0;

/// Why a Uneekor export cannot be read; each names the row (1-based, the header is row 1) or column.
#[derive(Debug, thiserror::Error)]
pub enum UneekorCsvError {
    #[error("not a Uneekor shot export: {0}")]
    Layout(String),
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
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Speed,
    Angle,
    Spin,
    Millimetre,
    Length,
}

/// The fields read (name, kind, required), in the order the constants below index them.
const FIELDS: [(&str, Kind, bool); 13] = [
    ("ball_speed", Kind::Speed, true),
    ("launch_angle", Kind::Angle, true),
    ("side_angle", Kind::Angle, true),
    ("back_spin", Kind::Spin, true),
    ("side_spin", Kind::Spin, true),
    ("club_speed", Kind::Speed, true),
    ("attack_angle", Kind::Angle, true),
    ("club_path", Kind::Angle, true),
    ("club_face_angle", Kind::Angle, true),
    ("dynamic_loft", Kind::Angle, true),
    ("impact_x", Kind::Millimetre, false),
    ("impact_y", Kind::Millimetre, false),
    ("carry_distance", Kind::Length, false),
];

/// Whether `text`'s first line is a Uneekor header (`ball_speed` and `club_face_angle` among its fields).
pub fn is_uneekor_csv(text: &str) -> bool {
    let first = text.trim_start_matches('\u{feff}').lines().next().unwrap_or("");
    let names: Vec<&str> = first.split(',').map(|h| split(h.trim().trim_matches('"')).0).collect();
    names.contains(&"ball_speed") && names.contains(&"club_face_angle")
}

fn columns(header: &csv::StringRecord) -> Result<[Option<(usize, Real)>; FIELDS.len()], UneekorCsvError> {
    let mut out = [None; FIELDS.len()];
    for (k, (name, kind, required)) in FIELDS.iter().enumerate() {
        let Some((i, unit)) = header.iter().enumerate().find_map(|(i, h)| {
            let (n, unit) = split(h);
            (n == *name).then_some((i, unit))
        }) else {
            if *required {
                return Err(UneekorCsvError::Layout(format!("no column `{name}` in the header")));
            }
            continue;
        };
        let (factor, expected) = match (kind, unit) {
            (Kind::Speed, None) => (speed_to_mph("m/s"), "mph, km/h or m/s"),
            (Kind::Speed, Some(u)) => (speed_to_mph(u), "mph, km/h or m/s"),
            (Kind::Length, None) => (length_to_yd("m"), "yd or m"),
            (Kind::Length, Some(u)) => (length_to_yd(u), "yd or m"),
            (Kind::Angle, u) => (u.is_none_or(|u| u == "deg").then_some(1.0), "deg"),
            (Kind::Spin, u) => (u.is_none_or(|u| u == "rpm").then_some(1.0), "rpm"),
            (Kind::Millimetre, u) => (u.is_none_or(|u| u == "mm").then_some(1.0), "mm"),
        };
        let Some(factor) = factor else {
            return Err(UneekorCsvError::Unit {
                column: header.get(i).unwrap_or("").trim().to_string(),
                unit: unit.unwrap_or("").to_string(),
                expected,
            });
        };
        out[k] = Some((i, factor));
    }
    Ok(out)
}

/// The measured shots of a Uneekor export with each row's [`RowLabels`], and the rows skipped: without ball or
/// club speed, or any ball number not captured; with a club speed but attack angle, club path, face angle or
/// dynamic loft not captured. An impact not captured leaves the shot unlocated (at the face centre).
pub fn read_labelled(text: &str) -> Result<(Vec<(DatasetLine, RowLabels)>, SkippedRows), UneekorCsvError> {
    let text = text.trim_start_matches('\u{feff}');
    let mut reader = csv::ReaderBuilder::new().has_headers(false).flexible(true).from_reader(text.as_bytes());
    let mut records = reader.records();
    let header = match records.next() {
        Some(r) => r.map_err(|source| UneekorCsvError::Csv { row: 1, source })?,
        None => return Err(UneekorCsvError::Layout("no header row".into())),
    };
    let cols = columns(&header)?;
    let club_col = header.iter().position(|h| matches!(split(h).0, "club" | "club_name"));
    let mut lines = Vec::new();
    let mut skipped = SkippedRows::default();
    for (k, rec) in records.enumerate() {
        let row = k + 2;
        let rec = rec.map_err(|source| UneekorCsvError::Csv { row, source })?;
        if rec.iter().all(|c| c.trim().is_empty()) {
            continue;
        }
        let value = |k: usize| -> Result<Option<Real>, UneekorCsvError> {
            let Some((i, factor)) = cols[k] else { return Ok(None) };
            let cell = rec.get(i).unwrap_or("").trim();
            if cell.is_empty() {
                return Ok(None);
            }
            let v: Real = cell.parse().map_err(|_| UneekorCsvError::Number {
                row,
                column: header.get(i).unwrap_or("").trim().to_string(),
                value: cell.to_string(),
            })?;
            Ok((v != NOT_CAPTURED).then_some(v * factor))
        };
        let v: Vec<Option<Real>> = (0..FIELDS.len()).map(value).collect::<Result<_, _>>()?;
        let (Some(club_speed), [Some(ball_speed), Some(launch), Some(direction), Some(back), Some(side)]) =
            (v[5], [v[0], v[1], v[2], v[3], v[4]])
        else {
            skipped.without_club_or_ball += 1;
            continue;
        };
        let [Some(attack), Some(path), Some(face), Some(loft)] = [v[6], v[7], v[8], v[9]] else {
            skipped.incomplete_club_data += 1;
            continue;
        };
        let delivery = DeliveryInput {
            club_speed_mph: club_speed,
            attack_angle_deg: attack,
            club_path_deg: path,
            face_angle_deg: face,
            dynamic_loft_deg: Some(loft),
            impact_h_mm: v[10].unwrap_or(0.0),
            impact_v_mm: v[11].unwrap_or(0.0),
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
            carry_yd: v[12],
        };
        let club = club_col.and_then(|i| rec.get(i)).map(str::trim).filter(|c| !c.is_empty());
        let labels = RowLabels {
            club: club.map(str::to_string),
            spin_measured: true,
            axis_measured: true,
            impact_located: v[10].is_some() && v[11].is_some(),
        };
        lines.push((DatasetLine { delivery, measured }, labels));
    }
    Ok((lines, skipped))
}
