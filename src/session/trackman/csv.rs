//! TrackMan Performance Studio's CSV layout, out and in: a `sep=,` line, the header, a units row, then one row
//! per shot, every value quoted; right positive for club path, face angle and launch direction (as on the wire).
//! Out: a recorded prediction per row (club data from the rig's delivery, ball data from the launch and its
//! flight). In: rows with club and ball data as measured shots for `compare` and `fit` (the club data is the
//! delivery, the ball data the measurement), in imperial or metric units as the units row says.
//!
//! TrackMan's layout has no column for what a model needs beyond its club data (the head's angular velocity)
//! nor for a shot that is both predicted and measured, so an export adds [`IMPACTD_COLUMNS`] after TrackMan's,
//! each named `impactd: ...`: the head's angular velocity (world frame) and, for a shot a launch monitor measured
//! live, its measured ball data and device. Reading, TrackMan's `Dynamic Lie` and the angular velocity complete the
//! delivery, and the measured columns, when filled, are the measurement (TrackMan's ball columns then hold the
//! recorded prediction), so `compare` on an export reproduces the residuals the daemon recorded live.

use crate::math::Real;
use crate::pairing::DatasetLine;
use crate::units::{MPS_PER_MPH, M_PER_YD};
use crate::wire::{DeliveryInput, LaunchFields, LaunchPrediction};

pub use super::rows::{RowLabels, SkippedRows};

/// The columns of an export, with their units row (empty for text).
pub const COLUMNS: [(&str, &str); 61] = [
    ("Date", ""),
    ("TMD No", ""),
    ("TMD Filename", ""),
    ("Player", ""),
    ("Club", ""),
    ("Ball", ""),
    ("Club Speed", "[mph]"),
    ("Attack Angle", "[deg]"),
    ("Club Path", "[deg]"),
    ("Low Point", "[in]"),
    ("Swing Plane", "[deg]"),
    ("Swing Direction", "[deg]"),
    ("Dyn. Loft", "[deg]"),
    ("Face Angle", "[deg]"),
    ("Face To Path", "[deg]"),
    ("Ball Speed", "[mph]"),
    ("Smash Factor", "[]"),
    ("Launch Angle", "[deg]"),
    ("Launch Direction", "[deg]"),
    ("Spin Rate", "[rpm]"),
    ("Spin Rate Type", ""),
    ("Spin Axis", "[deg]"),
    ("Max Height - Dist.", "[yds]"),
    ("Max Height - Height", "[ft]"),
    ("Max Height - Side", "[ft]"),
    ("Last data Point - Length", "[yds]"),
    ("Last data Point - Side", "[ft]"),
    ("Last data Point - Height", "[ft]"),
    ("Last data Point - Time", "[s]"),
    ("Carry Flat - Length", "[yds]"),
    ("Carry Flat - Side", "[yds]"),
    ("Carry Flat - Land. Angle", "[deg]"),
    ("Carry Flat - Ball Speed", "[mph]"),
    ("Carry Flat - Time", "[s]"),
    ("Est. Total Flat - Length", "[yds]"),
    ("Est. Total Flat - Side", "[yds]"),
    ("Dynamic Lie", "[deg]"),
    ("Impact Offset", "[mm]"),
    ("Impact Height", "[mm]"),
    ("Curve", "[ft]"),
    ("Spin Axis (Sim)", "[deg]"),
    ("Curve (Sim)", "[ft]"),
    ("Carry (Sim)", "[yds]"),
    ("Total (Sim)", "[yds]"),
    ("Carry Side (Sim)", "[ft]"),
    ("Total side (Sim)", "[ft]"),
    ("Landing Angle (Sim)", "[deg]"),
    ("Spin Loft", "[deg]"),
    ("Swing Radius", "[in]"),
    ("Low Point Height", "[mm]"),
    ("Low Point Side", "[mm]"),
    ("D Plane Tilt", "[deg]"),
    ("Ball Speed Diff", "[mph]"),
    ("Smash Index", "[]"),
    ("Spin Rate Diff", "[rpm]"),
    ("Spin Index", "[]"),
    ("Gyro Angle", "[deg]"),
    ("Use In Stat", ""),
    ("Tags", ""),
    ("Condition", ""),
    ("Email", ""),
];

/// impactd's columns after TrackMan's, with their units row.
pub const IMPACTD_COLUMNS: [(&str, &str); 9] = [
    ("impactd: Club Angular Velocity X", "[rad/s]"),
    ("impactd: Club Angular Velocity Y", "[rad/s]"),
    ("impactd: Club Angular Velocity Z", "[rad/s]"),
    ("impactd: Measured Ball Speed", "[mph]"),
    ("impactd: Measured Launch Angle", "[deg]"),
    ("impactd: Measured Launch Direction", "[deg]"),
    ("impactd: Measured Backspin", "[rpm]"),
    ("impactd: Measured Sidespin", "[rpm]"),
    ("impactd: Measured By", ""),
];

/// Why a TrackMan CSV cannot be read; each names the row (1-based, as a spreadsheet counts) and column.
#[derive(Debug, thiserror::Error)]
pub enum TrackmanCsvError {
    #[error("not a TrackMan export: {0}")]
    Layout(String),
    #[error("row {row}: {source}")]
    Csv {
        row: usize,
        #[source]
        source: csv::Error,
    },
    #[error("row {row}, column `{column}`: `{value}` is not a number")]
    Number { row: usize, column: String, value: String },
    #[error("row {row}: column `{column}` is empty (a measured shot needs it)")]
    Missing { row: usize, column: &'static str },
    #[error("column `{column}`: unit `{unit}` is not one impactd reads")]
    Unit { column: String, unit: String },
    #[error("writing: {0}")]
    Write(#[source] csv::Error),
}

fn num(v: Real, decimals: usize) -> String {
    if v.is_finite() {
        format!("{v:.decimals$}")
    } else {
        String::new()
    }
}

/// The measurement a TrackMan row pairs with a prediction: the shot's comparison made live with this prediction's
/// model, else the shot's comparison with any model (what `impactd export` and the bay screen's CSV both write).
pub fn measured_for<'a>(
    p: &LaunchPrediction,
    comparisons: &'a [crate::wire::ComparisonMessage],
) -> Option<(&'a LaunchFields, &'a str)> {
    let of_shot = |c: &&crate::wire::ComparisonMessage| c.rig == p.rig && c.shot == p.shot;
    comparisons
        .iter()
        .filter(of_shot)
        .find(|c| c.model == p.model)
        .or_else(|| comparisons.iter().find(of_shot))
        .map(|c| (&c.measured, c.device.as_str()))
}

/// The row of one prediction (imperial, as [`COLUMNS`]'s units row), then [`IMPACTD_COLUMNS`]: `measured` is the
/// shot's measurement and the device that made it, when a launch monitor measured it. `file` names the recording.
pub fn row(p: &LaunchPrediction, file: &str, date: &str, measured: Option<(&LaunchFields, &str)>) -> Vec<String> {
    let d = &p.delivery;
    let l = &p.launch;
    let arc = d.swing_arc;
    let f = p.flight.as_ref();
    let yd = |m: Real| m / M_PER_YD;
    let ft = |m: Real| m / 0.3048;
    let opt = |v: Option<Real>, decimals| v.map_or(String::new(), |v| num(v, decimals));
    let mut cells = vec![String::new(); COLUMNS.len() + IMPACTD_COLUMNS.len()];
    let mut set = |name: &str, value: String| {
        if let Some(i) = COLUMNS.iter().chain(IMPACTD_COLUMNS.iter()).position(|(n, _)| *n == name) {
            cells[i] = value;
        }
    };
    set("Date", date.to_string());
    set("TMD No", p.shot.to_string());
    set("TMD Filename", file.to_string());
    set("Player", p.labels.player.clone().unwrap_or_default());
    set("Club", crate::session::club_of(p).to_string());
    set("Club Speed", num(d.club_speed_mph, 6));
    set("Attack Angle", num(d.attack_angle_deg, 6));
    set("Club Path", num(d.club_path_deg, 6));
    set("Low Point", opt(arc.map(|a| a.low_point_distance_mm / 25.4), 6));
    set("Swing Plane", opt(arc.map(|a| a.swing_plane_deg), 6));
    set("Swing Direction", opt(arc.map(|a| a.swing_direction_deg), 6));
    set("Dyn. Loft", num(d.dynamic_loft_deg, 6));
    set("Face Angle", num(d.face_angle_deg, 6));
    set("Face To Path", num(d.face_to_path_deg, 6));
    set("Ball Speed", num(l.launch.ball_speed_mph, 6));
    set("Smash Factor", num(l.smash_factor, 6));
    set("Launch Angle", num(l.launch.launch_angle_deg, 6));
    set("Launch Direction", num(l.launch.launch_direction_deg, 6));
    set("Spin Rate", num(l.launch.total_spin_rpm, 3));
    set("Spin Rate Type", "Estimated".into());
    set("Spin Axis", num(l.launch.spin_axis_deg, 6));
    set("Max Height - Height", opt(f.map(|f| ft(f.apex_m)), 6));
    set("Carry Flat - Length", opt(f.map(|f| yd(f.carry_m)), 6));
    set("Carry Flat - Side", opt(f.map(|f| yd(f.offline_m)), 6));
    set("Carry Flat - Land. Angle", opt(f.map(|f| f.land_angle_deg), 6));
    set("Carry Flat - Ball Speed", opt(f.map(|f| f.land_speed_mps / MPS_PER_MPH), 6));
    set("Carry Flat - Time", opt(f.map(|f| f.hang_time_s), 6));
    set("Est. Total Flat - Length", opt(f.map(|f| yd(f.total_m)), 6));
    set("Dynamic Lie", num(d.dynamic_lie_deg, 6));
    set("Impact Offset", num(d.impact_h_mm, 6));
    set("Impact Height", num(d.impact_v_mm, 6));
    set("Spin Loft", num(d.spin_loft_deg, 6));
    set("Low Point Height", opt(arc.map(|a| a.low_point_height_mm), 6));
    set("Use In Stat", "TRUE".into());
    set("Tags", p.labels.tags.join(";"));
    for (axis, w) in ["X", "Y", "Z"].iter().zip(d.club_angular_velocity_radps) {
        set(&format!("impactd: Club Angular Velocity {axis}"), num(w, 9));
    }
    if let Some((m, device)) = measured {
        set("impactd: Measured Ball Speed", num(m.ball_speed_mph, 9));
        set("impactd: Measured Launch Angle", num(m.launch_angle_deg, 9));
        set("impactd: Measured Launch Direction", num(m.launch_direction_deg, 9));
        set("impactd: Measured Backspin", num(m.backspin_rpm, 9));
        set("impactd: Measured Sidespin", num(m.sidespin_rpm, 9));
        set("impactd: Measured By", device.to_string());
    }
    cells
}

/// Writes the `sep=,` line, the header and the units row, then `rows`.
pub fn write(out: impl std::io::Write, rows: &[Vec<String>]) -> Result<(), TrackmanCsvError> {
    let mut out = out;
    out.write_all(b"sep=,\r\n").map_err(|e| TrackmanCsvError::Write(e.into()))?;
    let mut w = csv::WriterBuilder::new()
        .quote_style(csv::QuoteStyle::Always)
        .terminator(csv::Terminator::CRLF)
        .from_writer(out);
    let columns = || COLUMNS.iter().chain(IMPACTD_COLUMNS.iter());
    w.write_record(columns().map(|c| c.0)).map_err(TrackmanCsvError::Write)?;
    w.write_record(columns().map(|c| c.1)).map_err(TrackmanCsvError::Write)?;
    for r in rows {
        w.write_record(r).map_err(TrackmanCsvError::Write)?;
    }
    w.flush().map_err(|e| TrackmanCsvError::Write(e.into()))
}

/// Whether `text` looks like a TrackMan export (a `sep=` line, or a header with `Club Speed` and `Ball Speed`).
pub fn is_trackman_csv(text: &str) -> bool {
    let first = text.trim_start_matches('\u{feff}').lines().next().unwrap_or("");
    first.trim().starts_with("sep=") || (first.contains("Club Speed") && first.contains("Ball Speed"))
}

/// How many base units (mph, deg, rpm, yd, mm) one of `unit` is.
fn factor(column: &str, unit: &str) -> Result<Real, TrackmanCsvError> {
    let f = match unit {
        "" | "[]" | "[mph]" | "[deg]" | "[rpm]" | "[yds]" | "[mm]" | "[rad/s]" => 1.0,
        "[km/h]" => 1.0 / 1.609344,
        "[m/s]" => 1.0 / MPS_PER_MPH,
        "[m]" if column.contains("Length") => 1.0 / M_PER_YD,
        "[cm]" => 10.0,
        _ => return Err(TrackmanCsvError::Unit { column: column.into(), unit: unit.into() }),
    };
    Ok(f)
}

/// The measured shots of a TrackMan export: rows with club data (club speed, attack angle, club path, face angle,
/// dynamic loft) and ball data (ball speed, launch angle and direction, spin rate). Rows without club or ball data
/// are skipped and counted.
pub fn read(text: &str) -> Result<(Vec<DatasetLine>, usize), TrackmanCsvError> {
    let (rows, skipped) = read_labelled(text)?;
    Ok((rows.into_iter().map(|(line, _)| line).collect(), skipped.total()))
}

/// [`read`] with each row's [`RowLabels`] and the skipped rows by reason.
pub fn read_labelled(text: &str) -> Result<(Vec<(DatasetLine, RowLabels)>, SkippedRows), TrackmanCsvError> {
    let text = text.trim_start_matches('\u{feff}');
    let (body, first_row) = match text.lines().next() {
        Some(l) if l.trim().starts_with("sep=") => (&text[l.len()..], 2),
        _ => (text, 1),
    };
    let mut rows =
        csv::ReaderBuilder::new().has_headers(false).flexible(true).from_reader(body.trim_start().as_bytes());
    let mut records = rows.records();
    let header = match records.next() {
        Some(r) => r.map_err(|source| TrackmanCsvError::Csv { row: first_row, source })?,
        None => return Err(TrackmanCsvError::Layout("no header row".into())),
    };
    let col = |name: &str| header.iter().position(|h| h.trim() == name);
    let need = [
        "Club Speed",
        "Attack Angle",
        "Club Path",
        "Face Angle",
        "Ball Speed",
        "Launch Angle",
        "Launch Direction",
        "Spin Rate",
        "Spin Axis",
    ];
    for n in need {
        if col(n).is_none() {
            return Err(TrackmanCsvError::Layout(format!("no column `{n}` in the header")));
        }
    }
    let units = match records.next() {
        Some(r) => r.map_err(|source| TrackmanCsvError::Csv { row: first_row + 1, source })?,
        None => return Ok((Vec::new(), SkippedRows::default())),
    };
    let has_units = units.iter().any(|u| u.trim().starts_with('['));
    let mut lines = Vec::new();
    let mut skipped = SkippedRows::default();
    let data = if has_units { None } else { Some(Ok(units.clone())) };
    let first_data = first_row + if has_units { 2 } else { 1 };
    for (k, rec) in data.into_iter().chain(records).enumerate() {
        let row = first_data + k;
        let rec = rec.map_err(|source| TrackmanCsvError::Csv { row, source })?;
        let value = |name: &'static str| -> Result<Option<Real>, TrackmanCsvError> {
            let Some(i) = col(name) else { return Ok(None) };
            let cell = rec.get(i).unwrap_or("").trim();
            if cell.is_empty() {
                return Ok(None);
            }
            let v: Real =
                cell.parse().map_err(|_| TrackmanCsvError::Number { row, column: name.into(), value: cell.into() })?;
            let unit = if has_units { units.get(i).unwrap_or("").trim() } else { "" };
            Ok(Some(v * factor(name, unit)?))
        };
        let (Some(club_speed), Some(ball_speed)) = (value("Club Speed")?, value("Ball Speed")?) else {
            skipped.without_club_or_ball += 1;
            continue;
        };
        let club = [value("Attack Angle")?, value("Club Path")?, value("Face Angle")?, value("Dyn. Loft")?];
        let [Some(attack), Some(path), Some(face), Some(loft)] = club else {
            skipped.incomplete_club_data += 1;
            continue;
        };
        let must = |name: &'static str| value(name)?.ok_or(TrackmanCsvError::Missing { row, column: name });
        // No axis is no measurement of it: the shot's spin is split as all backspin and its axis not compared.
        let (spin, axis) = (must("Spin Rate")?, value("Spin Axis")?);
        let w = [
            value("impactd: Club Angular Velocity X")?,
            value("impactd: Club Angular Velocity Y")?,
            value("impactd: Club Angular Velocity Z")?,
        ];
        let delivery = DeliveryInput {
            club_speed_mph: club_speed,
            attack_angle_deg: attack,
            club_path_deg: path,
            face_angle_deg: face,
            dynamic_loft_deg: Some(loft),
            impact_h_mm: value("Impact Offset")?.unwrap_or(0.0),
            impact_v_mm: value("Impact Height")?.unwrap_or(0.0),
            club_angular_velocity_radps: match w {
                [Some(x), Some(y), Some(z)] => Some([x, y, z]),
                _ => None,
            },
            handedness: None,
            dynamic_lie_deg: value("Dynamic Lie")?,
        };
        let axis_rad = axis.unwrap_or(0.0).to_radians();
        let measured = match value("impactd: Measured Ball Speed")? {
            // A shot measured live: the launch monitor's numbers (the ball columns hold the prediction).
            Some(ball_speed_mph) => LaunchFields {
                ball_speed_mph,
                launch_angle_deg: must("impactd: Measured Launch Angle")?,
                launch_direction_deg: must("impactd: Measured Launch Direction")?,
                backspin_rpm: must("impactd: Measured Backspin")?,
                sidespin_rpm: must("impactd: Measured Sidespin")?,
                carry_yd: None,
            },
            None => LaunchFields {
                ball_speed_mph: ball_speed,
                launch_angle_deg: must("Launch Angle")?,
                launch_direction_deg: must("Launch Direction")?,
                backspin_rpm: spin * axis_rad.cos(),
                sidespin_rpm: spin * axis_rad.sin(),
                carry_yd: value("Carry Flat - Length")?,
            },
        };
        let text_of = |name: &str| col(name).and_then(|i| rec.get(i)).map(str::trim).filter(|c| !c.is_empty());
        let spin_measured = text_of("Spin Rate Type").is_none_or(|t| t.eq_ignore_ascii_case("measured"));
        let labels = RowLabels {
            club: text_of("Club").map(str::to_string),
            spin_measured,
            axis_measured: spin_measured && axis.is_some(),
            impact_located: text_of("Impact Height").is_some(),
        };
        lines.push((DatasetLine { delivery, measured }, labels));
    }
    Ok((lines, skipped))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hand-made export in TrackMan's layout (metric units row) reads as measured shots; a row without club data
    /// is skipped; a bad number names its row and column.
    #[test]
    fn an_export_reads_as_measured_shots() {
        let header: Vec<&str> = COLUMNS.iter().map(|c| c.0).collect();
        let mut units: Vec<&str> = COLUMNS.iter().map(|c| c.1).collect();
        units[6] = "[km/h]";
        units[15] = "[km/h]";
        let mut row = vec![""; COLUMNS.len()];
        row[6] = "160.934";
        row[7] = "-2";
        row[8] = "1";
        row[12] = "14";
        row[13] = "0.5";
        row[15] = "241.4016";
        row[17] = "12";
        row[18] = "1.5";
        row[19] = "3000";
        row[21] = "10";
        let empty = vec![""; COLUMNS.len()];
        let q = |r: &[&str]| r.iter().map(|c| format!("\"{c}\"")).collect::<Vec<_>>().join(",");
        let text = format!("sep=,\n{}\n{}\n{}\n{}\n", q(&header), q(&units), q(&row), q(&empty));
        assert!(is_trackman_csv(&text));
        let (lines, skipped) = read(&text).unwrap();
        assert_eq!((lines.len(), skipped), (1, 1));
        assert_eq!(lines[0].delivery.dynamic_loft_deg, Some(14.0));
        let l = &lines[0];
        assert!((l.delivery.club_speed_mph - 100.0).abs() < 1e-3, "{l:?}");
        assert!((l.measured.ball_speed_mph - 150.0).abs() < 1e-3);
        assert!((l.measured.sidespin_rpm - 3000.0 * 10f64.to_radians().sin()).abs() < 1e-9);
        // A club speed without the rest of the club data is skipped and counted, never read with zeros; a
        // measured shot without a spin axis is read, its axis marked unmeasured (not 0).
        let mut partial = row.clone();
        partial[8] = "";
        let mut no_loft = row.clone();
        no_loft[12] = "";
        let mut no_axis = row.clone();
        no_axis[21] = "";
        let text =
            format!("{}\n{}\n{}\n{}\n{}\n{}\n", q(&header), q(&units), q(&row), q(&partial), q(&no_loft), q(&no_axis));
        let (rows, skipped) = read_labelled(&text).unwrap();
        assert_eq!(skipped, SkippedRows { without_club_or_ball: 0, incomplete_club_data: 2 });
        assert_eq!(rows.len(), 2);
        assert!(rows[0].1.spin_measured && rows[0].1.axis_measured);
        assert!(rows[1].1.spin_measured && !rows[1].1.axis_measured);
        assert_eq!((rows[1].0.measured.backspin_rpm, rows[1].0.measured.sidespin_rpm), (3000.0, 0.0));
        row[17] = "twelve";
        let bad = format!("sep=,\n{}\n{}\n{}\n", q(&header), q(&units), q(&row));
        let e = read(&bad).unwrap_err().to_string();
        assert!(e.contains("row 4") && e.contains("Launch Angle"), "{e}");
    }
}
