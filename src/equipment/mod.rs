//! Equipment: the clubhead, the ball and (later) the soil, with presets from the seed's tables.
//!
//! Presets transcribe Table 3.1 (clubheads and ball), Table 3.3 (adjusted impulse-momentum parameters) and
//! Table 3.4 (tangential restitution) of the seed, as recorded in `tests/data/seed-tables.toml`. A user's own
//! club loads from TOML with the same field names ([`ClubSpec::from_toml_str`]); every field is validated and a
//! bad one is named in the error.

mod club_file;
mod outline;

use crate::face::{Face, FaceShape};
use crate::math::{Matrix3, Real, Vector3};

pub use club_file::ClubFile;
pub use outline::FaceOutline;

/// Errors of the equipment layer.
#[derive(Debug, thiserror::Error)]
pub enum EquipmentError {
    #[error("unknown club preset '{0}' (expected driver or iron7, or a path to a .toml file)")]
    UnknownPreset(String),
    #[error("club file is not valid TOML for a club: {0}")]
    Parse(String),
    #[error("club field `{field}` {reason}")]
    Invalid { field: &'static str, reason: String },
}

/// The golf ball (Table 3.1): a sphere with isotropic inertia about its centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallSpec {
    pub mass_kg: Real,
    pub radius_m: Real,
    /// Moment of inertia about any axis through the centre (kg m^2).
    pub inertia_kg_m2: Real,
}

impl BallSpec {
    /// The seed's ball, Table 3.1: 45.9 g, 21.3 mm, 83.36 g cm^2.
    pub const SEED: BallSpec = BallSpec { mass_kg: 0.0459, radius_m: 0.0213, inertia_kg_m2: 83.36e-7 };
}

impl Default for BallSpec {
    fn default() -> Self {
        Self::SEED
    }
}

/// Parameters of the adjusted (Danaei, Table 3.3) and slip (Cross and Dewhurst, Table 3.4) impulse-momentum
/// variants, identified per club in the seed.
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
}

impl ImpulseTuning {
    /// Table 3.3 and 3.4, driver column.
    pub const DRIVER: ImpulseTuning = ImpulseTuning {
        adjusted_delta_mass_kg: 0.00254,
        adjusted_ball_cg_shift_m: Vector3::new(0.0, -0.482e-3, -0.068e-3),
        slip_e_y: -0.0103,
        slip_e_z: -0.0151,
    };
    /// Table 3.3 and 3.4, 7-iron column.
    pub const IRON7: ImpulseTuning = ImpulseTuning {
        adjusted_delta_mass_kg: 0.0101,
        adjusted_ball_cg_shift_m: Vector3::new(-0.395e-3, -0.182e-3, -0.071e-3),
        slip_e_y: 0.0183,
        slip_e_z: 0.0423,
    };
}

/// A clubhead, described in its club frame (origin at the CG; x forward, y up, z toward the toe at a square
/// address).
#[derive(Debug, Clone, PartialEq)]
pub struct ClubSpec {
    /// Preset name or the `name` field of a club file.
    pub name: String,
    pub mass_kg: Real,
    /// Inertia tensor about the CG, club frame (kg m^2).
    pub inertia_kg_m2: Matrix3,
    /// Its inverse, kept beside it for the solvers.
    pub inertia_inv_kg_m2: Matrix3,
    /// Face centre, static loft and curvature.
    pub face: Face,
    /// Half the usable face width (toe-heel) and height (m): the box the impact detector searches.
    pub face_half_width_m: Real,
    pub face_half_height_m: Real,
    /// The face's outline: impact locations outside are rejected ([`FaceOutline`]).
    pub face_outline: FaceOutline,
    /// Shaft mass (kg), for reference (the seed's section 3.1.4).
    pub shaft_mass_kg: Real,
    /// Variant parameters of the impulse-momentum family.
    pub impulse: ImpulseTuning,
    /// Parameters of the continuous two-layer model (Table 3.5).
    pub continuous: crate::impact::continuous::TwoLayerParams,
}

impl ClubSpec {
    /// The seed's driver (Table 3.1, 3.3, 3.4).
    pub fn driver() -> Self {
        Self::build(
            "driver",
            0.204,
            [[2843.0, -733.0, 530.2], [-733.0, 5679.0, 0.5], [530.2, 0.5, 4085.0]],
            Vector3::new(0.0408, 0.0114, 0.001),
            9.8,
            FaceShape::Torus { bulge_radius_m: 0.305, roll_radius_m: 0.305 },
            (0.050, 0.030),
            0.060,
            ImpulseTuning::DRIVER,
        )
    }

    /// The seed's 7-iron (Table 3.1, 3.3, 3.4).
    pub fn iron7() -> Self {
        Self::build(
            "iron7",
            0.264,
            [[2752.0, -51.0, -53.0], [-51.0, 2889.0, -429.0], [-53.0, -429.0, 576.6]],
            Vector3::new(0.00361, 0.00485, 0.00112),
            30.5,
            FaceShape::Plane,
            (0.038, 0.025),
            0.104,
            ImpulseTuning::IRON7,
        )
    }

    #[allow(clippy::too_many_arguments)]
    fn build(
        name: &str,
        mass_kg: Real,
        inertia_g_cm2: [[Real; 3]; 3],
        cg_to_face_center_m: Vector3,
        loft_deg: Real,
        shape: FaceShape,
        (face_half_width_m, face_half_height_m): (Real, Real),
        shaft_mass_kg: Real,
        impulse: ImpulseTuning,
    ) -> Self {
        let inertia_kg_m2 = g_cm2_to_kg_m2(&inertia_g_cm2);
        ClubSpec {
            name: name.to_string(),
            mass_kg,
            inertia_inv_kg_m2: inertia_kg_m2.try_inverse().unwrap_or_else(Matrix3::zeros),
            inertia_kg_m2,
            face: Face { center_m: cg_to_face_center_m, loft_rad: loft_deg.to_radians(), shape },
            face_half_width_m,
            face_half_height_m,
            face_outline: if shape.is_curved() { FaceOutline::driver() } else { FaceOutline::iron7() },
            shaft_mass_kg,
            impulse,
            continuous: if shape.is_curved() {
                crate::impact::continuous::TwoLayerParams::DRIVER
            } else {
                crate::impact::continuous::TwoLayerParams::IRON7
            },
        }
    }

    /// A preset by name: `driver` or `iron7`.
    pub fn preset(name: &str) -> Result<Self, EquipmentError> {
        match name {
            "driver" => Ok(Self::driver()),
            "iron7" | "7iron" | "7i" => Ok(Self::iron7()),
            other => Err(EquipmentError::UnknownPreset(other.to_string())),
        }
    }

    /// Names of the presets.
    pub const PRESETS: [&'static str; 2] = ["driver", "iron7"];

    /// A club from the text of a TOML club file (the fields of [`ClubFile`]).
    pub fn from_toml_str(text: &str) -> Result<Self, EquipmentError> {
        let file: ClubFile = toml::from_str(text).map_err(|e| EquipmentError::Parse(e.message().to_string()))?;
        file.into_spec()
    }

    /// Static loft in degrees.
    pub fn loft_deg(&self) -> Real {
        self.face.loft_rad.to_degrees()
    }

    /// Whether the impact location `(h, v)` (m) is on the face (inside its outline).
    pub fn on_face(&self, h_m: Real, v_m: Real) -> bool {
        self.face_outline.contains(h_m, v_m)
    }
}

/// Converts a g cm^2 tensor (the seed's unit) to kg m^2.
pub fn g_cm2_to_kg_m2(t: &[[Real; 3]; 3]) -> Matrix3 {
    Matrix3::from_fn(|i, j| t[i][j] * 1e-7)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The presets must equal the seed tables as transcribed in tests/data/seed-tables.toml.
    #[test]
    fn presets_match_the_seed_tables() {
        let text = include_str!("../../tests/data/seed-tables.toml");
        let tables: toml::Value = toml::from_str(text).unwrap();
        for (name, club) in [("driver", ClubSpec::driver()), ("iron7", ClubSpec::iron7())] {
            let t = &tables["clubs"][name];
            let f = |k: &str| t[k].as_float().unwrap();
            assert_eq!(club.mass_kg, f("mass_kg"));
            assert!((club.loft_deg() - f("loft_deg")).abs() < 1e-12);
            assert_eq!(club.shaft_mass_kg, f("shaft_mass_kg"));
            let c = t["cg_to_face_center_m"].as_array().unwrap();
            for i in 0..3 {
                assert_eq!(club.face.center_m[i], c[i].as_float().unwrap());
                let row = t["inertia_g_cm2"][i].as_array().unwrap();
                for j in 0..3 {
                    assert!((club.inertia_kg_m2[(i, j)] - row[j].as_float().unwrap() * 1e-7).abs() < 1e-18);
                }
            }
            let adj = &tables["im"]["adjusted"][name];
            assert_eq!(club.impulse.adjusted_delta_mass_kg, adj["delta_mass_kg"].as_float().unwrap());
            let s = adj["ball_cg_shift_m"].as_array().unwrap();
            for i in 0..3 {
                assert_eq!(club.impulse.adjusted_ball_cg_shift_m[i], s[i].as_float().unwrap());
            }
            let c = &tables["continuous"]["two_layer"][name];
            let p = club.continuous;
            assert_eq!(p.k_v_n_per_m3, c["k_v_n_per_m3"].as_float().unwrap());
            assert_eq!(p.d_s_per_m, c["d_s_per_m"].as_float().unwrap());
            assert_eq!(p.mu, c["mu"].as_float().unwrap());
            assert_eq!(p.k_ball_nm_per_rad, c["k_ball_nm_per_rad"].as_float().unwrap());
            assert_eq!(p.c_ball_nms_per_rad, c["c_ball_nms_per_rad"].as_float().unwrap());
            assert_eq!(p.cover_thickness_m, c["cover_thickness_m"].as_float().unwrap());
            assert_eq!(p.v_tr_mps, c["v_tr_mps"].as_float().unwrap());
            let slip = &tables["im"]["slip"][name];
            assert_eq!(club.impulse.slip_e_y, slip["e_y"].as_float().unwrap());
            assert_eq!(club.impulse.slip_e_z, slip["e_z"].as_float().unwrap());
        }
        let b = &tables["ball"];
        assert_eq!(BallSpec::SEED.mass_kg, b["mass_kg"].as_float().unwrap());
        assert_eq!(BallSpec::SEED.radius_m, b["radius_m"].as_float().unwrap());
        assert_eq!(BallSpec::SEED.inertia_kg_m2, b["inertia_kg_m2"].as_float().unwrap());
    }

    #[test]
    fn preset_inertias_are_positive_definite() {
        for club in [ClubSpec::driver(), ClubSpec::iron7()] {
            assert!(club.inertia_kg_m2.cholesky().is_some(), "{}", club.name);
            assert!((club.inertia_kg_m2 * club.inertia_inv_kg_m2 - Matrix3::identity()).norm() < 1e-12);
        }
    }
}
