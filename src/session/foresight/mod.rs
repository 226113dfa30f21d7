//! Foresight Sports' CSV export (FSX 2020 / FSX Play, from a GCQuad, GC3 or QuadMAX) in, as measured shots for
//! `compare` and `fit`: one header row whose columns carry their unit and sign convention in brackets (`Club Path
//! (deg out-in-/in-out+)`, `Face Impact Horizontal (mm toe-/heel+)`), then one row per shot.
//!
//! Read into impactd's conventions (docs/session.md, ARCHITECTURE.md section 2; a right-handed player, as the
//! export's signs are written):
//!
//! | Foresight column | impactd field | mapping |
//! |---|---|---|
//! | `Club Speed (mph)` | `club_speed_mph` | as is (km/h, m/s converted); 1000 or more is Foresight's "no club data" |
//! | `Angle of Attack (deg)` | `attack_angle_deg` | as is (up +) |
//! | `Club Path (deg out-in-/in-out+)` | `club_path_deg` | as is: in-to-out is right + |
//! | `Face to Target (deg closed-/open+)` | `face_angle_deg` | as is: open is right + |
//! | `Loft (deg)` | `dynamic_loft_deg` | as is |
//! | `Face Impact Horizontal (mm toe-/heel+)` | `impact_h_mm` | negated: impactd's `h` is toward the toe + |
//! | `Face Impact Vertical (mm low-/high+)` | `impact_v_mm` | as is: up the face + |
//! | `Ball Speed (mph)` | `ball_speed_mph` | as is (km/h, m/s converted) |
//! | `Launch Angle (deg)` | `launch_angle_deg` | as is |
//! | `Push/Pull (deg L-/R+)` | `launch_direction_deg` | as is: right + |
//! | `Back Spin (rpm)` | `backspin_rpm` | as is |
//! | `Side Spin (rpm L-/R+)` | `sidespin_rpm` | as is: right (fade for a right-hander) + |
//! | `Carry (yds)` | `carry_yd` | as is (m converted) |
//!
//! `Lie (deg toe down-/toe up+)` and `Closure Rate (deg/sec)` are checked (unit and signs) but not used: the lie's
//! zero is the club soled at its own static lie, which the export does not give, and a closure rate is one
//! component of the head's angular velocity, not the vector a delivery takes. A header whose unit or sign
//! convention differs from the table (a newer layout, a left-handed export) is an error naming the column, never
//! read with a guessed sign. The club speed sentinel (1000 mph or more when the club was not measured) is read as
//! no club data, as public readers of these exports treat it.

#[cfg(test)]
mod tests;

use crate::math::Real;
use crate::pairing::DatasetLine;
use crate::wire::{DeliveryInput, LaunchFields};

use super::labelled_header::{length_to_yd, speed_to_mph, split};
use super::trackman_rows::{RowLabels, SkippedRows};

/// Why a Foresight export cannot be read; each names the row (1-based, the header is row 1) or column.
#[derive(Debug, thiserror::Error)]
pub enum ForesightCsvError {
    #[error("not a Foresight FSX export: {0}")]
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
    #[error(
        "column `{column}`: sign convention `{found}` where impactd reads `{expected}`; export with Foresight's \
         default (right-handed) conventions"
    )]
    Convention { column: String, found: String, expected: &'static str },
}

/// What a column's unit is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Speed,
    Angle,
    Spin,
    Millimetre,
    Length,
    AngularRate,
}

/// A column impactd reads: its name, kind, the sign convention after the unit, and whether a file must have it.
struct Spec {
    name: &'static str,
    kind: Kind,
    signs: &'static str,
    required: bool,
}

const fn spec(name: &'static str, kind: Kind, signs: &'static str, required: bool) -> Spec {
    Spec { name, kind, signs, required }
}

/// The columns read, in the order [`Cols`] indexes them.
const SPECS: [Spec; 15] = [
    spec("Ball Speed", Kind::Speed, "", true),
    spec("Launch Angle", Kind::Angle, "", true),
    spec("Push/Pull", Kind::Angle, "L-/R+", true),
    spec("Back Spin", Kind::Spin, "", true),
    spec("Side Spin", Kind::Spin, "L-/R+", true),
    spec("Club Speed", Kind::Speed, "", true),
    spec("Angle of Attack", Kind::Angle, "", true),
    spec("Club Path", Kind::Angle, "out-in-/in-out+", true),
    spec("Face to Target", Kind::Angle, "closed-/open+", true),
    spec("Loft", Kind::Angle, "", true),
    spec("Face Impact Horizontal", Kind::Millimetre, "toe-/heel+", false),
    spec("Face Impact Vertical", Kind::Millimetre, "low-/high+", false),
    spec("Lie", Kind::Angle, "toe down-/toe up+", false),
    spec("Closure Rate", Kind::AngularRate, "", false),
    spec("Carry", Kind::Length, "", false),
];

const BALL_SPEED: usize = 0;
const LAUNCH_ANGLE: usize = 1;
const PUSH_PULL: usize = 2;
const BACK_SPIN: usize = 3;
const SIDE_SPIN: usize = 4;
const CLUB_SPEED: usize = 5;
const ATTACK: usize = 6;
const PATH: usize = 7;
const FACE: usize = 8;
const LOFT: usize = 9;
const IMPACT_H: usize = 10;
const IMPACT_V: usize = 11;
const CARRY: usize = 14;

/// Foresight's club speed when the club was not measured is a large sentinel; any speed from here up is one.
pub const NO_CLUB_SPEED_MPH: Real = 1000.0;

/// Whether `text`'s first line is a Foresight FSX header (`Push/Pull (` or `Face Impact Horizontal (`).
pub fn is_foresight_csv(text: &str) -> bool {
    let first = text.trim_start_matches('\u{feff}').lines().next().unwrap_or("");
    first.contains("Push/Pull (") || first.contains("Face Impact Horizontal (")
}

/// Each spec's column index and factor to impactd's unit, from the header.
fn columns(header: &csv::StringRecord) -> Result<[Option<(usize, Real)>; SPECS.len()], ForesightCsvError> {
    let mut out = [None; SPECS.len()];
    for (k, s) in SPECS.iter().enumerate() {
        let Some((i, inside)) = header.iter().enumerate().find_map(|(i, h)| {
            let (name, inside) = split(h);
            (name == s.name).then_some((i, inside))
        }) else {
            if s.required {
                return Err(ForesightCsvError::Layout(format!("no column `{} (...)` in the header", s.name)));
            }
            continue;
        };
        let column = header.get(i).unwrap_or("").trim().to_string();
        let inside = inside.unwrap_or("");
        let (unit, signs) = inside.split_once(' ').map_or((inside, ""), |(u, rest)| (u, rest.trim()));
        let (factor, expected) = match s.kind {
            Kind::Speed => (speed_to_mph(unit), "mph, km/h or m/s"),
            Kind::Angle => ((unit == "deg").then_some(1.0), "deg"),
            Kind::Spin => ((unit == "rpm").then_some(1.0), "rpm"),
            Kind::Millimetre => ((unit == "mm").then_some(1.0), "mm"),
            Kind::Length => (length_to_yd(unit), "yds or m"),
            Kind::AngularRate => ((unit == "deg/sec").then_some(1.0), "deg/sec"),
        };
        let Some(factor) = factor else {
            return Err(ForesightCsvError::Unit { column, unit: unit.to_string(), expected });
        };
        if signs != s.signs {
            return Err(ForesightCsvError::Convention { column, found: signs.to_string(), expected: s.signs });
        }
        out[k] = Some((i, factor));
    }
    Ok(out)
}

/// The measured shots of a Foresight export with each row's [`RowLabels`], and the rows skipped: without ball
/// speed or club speed (or with the no-club-data sentinel), or with a club speed but not all of attack angle,
/// club path, face to target and loft.
pub fn read_labelled(text: &str) -> Result<(Vec<(DatasetLine, RowLabels)>, SkippedRows), ForesightCsvError> {
    let text = text.trim_start_matches('\u{feff}');
    let mut reader = csv::ReaderBuilder::new().has_headers(false).flexible(true).from_reader(text.as_bytes());
    let mut records = reader.records();
    let header = match records.next() {
        Some(r) => r.map_err(|source| ForesightCsvError::Csv { row: 1, source })?,
        None => return Err(ForesightCsvError::Layout("no header row".into())),
    };
    let cols = columns(&header)?;
    let club_col = header.iter().position(|h| split(h).0 == "Club Name");
    let mut lines = Vec::new();
    let mut skipped = SkippedRows::default();
    for (k, rec) in records.enumerate() {
        let row = k + 2;
        let rec = rec.map_err(|source| ForesightCsvError::Csv { row, source })?;
        if rec.iter().all(|c| c.trim().is_empty()) {
            continue;
        }
        let value = |k: usize| -> Result<Option<Real>, ForesightCsvError> {
            let Some((i, factor)) = cols[k] else { return Ok(None) };
            let cell = rec.get(i).unwrap_or("").trim();
            if cell.is_empty() {
                return Ok(None);
            }
            let v: Real = cell.parse().map_err(|_| ForesightCsvError::Number {
                row,
                column: header.get(i).unwrap_or("").trim().to_string(),
                value: cell.to_string(),
            })?;
            Ok(Some(v * factor))
        };
        let club_speed = value(CLUB_SPEED)?.filter(|s| *s < NO_CLUB_SPEED_MPH);
        let ball = [value(BALL_SPEED)?, value(LAUNCH_ANGLE)?, value(PUSH_PULL)?, value(BACK_SPIN)?, value(SIDE_SPIN)?];
        let (Some(club_speed), [Some(ball_speed), Some(launch), Some(direction), Some(back), Some(side)]) =
            (club_speed, ball)
        else {
            skipped.without_club_or_ball += 1;
            continue;
        };
        let [Some(attack), Some(path), Some(face), Some(loft)] =
            [value(ATTACK)?, value(PATH)?, value(FACE)?, value(LOFT)?]
        else {
            skipped.incomplete_club_data += 1;
            continue;
        };
        let (h, v) = (value(IMPACT_H)?, value(IMPACT_V)?);
        let delivery = DeliveryInput {
            club_speed_mph: club_speed,
            attack_angle_deg: attack,
            club_path_deg: path,
            face_angle_deg: face,
            dynamic_loft_deg: Some(loft),
            // Foresight's toe- / heel+ against impactd's toward-the-toe +.
            impact_h_mm: h.map_or(0.0, |h| -h),
            impact_v_mm: v.unwrap_or(0.0),
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
            carry_yd: value(CARRY)?,
        };
        let club = club_col.and_then(|i| rec.get(i)).map(str::trim).filter(|c| !c.is_empty());
        let labels = RowLabels {
            club: club.map(str::to_string),
            spin_measured: true,
            axis_measured: true,
            impact_located: h.is_some() && v.is_some(),
        };
        lines.push((DatasetLine { delivery, measured }, labels));
    }
    Ok((lines, skipped))
}
