//! `--table` of `impactd predict` and `impactd flight`: the launch lines as a table a person reads, one row per
//! line, in `--units imperial|metric` (the JSON lines carry both systems; the table shows one). The columns are
//! the ball's TrackMan numbers and, when the line has a flight, the flight's; an error line becomes a row that
//! says so. A writer of JSON lines like `flight_lines::FlightLines`, so the commands write through it unchanged.

use std::io::Write;

use impactd::session::Units;
use serde_json::{Map, Value};

/// A column: title, imperial key and factor, metric key and factor, unit names, width, decimals.
struct Column {
    title: &'static str,
    imperial: (&'static str, f64, &'static str),
    metric: (&'static str, f64, &'static str),
    width: usize,
    decimals: usize,
}

const fn col(
    title: &'static str,
    imperial: (&'static str, f64, &'static str),
    metric: (&'static str, f64, &'static str),
    width: usize,
    decimals: usize,
) -> Column {
    Column { title, imperial, metric, width, decimals }
}

/// A column with the same key and unit in both systems.
const fn one(title: &'static str, key: &'static str, unit: &'static str, width: usize, decimals: usize) -> Column {
    col(title, (key, 1.0, unit), (key, 1.0, unit), width, decimals)
}

/// The ball's columns, then the flight's (shown when a line has `carry_m`).
const BALL: [Column; 6] = [
    col("BallSp", ("ball_speed_mph", 1.0, "mph"), ("ball_speed_mps", 1.0, "m/s"), 6, 1),
    one("Smash", "smash_factor", "", 5, 2),
    one("Launch", "launch_angle_deg", "deg", 6, 1),
    one("Dir", "launch_direction_deg", "deg", 5, 1),
    one("Spin", "total_spin_rpm", "rpm", 6, 0),
    one("Axis", "spin_axis_deg", "deg", 5, 1),
];
/// 1 yd = 3 ft exactly.
const FLIGHT: [Column; 6] = [
    col("Carry", ("carry_yd", 1.0, "yd"), ("carry_m", 1.0, "m"), 6, 1),
    col("Total", ("total_yd", 1.0, "yd"), ("total_m", 1.0, "m"), 6, 1),
    col("Side", ("offline_yd", 1.0, "yd"), ("offline_m", 1.0, "m"), 6, 1),
    col("Apex", ("apex_yd", 3.0, "ft"), ("apex_m", 1.0, "m"), 5, 0),
    one("Land", "land_angle_deg", "deg", 5, 1),
    one("Hang", "hang_time_s", "s", 5, 1),
];

/// Width of the first column (`#line model`).
const NAME: usize = 24;

/// A writer that turns each JSON line written through it into a table row (the header before the first).
pub struct TableLines<W: Write> {
    out: W,
    units: Units,
    /// Whether the flight's columns are shown (decided by the first line: a table keeps its columns).
    flight: Option<bool>,
    /// The input line answered (a line answered by several models gives a row per model).
    line: u64,
    first_model: Option<String>,
}

impl<W: Write> TableLines<W> {
    /// A writer whose every JSON line becomes a row of a table on `out`.
    pub fn new(out: W, units: Units) -> super::line_writer::LineWriter<Self> {
        super::line_writer::LineWriter::new(TableLines { out, units, flight: None, line: 0, first_model: None })
    }

    fn columns(&self) -> impl Iterator<Item = &'static Column> {
        let flight = if self.flight == Some(true) { &FLIGHT[..] } else { &[] };
        BALL.iter().chain(flight.iter())
    }

    fn header(&mut self) -> std::io::Result<()> {
        let (mut titles, mut units) = (format!("{:<NAME$}", "line"), format!("{:<NAME$}", ""));
        for c in self.columns() {
            let unit = if self.units == Units::Metric { c.metric.2 } else { c.imperial.2 };
            titles += &format!(" {:>w$}", c.title, w = c.width);
            units += &format!(" {unit:>w$}", w = c.width);
        }
        writeln!(self.out, "{titles}")?;
        writeln!(self.out, "{units}")
    }

    fn line(&mut self, bytes: &[u8]) -> std::io::Result<()> {
        if bytes.iter().all(u8::is_ascii_whitespace) {
            return Ok(());
        }
        let map = serde_json::from_slice::<Map<String, Value>>(bytes).unwrap_or_default();
        if self.flight.is_none() {
            self.flight = Some(map.contains_key("carry_m"));
            self.header()?;
        }
        if let Some(error) = map.get("error") {
            self.line = map.get("line").and_then(Value::as_u64).unwrap_or(self.line + 1);
            return writeln!(
                self.out,
                "{:<NAME$} error: {}",
                format!("#{}", self.line),
                error.as_str().unwrap_or_default()
            );
        }
        let model = map.get("model").and_then(Value::as_str);
        // A new input line: no model named, or the first model again.
        if model.is_none() || self.first_model.is_none() || self.first_model.as_deref() == model {
            self.line += 1;
            self.first_model = self.first_model.take().or(model.map(str::to_string));
        }
        let mut name = format!("#{}", self.line);
        if let Some(model) = model {
            name += &format!(" {model}");
        }
        let mut row = format!("{:<NAME$}", name.chars().take(NAME).collect::<String>());
        for c in self.columns() {
            let (key, factor, _) = if self.units == Units::Metric { c.metric } else { c.imperial };
            match map.get(key).and_then(Value::as_f64).filter(|v| v.is_finite()) {
                Some(v) => row += &format!(" {:>w$.d$}", v * factor, w = c.width, d = c.decimals),
                None => row += &format!(" {:>w$}", "-", w = c.width),
            }
        }
        if let Some(e) = map.get("flight_error").and_then(Value::as_str) {
            row += &format!("  (no flight: {e})");
        }
        writeln!(self.out, "{row}")
    }
}

impl<W: Write> super::line_writer::LineSink for TableLines<W> {
    fn line(&mut self, line: &[u8]) -> std::io::Result<()> {
        TableLines::line(self, line)
    }

    fn flush_out(&mut self) -> std::io::Result<()> {
        self.out.flush()
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn table(lines: &str, units: Units) -> String {
        let mut out = Vec::new();
        let mut t = TableLines::new(&mut out, units);
        t.write_all(lines.as_bytes()).unwrap();
        t.flush().unwrap();
        drop(t);
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn each_line_is_a_row_in_the_units_asked_for() {
        let line = r#"{"ball_speed_mph":150.0,"ball_speed_mps":67.056,"carry_yd":250.0,"carry_m":228.6,"apex_yd":30.0,"apex_m":27.432}"#;
        let imperial = table(&format!("{line}\n{{\"line\":2,\"error\":\"bad\"}}\n"), Units::Imperial);
        let rows: Vec<&str> = imperial.lines().collect();
        assert!(rows[1].contains("mph") && rows[1].contains("yd") && rows[1].contains("ft"), "{imperial}");
        assert!(rows[2].contains(" 150.0") && rows[2].contains(" 250.0") && rows[2].contains(" 90"), "{imperial}");
        assert!(rows[3].starts_with("#2") && rows[3].contains("error: bad"), "{imperial}");
        let metric = table(&format!("{line}\n"), Units::Metric);
        let rows: Vec<&str> = metric.lines().collect();
        assert!(rows[1].contains("m/s") && !rows[1].contains("mph") && !rows[1].contains("yd"), "{metric}");
        assert!(rows[2].contains(" 67.1") && rows[2].contains(" 228.6") && rows[2].contains(" 27"), "{metric}");
        // Without a flight, no flight columns.
        let ball = table("{\"ball_speed_mph\":150.0}\n", Units::Imperial);
        assert!(!ball.contains("Carry"), "{ball}");
    }
}
