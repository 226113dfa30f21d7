//! A rig's air and turf (`[rig.conditions]`): the ball flight added to each prediction and drawn on the bay
//! screen flies in them. Absent, TrackMan's tour conditions (sea level, calm, 22.5 C, 50 % humidity) and
//! Penner's fairway; the same names and units as `impactd flight`'s flags.

use serde::{Deserialize, Serialize};

use crate::flight::{Conditions, ConditionsError, Flight, Turf, TurfError};

/// `[rig.conditions]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConditionsConfig {
    #[serde(default = "default_temperature_c")]
    pub temperature_c: f64,
    #[serde(default)]
    pub altitude_m: f64,
    /// Relative humidity in percent, 0-100.
    #[serde(default = "default_humidity_pct")]
    pub humidity_pct: f64,
    /// Station pressure (hPa); absent: the standard atmosphere at `altitude_m`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure_hpa: Option<f64>,
    #[serde(default)]
    pub wind_mps: f64,
    /// The direction the wind blows toward (deg from the target line, right +): 0 tailwind, 180 headwind.
    #[serde(default)]
    pub wind_dir_deg: f64,
    /// The turf's firmness, 0 soft to 1 firm.
    #[serde(default = "default_firmness")]
    pub firmness: f64,
}

fn default_temperature_c() -> f64 {
    Conditions::default().temperature_c
}
fn default_humidity_pct() -> f64 {
    Conditions::default().humidity * 100.0
}
fn default_firmness() -> f64 {
    Turf::default().firmness
}

/// Why a rig's `[rig.conditions]` give no flight: a field out of its range, said in the config's own units.
#[derive(Debug, thiserror::Error)]
pub enum ConditionsConfigError {
    #[error("`humidity_pct` is relative humidity in percent, 0-100, got {0}")]
    HumidityPct(f64),
    #[error("{0}")]
    Air(#[from] ConditionsError),
    #[error("{0}")]
    Turf(#[from] TurfError),
}

impl ConditionsConfig {
    /// The flight model in these conditions, or why not (the field and its range).
    pub fn flight(&self) -> Result<Flight, ConditionsConfigError> {
        if !(self.humidity_pct.is_finite() && (0.0..=100.0).contains(&self.humidity_pct)) {
            return Err(ConditionsConfigError::HumidityPct(self.humidity_pct));
        }
        let conditions = Conditions {
            temperature_c: self.temperature_c,
            pressure_hpa: self.pressure_hpa,
            humidity: self.humidity_pct / 100.0,
            altitude_m: self.altitude_m,
            wind_mps: self.wind_mps,
            wind_dir_deg: self.wind_dir_deg,
        };
        conditions.validate()?;
        let turf = Turf { firmness: self.firmness };
        turf.validate()?;
        Ok(Flight { conditions, turf, ..Flight::default() })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn absent_fields_are_the_defaults_and_bad_ones_are_named() {
        let c: ConditionsConfig = toml::from_str("").unwrap();
        assert_eq!(c.flight().unwrap(), Flight::default());
        let c: ConditionsConfig = toml::from_str("altitude_m = 1600.0\nhumidity_pct = 20.0").unwrap();
        let f = c.flight().unwrap();
        assert_eq!((f.conditions.altitude_m, f.conditions.humidity), (1600.0, 0.2));
        let c: ConditionsConfig = toml::from_str("wind_mps = -3.0").unwrap();
        assert!(c.flight().unwrap_err().to_string().contains("wind_mps"));
        let c: ConditionsConfig = toml::from_str("humidity_pct = 150.0").unwrap();
        assert!(c.flight().unwrap_err().to_string().contains("humidity_pct"));
        assert!(toml::from_str::<ConditionsConfig>("temp_c = 3.0").is_err());
    }
}
