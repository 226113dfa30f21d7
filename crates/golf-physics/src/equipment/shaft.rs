//! The shaft (seed section 4.1, Tables 4.1 and 4.2): three hollow tapered steel segments, butt to tip.
//!
//! The seed models the 7-iron's steel shaft as three hollow cylinders whose outer radius and wall thickness vary
//! linearly along each segment, fitted (least squares) to the shaft's measured EI curve. Stations, from the butt:
//!
//! | station | from butt (m) | outer radius (mm) | wall (mm) |
//! |---|---|---|---|
//! | butt | 0 | 7.6 (Table 4.1) | 0.348 |
//! | 1 | L₁ = 0.273 | R₁ = 7.24 | 0.381 |
//! | 2 | L₁ + L₂ = 0.882 | R₂ = 5.08 | 0.549 |
//! | tip | 0.965 | 4.7 (Table 4.1) | 0.549 (the seed gives no tip wall; segment 3 keeps segment 2's) |
//!
//! Material SAE 8655 steel, E = 190 GPa, ν = 0.29, so G = E / (2 (1 + ν)) = 73.6 GPa (isotropic, the seed's
//! assumption after heat treatment).
//!
//! - Bending stiffness `EI(x)` with `I = π (R⁴ − Rᵢ⁴) / 4`, what the three-point bending test of eq. 4.1,
//!   `δ = F L³ / (48 EI)`, measures at each station.
//! - Torsional stiffness `GJ(x)` with `J = π (R⁴ − Rᵢ⁴) / 2`, eq. 4.2, `θ = T L / (GJ)`.
//!
//! The seed states that this geometry with 7.46 g/cm³ weighs 104 g. It does not: the tube's volume is 16.27 cm³,
//! 121.4 g at 7.46 g/cm³. The seed's measured mass (Table 4.1, 104 g) is what the shaft weighs, so the model
//! keeps the geometry for the stiffness and spreads the 104 g in proportion to the cross-section
//! ([`ShaftSpec::mass_per_length_kg_per_m`]), an effective density of 6.39 g/cm³.

use super::EquipmentError;
use crate::math::Real;

/// One station of the shaft's profile.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShaftStation {
    /// Distance from the butt (m).
    pub from_butt_m: Real,
    /// Outer radius (m).
    pub outer_radius_m: Real,
    /// Wall thickness (m).
    pub wall_m: Real,
}

/// A hollow tapered shaft: stations from butt to tip, linear between them.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShaftSpec {
    /// Stations from the butt (first, at 0) to the tip (last, at the shaft's length).
    pub stations: Vec<ShaftStation>,
    /// Young's modulus of the material (Pa).
    pub youngs_modulus_pa: Real,
    /// Poisson's ratio of the material.
    pub poisson_ratio: Real,
    /// The material's density (kg/m³), as the seed gives it.
    pub density_kg_m3: Real,
    /// The shaft's mass (kg); the mass per length is scaled so the shaft weighs this.
    pub mass_kg: Real,
}

impl ShaftSpec {
    /// The seed's 7-iron shaft, Tables 4.1 and 4.2.
    pub fn iron7() -> Self {
        let st = |from_butt_m, outer_radius_m, wall_m| ShaftStation { from_butt_m, outer_radius_m, wall_m };
        ShaftSpec {
            stations: vec![
                st(0.0, 7.6e-3, 0.348e-3),
                st(0.273, 7.24e-3, 0.381e-3),
                st(0.273 + 0.609, 5.08e-3, 0.549e-3),
                st(0.965, 4.7e-3, 0.549e-3),
            ],
            youngs_modulus_pa: 190e9,
            poisson_ratio: 0.29,
            density_kg_m3: 7460.0,
            mass_kg: 0.104,
        }
    }

    /// Checks the profile and material, naming a bad field.
    pub fn validate(&self) -> Result<(), EquipmentError> {
        let invalid = |field, reason: String| Err(EquipmentError::Invalid { field, reason });
        if self.stations.len() < 2 {
            return invalid("shaft.stations", "needs at least the butt and the tip".into());
        }
        if self.stations[0].from_butt_m != 0.0 {
            return invalid("shaft.stations", "the first station is the butt, at 0 m".into());
        }
        for (i, s) in self.stations.iter().enumerate() {
            if !(s.outer_radius_m.is_finite() && s.outer_radius_m > 0.0) {
                return invalid("shaft.stations", format!("station {i}: outer radius must be positive"));
            }
            if !(s.wall_m.is_finite() && s.wall_m > 0.0 && s.wall_m <= s.outer_radius_m) {
                return invalid("shaft.stations", format!("station {i}: wall must be in (0, outer radius]"));
            }
            if i > 0
                && s.from_butt_m.partial_cmp(&self.stations[i - 1].from_butt_m) != Some(std::cmp::Ordering::Greater)
            {
                return invalid("shaft.stations", format!("station {i}: positions must increase"));
            }
        }
        for (field, v) in [
            ("shaft.youngs_modulus_pa", self.youngs_modulus_pa),
            ("shaft.density_kg_m3", self.density_kg_m3),
            ("shaft.mass_kg", self.mass_kg),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return invalid(field, format!("must be positive, got {v}"));
            }
        }
        if !(self.poisson_ratio > -1.0 && self.poisson_ratio < 0.5) {
            return invalid("shaft.poisson_ratio", format!("must lie in (-1, 0.5), got {}", self.poisson_ratio));
        }
        Ok(())
    }

    /// Length (m).
    pub fn length_m(&self) -> Real {
        self.stations.last().map_or(0.0, |s| s.from_butt_m)
    }

    /// Shear modulus `G = E / (2 (1 + ν))` (Pa).
    pub fn shear_modulus_pa(&self) -> Real {
        self.youngs_modulus_pa / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Outer radius and wall thickness at `x` from the butt (m), linear between stations.
    pub fn section_at(&self, x_m: Real) -> (Real, Real) {
        let st = &self.stations;
        let x = x_m.clamp(0.0, self.length_m());
        let i = st.iter().rposition(|s| s.from_butt_m <= x).unwrap_or(0).min(st.len() - 2);
        let (a, b) = (st[i], st[i + 1]);
        let f = (x - a.from_butt_m) / (b.from_butt_m - a.from_butt_m);
        (a.outer_radius_m + f * (b.outer_radius_m - a.outer_radius_m), a.wall_m + f * (b.wall_m - a.wall_m))
    }

    /// Cross-section area `π (R² − Rᵢ²)` (m²).
    pub fn area_m2(&self, x_m: Real) -> Real {
        let (r, t) = self.section_at(x_m);
        std::f64::consts::PI * (r * r - (r - t) * (r - t))
    }

    /// Second moment of area `I = π (R⁴ − Rᵢ⁴) / 4` (m⁴).
    pub fn second_moment_m4(&self, x_m: Real) -> Real {
        let (r, t) = self.section_at(x_m);
        std::f64::consts::FRAC_PI_4 * (r.powi(4) - (r - t).powi(4))
    }

    /// Bending stiffness `EI` (N m²) at `x` from the butt: what eq. 4.1's three-point test measures.
    pub fn ei_n_m2(&self, x_m: Real) -> Real {
        self.youngs_modulus_pa * self.second_moment_m4(x_m)
    }

    /// Torsional stiffness `GJ` (N m²), `J = 2 I` for a circular tube (eq. 4.2).
    pub fn gj_n_m2(&self, x_m: Real) -> Real {
        self.shear_modulus_pa() * 2.0 * self.second_moment_m4(x_m)
    }

    /// Axial stiffness `EA` (N).
    pub fn ea_n(&self, x_m: Real) -> Real {
        self.youngs_modulus_pa * self.area_m2(x_m)
    }

    /// The tube's volume (m³), integrated exactly over each linear segment (Simpson is exact for the quadratic
    /// area).
    pub fn volume_m3(&self) -> Real {
        self.stations
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0].from_butt_m, w[1].from_butt_m);
                (b - a) / 6.0 * (self.area_m2(a) + 4.0 * self.area_m2(0.5 * (a + b)) + self.area_m2(b))
            })
            .sum()
    }

    /// The mass the geometry and material density give (kg): 121.4 g for the seed's shaft.
    pub fn geometric_mass_kg(&self) -> Real {
        self.density_kg_m3 * self.volume_m3()
    }

    /// The density that makes the tube weigh `mass_kg` (kg/m³).
    pub fn effective_density_kg_m3(&self) -> Real {
        self.mass_kg / self.volume_m3()
    }

    /// Mass per length (kg/m) at `x`, scaled so the whole shaft weighs `mass_kg`.
    pub fn mass_per_length_kg_per_m(&self, x_m: Real) -> Real {
        self.effective_density_kg_m3() * self.area_m2(x_m)
    }

    /// Polar mass moment per length about the shaft's axis (kg m), `ρ J`.
    pub fn polar_inertia_per_length_kg_m(&self, x_m: Real) -> Real {
        self.effective_density_kg_m3() * 2.0 * self.second_moment_m4(x_m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The preset equals the seed's tables as transcribed in `tests/data/seed-tables.toml`.
    #[test]
    fn preset_matches_seed_tables() {
        let tables: toml::Value = toml::from_str(include_str!("../../../../tests/data/seed-tables.toml")).unwrap();
        let t = &tables["shaft"]["iron7"];
        let f = |k: &str| t[k].as_float().unwrap();
        let s = ShaftSpec::iron7();
        s.validate().unwrap();
        assert_eq!(s.mass_kg, f("mass_kg"));
        assert!((s.length_m() - f("length_m")).abs() < 1e-12);
        assert_eq!(s.stations[0].outer_radius_m, f("butt_radius_m"));
        assert_eq!(s.stations[3].outer_radius_m, f("tip_radius_m"));
        assert_eq!(s.stations[0].wall_m, f("wall_butt_m"));
        assert_eq!(s.stations[1].from_butt_m, f("segment1_length_m"));
        assert_eq!(s.stations[1].outer_radius_m, f("segment1_radius_m"));
        assert_eq!(s.stations[1].wall_m, f("segment1_wall_m"));
        assert!((s.stations[2].from_butt_m - f("segment1_length_m") - f("segment2_length_m")).abs() < 1e-12);
        assert_eq!(s.stations[2].outer_radius_m, f("segment2_radius_m"));
        assert_eq!(s.stations[2].wall_m, f("segment2_wall_m"));
        assert_eq!(s.youngs_modulus_pa, f("youngs_modulus_pa"));
        assert_eq!(s.poisson_ratio, f("poisson_ratio"));
        assert_eq!(s.density_kg_m3, f("density_kg_m3"));
    }

    /// Closed forms at the butt: I = π (R⁴ − Rᵢ⁴)/4 with R = 7.6 mm, Rᵢ = 7.252 mm gives EI = 85.1 N m²
    /// (a stiff steel shaft's butt EI is 70-90 N m²); G = 190 / 2.58 = 73.64 GPa.
    #[test]
    fn section_closed_forms() {
        let s = ShaftSpec::iron7();
        let (r, ri) = (7.6e-3_f64, 7.252e-3_f64);
        let ei = 190e9 * std::f64::consts::FRAC_PI_4 * (r.powi(4) - ri.powi(4));
        assert!((s.ei_n_m2(0.0) - ei).abs() < 1e-9 * ei);
        assert!((s.ei_n_m2(0.0) - 85.1).abs() < 0.1, "{}", s.ei_n_m2(0.0));
        assert!((s.shear_modulus_pa() - 73.643e9).abs() < 0.001e9);
        assert!((s.gj_n_m2(0.5) / s.ei_n_m2(0.5) - 1.0 / 1.29).abs() < 1e-12);
        // Linear between stations: halfway along segment 2.
        let (r_mid, t_mid) = s.section_at(0.273 + 0.3045);
        assert!((r_mid - 6.16e-3).abs() < 1e-12 && (t_mid - 0.465e-3).abs() < 1e-12);
    }

    /// The seed's geometry and density weigh 121.4 g, not the 104 g it states; the model's mass per length
    /// integrates to 104 g.
    #[test]
    fn mass_from_geometry_and_the_stated_mass() {
        let s = ShaftSpec::iron7();
        assert!((s.geometric_mass_kg() - 0.1214).abs() < 0.0001, "{}", s.geometric_mass_kg());
        let n = 2000;
        let h = s.length_m() / n as Real;
        let m: Real = (0..n).map(|i| s.mass_per_length_kg_per_m((i as Real + 0.5) * h) * h).sum();
        assert!((m - 0.104).abs() < 1e-6, "{m}");
        assert!((s.effective_density_kg_m3() - 6391.0).abs() < 1.0, "{}", s.effective_density_kg_m3());
    }

    #[test]
    fn validation_names_the_field() {
        let mut s = ShaftSpec::iron7();
        s.stations[2].wall_m = -1.0;
        let e = s.validate().unwrap_err().to_string();
        assert!(e.contains("shaft.stations") && e.contains("station 2"), "{e}");
        let mut s = ShaftSpec::iron7();
        s.poisson_ratio = 0.7;
        assert!(s.validate().unwrap_err().to_string().contains("poisson_ratio"));
    }
}
