//! A camera monitor's column header as `Name (unit and sign convention)`, e.g. Foresight's `Club Path (deg
//! out-in-/in-out+)`: [`split`] parts it, [`speed_to_mph`] and [`length_to_yd`] read the units impactd converts.
//! Shared by the Foresight and Uneekor readers; a unit not listed here is an error for the reader to name.

use crate::math::Real;
use crate::units::{MPS_PER_MPH, M_PER_YD};

/// `Name (inside)` as `("Name", Some("inside"))`; a header without a bracket as `(header, None)`.
pub fn split(header: &str) -> (&str, Option<&str>) {
    let h = header.trim().trim_start_matches('\u{feff}');
    match (h.find(" ("), h.ends_with(')')) {
        (Some(i), true) => (h[..i].trim(), Some(h[i + 2..h.len() - 1].trim())),
        _ => (h, None),
    }
}

/// How many mph one of `unit` is: mph, km/h (kph), m/s.
pub fn speed_to_mph(unit: &str) -> Option<Real> {
    match unit {
        "mph" => Some(1.0),
        "km/h" | "kph" | "kmh" => Some(1.0 / 1.609344),
        "m/s" | "mps" => Some(1.0 / MPS_PER_MPH),
        _ => None,
    }
}

/// How many yards one of `unit` is: yds, yd, m.
pub fn length_to_yd(unit: &str) -> Option<Real> {
    match unit {
        "yds" | "yd" | "yards" => Some(1.0),
        "m" | "meters" | "metres" => Some(1.0 / M_PER_YD),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headers_split_into_name_and_unit() {
        assert_eq!(split("Club Path (deg out-in-/in-out+)"), ("Club Path", Some("deg out-in-/in-out+")));
        assert_eq!(split("\u{feff}Club Name"), ("Club Name", None));
        assert_eq!(split("Efficiency"), ("Efficiency", None));
        assert!((speed_to_mph("km/h").unwrap() * 160.934_4 - 100.0).abs() < 1e-9);
        assert!(speed_to_mph("knots").is_none() && length_to_yd("ft").is_none());
    }
}
