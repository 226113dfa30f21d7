//! Soil (seed section 4.2 and Table 4.3): the Bekker pressure-sinkage parameters of a sandy loam at three
//! compactions, or a soil file.
//!
//! - Bekker, eq. 4.3: `σ(z) = (k_c / b + k_φ) zⁿ`, with `b` the smaller dimension of the contact area; `k_c` in
//!   N/m^(n+1) and `k_φ` in N/m^(n+2) (Table 4.3 prints kN).
//! - Shear strength, eq. 4.6-4.7: Mohr-Coulomb `τ = c + σ tan Φ` with no cohesion and Φ = 30°, so `τ = σ / √3`.
//! - Passive earth pressure, eq. 4.10-4.11: `σ_p = γ_s z N_Φ` (cohesion ignored), flow value
//!   `N_Φ = tan²(45° + Φ/2) = 3`. The seed calls `γ_s` "the density of the soil"; as in terramechanics
//!   (Wong) it is the unit weight `ρ g` (N/m³), which [`SoilSpec::unit_weight_n_per_m3`] gives.
//!
//! A soil file has the fields of [`SoilSpec`]:
//!
//! ```toml
//! name = "wet fairway"
//! density_kg_m3 = 1800.0
//! n = 0.9
//! k_c_n_per_m_n1 = 20000.0     # N/m^(n+1)
//! k_phi_n_per_m_n2 = 3.0e6     # N/m^(n+2)
//! # optional: friction_angle_deg = 30.0
//! ```

use super::EquipmentError;
use crate::math::Real;

/// Reads a named file's text, for the loaders that take a path (the caller's IO: this crate does none).
pub type ReadFile<'a> = &'a dyn Fn(&std::path::Path) -> std::io::Result<String>;

/// Standard gravity (m/s²), for the soil's unit weight.
pub const GRAVITY_MPS2: Real = 9.80665;

/// A soil's parameters (Table 4.3 and eq. 4.6-4.11).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoilSpec {
    /// Preset name or the file's `name`.
    #[serde(default)]
    pub name: String,
    /// Bulk density `ρ` (kg/m³).
    pub density_kg_m3: Real,
    /// Sinkage exponent `n`.
    pub n: Real,
    /// Cohesive modulus `k_c` (N/m^(n+1)).
    pub k_c_n_per_m_n1: Real,
    /// Frictional modulus `k_φ` (N/m^(n+2)).
    pub k_phi_n_per_m_n2: Real,
    /// Angle of internal shearing resistance Φ (deg); the seed's 30° gives `τ = σ/√3` and `N_Φ = 3`.
    #[serde(default = "default_friction_angle_deg")]
    pub friction_angle_deg: Real,
}

fn default_friction_angle_deg() -> Real {
    30.0
}

impl SoilSpec {
    fn preset_of(name: &str, density_kg_m3: Real, n: Real, k_c_kn: Real, k_phi_kn: Real) -> Self {
        SoilSpec {
            name: name.to_string(),
            density_kg_m3,
            n,
            k_c_n_per_m_n1: k_c_kn * 1e3,
            k_phi_n_per_m_n2: k_phi_kn * 1e3,
            friction_angle_deg: 30.0,
        }
    }

    /// Table 4.3, soft sandy loam.
    pub fn soft() -> Self {
        Self::preset_of("soft", 1530.0, 0.66, 10.5, 1260.0)
    }

    /// Table 4.3, medium sandy loam.
    pub fn medium() -> Self {
        Self::preset_of("medium", 1910.0, 1.00, 32.8, 4580.0)
    }

    /// Table 4.3, firmly compacted sandy loam.
    pub fn firm() -> Self {
        Self::preset_of("firm", 2300.0, 1.20, 48.4, 15000.0)
    }

    /// This soil pressing `factor` times as hard at every sinkage (both moduli of eq. 4.3 scaled): how the
    /// ground model's response to the soil's strength is measured (research/ground-parts.md).
    pub fn with_moduli_scaled(mut self, factor: Real) -> Self {
        self.k_c_n_per_m_n1 *= factor;
        self.k_phi_n_per_m_n2 *= factor;
        self
    }

    /// Names of the presets.
    pub const PRESETS: [&'static str; 3] = ["soft", "medium", "firm"];

    /// A preset by name.
    pub fn preset(name: &str) -> Result<Self, EquipmentError> {
        match name {
            "soft" => Ok(Self::soft()),
            "medium" => Ok(Self::medium()),
            "firm" => Ok(Self::firm()),
            other => Err(EquipmentError::UnknownSoil(other.to_string())),
        }
    }

    /// A soil from the text of a TOML soil file, validated.
    pub fn from_toml_str(text: &str) -> Result<Self, EquipmentError> {
        let soil: SoilSpec = toml::from_str(text).map_err(|e| EquipmentError::Parse(e.into()))?;
        soil.validate()?;
        Ok(soil)
    }

    /// A preset name or the path of a soil file, whose text `read_file` gives (this crate reads no files: impactd
    /// passes its size-capped reader).
    pub fn load_with(name_or_path: &str, read_file: ReadFile<'_>) -> Result<Self, EquipmentError> {
        if Self::PRESETS.contains(&name_or_path) {
            return Self::preset(name_or_path);
        }
        let path = std::path::Path::new(name_or_path);
        let text = read_file(path).map_err(|e| {
            if e.kind() == std::io::ErrorKind::NotFound {
                EquipmentError::UnknownSoil(name_or_path.to_string())
            } else {
                EquipmentError::SoilRead { path: name_or_path.to_string(), source: e }
            }
        })?;
        let mut soil = Self::from_toml_str(&text)?;
        if soil.name.is_empty() {
            soil.name = name_or_path.to_string();
        }
        Ok(soil)
    }

    /// Checks every field, naming a bad one.
    pub fn validate(&self) -> Result<(), EquipmentError> {
        let invalid = |field, reason: String| Err(EquipmentError::Invalid { field, reason });
        for (field, v) in
            [("density_kg_m3", self.density_kg_m3), ("n", self.n), ("k_phi_n_per_m_n2", self.k_phi_n_per_m_n2)]
        {
            if !(v.is_finite() && v > 0.0) {
                return invalid(field, format!("must be positive, got {v}"));
            }
        }
        if !(self.k_c_n_per_m_n1.is_finite() && self.k_c_n_per_m_n1 >= 0.0) {
            return invalid("k_c_n_per_m_n1", format!("must not be negative, got {}", self.k_c_n_per_m_n1));
        }
        if self.n > 3.0 {
            return invalid("n", format!("a sinkage exponent above 3 is not a soil, got {}", self.n));
        }
        if !(self.friction_angle_deg > 0.0 && self.friction_angle_deg < 60.0) {
            return invalid("friction_angle_deg", format!("must lie in (0, 60), got {}", self.friction_angle_deg));
        }
        Ok(())
    }

    /// Bekker's pressure at sinkage `z_m` under a contact whose smaller dimension is `b_m`, eq. 4.3 (Pa).
    #[inline]
    pub fn pressure_pa(&self, z_m: Real, b_m: Real) -> Real {
        if z_m <= 0.0 {
            return 0.0;
        }
        // zⁿ as exp(n ln z): the same to a few units in the last place, at a third of `powf`'s cost here.
        (self.k_c_n_per_m_n1 / b_m + self.k_phi_n_per_m_n2) * (self.n * z_m.ln()).exp()
    }

    /// `tan Φ`: the shear strength per unit normal stress, eq. 4.6 without cohesion (1/√3 at 30°, eq. 4.7).
    pub fn shear_ratio(&self) -> Real {
        self.friction_angle_deg.to_radians().tan()
    }

    /// The flow value `N_Φ = tan²(45° + Φ/2)`, eq. 4.11 (3 at 30°).
    pub fn flow_value(&self) -> Real {
        (std::f64::consts::FRAC_PI_4 + 0.5 * self.friction_angle_deg.to_radians()).tan().powi(2)
    }

    /// Unit weight `γ_s = ρ g` (N/m³), eq. 4.10.
    pub fn unit_weight_n_per_m3(&self) -> Real {
        self.density_kg_m3 * GRAVITY_MPS2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The presets equal Table 4.3 as transcribed in `tests/data/seed-tables.toml` (kN -> N).
    #[test]
    fn presets_match_table_4_3() {
        let tables: toml::Value = toml::from_str(include_str!("../../../../tests/data/seed-tables.toml")).unwrap();
        for name in SoilSpec::PRESETS {
            let t = &tables["soil"][name];
            let s = SoilSpec::preset(name).unwrap();
            s.validate().unwrap();
            assert_eq!(s.density_kg_m3, t["density_kg_m3"].as_float().unwrap());
            assert_eq!(s.n, t["n"].as_float().unwrap());
            assert!((s.k_c_n_per_m_n1 - 1e3 * t["k_c_kn"].as_float().unwrap()).abs() < 1e-9);
            assert!((s.k_phi_n_per_m_n2 - 1e3 * t["k_phi_kn"].as_float().unwrap()).abs() < 1e-6);
        }
    }

    /// Eq. 4.7 and 4.11 at Φ = 30°: τ/σ = 1/√3 and N_Φ = 3 exactly (to rounding).
    #[test]
    fn thirty_degrees_gives_the_seeds_constants() {
        let s = SoilSpec::firm();
        assert!((s.shear_ratio() - 1.0 / 3f64.sqrt()).abs() < 1e-15);
        assert!((s.flow_value() - 3.0).abs() < 1e-12);
    }

    /// Eq. 4.3 by hand, firm soil, z = 1 cm under a 2 cm contact: (48.4e3/0.02 + 15e6) 0.01^1.2 = 69.3 kPa.
    #[test]
    fn bekker_pressure_by_hand() {
        let s = SoilSpec::firm();
        let want = (48.4e3 / 0.02 + 15e6) * 0.01f64.powf(1.2);
        assert!((s.pressure_pa(0.01, 0.02) - want).abs() < 1e-9 * want);
        assert!((want - 69.3e3).abs() < 0.1e3, "{want}");
        assert_eq!(s.pressure_pa(-0.001, 0.02), 0.0);
    }

    /// Table 4.3's soils do not order by pressure at every depth: the smaller sinkage exponent of the soft soil
    /// (zⁿ with n = 0.66 against 1.2) makes it press harder than the firm one below 14.7 mm of sinkage under a
    /// 2 cm contact (1.785e6 z^0.66 = 1.742e7 z^1.2) and harder than the medium one below 25.5 mm; beyond
    /// 25.5 mm the order is soft < medium < firm.
    #[test]
    fn table_4_3_orders_only_beyond_the_crossovers() {
        let p = |z: Real| -> Vec<Real> {
            SoilSpec::PRESETS.iter().map(|n| SoilSpec::preset(n).unwrap().pressure_pa(z, 0.02)).collect()
        };
        let deep = p(0.03);
        assert!(deep[0] < deep[1] && deep[1] < deep[2], "{deep:?}");
        let shallow = p(0.005);
        assert!(shallow[0] > shallow[1] && shallow[0] > shallow[2], "{shallow:?}");
        let cross = |a: &SoilSpec, b: &SoilSpec| {
            let (mut lo, mut hi) = (1e-4, 0.2);
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if a.pressure_pa(mid, 0.02) > b.pressure_pa(mid, 0.02) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            lo
        };
        assert!((cross(&SoilSpec::soft(), &SoilSpec::firm()) - 0.0147).abs() < 0.0002);
        assert!((cross(&SoilSpec::soft(), &SoilSpec::medium()) - 0.0255).abs() < 0.0003);
    }

    #[test]
    fn soil_file_round_trip_and_errors() {
        let s = SoilSpec::from_toml_str(
            "name = \"wet\"\ndensity_kg_m3 = 1800.0\nn = 0.9\nk_c_n_per_m_n1 = 2.0e4\nk_phi_n_per_m_n2 = 3.0e6\n",
        )
        .unwrap();
        assert_eq!(s.name, "wet");
        assert_eq!(s.friction_angle_deg, 30.0);
        let e =
            SoilSpec::from_toml_str("density_kg_m3 = 1800.0\nn = -1.0\nk_c_n_per_m_n1 = 0.0\nk_phi_n_per_m_n2 = 1.0\n")
                .unwrap_err()
                .to_string();
        assert!(e.contains("`n`"), "{e}");
        let e = SoilSpec::from_toml_str("density = 1.0").unwrap_err().to_string();
        assert!(e.contains("unknown field"), "{e}");
        assert!(matches!(
            SoilSpec::load_with("mud", &|_| Err(std::io::ErrorKind::NotFound.into())),
            Err(EquipmentError::UnknownSoil(_))
        ));
    }
}
