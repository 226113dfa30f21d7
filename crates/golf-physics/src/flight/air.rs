//! Air: density from temperature, pressure, humidity and altitude; viscosity; wind.

use crate::math::{Real, Vector3};

/// Conditions of a shot.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Conditions {
    /// Air temperature (°C).
    pub temperature_c: Real,
    /// Station pressure (hPa); `None`: the standard atmosphere at `altitude_m`.
    pub pressure_hpa: Option<Real>,
    /// Relative humidity, 0-1.
    pub humidity: Real,
    /// Altitude above sea level (m); sets the pressure when `pressure_hpa` is `None`.
    pub altitude_m: Real,
    /// Wind speed (m/s) and the direction it blows toward (deg from the target line, right +): 0 is a tailwind,
    /// 180 a headwind, 90 blows left to right.
    pub wind_mps: Real,
    /// See `wind_mps`.
    pub wind_dir_deg: Real,
}

impl Default for Conditions {
    /// TrackMan's tour-average conditions: sea level, calm, 22.5 C, 50 % humidity.
    fn default() -> Self {
        Conditions {
            temperature_c: 22.5,
            pressure_hpa: None,
            humidity: 0.5,
            altitude_m: 0.0,
            wind_mps: 0.0,
            wind_dir_deg: 0.0,
        }
    }
}

/// A condition out of its range, named.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ConditionsError {
    /// `field` is `value`, outside `min..=max`.
    #[error("`{field}` must be within {min} and {max}, got {value}")]
    OutOfRange {
        /// The field's name in the configuration (`temperature_c`, `humidity`, ...).
        field: &'static str,
        /// What it was.
        value: Real,
        /// Its smallest and largest allowed values.
        min: Real,
        /// See `min`.
        max: Real,
    },
}

impl Conditions {
    /// Checks the numbers, naming a bad one.
    pub fn validate(&self) -> Result<(), ConditionsError> {
        let checks: [(&'static str, Real, Real, Real); 5] = [
            ("temperature_c", self.temperature_c, -40.0, 55.0),
            ("humidity", self.humidity, 0.0, 1.0),
            ("altitude_m", self.altitude_m, -500.0, 5000.0),
            ("wind_mps", self.wind_mps, 0.0, 40.0),
            ("wind_dir_deg", self.wind_dir_deg, -360.0, 360.0),
        ];
        let pressure = self.pressure_hpa.map(|p| ("pressure_hpa", p, 500.0, 1100.0));
        for (field, value, min, max) in checks.into_iter().chain(pressure) {
            if !(value.is_finite() && (min..=max).contains(&value)) {
                return Err(ConditionsError::OutOfRange { field, value, min, max });
            }
        }
        Ok(())
    }

    /// Station pressure (Pa): given, or the standard atmosphere at the altitude (ICAO troposphere).
    pub fn pressure_pa(&self) -> Real {
        match self.pressure_hpa {
            Some(p) => p * 100.0,
            None => 101_325.0 * (1.0 - 2.25577e-5 * self.altitude_m).powf(5.25588),
        }
    }

    /// Air density (kg/m³): dry air and water vapour as ideal gases, saturation pressure by Tetens' formula.
    pub fn density_kg_m3(&self) -> Real {
        let t_k = self.temperature_c + 273.15;
        let p_sat = 610.78 * (17.27 * self.temperature_c / (self.temperature_c + 237.3)).exp();
        let p_v = self.humidity * p_sat;
        let p_d = self.pressure_pa() - p_v;
        p_d / (287.058 * t_k) + p_v / (461.495 * t_k)
    }

    /// Dynamic viscosity of air (Pa s), Sutherland's law.
    pub fn viscosity_pa_s(&self) -> Real {
        let t = self.temperature_c + 273.15;
        1.716e-5 * (t / 273.15).powf(1.5) * (273.15 + 110.4) / (t + 110.4)
    }

    /// The wind's velocity (m/s, world).
    pub fn wind_mps(&self) -> Vector3 {
        let d = self.wind_dir_deg.to_radians();
        Vector3::new(self.wind_mps * d.cos(), 0.0, self.wind_mps * d.sin())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The standard atmosphere: 1.225 kg/m³ at 15 C, 1013.25 hPa, dry; about 1.0 kg/m³ at 2000 m.
    #[test]
    fn standard_density() {
        let c = Conditions { temperature_c: 15.0, humidity: 0.0, ..Default::default() };
        assert!((c.density_kg_m3() - 1.225).abs() < 0.001, "{}", c.density_kg_m3());
        let high = Conditions { temperature_c: 2.0, humidity: 0.0, altitude_m: 2000.0, ..Default::default() };
        assert!((high.density_kg_m3() - 1.007).abs() < 0.01, "{}", high.density_kg_m3());
        // Humid air is lighter than dry air at the same pressure and temperature.
        let humid = Conditions { humidity: 1.0, ..c };
        assert!(humid.density_kg_m3() < c.density_kg_m3());
    }
}
