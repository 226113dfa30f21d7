//! One shot a line, as `impactd watch` prints them while they land: TrackMan's metrics a fitter reads at the
//! bay (club speed, attack, path, face, face to path, dynamic loft, ball speed, smash, launch, direction, spin,
//! spin axis, carry, total, side, apex, land angle) in either unit system, under a two-line header (names, then
//! units). A metric the shot does not have (no flight) shows as `-`; a metric with an uncertainty shows its one
//! sigma beside it (`162.8±2.1`), blank where the shot carries none.

use crate::wire::LaunchPrediction;

use super::metrics::{index, Units, METRICS};
use super::sigma::{has_sigma, sigma};

/// The columns: the metric's base key, its short title, its width and its decimals.
const COLUMNS: [(&str, &str, usize, usize); 17] = [
    ("club_speed", "ClubSp", 6, 1),
    ("attack_angle", "Attack", 6, 1),
    ("club_path", "Path", 5, 1),
    ("face_angle", "Face", 5, 1),
    ("face_to_path", "F2P", 5, 1),
    ("dynamic_loft", "DLoft", 5, 1),
    ("ball_speed", "BallSp", 6, 1),
    ("smash_factor", "Smash", 5, 2),
    ("launch_angle", "Launch", 6, 1),
    ("launch_direction", "Dir", 5, 1),
    ("spin_rate", "Spin", 6, 0),
    ("spin_axis", "Axis", 5, 1),
    ("carry", "Carry", 6, 1),
    ("total", "Total", 6, 1),
    ("side", "Side", 6, 1),
    ("apex", "Apex", 5, 1),
    ("land_angle", "Land", 5, 1),
];

/// Width of the shot's name column (`rig#shot club player`).
const NAME: usize = 22;

/// Width a one-sigma uncertainty adds to its column (`±2.1`, `±480`).
const SIGMA: usize = 5;

/// A column's width with its uncertainty's.
fn width_of(base: &str, width: usize) -> usize {
    if has_sigma(base) {
        width + SIGMA
    } else {
        width
    }
}

/// The two header lines: titles, then units.
pub fn header(units: Units) -> [String; 2] {
    let mut titles = format!("{:<NAME$}", "shot");
    let mut unit_line = format!("{:<NAME$}", "");
    for (base, title, width, _) in COLUMNS {
        let width = width_of(base, width);
        let unit = index(base).map(|i| METRICS[i].quantity.unit(units).0).unwrap_or("");
        titles += &format!(" {title:>width$}");
        unit_line += &format!(" {:>width$}", if unit.is_empty() { "" } else { unit });
    }
    [titles, unit_line]
}

/// A shot's line: its rig and number, club and player labels, then each column in `units`.
pub fn row(p: &LaunchPrediction, units: Units) -> String {
    let mut name = format!("{}#{} {}", p.rig, p.shot, super::club_of(p));
    if let Some(player) = &p.labels.player {
        name += &format!(" {player}");
    }
    let name: String = name.chars().take(NAME).collect();
    let mut line = format!("{name:<NAME$}");
    for (base, _, width, decimals) in COLUMNS {
        let scale = index(base).map_or(1.0, |i| METRICS[i].quantity.unit(units).1);
        let value = index(base).and_then(|i| (METRICS[i].value)(p).filter(|v| v.is_finite())).map(|v| v * scale);
        let cell = match value {
            Some(v) => format!("{v:.decimals$}"),
            None => "-".into(),
        };
        let cell = match (value, sigma(p, base)) {
            (Some(_), Some(s)) => format!("{cell}±{:.decimals$}", s * scale),
            _ if has_sigma(base) => format!("{cell}{:SIGMA$}", ""),
            _ => cell,
        };
        line += &format!(" {cell:>w$}", w = width_of(base, width));
    }
    line
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_column_names_a_metric_and_lines_align() {
        for (base, ..) in COLUMNS {
            assert!(index(base).is_some(), "{base}");
        }
        let [t, u] = header(Units::Imperial);
        assert_eq!(t.len(), u.len());
        assert!(u.contains("mph") && u.contains("yd") && u.contains("ft") && u.contains("rpm"), "{u}");
        let [_, m] = header(Units::Metric);
        assert!(m.contains("m/s") && !m.contains("mph") && !m.contains("yd"), "{m}");
    }
}
