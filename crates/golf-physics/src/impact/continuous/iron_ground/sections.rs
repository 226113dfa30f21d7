//! The club-file sections the iron-plus-ground model reads: `[soil]`, `[sole]` and `[shaft]` (seed chapter 4).
//!
//! ```toml
//! [soil]                   # Table 4.3: a preset, or every field of a soil file (equipment::soil)
//! preset = "firm"          # soft | medium | firm | none (no ground: the ball on a tee)
//! [sole]                   # any field of equipment::sole::SoleSpec; the rest keep the typical 7-iron's
//! lie_deg = 63.0
//! leading_edge_below_face_centre_m = 0.020
//! [shaft]                  # any field of equipment::shaft::ShaftSpec; the rest keep Tables 4.1-4.2
//! youngs_modulus_pa = 190e9
//! mass_kg = 0.104
//! ```
//!
//! Without a section the model takes firm soil (Table 4.3), the typical 7-iron sole of `equipment::sole` and the
//! seed's shaft (Tables 4.1-4.2). `impactd predict --soil` and the daemon's `soil` replace the `[soil]` section.

use serde::Deserialize;

use super::GroundModel;
use crate::equipment::shaft::{ShaftSpec, ShaftStation};
use crate::equipment::soil::{ReadFile, SoilSpec};
use crate::equipment::sole::SoleSpec;
use crate::equipment::{EquipmentError, ModelSections};
use crate::impact::impulse::section;
use crate::impact::ImpactError;
use crate::math::Real;

/// The names of the sections this model reads.
pub const SECTIONS: [&str; 3] = ["soil", "sole", "shaft"];

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct SoleSection {
    lie_deg: Option<Real>,
    sole_width_m: Option<Real>,
    sole_length_m: Option<Real>,
    bounce_deg: Option<Real>,
    sole_radius_m: Option<Real>,
    leading_edge_below_face_centre_m: Option<Real>,
    shaft_tip_from_cg_m: Option<[Real; 3]>,
    toe_down_deg: Option<Real>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct ShaftSection {
    stations: Option<Vec<ShaftStation>>,
    youngs_modulus_pa: Option<Real>,
    poisson_ratio: Option<Real>,
    density_kg_m3: Option<Real>,
    mass_kg: Option<Real>,
}

fn invalid(section: &'static str, source: EquipmentError) -> ImpactError {
    ImpactError::Part { section, source }
}

/// The name that stands for no ground at all: the same strike off a tee (`--soil none`).
pub const TEED: &str = "none";

/// Whether a `[soil]` section means no ground (`preset = "none"`).
pub fn is_teed(table: &toml::Table) -> bool {
    table.get("preset").and_then(|v| v.as_str()) == Some(TEED)
}

/// The `[soil]` section a `--soil` or daemon `soil` value stands for: a preset, a soil file (its text read by
/// `read_file`), or `none`.
pub fn soil_arg_section_with(name_or_path: &str, read_file: ReadFile<'_>) -> Result<toml::Table, ImpactError> {
    if name_or_path == TEED {
        let mut t = toml::Table::new();
        t.insert("preset".into(), toml::Value::String(TEED.into()));
        return Ok(t);
    }
    let spec = SoilSpec::load_with(name_or_path, read_file).map_err(|source| ImpactError::Soil { source })?;
    Ok(soil_section(&spec))
}

/// The soil of a `[soil]` section: `preset = "..."` or a soil file's fields.
pub fn soil_of(table: &toml::Table) -> Result<SoilSpec, ImpactError> {
    if let Some(preset) = table.get("preset") {
        if table.len() > 1 {
            return Err(ImpactError::InvalidParameter {
                field: "[soil].preset".into(),
                reason: "give a preset or the soil's fields, not both".into(),
            });
        }
        let name = preset.as_str().ok_or_else(|| ImpactError::InvalidParameter {
            field: "[soil].preset".into(),
            reason: "must be a string (soft, medium, firm or none)".into(),
        })?;
        return SoilSpec::preset(name).map_err(|e| invalid("soil", e));
    }
    let soil = SoilSpec::deserialize(toml::Value::Table(table.clone()))
        .map_err(|e| ImpactError::InvalidParameter { field: "[soil]".into(), reason: e.message().to_string() })?;
    soil.validate().map_err(|e| invalid("soil", e))?;
    Ok(soil)
}

/// The `[soil]` section that stands for `soil` (what `--soil` and the daemon's `soil` insert).
pub fn soil_section(soil: &SoilSpec) -> toml::Table {
    if SoilSpec::PRESETS.contains(&soil.name.as_str()) && SoilSpec::preset(&soil.name).ok().as_ref() == Some(soil) {
        let mut t = toml::Table::new();
        t.insert("preset".into(), toml::Value::String(soil.name.clone()));
        return t;
    }
    toml::Table::try_from(soil).unwrap_or_default()
}

impl GroundModel {
    /// The model of a club file's `[soil]`, `[sole]` and `[shaft]` sections (defaults above), each validated.
    /// The sole's lie is the club's static lie (`club_lie_deg`) unless `[sole]` gives its own.
    pub fn from_sections(sections: &ModelSections, club_lie_deg: Real) -> Result<Self, ImpactError> {
        let teed = sections.get("soil").is_some_and(is_teed);
        let soil = sections.get("soil").filter(|_| !teed).map(soil_of).transpose()?.unwrap_or_else(SoilSpec::firm);
        let mut model = GroundModel::new(soil);
        model.with_ground = !teed;
        model.sole.lie_deg = club_lie_deg;
        model.sole.validate().map_err(|e| invalid("sole", e))?;
        if let Some(s) = section::<SoleSection>(sections, "sole")? {
            let d = SoleSpec { lie_deg: club_lie_deg, ..SoleSpec::IRON7 };
            model.sole = SoleSpec {
                lie_deg: s.lie_deg.unwrap_or(d.lie_deg),
                sole_width_m: s.sole_width_m.unwrap_or(d.sole_width_m),
                sole_length_m: s.sole_length_m.unwrap_or(d.sole_length_m),
                bounce_deg: s.bounce_deg.unwrap_or(d.bounce_deg),
                sole_radius_m: s.sole_radius_m.unwrap_or(d.sole_radius_m),
                leading_edge_below_face_centre_m: s
                    .leading_edge_below_face_centre_m
                    .unwrap_or(d.leading_edge_below_face_centre_m),
                shaft_tip_from_cg_m: s.shaft_tip_from_cg_m.unwrap_or(d.shaft_tip_from_cg_m),
                toe_down_deg: s.toe_down_deg.unwrap_or(d.toe_down_deg),
            };
            model.sole.validate().map_err(|e| invalid("sole", e))?;
        }
        if let Some(s) = section::<ShaftSection>(sections, "shaft")? {
            let d = ShaftSpec::iron7();
            model.shaft = ShaftSpec {
                stations: s.stations.unwrap_or(d.stations),
                youngs_modulus_pa: s.youngs_modulus_pa.unwrap_or(d.youngs_modulus_pa),
                poisson_ratio: s.poisson_ratio.unwrap_or(d.poisson_ratio),
                density_kg_m3: s.density_kg_m3.unwrap_or(d.density_kg_m3),
                mass_kg: s.mass_kg.unwrap_or(d.mass_kg),
            };
            model.shaft.validate().map_err(|e| invalid("shaft", e))?;
        }
        Ok(model)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sections(text: &str) -> ModelSections {
        let mut s = ModelSections::default();
        for (name, value) in text.parse::<toml::Table>().unwrap() {
            s.insert(&name, value.as_table().unwrap().clone());
        }
        s
    }

    #[test]
    fn defaults_presets_partial_sections_and_bad_fields() {
        let iron = crate::equipment::ClubSpec::IRON_LIE_DEG;
        let m = GroundModel::from_sections(&ModelSections::default(), iron).unwrap();
        assert_eq!((m.soil.name.as_str(), m.sole, m.shaft.clone()), ("firm", SoleSpec::IRON7, ShaftSpec::iron7()));
        // The club's own static lie is the sole's unless `[sole]` says otherwise.
        let m = GroundModel::from_sections(
            &sections(
                "[sole]
bounce_deg = 6.0
",
            ),
            61.0,
        )
        .unwrap();
        assert_eq!((m.sole.lie_deg, m.sole.bounce_deg), (61.0, 6.0));
        let m = GroundModel::from_sections(
            &sections("[soil]\npreset = \"soft\"\n[sole]\nlie_deg = 63.0\n[shaft]\nmass_kg = 0.110\n"),
            iron,
        )
        .unwrap();
        assert_eq!(m.soil, SoilSpec::soft());
        assert_eq!((m.sole.lie_deg, m.sole.sole_width_m), (63.0, SoleSpec::IRON7.sole_width_m));
        assert_eq!((m.shaft.mass_kg, m.shaft.stations.len()), (0.110, 4));
        // A soil's own fields, and the section that stands for a soil reads back as that soil.
        let own = "[soil]\ndensity_kg_m3 = 1800.0\nn = 0.9\nk_c_n_per_m_n1 = 2e4\nk_phi_n_per_m_n2 = 3e6\n";
        let m = GroundModel::from_sections(&sections(own), iron).unwrap();
        assert_eq!(m.soil.n, 0.9);
        assert_eq!(soil_of(&soil_section(&m.soil)).unwrap(), m.soil);
        assert_eq!(soil_section(&SoilSpec::medium()).get("preset").and_then(|v| v.as_str()), Some("medium"));
        // `none`: no ground, the same club on a teed ball.
        assert!(GroundModel::from_sections(&ModelSections::default(), iron).unwrap().with_ground);
        let m = GroundModel::from_sections(&sections("[soil]\npreset = \"none\"\n"), iron).unwrap();
        assert!(!m.with_ground);
        assert!(is_teed(&soil_arg_section_with("none", &|_| Err(std::io::ErrorKind::NotFound.into())).unwrap()));
        assert!(soil_arg_section_with("mud", &|_| Err(std::io::ErrorKind::NotFound.into()))
            .unwrap_err()
            .to_string()
            .contains("soil"));
        for (text, field) in [
            ("[soil]\npreset = \"mud\"\n", "[soil]"),
            ("[sole]\nlie_deg = 120.0\n", "[sole]"),
            ("[sole]\nlie = 60.0\n", "sole"),
            ("[shaft]\nmass_kg = -1.0\n", "[shaft]"),
        ] {
            let e = GroundModel::from_sections(&sections(text), iron).unwrap_err().to_string();
            assert!(e.contains(field), "{text}: {e}");
        }
    }
}
