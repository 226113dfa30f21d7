//! A club written as the club file [`crate::equipment::load_club`] reads back, with its model sections
//! (`[adjusted]`, `[slip]`, `[continuous]`, ...), so `predict --club` and `run` accept a fitted club.

use serde::Serialize;

use super::IdentifyError;
use crate::equipment::LoadedClub;
use crate::face::FaceShape;
use crate::math::Real;

#[derive(Serialize)]
struct File {
    name: String,
    mass_kg: Real,
    cg_to_face_center_m: [Real; 3],
    inertia_kg_m2: [[Real; 3]; 3],
    loft_deg: Real,
    #[serde(skip_serializing_if = "Option::is_none")]
    bulge_radius_m: Option<Real>,
    #[serde(skip_serializing_if = "Option::is_none")]
    roll_radius_m: Option<Real>,
    shaft_mass_kg: Real,
    #[serde(skip_serializing_if = "is_zero")]
    shaft_heel_toe_inertia_g_cm2: Real,
    face_half_width_m: Real,
    face_half_height_m: Real,
    /// The model sections (`[adjusted]`, `[continuous]`, ...), each as its model reads it.
    #[serde(flatten)]
    sections: std::collections::BTreeMap<String, toml::Table>,
}

fn is_zero(x: &Real) -> bool {
    *x == 0.0
}

/// The club file of `club`, headed by `comment` (each line prefixed with `# `).
pub fn to_toml(loaded: &LoadedClub, comment: &str) -> Result<String, IdentifyError> {
    let club = &loaded.club;
    let (bulge, roll) = match club.face.shape {
        FaceShape::Plane => (None, None),
        FaceShape::Torus { bulge_radius_m, roll_radius_m } => {
            (bulge_radius_m.is_finite().then_some(bulge_radius_m), roll_radius_m.is_finite().then_some(roll_radius_m))
        }
    };
    let i = &club.head_inertia_kg_m2();
    let file = File {
        name: club.name.clone(),
        mass_kg: club.mass_kg,
        cg_to_face_center_m: club.face.center_m.into(),
        inertia_kg_m2: [
            [i[(0, 0)], i[(0, 1)], i[(0, 2)]],
            [i[(1, 0)], i[(1, 1)], i[(1, 2)]],
            [i[(2, 0)], i[(2, 1)], i[(2, 2)]],
        ],
        loft_deg: club.face.loft_rad.to_degrees(),
        bulge_radius_m: bulge,
        roll_radius_m: roll,
        shaft_mass_kg: club.shaft_mass_kg,
        shaft_heel_toe_inertia_g_cm2: club.shaft_heel_toe_inertia_kg_m2 * 1e7,
        face_half_width_m: club.face_half_width_m,
        face_half_height_m: club.face_half_height_m,
        sections: loaded
            .sections
            .names()
            .filter_map(|n| loaded.sections.get(n).map(|t| (n.to_string(), t.clone())))
            .collect(),
    };
    let body = toml::to_string(&file).map_err(IdentifyError::Write)?;
    let mut out: String = comment.lines().map(|l| format!("# {l}\n")).collect();
    out.push_str(&body);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::{ClubFile, ClubSpec, ModelSections};

    #[test]
    fn presets_round_trip_through_the_club_file() {
        for club in [ClubSpec::driver(), ClubSpec::iron7()] {
            let mut sections = ModelSections::default();
            let mut slip = toml::Table::new();
            slip.insert("e_y".into(), 0.0071.into());
            slip.insert("e_z".into(), (-0.02).into());
            sections.insert("slip", slip.clone());
            let loaded = LoadedClub { club: club.clone(), sections };
            let text = to_toml(&loaded, "fitted\nby eq. 3.13").unwrap();
            assert!(text.starts_with("# fitted\n# by eq. 3.13\n"));
            let back = ClubFile::parse(&text).unwrap();
            assert_eq!(back.sections.get("slip"), Some(&slip));
            assert_eq!(back.club.face.shape, club.face.shape);
            assert!((back.club.face.loft_rad - club.face.loft_rad).abs() < 1e-12);
            assert!((back.club.inertia_kg_m2 - club.inertia_kg_m2).norm() < 1e-15);
        }
    }
}
