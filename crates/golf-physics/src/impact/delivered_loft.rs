//! The dynamic loft a golfer delivers with a club when a delivery does not say (`impactd predict` without
//! `dynamic_loft_deg`, the face maps): not the static loft (a square shaft at impact, which launches a 7-iron at
//! 23 deg and 6,700 rpm where tour players launch it at 16.3 deg) but the static loft less the shaft lean and
//! de-lofting tour players deliver with clubs of that loft.
//!
//! TrackMan's PGA Tour averages give club speed, attack angle and launch, not dynamic loft. For each preset with
//! a row in that table (driver, 3-wood, hybrid, 4- to 9-iron, pitching wedge) [`super::tour::dynamic_loft_for_launch`]
//! finds the loft at which the `adjusted` model (Table 3.3) launches a centred, square strike of the row's speed
//! and attack at the row's launch angle; the difference from the preset's static loft is the delivered de-lofting
//! (negative for the driver, whose shaft leans back and bends forward at impact). A club's default dynamic loft is
//! its static loft less the de-lofting interpolated linearly in static loft between those presets (held at the
//! nearest end beyond them: the wedges above the pitching wedge keep its de-lofting).
//!
//! The curve is derived once per process from the embedded presets (10 bisections of about 15 adjusted
//! predictions each, well under a millisecond); `impactd models --presets` tables it (docs/club-files.md).

use std::sync::OnceLock;

use super::tour::{dynamic_loft_for_launch, TourAverage};
use super::{registry, Equipment};
use crate::equipment::presets;
use crate::math::Real;

/// TrackMan's PGA Tour averages (tests/data/trackman-pga-tour-averages.csv: the widely published ~2014 table)
/// for the clubs with a preset, by preset name.
pub const TOUR_ROWS: [(&str, TourAverage); 10] = [
    ("driver", row("driver", 113.0, -1.3, 167.0, 10.9, 2686.0)),
    ("wood3", row("3w", 107.0, -2.9, 158.0, 9.2, 3655.0)),
    ("hybrid", row("hybrid", 100.0, -3.3, 146.0, 10.2, 4437.0)),
    ("iron4", row("4i", 96.0, -3.4, 137.0, 11.0, 4836.0)),
    ("iron5", row("5i", 94.0, -3.7, 132.0, 12.1, 5361.0)),
    ("iron6", row("6i", 92.0, -4.1, 127.0, 14.1, 6231.0)),
    ("iron7", row("7i", 90.0, -4.3, 120.0, 16.3, 7097.0)),
    ("iron8", row("8i", 87.0, -4.5, 115.0, 18.1, 7998.0)),
    ("iron9", row("9i", 85.0, -4.7, 109.0, 20.4, 8647.0)),
    ("pw", row("pw", 83.0, -5.0, 102.0, 24.2, 9304.0)),
];

const fn row(club: &'static str, speed: Real, attack: Real, ball: Real, launch: Real, spin: Real) -> TourAverage {
    TourAverage {
        club,
        club_speed_mph: speed,
        attack_angle_deg: attack,
        ball_speed_mph: ball,
        launch_angle_deg: launch,
        spin_rpm: spin,
    }
}

/// One point of the curve: a preset's static loft and the dynamic loft tour players deliver with it (deg).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeliveredLoft {
    /// The preset's name.
    pub preset: &'static str,
    /// Its static loft (deg).
    pub static_loft_deg: Real,
    /// The dynamic loft tour players deliver with it (deg).
    pub dynamic_loft_deg: Real,
}

impl DeliveredLoft {
    /// Static less dynamic loft (deg): forward shaft lean and de-lofting; negative adds loft.
    pub fn delofting_deg(&self) -> Real {
        self.static_loft_deg - self.dynamic_loft_deg
    }
}

/// The derived points, in static-loft order (a preset that fails to derive is left out; every embedded one
/// derives, `crates/golf-physics/tests/tour_deliveries.rs`).
pub fn curve() -> &'static [DeliveredLoft] {
    static CURVE: OnceLock<Vec<DeliveredLoft>> = OnceLock::new();
    CURVE.get_or_init(|| {
        let mut points: Vec<DeliveredLoft> = TOUR_ROWS.iter().filter_map(|(name, row)| derive(name, row)).collect();
        points.sort_by(|a, b| a.static_loft_deg.total_cmp(&b.static_loft_deg));
        points
    })
}

fn derive(preset: &'static str, row: &TourAverage) -> Option<DeliveredLoft> {
    let club = presets::find(preset)?.load().ok()?;
    let model = registry::build_one("adjusted", &club, &registry::BuildOptions::default()).ok()?;
    let equipment = Equipment::new(club.club.clone());
    let dynamic_loft_deg = dynamic_loft_for_launch(model.as_ref(), &equipment, row).ok()?;
    Some(DeliveredLoft { preset, static_loft_deg: club.club.loft_deg(), dynamic_loft_deg })
}

/// The dynamic loft (deg) tour players deliver with a club of `static_loft_deg`: the static loft less the
/// de-lofting interpolated on [`curve`] (the static loft itself if the curve is empty).
pub fn delivered_loft_deg(static_loft_deg: Real) -> Real {
    static_loft_deg - delofting_deg(curve(), static_loft_deg)
}

fn delofting_deg(points: &[DeliveredLoft], static_loft_deg: Real) -> Real {
    let (Some(first), Some(last)) = (points.first(), points.last()) else {
        return 0.0;
    };
    if static_loft_deg <= first.static_loft_deg {
        return first.delofting_deg();
    }
    if static_loft_deg >= last.static_loft_deg {
        return last.delofting_deg();
    }
    for w in points.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        if static_loft_deg <= b.static_loft_deg {
            let span = b.static_loft_deg - a.static_loft_deg;
            let u = if span > 0.0 { (static_loft_deg - a.static_loft_deg) / span } else { 0.0 };
            return a.delofting_deg() * (1.0 - u) + b.delofting_deg() * u;
        }
    }
    last.delofting_deg()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn point(s: Real, d: Real) -> DeliveredLoft {
        DeliveredLoft { preset: "x", static_loft_deg: s, dynamic_loft_deg: d }
    }

    /// Linear between points, held beyond the ends, the static loft with no points.
    #[test]
    fn interpolates_and_holds_the_ends() {
        let pts = [point(10.0, 14.0), point(30.0, 21.0)];
        assert!((delofting_deg(&pts, 20.0) - (-4.0 + 9.0) / 2.0).abs() < 1e-12);
        assert_eq!(delofting_deg(&pts, 5.0), -4.0);
        assert_eq!(delofting_deg(&pts, 60.0), 9.0);
        assert_eq!(delofting_deg(&[], 30.0), 0.0);
    }
}
