//! A club written as the TOML that [`ClubSpec::from_toml_str`] reads back (the fitted parameters in their
//! `[adjusted]`, `[slip]` and `[continuous]` sections), so `predict` and `run` accept a fitted club.

use serde::Serialize;

use super::IdentifyError;
use crate::equipment::ClubSpec;
use crate::face::FaceShape;
use crate::impact::continuous::TwoLayerParams;
use crate::math::Real;

#[derive(Serialize)]
struct Adjusted {
    delta_mass_kg: Real,
    ball_cg_shift_m: [Real; 3],
}

#[derive(Serialize)]
struct Slip {
    e_y: Real,
    e_z: Real,
}

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
    face_half_width_m: Real,
    face_half_height_m: Real,
    adjusted: Adjusted,
    slip: Slip,
    continuous: TwoLayerParams,
}

/// The club file of `club`, headed by `comment` (each line prefixed with `# `).
pub fn to_toml(club: &ClubSpec, comment: &str) -> Result<String, IdentifyError> {
    let (bulge, roll) = match club.face.shape {
        FaceShape::Plane => (None, None),
        FaceShape::Torus { bulge_radius_m, roll_radius_m } => {
            (bulge_radius_m.is_finite().then_some(bulge_radius_m), roll_radius_m.is_finite().then_some(roll_radius_m))
        }
    };
    let i = &club.inertia_kg_m2;
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
        face_half_width_m: club.face_half_width_m,
        face_half_height_m: club.face_half_height_m,
        adjusted: Adjusted {
            delta_mass_kg: club.impulse.adjusted_delta_mass_kg,
            ball_cg_shift_m: club.impulse.adjusted_ball_cg_shift_m.into(),
        },
        slip: Slip { e_y: club.impulse.slip_e_y, e_z: club.impulse.slip_e_z },
        continuous: club.continuous,
    };
    let body = toml::to_string(&file).map_err(|e| IdentifyError::Write(e.to_string()))?;
    let mut out: String = comment.lines().map(|l| format!("# {l}\n")).collect();
    out.push_str(&body);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_round_trip_through_the_club_file() {
        for mut club in [ClubSpec::driver(), ClubSpec::iron7()] {
            club.impulse.adjusted_delta_mass_kg = 0.0071;
            club.continuous.mu = 0.41;
            let text = to_toml(&club, "fitted\nby eq. 3.13").unwrap();
            assert!(text.starts_with("# fitted\n# by eq. 3.13\n"));
            let back = ClubSpec::from_toml_str(&text).unwrap();
            assert_eq!(back.impulse, club.impulse);
            assert_eq!(back.continuous, club.continuous);
            assert_eq!(back.face.shape, club.face.shape);
            assert!((back.face.loft_rad - club.face.loft_rad).abs() < 1e-12);
            assert!((back.inertia_kg_m2 - club.inertia_kg_m2).norm() < 1e-15);
        }
    }
}
