//! TrackMan's metrics of a shot as a session reads them: each with its name, its unit in either system, and its
//! value taken from a recorded [`LaunchPrediction`] (delivery, launch and flight). Values are held in one base
//! unit per metric; the other system's unit is a scale factor away, so means, SDs and medians convert exactly.

use serde::Serialize;

use crate::math::Real;
use crate::units::{MPS_PER_MPH, M_PER_YD};
use crate::wire::LaunchPrediction;

/// Which units human-readable output uses (JSON carries both).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, serde::Deserialize, clap::ValueEnum)]
#[serde(rename_all = "snake_case")]
pub enum Units {
    /// mph, yd, ft, in.
    #[default]
    Imperial,
    /// m/s, m, cm.
    Metric,
}

/// What a metric measures, which fixes its units.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Base m/s: mph or m/s.
    Speed,
    /// deg in both systems.
    Angle,
    /// rpm in both systems.
    Spin,
    /// No unit.
    Ratio,
    /// s in both systems.
    Time,
    /// Base m: yd or m.
    Distance,
    /// Base m: ft or m (heights).
    Height,
    /// Base m: in or cm (the low point).
    Short,
}

impl Quantity {
    /// The unit's name and how many of it make one base unit.
    pub fn unit(self, units: Units) -> (&'static str, Real) {
        match (self, units) {
            (Quantity::Speed, Units::Imperial) => ("mph", 1.0 / MPS_PER_MPH),
            (Quantity::Speed, Units::Metric) => ("m/s", 1.0),
            (Quantity::Angle, _) => ("deg", 1.0),
            (Quantity::Spin, _) => ("rpm", 1.0),
            (Quantity::Ratio, _) => ("", 1.0),
            (Quantity::Time, _) => ("s", 1.0),
            (Quantity::Distance, Units::Imperial) => ("yd", 1.0 / M_PER_YD),
            (Quantity::Height, Units::Imperial) => ("ft", 1.0 / 0.3048),
            (Quantity::Short, Units::Imperial) => ("in", 1.0 / 0.0254),
            (Quantity::Distance | Quantity::Height, Units::Metric) => ("m", 1.0),
            (Quantity::Short, Units::Metric) => ("cm", 100.0),
        }
    }

    /// The JSON key of a metric in a system: `club_speed_mph`, `carry_m`, `launch_angle_deg`, `smash_factor`.
    pub fn key(self, base: &str, units: Units) -> String {
        let unit = match self.unit(units).0 {
            "m/s" => "mps",
            u => u,
        };
        if unit.is_empty() {
            base.to_string()
        } else {
            format!("{base}_{unit}")
        }
    }
}

/// One of TrackMan's metrics.
#[derive(Debug, Clone, Copy)]
pub struct Metric {
    /// TrackMan's name.
    pub name: &'static str,
    /// The key without its unit (`club_speed`).
    pub base: &'static str,
    pub quantity: Quantity,
    /// The value in the base unit, when the prediction has it.
    pub value: fn(&LaunchPrediction) -> Option<Real>,
}

/// TrackMan's metrics, in the order of its reports.
pub const METRICS: [Metric; 22] = [
    Metric {
        name: "Club Speed",
        base: "club_speed",
        quantity: Quantity::Speed,
        value: |p| Some(p.delivery.club_speed_mps),
    },
    Metric {
        name: "Attack Angle",
        base: "attack_angle",
        quantity: Quantity::Angle,
        value: |p| Some(p.delivery.attack_angle_deg),
    },
    Metric {
        name: "Club Path",
        base: "club_path",
        quantity: Quantity::Angle,
        value: |p| Some(p.delivery.club_path_deg),
    },
    Metric {
        name: "Face Angle",
        base: "face_angle",
        quantity: Quantity::Angle,
        value: |p| Some(p.delivery.face_angle_deg),
    },
    Metric {
        name: "Face To Path",
        base: "face_to_path",
        quantity: Quantity::Angle,
        value: |p| Some(p.delivery.face_to_path_deg),
    },
    Metric {
        name: "Dyn. Loft",
        base: "dynamic_loft",
        quantity: Quantity::Angle,
        value: |p| Some(p.delivery.dynamic_loft_deg),
    },
    Metric {
        name: "Spin Loft",
        base: "spin_loft",
        quantity: Quantity::Angle,
        value: |p| Some(p.delivery.spin_loft_deg),
    },
    Metric {
        name: "Swing Plane",
        base: "swing_plane",
        quantity: Quantity::Angle,
        value: |p| p.delivery.swing_arc.map(|a| a.swing_plane_deg),
    },
    Metric {
        name: "Swing Direction",
        base: "swing_direction",
        quantity: Quantity::Angle,
        value: |p| p.delivery.swing_arc.map(|a| a.swing_direction_deg),
    },
    Metric {
        name: "Low Point",
        base: "low_point",
        quantity: Quantity::Short,
        value: |p| p.delivery.swing_arc.map(|a| a.low_point_distance_mm * 1e-3),
    },
    Metric {
        name: "Ball Speed",
        base: "ball_speed",
        quantity: Quantity::Speed,
        value: |p| Some(p.launch.launch.ball_speed_mps),
    },
    Metric {
        name: "Smash Factor",
        base: "smash_factor",
        quantity: Quantity::Ratio,
        value: |p| Some(p.launch.smash_factor),
    },
    Metric {
        name: "Launch Angle",
        base: "launch_angle",
        quantity: Quantity::Angle,
        value: |p| Some(p.launch.launch.launch_angle_deg),
    },
    Metric {
        name: "Launch Direction",
        base: "launch_direction",
        quantity: Quantity::Angle,
        value: |p| Some(p.launch.launch.launch_direction_deg),
    },
    Metric {
        name: "Spin Rate",
        base: "spin_rate",
        quantity: Quantity::Spin,
        value: |p| Some(p.launch.launch.total_spin_rpm),
    },
    Metric {
        name: "Spin Axis",
        base: "spin_axis",
        quantity: Quantity::Angle,
        value: |p| Some(p.launch.launch.spin_axis_deg),
    },
    Metric {
        name: "Carry",
        base: "carry",
        quantity: Quantity::Distance,
        value: |p| p.flight.as_ref().map(|f| f.carry_m),
    },
    Metric {
        name: "Total",
        base: "total",
        quantity: Quantity::Distance,
        value: |p| p.flight.as_ref().map(|f| f.total_m),
    },
    Metric {
        name: "Side",
        base: "side",
        quantity: Quantity::Distance,
        value: |p| p.flight.as_ref().map(|f| f.offline_m),
    },
    Metric { name: "Height", base: "apex", quantity: Quantity::Height, value: |p| p.flight.as_ref().map(|f| f.apex_m) },
    Metric {
        name: "Land. Angle",
        base: "land_angle",
        quantity: Quantity::Angle,
        value: |p| p.flight.as_ref().map(|f| f.land_angle_deg),
    },
    Metric {
        name: "Hang Time",
        base: "hang_time",
        quantity: Quantity::Time,
        value: |p| p.flight.as_ref().map(|f| f.hang_time_s),
    },
];

/// The index of a metric by its base key.
pub fn index(base: &str) -> Option<usize> {
    METRICS.iter().position(|m| m.base == base)
}

/// Index of carry in [`METRICS`].
pub const CARRY: usize = 16;
/// Index of side in [`METRICS`].
pub const SIDE: usize = 18;
/// Index of ball speed in [`METRICS`].
pub const BALL_SPEED: usize = 10;
/// Index of smash factor in [`METRICS`].
pub const SMASH: usize = 11;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_name_their_metric() {
        assert_eq!(index("carry"), Some(CARRY));
        assert_eq!(index("side"), Some(SIDE));
        assert_eq!(index("ball_speed"), Some(BALL_SPEED));
        assert_eq!(index("smash_factor"), Some(SMASH));
    }

    #[test]
    fn keys_carry_their_unit() {
        assert_eq!(Quantity::Speed.key("club_speed", Units::Imperial), "club_speed_mph");
        assert_eq!(Quantity::Speed.key("club_speed", Units::Metric), "club_speed_mps");
        assert_eq!(Quantity::Ratio.key("smash_factor", Units::Metric), "smash_factor");
        let (_, yd) = Quantity::Distance.unit(Units::Imperial);
        assert!((100.0 * M_PER_YD * yd - 100.0).abs() < 1e-12);
    }
}
