//! The flight added to launch lines: `impactd flight` answers each launch with the launch's own fields followed
//! by the trajectory's (`carry_yd`, `total_yd`, `apex_m`, `offline_yd`, ...), and `impactd predict --flight`
//! adds the same fields to each prediction, so `predict --flight` and `predict | flight` print the same lines.

use std::io::Write;

use impactd::flight::Flight;
use impactd::wire::FlightInput;
use serde_json::{Map, Value};

/// A launch line (`impactd predict`'s fields) with its flight's fields added; an error names the field. Fields
/// the flight does not read (sanity flags, the contact's course, labels, ...) are carried through; the flight's
/// own fields replace those of an earlier flight.
pub fn with_flight(mut line: Map<String, Value>, flight: &Flight, every_s: f64) -> Result<Map<String, Value>, String> {
    let input: FlightInput = serde_json::from_value(Value::Object(line.clone())).map_err(|e| e.to_string())?;
    let launch = input.to_launch().map_err(|e| e.to_string())?;
    let trajectory = flight.fly(&launch, every_s);
    physical(&trajectory)?;
    match serde_json::to_value(trajectory).map_err(|e| e.to_string())? {
        Value::Object(fields) => line.extend(fields),
        other => return Err(format!("a trajectory serialized as {other}")),
    }
    Ok(line)
}

/// Where the bounce-and-roll model runs away: a ball that barely flies (launched flat or down) "lands" with most
/// of its launch speed and rolls on for hundreds of yards (70 m/s at 0.5 deg: 9 yd of carry, 1,290 yd of roll
/// on the default fairway). Such a launch is refused rather than answered: the roll may be at most twice the
/// carry plus [`ROLL_MARGIN_YD`], and the total at most [`MAX_TOTAL_YD`] (the longest drives on record total
/// about 515 yd). Every launch of a struck full shot stays inside (a 100 mph driver: 177 yd carry, 199 roll).
pub const ROLL_MARGIN_YD: f64 = 100.0;
pub const MAX_TOTAL_YD: f64 = 600.0;

fn physical(t: &impactd::flight::Trajectory) -> Result<(), String> {
    let runaway = t.roll_yd > 2.0 * t.carry_yd + ROLL_MARGIN_YD || t.total_yd > MAX_TOTAL_YD;
    if !(t.roll_yd.is_finite() && t.total_yd.is_finite()) || runaway {
        return Err(format!(
            "the flight gives {:.0} yd of roll after {:.0} yd of carry ({:.0} yd in all): beyond twice the carry \
             plus {ROLL_MARGIN_YD} yd of roll or {MAX_TOTAL_YD} yd in all, where the bounce and roll model runs \
             away; not a launch it can fly",
            t.roll_yd, t.carry_yd, t.total_yd
        ));
    }
    Ok(())
}

/// A writer of JSON lines that adds the flight to each launch line written through it (`predict --flight`).
/// Error lines (`{"line", "error"}`) pass unchanged; a launch the flight refuses keeps its fields and gains
/// `flight_error`.
pub struct FlightLines<W: Write> {
    out: W,
    flight: Flight,
}

impl<W: Write> FlightLines<W> {
    /// A writer whose every JSON line is answered with its flight on `out`.
    pub fn new(out: W, flight: Flight) -> super::line_writer::LineWriter<Self> {
        super::line_writer::LineWriter::new(FlightLines { out, flight })
    }

    fn line(&mut self, bytes: &[u8]) -> std::io::Result<()> {
        let text = match serde_json::from_slice::<Map<String, Value>>(bytes) {
            Ok(map) if !map.contains_key("error") => {
                let answered = match with_flight(map.clone(), &self.flight, 0.0) {
                    Ok(m) => m,
                    Err(reason) => {
                        let mut m = map;
                        m.insert("flight_error".into(), Value::String(reason));
                        m
                    }
                };
                serde_json::to_vec(&answered).map_err(std::io::Error::other)?
            }
            _ => bytes.to_vec(),
        };
        self.out.write_all(&text)?;
        self.out.write_all(b"\n")
    }
}

impl<W: Write> super::line_writer::LineSink for FlightLines<W> {
    fn line(&mut self, line: &[u8]) -> std::io::Result<()> {
        FlightLines::line(self, line)
    }

    fn flush_out(&mut self) -> std::io::Result<()> {
        self.out.flush()
    }
}
