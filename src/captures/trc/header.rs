//! A TRC file's five header lines: `PathFileType`, the names and values of `DataRate`, `CameraRate`, `NumFrames`,
//! `NumMarkers`, `Units`, `OrigDataRate`, `OrigDataStartFrame`, `OrigNumFrames`, the marker names after `Frame#`
//! and `Time` (one name every third column), and the coordinate names (`X1 Y1 Z1 X2 ...`).

use std::io::BufRead;

use super::super::lines::Lines;
use super::super::CaptureError;

/// The most markers a TRC may name.
pub const MAX_MARKERS: usize = 100_000;

/// What a TRC's header says.
#[derive(Debug, Clone, PartialEq)]
pub struct TrcHeader {
    pub data_rate_hz: f64,
    pub camera_rate_hz: Option<f64>,
    /// `NumFrames` as written (the frames are counted as read).
    pub num_frames: u64,
    pub labels: Vec<String>,
    /// `Units` as written (empty: none).
    pub units: String,
    pub orig_data_start_frame: Option<u64>,
}

fn cells(text: &str) -> Vec<&str> {
    text.split('\t').map(str::trim).collect()
}

fn next<'a, R: BufRead>(lines: &'a mut Lines<R>, what: &str) -> Result<(u64, &'a str), CaptureError> {
    let after = lines.line();
    lines.next_line()?.ok_or_else(|| CaptureError::Text {
        format: "TRC",
        line: after + 1,
        reason: format!("the file ends before {what}"),
    })
}

fn bad(line: u64, reason: String) -> CaptureError {
    CaptureError::Text { format: "TRC", line, reason }
}

/// Reads the five header lines; `units_override` stands in for a missing or unknown `Units` (the caller reports
/// it).
pub fn read<R: BufRead>(lines: &mut Lines<R>, units_override: bool) -> Result<TrcHeader, CaptureError> {
    let (n, first) = next(lines, "its header")?;
    if !first.starts_with("PathFileType") {
        let shown: String = first.chars().take(40).collect();
        return Err(bad(n, format!("a TRC file starts with `PathFileType`; this one with `{shown}`")));
    }
    if !first.contains('\t') {
        return Err(bad(n, "a TRC file's lines are tab-separated; this one has no tab".into()));
    }
    let (n_keys, keys) = next(lines, "the line naming DataRate, NumFrames, NumMarkers and Units")?;
    let keys: Vec<String> = cells(keys).into_iter().map(str::to_string).collect();
    let (n_values, values) = next(lines, "the line of the header's values")?;
    let values: Vec<String> = cells(values).into_iter().map(str::to_string).collect();
    if !keys.iter().any(|k| k == "DataRate") {
        return Err(bad(n_keys, format!("no `DataRate` among the header's names ({})", keys.join(", "))));
    }
    let value = |key: &str| -> Result<Option<&str>, CaptureError> {
        let Some(at) = keys.iter().position(|k| k == key) else { return Ok(None) };
        match values.get(at).map(String::as_str) {
            Some(v) => Ok(Some(v)),
            None => Err(bad(n_values, format!("no value for `{key}` (column {} of line {n_keys})", at + 1))),
        }
    };
    let required = |key: &str| -> Result<&str, CaptureError> {
        value(key)?.ok_or_else(|| bad(n_keys, format!("no `{key}` among the header's names ({})", keys.join(", "))))
    };
    let number = |key: &str, text: &str| -> Result<f64, CaptureError> {
        text.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| bad(n_values, format!("{key} `{text}` is not a number")))
    };
    let data_rate_hz = number("DataRate", required("DataRate")?)?;
    if !(data_rate_hz > 0.0 && data_rate_hz < 1e6) {
        return Err(bad(n_values, format!("DataRate {data_rate_hz} Hz is not a frame rate")));
    }
    let camera_rate_hz = match value("CameraRate")? {
        Some(v) if !v.is_empty() => Some(number("CameraRate", v)?),
        _ => None,
    };
    let count = |key: &str, max: f64| -> Result<u64, CaptureError> {
        let v = number(key, required(key)?)?;
        if v < 0.0 || v.fract() != 0.0 || v > max {
            return Err(bad(n_values, format!("{key} {v} is not a count (0 to {max})")));
        }
        Ok(v as u64)
    };
    let num_frames = count("NumFrames", 1e12)?;
    let num_markers = count("NumMarkers", MAX_MARKERS as f64)? as usize;
    let units = match value("Units")? {
        Some(u) => u.to_string(),
        None if units_override => String::new(),
        None => {
            return Err(bad(
                n_keys,
                "no `Units` among the header's names: a TRC states its units (mm, cm, m, ...); give --units to \
                 read it in units you know"
                    .into(),
            ))
        }
    };
    if units.is_empty() && !units_override {
        return Err(bad(n_values, "`Units` is empty: give --units to read the file in units you know".into()));
    }
    if !units_override && super::super::units::metres_per_unit(&units).is_none() {
        return Err(bad(
            n_values,
            format!("Units `{units}` is not one of {}: give --units to read it anyway", super::super::units::names()),
        ));
    }
    let orig_data_start_frame = match value("OrigDataStartFrame")? {
        Some(v) if !v.is_empty() => Some(count("OrigDataStartFrame", 1e12)?),
        _ => None,
    };
    let (n, names) = next(lines, "the marker names (`Frame#`, `Time`, then one name every third column)")?;
    let names = cells(names);
    if names.first() != Some(&"Frame#") || names.get(1) != Some(&"Time") {
        return Err(bad(n, "the marker-name line starts with `Frame#` and `Time`".into()));
    }
    let labels: Vec<String> = names[2..].iter().filter(|c| !c.is_empty()).map(|c| c.to_string()).collect();
    if labels.len() != num_markers {
        return Err(bad(
            n,
            format!("{} marker names, where NumMarkers (line {n_values}) is {num_markers}", labels.len()),
        ));
    }
    let misplaced = names[2..].iter().enumerate().find(|(i, c)| !c.is_empty() && i % 3 != 0);
    if let Some((i, c)) = misplaced {
        return Err(bad(
            n,
            format!("marker name `{c}` in column {}: the names stand every third column from 3", i + 3),
        ));
    }
    let (n, axes) = next(lines, "the coordinate names (X1, Y1, Z1, ...)")?;
    let axes = cells(axes).into_iter().filter(|c| !c.is_empty()).count();
    if axes != 3 * num_markers {
        return Err(bad(n, format!("{axes} coordinate names where {num_markers} markers need {}", 3 * num_markers)));
    }
    Ok(TrcHeader { data_rate_hz, camera_rate_hz, num_frames, labels, units, orig_data_start_frame })
}
