//! The identified parameters of the adjusted (Danaei, seed Table 3.3) and slip (Cross and Dewhurst, Table 3.4)
//! variants, and their club-file sections `[adjusted]` and `[slip]`.

use serde::Deserialize;

use super::oblique::ObliqueRise;
use crate::equipment::{ClubSpec, ModelSections};
use crate::impact::ImpactError;
use crate::math::{Real, Vector3};

/// Parameters of the adjusted and slip variants, identified per club in the seed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpulseTuning {
    /// Mass added to the head (kg), Table 3.3.
    pub adjusted_delta_mass_kg: Real,
    /// Shift of the ball's CG in the impact frame (x' normal, y' up the face, z' toe), m, Table 3.3.
    pub adjusted_ball_cg_shift_m: Vector3,
    /// Tangential restitution along y' (eq. 3.11), Table 3.4.
    pub slip_e_y: Real,
    /// Tangential restitution along z' (eq. 3.12), Table 3.4.
    pub slip_e_z: Real,
    /// Cross's rise of both with the impact's obliquity (`oblique.rs`); `None`: Table 3.4's constants.
    pub slip_oblique: Option<ObliqueRise>,
}

/// `[adjusted]`: the Danaei parameters (Table 3.3).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct AdjustedSection {
    delta_mass_kg: Real,
    ball_cg_shift_m: [Real; 3],
}

/// `[slip]`: the Cross and Dewhurst tangential restitution (Table 3.4).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct SlipSection {
    e_y: Real,
    e_z: Real,
    oblique_from_deg: Option<Real>,
    oblique_full_deg: Option<Real>,
    oblique_e_t: Option<Real>,
}

fn invalid(field: &str, reason: impl Into<String>) -> ImpactError {
    ImpactError::InvalidParameter { field: field.to_string(), reason: reason.into() }
}

fn finite(field: &str, v: Real) -> Result<Real, ImpactError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(invalid(field, format!("must be a finite number, got {v}")))
    }
}

/// A model's section of a club file as its serde type, a bad field named with the section.
pub(crate) fn section<T: serde::de::DeserializeOwned>(
    sections: &ModelSections,
    name: &str,
) -> Result<Option<T>, ImpactError> {
    sections
        .get(name)
        .map(|t| T::deserialize(toml::Value::Table(t.clone())).map_err(|e| invalid(name, e.message().to_string())))
        .transpose()
}

impl ImpulseTuning {
    /// Table 3.3 and 3.4, driver column.
    pub const DRIVER: ImpulseTuning = ImpulseTuning {
        adjusted_delta_mass_kg: 0.00254,
        adjusted_ball_cg_shift_m: Vector3::new(0.0, -0.482e-3, -0.068e-3),
        slip_e_y: -0.0103,
        slip_e_z: -0.0151,
        slip_oblique: None,
    };
    /// Table 3.3 and 3.4, 7-iron column.
    pub const IRON7: ImpulseTuning = ImpulseTuning {
        adjusted_delta_mass_kg: 0.0101,
        adjusted_ball_cg_shift_m: Vector3::new(-0.395e-3, -0.182e-3, -0.071e-3),
        slip_e_y: 0.0183,
        slip_e_z: 0.0423,
        slip_oblique: None,
    };

    /// The seed's values for a club: the driver's for a curved face, the 7-iron's for a flat one.
    pub fn seed_for(club: &ClubSpec) -> Self {
        if club.is_wood() {
            Self::DRIVER
        } else {
            Self::IRON7
        }
    }

    /// The seed's values for the club, overridden by the club file's `[adjusted]` and `[slip]` sections.
    pub fn from_sections(club: &ClubSpec, sections: &ModelSections) -> Result<Self, ImpactError> {
        let mut t = Self::seed_for(club);
        if let Some(a) = section::<AdjustedSection>(sections, "adjusted")? {
            let dm = finite("adjusted.delta_mass_kg", a.delta_mass_kg)?;
            if dm < 0.0 || dm > club.mass_kg {
                return Err(invalid("adjusted.delta_mass_kg", "must be within 0 and the head mass"));
            }
            t.adjusted_delta_mass_kg = dm;
            for i in 0..3 {
                t.adjusted_ball_cg_shift_m[i] = finite("adjusted.ball_cg_shift_m", a.ball_cg_shift_m[i])?;
            }
        }
        if let Some(s) = section::<SlipSection>(sections, "slip")? {
            for (name, e) in [("slip.e_y", s.e_y), ("slip.e_z", s.e_z)] {
                if !(-1.0..=1.0).contains(&finite(name, e)?) {
                    return Err(invalid(name, "must be within -1 and 1"));
                }
            }
            t.slip_e_y = s.e_y;
            t.slip_e_z = s.e_z;
            t.slip_oblique = match (s.oblique_from_deg, s.oblique_full_deg, s.oblique_e_t) {
                (None, None, None) => None,
                (Some(from), Some(full), Some(e_t)) => Some(ObliqueRise::new(from, full, e_t)?),
                _ => {
                    return Err(invalid(
                        "slip.oblique_*",
                        "give all three of oblique_from_deg, oblique_full_deg and oblique_e_t, or none",
                    ))
                }
            };
        }
        Ok(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::ClubFile;

    /// Table 3.3 and 3.4 as transcribed in tests/data/seed-tables.toml.
    #[test]
    #[allow(clippy::needless_range_loop)]
    fn presets_match_the_seed_tables() {
        let tables: toml::Value = toml::from_str(include_str!("../../../../../tests/data/seed-tables.toml")).unwrap();
        for (name, club) in [("driver", ClubSpec::driver()), ("iron7", ClubSpec::iron7())] {
            let t = ImpulseTuning::seed_for(&club);
            let adj = &tables["im"]["adjusted"][name];
            assert_eq!(t.adjusted_delta_mass_kg, adj["delta_mass_kg"].as_float().unwrap());
            let s = adj["ball_cg_shift_m"].as_array().unwrap();
            for i in 0..3 {
                assert_eq!(t.adjusted_ball_cg_shift_m[i], s[i].as_float().unwrap());
            }
            let slip = &tables["im"]["slip"][name];
            assert_eq!(t.slip_e_y, slip["e_y"].as_float().unwrap());
            assert_eq!(t.slip_e_z, slip["e_z"].as_float().unwrap());
        }
    }

    const FLAT: &str = r#"
        mass_kg = 0.204
        cg_to_face_center_m = [0.0408, 0.0114, 0.001]
        inertia_g_cm2 = [[2843.0, -733.0, 530.2], [-733.0, 5679.0, 0.5], [530.2, 0.5, 4085.0]]
        loft_deg = 9.8
    "#;

    #[test]
    fn a_flat_face_by_default_uses_the_iron_tuning() {
        let loaded = ClubFile::parse(FLAT).unwrap();
        assert_eq!(ImpulseTuning::from_sections(&loaded.club, &loaded.sections).unwrap(), ImpulseTuning::IRON7);
    }

    #[test]
    fn sections_override_and_bad_fields_are_named() {
        let text = format!("{FLAT}\n[slip]\ne_y = 0.1\ne_z = -0.2\n");
        let loaded = ClubFile::parse(&text).unwrap();
        let t = ImpulseTuning::from_sections(&loaded.club, &loaded.sections).unwrap();
        assert_eq!((t.slip_e_y, t.slip_e_z), (0.1, -0.2));
        assert_eq!(t.adjusted_delta_mass_kg, ImpulseTuning::IRON7.adjusted_delta_mass_kg);
        let bad = ClubFile::parse(&format!("{FLAT}\n[slip]\ne_y = 2.0\ne_z = 0.0\n")).unwrap();
        let e = ImpulseTuning::from_sections(&bad.club, &bad.sections).unwrap_err().to_string();
        assert!(e.contains("slip.e_y"), "{e}");
        let typo = ClubFile::parse(&format!("{FLAT}\n[adjusted]\ndelta_mass = 0.01\n")).unwrap();
        let e = ImpulseTuning::from_sections(&typo.club, &typo.sections).unwrap_err().to_string();
        assert!(e.contains("adjusted") && e.contains("delta_mass"), "{e}");
    }

    /// The obliquity law is read whole or not at all; its angles are checked.
    #[test]
    fn the_oblique_rise_is_read_whole() {
        let slip = "[slip]\ne_y = 0.0183\ne_z = 0.0423\n";
        let whole = format!("{FLAT}\n{slip}oblique_from_deg = 32.8\noblique_full_deg = 40.0\noblique_e_t = 0.25\n");
        let loaded = ClubFile::parse(&whole).unwrap();
        let t = ImpulseTuning::from_sections(&loaded.club, &loaded.sections).unwrap();
        assert_eq!(t.slip_oblique, Some(ObliqueRise { from_deg: 32.8, full_deg: 40.0, e_t: 0.25 }));
        for part in ["oblique_from_deg = 32.8\n", "oblique_full_deg = 40.0\noblique_e_t = 0.25\n"] {
            let loaded = ClubFile::parse(&format!("{FLAT}\n{slip}{part}")).unwrap();
            let e = ImpulseTuning::from_sections(&loaded.club, &loaded.sections).unwrap_err().to_string();
            assert!(e.contains("slip.oblique_*"), "{e}");
        }
        let reversed = format!("{FLAT}\n{slip}oblique_from_deg = 40\noblique_full_deg = 30.0\noblique_e_t = 0.25\n");
        let loaded = ClubFile::parse(&reversed).unwrap();
        let e = ImpulseTuning::from_sections(&loaded.club, &loaded.sections).unwrap_err().to_string();
        assert!(e.contains("slip.oblique_full_deg"), "{e}");
    }
}
