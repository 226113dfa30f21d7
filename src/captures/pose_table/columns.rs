//! A pose table's column spec: which column is what, and in which units. Entries `key=value`, separated by `;`
//! or new lines (a line starting with `#` is a comment), given as `--columns` or in a sidecar file `TABLE.columns`:
//!
//! ```text
//! time=Time:s; position=X,Y,Z:mm; quaternion-xyzw=QX,QY,QZ,QW; origin=face-centre
//! ```
//!
//! - `time=COLUMN:UNIT` (`s`, `ms`, `us`, `ns`), or `rate=HZ` for rows evenly spaced from 0; one of them.
//! - `position=X,Y,Z:UNIT`: the body's origin in the lab, unit required (`units::LENGTH_UNITS`).
//! - The orientation, one of: `quaternion-xyzw=X,Y,Z,W`, `quaternion-wxyz=W,X,Y,Z`, `matrix=R11,R12,...,R33`
//!   (row-major; its columns are the body's axes in the lab), `euler-SEQ=A,B,C:deg|rad` (SEQ as SciPy names it:
//!   `ZYX` intrinsic, `xyz` extrinsic).
//! - `frame=COLUMN` (optional): the frame numbers; else the row's number from 1.
//! - `ball=X,Y,Z` (optional): a tracked ball's centre, in the position's unit; empty cells: not seen.
//! - `origin=body|face-centre` (optional, `body`): `face-centre` says the body's origin is the club's face
//!   centre (with the club frame's axes), so no `club_from_body` is needed: the pose is moved to the club frame
//!   by the club's `face.center_m`.
//! - `delimiter=,|;|tab` (optional): else found from the header line.

use super::orientation::OrientationKind;
use crate::captures::units;
use crate::captures::CaptureError;

/// Where the body's origin is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Origin {
    /// The tracked body's own (the configuration's `club_from_body` places it on the club).
    #[default]
    Body,
    /// The club's face centre, the club frame's axes.
    FaceCentre,
}

/// The time of each row.
#[derive(Debug, Clone, PartialEq)]
pub enum Time {
    /// A column in seconds times `seconds_per_unit`.
    Column { name: String, seconds_per_unit: f64 },
    /// Rows evenly spaced at this rate (Hz).
    Rate(f64),
}

/// What each column of a pose table is.
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnSpec {
    pub time: Time,
    pub frame: Option<String>,
    pub position: [String; 3],
    /// The position's unit as the spec names it, and its metres.
    pub units: String,
    pub metres_per_unit: f64,
    pub orientation: OrientationKind,
    pub orientation_columns: Vec<String>,
    pub ball: Option<[String; 3]>,
    pub origin: Origin,
    pub delimiter: Option<char>,
}

/// The keys a spec may hold.
pub const KEYS: &str = "time, rate, position, quaternion-xyzw, quaternion-wxyz, matrix, euler-SEQ, frame, ball, \
                        origin, delimiter";

const EXAMPLE: &str = "time=Time:s; position=X,Y,Z:mm; quaternion-xyzw=QX,QY,QZ,QW";

fn usage(entry: &str, reason: impl std::fmt::Display) -> CaptureError {
    CaptureError::Usage(format!("column spec `{entry}`: {reason}"))
}

/// `A,B,C:unit` as the names and the unit (`None` without a `:`).
fn names_and_unit(value: &str) -> (Vec<String>, Option<String>) {
    let (names, unit) = match value.rsplit_once(':') {
        Some((n, u)) => (n, Some(u.trim().to_string())),
        None => (value, None),
    };
    (names.split(',').map(|n| n.trim().to_string()).collect(), unit)
}

impl ColumnSpec {
    /// Parses a spec (module docs).
    pub fn parse(text: &str) -> Result<Self, CaptureError> {
        let (mut time, mut frame, mut position, mut orientation, mut ball) = (None, None, None, None, None);
        let (mut origin, mut delimiter) = (None, None);
        let entries = text.split(['\n', ';']).map(str::trim);
        for entry in entries.filter(|e| !e.is_empty() && !e.starts_with('#')) {
            let Some((key, value)) = entry.split_once('=') else {
                return Err(usage(entry, format!("not `key=value` (keys: {KEYS})")));
            };
            let (key, value) = (key.trim(), value.trim());
            let (names, unit) = names_and_unit(value);
            let count = |n: usize| -> Result<(), CaptureError> {
                if names.len() != n || names.iter().any(String::is_empty) {
                    return Err(usage(entry, format!("{key} names {n} columns, comma-separated")));
                }
                Ok(())
            };
            let once = |taken: bool| if taken { Err(usage(entry, format!("{key} is given twice"))) } else { Ok(()) };
            match key {
                "time" => {
                    once(time.is_some())?;
                    count(1)?;
                    let seconds_per_unit = match unit.as_deref() {
                        Some("s") => 1.0,
                        Some("ms") => 1e-3,
                        Some("us") => 1e-6,
                        Some("ns") => 1e-9,
                        Some(u) => return Err(usage(entry, format!("time unit `{u}` is not s, ms, us or ns"))),
                        None => {
                            return Err(usage(entry, "the time's unit is required: `time=COLUMN:s` (s, ms, us, ns)"))
                        }
                    };
                    time = Some(Time::Column { name: names[0].clone(), seconds_per_unit });
                }
                "rate" => {
                    once(time.is_some())?;
                    let hz = value.trim_end_matches("Hz").trim().parse::<f64>().ok();
                    let hz = hz.filter(|r| r.is_finite() && *r > 0.0 && *r < 1e6);
                    time = Some(Time::Rate(hz.ok_or_else(|| usage(entry, "rate is the rows' rate in Hz"))?));
                }
                "frame" => {
                    once(frame.is_some())?;
                    count(1)?;
                    frame = Some(names[0].clone());
                }
                "position" => {
                    once(position.is_some())?;
                    count(3)?;
                    let unit = unit.ok_or_else(|| {
                        usage(
                            entry,
                            format!("the position's unit is required: `position=X,Y,Z:mm` ({})", units::names()),
                        )
                    })?;
                    let metres = units::metres_per_unit(&unit)
                        .ok_or_else(|| usage(entry, format!("unit `{unit}` is not one of {}", units::names())))?;
                    position = Some(([names[0].clone(), names[1].clone(), names[2].clone()], unit, metres));
                }
                "ball" => {
                    once(ball.is_some())?;
                    count(3)?;
                    if unit.is_some() {
                        return Err(usage(entry, "the ball is in the position's unit; give no unit here"));
                    }
                    ball = Some([names[0].clone(), names[1].clone(), names[2].clone()]);
                }
                "origin" => {
                    once(origin.is_some())?;
                    origin = Some(match value {
                        "body" => Origin::Body,
                        "face-centre" | "face-center" => Origin::FaceCentre,
                        _ => return Err(usage(entry, "origin is `body` or `face-centre`")),
                    });
                }
                "delimiter" => {
                    once(delimiter.is_some())?;
                    delimiter = Some(match value {
                        "," | "comma" => ',',
                        ";" | "semicolon" => ';',
                        "tab" | "\\t" => '\t',
                        _ => return Err(usage(entry, "delimiter is `,`, `semicolon` or `tab`")),
                    });
                }
                _ => {
                    let kind = match key {
                        "quaternion-xyzw" => OrientationKind::Quaternion { scalar_last: true },
                        "quaternion-wxyz" => OrientationKind::Quaternion { scalar_last: false },
                        "matrix" => OrientationKind::Matrix,
                        k if k.starts_with("euler-") => {
                            let radians_per_unit = match unit.as_deref() {
                                Some("deg") => std::f64::consts::PI / 180.0,
                                Some("rad") => 1.0,
                                _ => return Err(usage(entry, "Euler angles need their unit: `:deg` or `:rad`")),
                            };
                            OrientationKind::euler(&k["euler-".len()..], radians_per_unit)
                                .map_err(|e| usage(entry, e))?
                        }
                        _ => return Err(usage(entry, format!("`{key}` is not a key (keys: {KEYS})"))),
                    };
                    if orientation.is_some() {
                        return Err(usage(entry, "the orientation is given twice"));
                    }
                    if unit.is_some() && !matches!(kind, OrientationKind::Euler { .. }) {
                        return Err(usage(entry, "a quaternion or matrix has no unit"));
                    }
                    count(kind.columns())?;
                    orientation = Some((kind, names));
                }
            }
        }
        let missing = |what: &str| CaptureError::Usage(format!("the column spec has no {what} (e.g. `{EXAMPLE}`)"));
        let time = time.ok_or_else(|| missing("time (`time=COLUMN:s` or `rate=HZ`)"))?;
        let (position, units, metres_per_unit) = position.ok_or_else(|| missing("position (`position=X,Y,Z:mm`)"))?;
        let (orientation, orientation_columns) = orientation.ok_or_else(|| {
            missing("orientation (`quaternion-xyzw=...`, `quaternion-wxyz=...`, `matrix=...` or `euler-ZYX=...:deg`)")
        })?;
        Ok(ColumnSpec {
            time,
            frame,
            position,
            units,
            metres_per_unit,
            orientation,
            orientation_columns,
            ball,
            origin: origin.unwrap_or_default(),
            delimiter,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_spec_reads_and_its_mistakes_are_named() {
        let s =
            ColumnSpec::parse("time=t:ms; position=x,y,z:cm\n# face centre\neuler-ZYX=a,b,c:deg; origin=face-centre")
                .unwrap();
        assert_eq!(s.time, Time::Column { name: "t".into(), seconds_per_unit: 1e-3 });
        assert_eq!((s.units.as_str(), s.metres_per_unit, s.origin), ("cm", 1e-2, Origin::FaceCentre));
        let err = |t: &str| ColumnSpec::parse(t).unwrap_err().to_string();
        assert!(err("time=t:s; position=x,y,z; matrix=a,b,c,d,e,f,g,h,i").contains("unit is required"));
        assert!(err("time=t:s; position=x,y,z:parsec; quaternion-xyzw=a,b,c,d").contains("`parsec` is not one of"));
        assert!(err("time=t:s; position=x,y,z:mm").contains("has no orientation"));
        assert!(err("time=t:s; position=x,y:mm; quaternion-xyzw=a,b,c,d").contains("position names 3 columns"));
        assert!(err("rate=240; position=x,y,z:mm; quat=a,b,c,d").contains("`quat` is not a key"));
        assert!(err("position=x,y,z:mm; quaternion-wxyz=a,b,c,d").contains("has no time"));
    }
}
