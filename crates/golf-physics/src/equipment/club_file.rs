//! The TOML form of a club, with validation that names the offending field.
//!
//! ```toml
//! name = "my driver"
//! mass_kg = 0.200
//! cg_to_face_center_m = [0.040, 0.011, 0.001]
//! inertia_g_cm2 = [[2843.0, -733.0, 530.2], [-733.0, 5679.0, 0.5], [530.2, 0.5, 4085.0]]
//! loft_deg = 10.5
//! bulge_radius_m = 0.305      # inf (or omitted) for a flat face
//! roll_radius_m = 0.305
//! # optional: shaft_mass_kg, shaft_heel_toe_inertia_g_cm2, lie_deg, face_half_width_m, face_half_height_m,
//! # face_outline_mm
//! # a polygon of impact locations [h toe +, v up +] in mm:
//! # face_outline_mm = [[-33.0, -17.0], [30.0, -19.0], [38.0, 0.0], [20.0, 27.0], [-33.0, 14.0]]
//! # and any model's section, read by that model: [adjusted], [slip], [continuous], ...
//! ```
//!
//! Every table in the file is a model's section; the rest are the club's physical fields.
//! `clubs/` holds example files: the seed's driver and 7-iron with the continuous model's one-cycle ball.

use std::collections::BTreeMap;

use serde::Deserialize;

use super::{g_cm2_to_kg_m2, ClubSpec, EquipmentError};
use crate::face::{Face, FaceShape};
use crate::math::{Real, Vector3};

/// A club as written in a TOML file. Unknown fields are rejected.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClubFile {
    /// The club's name (default: the file's name as given).
    pub name: Option<String>,
    /// Mass of the head (kg).
    pub mass_kg: Real,
    /// From the CG to the face centre, club frame (m).
    pub cg_to_face_center_m: [Real; 3],
    /// Inertia about the CG in the club frame, g cm^2 (the seed's unit). Give this or `inertia_kg_m2`.
    pub inertia_g_cm2: Option<[[Real; 3]; 3]>,
    /// Inertia about the CG in the club frame (kg m^2). Give this or `inertia_g_cm2`.
    pub inertia_kg_m2: Option<[[Real; 3]; 3]>,
    /// Static loft (deg).
    pub loft_deg: Real,
    /// Horizontal radius of the face's curvature (m; absent: flat across).
    pub bulge_radius_m: Option<Real>,
    /// Vertical radius of the face's curvature (m; absent: flat up the face).
    pub roll_radius_m: Option<Real>,
    /// Mass of the shaft (kg).
    pub shaft_mass_kg: Option<Real>,
    /// The inertia the shaft's tip adds about the heel-toe axis through the CG within a contact (g cm^2; default
    /// 0): models with a free head add it to the head's (`ClubSpec::shaft_heel_toe_inertia_kg_m2`).
    pub shaft_heel_toe_inertia_g_cm2: Option<Real>,
    /// Static lie (deg), the shaft's angle above the ground at address (default `ClubSpec::default_lie_deg`: a driver's for a curved face, an iron's for a flat one).
    pub lie_deg: Option<Real>,
    /// Half the usable face width, toe-heel (m).
    pub face_half_width_m: Option<Real>,
    /// Half the usable face height (m).
    pub face_half_height_m: Option<Real>,
    /// The face's outline as a polygon of impact locations `[h, v]` (mm).
    pub face_outline_mm: Option<Vec<[Real; 2]>>,
}

/// The model sections of a club file (`[adjusted]`, `[continuous]`, ...), each a TOML table that its model reads
/// and validates. Presets have none: every model then uses the seed's values for the club.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ModelSections(BTreeMap<String, toml::Table>);

impl ModelSections {
    /// The section named `name`, if the file has one.
    pub fn get(&self, name: &str) -> Option<&toml::Table> {
        self.0.get(name)
    }

    /// The names of the sections present.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.0.keys().map(String::as_str)
    }

    /// Adds or replaces a section (a fitted parameter set, a test's variation).
    pub fn insert(&mut self, name: &str, table: toml::Table) {
        self.0.insert(name.to_string(), table);
    }
}

/// A club as loaded from a preset or a file: the physical club and the file's model sections.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedClub {
    /// The physical club.
    pub club: ClubSpec,
    /// The file's model sections (`[adjusted]`, `[two_layer]`, ...).
    pub sections: ModelSections,
}

fn invalid(field: &'static str, reason: impl Into<String>) -> EquipmentError {
    EquipmentError::Invalid { field, reason: reason.into() }
}

fn finite(field: &'static str, v: Real) -> Result<Real, EquipmentError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(invalid(field, format!("must be a finite number, got {v}")))
    }
}

impl ClubFile {
    /// Parses a club file's text: its tables become [`ModelSections`], the rest must be the club's fields
    /// (unknown fields are errors that name them).
    pub fn parse(text: &str) -> Result<LoadedClub, EquipmentError> {
        let mut table: toml::Table = toml::from_str(text).map_err(|e| EquipmentError::Parse(e.into()))?;
        let section_names: Vec<String> = table.iter().filter(|(_, v)| v.is_table()).map(|(k, _)| k.clone()).collect();
        let mut sections = ModelSections::default();
        for name in section_names {
            if let Some(toml::Value::Table(t)) = table.remove(&name) {
                sections.insert(&name, t);
            }
        }
        let file = ClubFile::deserialize(toml::Value::Table(table)).map_err(|e| EquipmentError::Parse(e.into()))?;
        Ok(LoadedClub { club: file.into_spec()?, sections })
    }

    /// Validates the fields and builds the club.
    pub fn into_spec(self) -> Result<ClubSpec, EquipmentError> {
        let mass_kg = finite("mass_kg", self.mass_kg)?;
        if mass_kg <= 0.0 {
            return Err(invalid("mass_kg", format!("must be positive, got {mass_kg}")));
        }
        if mass_kg > 2.0 {
            return Err(invalid("mass_kg", format!("is {mass_kg} kg; a clubhead is well under 2 kg (units are kg)")));
        }
        let loft_deg = finite("loft_deg", self.loft_deg)?;
        if !(0.0..=70.0).contains(&loft_deg) {
            return Err(invalid("loft_deg", format!("must be within 0-70 deg, got {loft_deg}")));
        }
        let mut center = Vector3::zeros();
        for (i, v) in self.cg_to_face_center_m.iter().enumerate() {
            center[i] = finite("cg_to_face_center_m", *v)?;
        }
        if center.norm() > 0.2 {
            return Err(invalid("cg_to_face_center_m", "is more than 0.2 m long (units are metres)"));
        }
        let inertia = match (self.inertia_g_cm2, self.inertia_kg_m2) {
            (Some(t), None) => g_cm2_to_kg_m2(&t),
            (None, Some(t)) => crate::math::Matrix3::from_fn(|i, j| t[i][j]),
            (Some(_), Some(_)) => {
                return Err(invalid("inertia_g_cm2", "and inertia_kg_m2 are both given; give one"));
            }
            (None, None) => return Err(invalid("inertia_g_cm2", "is missing (or give inertia_kg_m2)")),
        };
        let field = if self.inertia_kg_m2.is_some() { "inertia_kg_m2" } else { "inertia_g_cm2" };
        if inertia.iter().any(|v| !v.is_finite()) {
            return Err(invalid(field, "has a non-finite entry"));
        }
        if (inertia - inertia.transpose()).abs().max() > 1e-9 * inertia.abs().max() {
            return Err(invalid(field, "must be symmetric"));
        }
        if inertia.cholesky().is_none() {
            return Err(invalid(field, "must be positive definite"));
        }
        let bulge = self.bulge_radius_m.unwrap_or(Real::INFINITY);
        let roll = self.roll_radius_m.unwrap_or(Real::INFINITY);
        for (name, r) in [("bulge_radius_m", bulge), ("roll_radius_m", roll)] {
            if r.is_nan() || r <= 0.0 {
                return Err(invalid(name, format!("must be positive (inf for flat), got {r}")));
            }
        }
        let shape = FaceShape::from_radii(bulge, roll);
        let (half_w, half_h) = match shape {
            FaceShape::Plane => (0.038, 0.025),
            FaceShape::Torus { .. } => (0.050, 0.030),
        };
        let face_half_width_m = finite("face_half_width_m", self.face_half_width_m.unwrap_or(half_w))?;
        let face_half_height_m = finite("face_half_height_m", self.face_half_height_m.unwrap_or(half_h))?;
        if face_half_width_m <= 0.0 {
            return Err(invalid("face_half_width_m", "must be positive"));
        }
        if face_half_height_m <= 0.0 {
            return Err(invalid("face_half_height_m", "must be positive"));
        }
        let face_outline = match self.face_outline_mm {
            Some(vertices_mm) => super::FaceOutline { vertices_mm },
            None if self.face_half_width_m.is_some() || self.face_half_height_m.is_some() => {
                super::FaceOutline::rectangle(face_half_width_m, face_half_height_m)
            }
            None if shape.is_curved() => super::FaceOutline::driver(),
            None => super::FaceOutline::iron7(),
        };
        face_outline.validate().map_err(|reason| invalid("face_outline_mm", reason))?;
        let shaft_mass_kg = finite("shaft_mass_kg", self.shaft_mass_kg.unwrap_or(0.0))?;
        if shaft_mass_kg < 0.0 {
            return Err(invalid("shaft_mass_kg", "must not be negative"));
        }
        let share_g_cm2 = finite("shaft_heel_toe_inertia_g_cm2", self.shaft_heel_toe_inertia_g_cm2.unwrap_or(0.0))?;
        if share_g_cm2 < 0.0 {
            return Err(invalid("shaft_heel_toe_inertia_g_cm2", "must not be negative"));
        }
        let lie_deg = finite("lie_deg", self.lie_deg.unwrap_or(ClubSpec::default_lie_deg(shape)))?;
        if !(lie_deg > 30.0 && lie_deg < 80.0) {
            // The same open range as the ground model's sole (`SoleSpec::validate`), which takes this lie.
            return Err(invalid("lie_deg", format!("must lie in (30, 80) deg, got {lie_deg}")));
        }
        let share_kg_m2 = share_g_cm2 * 1e-7;
        let mut inertia = inertia;
        inertia[(2, 2)] += share_kg_m2;
        let inertia_inv = inertia.try_inverse().ok_or_else(|| invalid(field, "must be invertible"))?;
        Ok(ClubSpec {
            name: self.name.unwrap_or_else(|| "custom".to_string()),
            mass_kg,
            inertia_kg_m2: inertia,
            inertia_inv_kg_m2: inertia_inv,
            shaft_heel_toe_inertia_kg_m2: share_kg_m2,
            face: Face { center_m: center, loft_rad: loft_deg.to_radians(), shape },
            face_half_width_m,
            face_half_height_m,
            face_outline,
            shaft_mass_kg,
            lie_deg,
        })
    }
}

impl ClubSpec {
    /// The physical club of a TOML club file's text (its model sections are ignored; see [`ClubFile::parse`] to
    /// keep them). A preset by name: `ClubSpec::preset` (presets.rs).
    pub fn from_toml_str(text: &str) -> Result<Self, EquipmentError> {
        ClubFile::parse(text).map(|loaded| loaded.club)
    }
}

#[cfg(test)]
mod tests {
    use super::super::*;

    const DRIVER: &str = r#"
        name = "seed driver"
        mass_kg = 0.204
        cg_to_face_center_m = [0.0408, 0.0114, 0.001]
        inertia_g_cm2 = [[2843.0, -733.0, 530.2], [-733.0, 5679.0, 0.5], [530.2, 0.5, 4085.0]]
        loft_deg = 9.8
        bulge_radius_m = 0.305
        roll_radius_m = 0.305
        shaft_mass_kg = 0.060
        face_half_width_m = 0.050
        face_half_height_m = 0.030
    "#;

    #[test]
    fn the_seed_driver_as_a_file_equals_the_preset() {
        let club = ClubSpec::from_toml_str(DRIVER).unwrap();
        let preset = ClubSpec::driver();
        assert_eq!(club.name, "seed driver");
        assert_eq!(club.face, preset.face);
        assert_eq!(club.inertia_kg_m2, preset.inertia_kg_m2);
        assert_eq!(club.shaft_mass_kg, preset.shaft_mass_kg);
        assert_eq!(
            (club.face_half_width_m, club.face_half_height_m),
            (preset.face_half_width_m, preset.face_half_height_m)
        );
    }

    fn err_of(text: &str) -> String {
        ClubSpec::from_toml_str(text).unwrap_err().to_string()
    }

    #[test]
    fn bad_fields_are_named() {
        assert!(err_of(&DRIVER.replace("mass_kg = 0.204", "mass_kg = -0.2")).contains("mass_kg"));
        assert!(err_of(&DRIVER.replace("loft_deg = 9.8", "loft_deg = 75")).contains("loft_deg"));
        let not_pd =
            DRIVER.replace("[2843.0, -733.0, 530.2], [-733.0, 5679.0", "[2843.0, -9733.0, 530.2], [-9733.0, 5679.0");
        let e = err_of(&not_pd);
        assert!(e.contains("inertia_g_cm2") && e.contains("positive definite"), "{e}");
        let missing = DRIVER.replace("mass_kg = 0.204", "");
        assert!(err_of(&missing).contains("mass_kg"));
        let unknown = format!("{DRIVER}\ncolour = \"red\"");
        assert!(err_of(&unknown).contains("colour"));
        let no_inertia = DRIVER.lines().filter(|l| !l.contains("inertia")).collect::<Vec<_>>().join("\n");
        assert!(err_of(&no_inertia).contains("inertia_g_cm2"));
    }

    #[test]
    fn tables_are_model_sections_and_the_rest_is_the_club() {
        let text = format!("{DRIVER}\n[adjusted]\ndelta_mass_kg = 0.003\nball_cg_shift_m = [0.0, 0.0, 0.0]\n");
        let loaded = ClubFile::parse(&text).unwrap();
        assert_eq!(loaded.club, ClubSpec::from_toml_str(DRIVER).unwrap());
        assert_eq!(loaded.sections.names().collect::<Vec<_>>(), ["adjusted"]);
        let adjusted = loaded.sections.get("adjusted").unwrap();
        assert_eq!(adjusted["delta_mass_kg"].as_float(), Some(0.003));
    }

    /// The outline: given as a polygon, defaulted to the half-width rectangle, or to the preset's; an outline
    /// that misses the face centre is refused by name.
    #[test]
    fn the_face_outline_loads_and_defaults() {
        use crate::equipment::FaceOutline;
        let poly = format!("{DRIVER}\nface_outline_mm = [[-20.0, -10.0], [20.0, -10.0], [0.0, 15.0]]");
        let club = ClubSpec::from_toml_str(&poly).unwrap();
        assert!(club.on_face(0.0, 0.0) && !club.on_face(0.019, 0.012));
        let rect = ClubSpec::from_toml_str(DRIVER).unwrap();
        assert_eq!(rect.face_outline, FaceOutline::rectangle(0.050, 0.030));
        let plain = DRIVER.lines().filter(|l| !l.contains("face_half")).collect::<Vec<_>>().join("\n");
        assert_eq!(ClubSpec::from_toml_str(&plain).unwrap().face_outline, FaceOutline::driver());
        let off = format!("{DRIVER}\nface_outline_mm = [[10.0, 10.0], [20.0, 10.0], [20.0, 20.0]]");
        assert!(err_of(&off).contains("face_outline_mm"));
    }
}
