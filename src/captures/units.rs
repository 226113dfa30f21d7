//! Length units as captures state them (TRC's `Units`, a pose table's `:mm`, `--units`): metres per unit.

use super::CaptureError;

/// The units a capture may state, each with its metres (the first name of each is the canonical one).
pub const LENGTH_UNITS: [(&[&str], f64); 6] = [
    (&["mm", "millimeter", "millimeters", "millimetre", "millimetres"], 1e-3),
    (&["cm", "centimeter", "centimeters", "centimetre", "centimetres"], 1e-2),
    (&["dm", "decimeter", "decimeters", "decimetre", "decimetres"], 0.1),
    (&["m", "meter", "meters", "metre", "metres"], 1.0),
    (&["in", "inch", "inches"], 0.0254),
    (&["ft", "foot", "feet"], 0.3048),
];

/// Metres per `unit` (case and surrounding space ignored), or `None` for a unit not in [`LENGTH_UNITS`].
pub fn metres_per_unit(unit: &str) -> Option<f64> {
    let unit = unit.trim().to_ascii_lowercase();
    LENGTH_UNITS.iter().find(|(names, _)| names.contains(&unit.as_str())).map(|(_, m)| *m)
}

/// [`metres_per_unit`], or an error naming the units known.
pub fn metres_per(unit: &str) -> Result<f64, CaptureError> {
    metres_per_unit(unit).ok_or_else(|| CaptureError::Usage(format!("units `{unit}`: not one of {}", names())))
}

/// The canonical unit names, comma-separated.
pub fn names() -> String {
    LENGTH_UNITS.iter().map(|(names, _)| names[0]).collect::<Vec<_>>().join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_read_as_metres_and_an_unknown_one_is_named() {
        assert_eq!(metres_per_unit(" MM "), Some(1e-3));
        assert_eq!(metres_per_unit("metres"), Some(1.0));
        assert_eq!(metres_per_unit("in"), Some(0.0254));
        let e = metres_per("furlong").unwrap_err().to_string();
        assert!(e.contains("furlong") && e.contains("mm, cm, dm, m, in, ft"), "{e}");
    }
}
