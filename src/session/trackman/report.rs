//! TrackMan's report JSON (`"Kind": "multiGroupReport"`, what TrackMan's web API returns for a session) in, as the
//! same measured shots as its CSV export (`csv`): each stroke's `Measurement` (not the
//! `NormalizedMeasurement`), in SI units as TrackMan gives them: `ClubSpeed` and `BallSpeed` in m/s (read as mph by
//! the CSV reader's factor), `ImpactOffset` and `ImpactHeight` in m (mm by a decimal shift, as the CSV export
//! writes them), angles in degrees, `SpinRate` in rpm. `ReducedAccuracy` lists what TrackMan could not measure in
//! full: a stroke naming `SpinRate` or `SpinAxis` there has its spin read as estimated (TrackMan's CSV has one
//! `Spin Rate Type` for both). Club names are the API's spellings (`7Iron`, `PitchingWedge`), read as the CSV's
//! (`7 Iron`, `Pitching Wedge`, [`csv_club_name`]). Strokes are numbered from 1 in the file's order.

use serde::Deserialize;

use crate::math::Real;
use crate::pairing::DatasetLine;
use crate::units::MPS_PER_MPH;
use crate::wire::{DeliveryInput, LaunchFields};

use super::rows::{RowLabels, SkippedRows};

/// Why a TrackMan report cannot be read; each names the stroke (1-based in the file) and field.
#[derive(Debug, thiserror::Error)]
pub enum TrackmanReportError {
    #[error("not a TrackMan report: {0}")]
    Json(#[source] serde_json::Error),
    #[error("stroke {stroke} ({id}): `Measurement.{field}` is missing (a measured shot needs it)")]
    Missing { stroke: usize, id: String, field: &'static str },
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "PascalCase")]
struct Report {
    stroke_groups: Vec<StrokeGroup>,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "PascalCase")]
struct StrokeGroup {
    #[serde(default)]
    club: Option<String>,
    #[serde(default)]
    strokes: Vec<Stroke>,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "PascalCase")]
struct Stroke {
    #[serde(default)]
    id: Option<String>,
    #[serde(default)]
    club: Option<String>,
    #[serde(default)]
    measurement: Option<Measurement>,
}

/// The fields of a stroke's `Measurement` a comparison uses (SI units, degrees, rpm).
#[derive(Debug, Default, Deserialize)]
#[serde(rename_all = "PascalCase")]
struct Measurement {
    club_speed: Option<Real>,
    attack_angle: Option<Real>,
    club_path: Option<Real>,
    face_angle: Option<Real>,
    dynamic_loft: Option<Real>,
    dynamic_lie: Option<Real>,
    impact_offset: Option<Real>,
    impact_height: Option<Real>,
    ball_speed: Option<Real>,
    launch_angle: Option<Real>,
    launch_direction: Option<Real>,
    spin_rate: Option<Real>,
    spin_axis: Option<Real>,
    #[serde(default)]
    reduced_accuracy: Option<Vec<String>>,
}

/// Whether `text` looks like a TrackMan report (a JSON object with `StrokeGroups` or the report's kind); the first
/// few kilobytes of a file are enough.
pub fn is_trackman_report(text: &str) -> bool {
    text.trim_start_matches('\u{feff}').trim_start().starts_with('{')
        && (text.contains("\"StrokeGroups\"") || text.contains("\"multiGroupReport\""))
}

/// TrackMan's CSV spelling of an API club name: a space between a number and a word and between two words
/// (`7Iron` -> `7 Iron`, `PitchingWedge` -> `Pitching Wedge`, `Driver` stays).
pub fn csv_club_name(api: &str) -> String {
    let mut out = String::new();
    let mut prev: Option<char> = None;
    for c in api.trim().chars() {
        if let Some(p) = prev {
            if (p.is_ascii_digit() && c.is_alphabetic()) || (p.is_lowercase() && c.is_uppercase()) {
                out.push(' ');
            }
        }
        out.push(c);
        prev = Some(c);
    }
    out
}

/// Metres to millimetres by a decimal shift of the number's shortest decimal form (`0.0123` m -> `12.3` mm
/// exactly, as TrackMan's CSV export would write it; a multiplication by 1000 can land one bit off).
fn mm_of_m(m: Real) -> Real {
    format!("{m}e3").parse().unwrap_or(m * 1000.0)
}

/// The measured shots of a report, with their labels, and the strokes left out by reason: without club or ball
/// speed; with a club speed but not every club value a delivery needs (never read as 0).
pub fn read_labelled(text: &str) -> Result<(Vec<(DatasetLine, RowLabels)>, SkippedRows), TrackmanReportError> {
    let report: Report =
        serde_json::from_str(text.trim_start_matches('\u{feff}')).map_err(TrackmanReportError::Json)?;
    let mut lines = Vec::new();
    let mut skipped = SkippedRows::default();
    let strokes = report.stroke_groups.iter().flat_map(|g| g.strokes.iter().map(move |s| (g, s)));
    for (k, (group, s)) in strokes.enumerate() {
        let stroke = k + 1;
        let empty = Measurement::default();
        let m = s.measurement.as_ref().unwrap_or(&empty);
        let (Some(club_speed), Some(ball_speed)) = (m.club_speed, m.ball_speed) else {
            skipped.without_club_or_ball += 1;
            continue;
        };
        let [Some(attack), Some(path), Some(face), Some(loft)] =
            [m.attack_angle, m.club_path, m.face_angle, m.dynamic_loft]
        else {
            skipped.incomplete_club_data += 1;
            continue;
        };
        let must = |v: Option<Real>, field: &'static str| {
            v.ok_or_else(|| TrackmanReportError::Missing { stroke, id: s.id.clone().unwrap_or_default(), field })
        };
        let spin = must(m.spin_rate, "SpinRate")?;
        let reduced = m.reduced_accuracy.as_deref().unwrap_or_default();
        let spin_measured = !reduced.iter().any(|r| r == "SpinRate" || r == "SpinAxis");
        let axis_rad = m.spin_axis.unwrap_or(0.0).to_radians();
        // The CSV reader's factor for a `[m/s]` column, so both layouts give the same number.
        let mph = |mps: Real| mps * (1.0 / MPS_PER_MPH);
        let delivery = DeliveryInput {
            club_speed_mph: mph(club_speed),
            attack_angle_deg: attack,
            club_path_deg: path,
            face_angle_deg: face,
            dynamic_loft_deg: Some(loft),
            impact_h_mm: m.impact_offset.map_or(0.0, mm_of_m),
            impact_v_mm: m.impact_height.map_or(0.0, mm_of_m),
            club_angular_velocity_radps: None,
            handedness: None,
            dynamic_lie_deg: m.dynamic_lie,
        };
        let measured = LaunchFields {
            ball_speed_mph: mph(ball_speed),
            launch_angle_deg: must(m.launch_angle, "LaunchAngle")?,
            launch_direction_deg: must(m.launch_direction, "LaunchDirection")?,
            backspin_rpm: spin * axis_rad.cos(),
            sidespin_rpm: spin * axis_rad.sin(),
            carry_yd: None,
        };
        let labels = RowLabels {
            club: s.club.as_deref().or(group.club.as_deref()).map(csv_club_name),
            spin_measured,
            axis_measured: spin_measured && m.spin_axis.is_some(),
            impact_located: m.impact_height.is_some(),
        };
        lines.push((DatasetLine { delivery, measured }, labels));
    }
    Ok((lines, skipped))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stroke of each kind: complete (reduced spin axis: spin estimated), club speed without a face angle
    /// (skipped, counted), no club data (skipped, counted), a ball without a launch angle (an error naming it).
    #[test]
    fn strokes_read_as_the_csv_would() {
        let text = r#"{"Kind": "multiGroupReport", "StrokeGroups": [{"Club": "7Iron", "Strokes": [
            {"Id": "a", "Club": "7Iron", "Measurement": {"ClubSpeed": 40.0, "AttackAngle": -4.1, "ClubPath": 1.5,
             "FaceAngle": -0.5, "DynamicLoft": 21.0, "ImpactOffset": 0.0123, "ImpactHeight": -0.004,
             "BallSpeed": 53.0, "LaunchAngle": 16.5, "LaunchDirection": 0.2, "SpinRate": 6500.0, "SpinAxis": 3.0,
             "ReducedAccuracy": ["SpinAxis"]}},
            {"Id": "b", "Club": "7Iron", "Measurement": {"ClubSpeed": 40.0, "AttackAngle": -4.1, "ClubPath": 1.5,
             "DynamicLoft": 21.0, "BallSpeed": 53.0}},
            {"Id": "c", "Measurement": {"BallSpeed": 53.0}}]}]}"#;
        assert!(is_trackman_report(text));
        let (rows, skipped) = read_labelled(text).unwrap();
        assert_eq!(skipped, SkippedRows { without_club_or_ball: 1, incomplete_club_data: 1 });
        let (line, labels) = &rows[0];
        assert!((line.delivery.club_speed_mph - 40.0 / MPS_PER_MPH).abs() < 1e-12);
        assert_eq!((line.delivery.impact_h_mm, line.delivery.impact_v_mm), (12.3, -4.0));
        assert_eq!(labels.club.as_deref(), Some("7 Iron"));
        assert!(!labels.spin_measured && !labels.axis_measured && labels.impact_located);
        let bad = text.replace("\"LaunchAngle\": 16.5, ", "");
        let e = read_labelled(&bad).unwrap_err().to_string();
        assert!(e.contains("stroke 1 (a)") && e.contains("LaunchAngle"), "{e}");
        assert!(read_labelled("{\"StrokeGroups\": 3}").is_err());
    }

    #[test]
    fn api_club_names_read_as_the_csv_spells_them() {
        assert_eq!(csv_club_name("7Iron"), "7 Iron");
        assert_eq!(csv_club_name("PitchingWedge"), "Pitching Wedge");
        assert_eq!(csv_club_name("Driver"), "Driver");
        assert_eq!(csv_club_name("5Hybrid"), "5 Hybrid");
    }
}
