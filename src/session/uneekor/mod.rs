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

use super::labelled_header::{length_to_yd, speed_to_mph, split};
use super::labelled_rows::{self, missing_column, Columns, LabelledCsvError, Row, ShotCells};
use super::trackman_rows::{RowLabels, SkippedRows};

/// Uneekor's "not captured".
pub const NOT_CAPTURED: Real = 99999.0;

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

/// Each field's column index and factor to impactd's unit, from the header.
struct UneekorColumns([Option<(usize, Real)>; FIELDS.len()]);

impl Columns for UneekorColumns {
    const EXPORT: &'static str = "Uneekor shot export";

    fn from_header(header: &csv::StringRecord) -> Result<Self, LabelledCsvError> {
        let mut out = [None; FIELDS.len()];
        for (k, (name, kind, required)) in FIELDS.iter().enumerate() {
            let Some((i, unit)) = header.iter().enumerate().find_map(|(i, h)| {
                let (n, unit) = split(h);
                (n == *name).then_some((i, unit))
            }) else {
                if *required {
                    return Err(missing_column::<Self>(format!("no column `{name}` in the header")));
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
                return Err(LabelledCsvError::Unit {
                    column: header.get(i).unwrap_or("").trim().to_string(),
                    unit: unit.unwrap_or("").to_string(),
                    expected,
                });
            };
            out[k] = Some((i, factor));
        }
        Ok(Self(out))
    }

    fn is_club_column(name: &str) -> bool {
        matches!(name, "club" | "club_name")
    }

    fn cells(&self, row: &Row) -> Result<ShotCells, LabelledCsvError> {
        let value = |k: usize| -> Result<Option<Real>, LabelledCsvError> {
            let Some((i, factor)) = self.0[k] else { return Ok(None) };
            Ok(row.number(i)?.filter(|v| *v != NOT_CAPTURED).map(|v| v * factor))
        };
        let v: Vec<Option<Real>> = (0..FIELDS.len()).map(value).collect::<Result<_, _>>()?;
        Ok(ShotCells {
            ball_speed_mph: v[0],
            launch_angle_deg: v[1],
            launch_direction_deg: v[2],
            backspin_rpm: v[3],
            sidespin_rpm: v[4],
            club_speed_mph: v[5],
            attack_angle_deg: v[6],
            club_path_deg: v[7],
            face_angle_deg: v[8],
            dynamic_loft_deg: v[9],
            impact_h_mm: v[10],
            impact_v_mm: v[11],
            carry_yd: v[12],
        })
    }
}

/// The measured shots of a Uneekor export with each row's [`RowLabels`], and the rows skipped: without ball or
/// club speed, or any ball number not captured; with a club speed but attack angle, club path, face angle or
/// dynamic loft not captured. An impact not captured leaves the shot unlocated (at the face centre).
pub fn read_labelled(text: &str) -> Result<(Vec<(DatasetLine, RowLabels)>, SkippedRows), LabelledCsvError> {
    labelled_rows::read_labelled::<UneekorColumns>(text)
}
