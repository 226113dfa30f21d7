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

use super::labelled_header::{length_to_yd, speed_to_mph, split};
use super::labelled_rows::{self, missing_column, Columns, LabelledCsvError, Row, ShotCells};
use super::trackman_rows::{RowLabels, SkippedRows};

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
struct ForesightColumns([Option<(usize, Real)>; SPECS.len()]);

impl Columns for ForesightColumns {
    const EXPORT: &'static str = "Foresight FSX export";

    fn from_header(header: &csv::StringRecord) -> Result<Self, LabelledCsvError> {
        let mut out = [None; SPECS.len()];
        for (k, s) in SPECS.iter().enumerate() {
            let Some((i, inside)) = header.iter().enumerate().find_map(|(i, h)| {
                let (name, inside) = split(h);
                (name == s.name).then_some((i, inside))
            }) else {
                if s.required {
                    return Err(missing_column::<Self>(format!("no column `{} (...)` in the header", s.name)));
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
                return Err(LabelledCsvError::Unit { column, unit: unit.to_string(), expected });
            };
            if signs != s.signs {
                return Err(LabelledCsvError::Convention { column, found: signs.to_string(), expected: s.signs });
            }
            out[k] = Some((i, factor));
        }
        Ok(Self(out))
    }

    fn is_club_column(name: &str) -> bool {
        name == "Club Name"
    }

    fn cells(&self, row: &Row) -> Result<ShotCells, LabelledCsvError> {
        let value = |k: usize| -> Result<Option<Real>, LabelledCsvError> {
            let Some((i, factor)) = self.0[k] else { return Ok(None) };
            Ok(row.number(i)?.map(|v| v * factor))
        };
        Ok(ShotCells {
            club_speed_mph: value(CLUB_SPEED)?.filter(|s| *s < NO_CLUB_SPEED_MPH),
            ball_speed_mph: value(BALL_SPEED)?,
            launch_angle_deg: value(LAUNCH_ANGLE)?,
            launch_direction_deg: value(PUSH_PULL)?,
            backspin_rpm: value(BACK_SPIN)?,
            sidespin_rpm: value(SIDE_SPIN)?,
            attack_angle_deg: value(ATTACK)?,
            club_path_deg: value(PATH)?,
            face_angle_deg: value(FACE)?,
            dynamic_loft_deg: value(LOFT)?,
            // Foresight's toe- / heel+ against impactd's toward-the-toe +.
            impact_h_mm: value(IMPACT_H)?.map(|h| -h),
            impact_v_mm: value(IMPACT_V)?,
            carry_yd: value(CARRY)?,
        })
    }
}

/// The measured shots of a Foresight export with each row's [`RowLabels`], and the rows skipped: without ball
/// speed or club speed (or with the no-club-data sentinel), or with a club speed but not all of attack angle,
/// club path, face to target and loft.
pub fn read_labelled(text: &str) -> Result<(Vec<(DatasetLine, RowLabels)>, SkippedRows), LabelledCsvError> {
    labelled_rows::read_labelled::<ForesightColumns>(text)
}
