//! Equipment: physical data only - the clubhead and the ball (later the shaft, the sole and the soil) - with
//! presets from the seed's tables, and club and soil files parsed from their text (reading them from disk is the
//! caller's: `impactd::equipment::load_club`).
//!
//! Presets transcribe Table 3.1 (clubheads and ball) of the seed, as recorded in `tests/data/seed-tables.toml`.
//! A model's identified parameters (Table 3.3-3.5) are not equipment: they live with the model
//! (`impact::impulse::ImpulseTuning`, `impact::continuous::TwoLayerParams`) and load from the model's own section
//! of the club file ([`ModelSections`]).

mod ball;
mod club;
mod club_file;
mod outline;
pub mod presets;
pub mod shaft;
pub mod soil;
pub mod sole;

pub use ball::BallSpec;
pub use club::ClubSpec;
pub use club_file::{ClubFile, LoadedClub, ModelSections};
pub use outline::FaceOutline;

use crate::math::{Matrix3, Real};

/// A TOML error that reads as its message alone (its line, column and excerpt are not what a club file's error
/// says); the error itself is kept in it.
#[derive(Debug, Clone, PartialEq)]
pub struct TomlMessage(pub Box<toml::de::Error>);

impl std::fmt::Display for TomlMessage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.0.message())
    }
}

impl std::error::Error for TomlMessage {}

impl From<toml::de::Error> for TomlMessage {
    fn from(e: toml::de::Error) -> Self {
        TomlMessage(Box::new(e))
    }
}

/// Errors of the equipment layer.
#[derive(Debug, thiserror::Error)]
pub enum EquipmentError {
    #[error("unknown club preset '{0}' (expected driver, wood3, hybrid, iron4-iron9, pw, gw, sw or lw, or a path to a .toml file)")]
    /// A club name that is no preset (and no `.toml` path).
    UnknownPreset(String),
    #[error("unknown soil '{0}' (expected soft, medium or firm, or a path to a soil .toml file)")]
    /// A soil name that is no preset, or a soil file that does not exist.
    UnknownSoil(String),
    #[error("club file is not valid TOML for a club: {0}")]
    /// A club or soil file's text that is not valid TOML for it.
    Parse(#[source] TomlMessage),
    /// A soil file that could not be read (said as a club file's parse error, as it always was).
    #[error("club file is not valid TOML for a club: {path}: {source}")]
    SoilRead {
        /// The soil file's path as given.
        path: String,
        #[source]
        /// Why it could not be read.
        source: std::io::Error,
    },
    #[error("club field `{field}` {reason}")]
    /// A field out of its range, or inconsistent with another.
    Invalid {
        /// The field, as the file names it.
        field: &'static str,
        /// What is wrong with it.
        reason: String,
    },
    #[error("club file {path}: {source}")]
    /// A club file that could not be read.
    Read {
        /// The path as given.
        path: String,
        /// Why it could not be read.
        source: std::io::Error,
    },
    #[error("club file {path} is larger than {max_bytes} bytes")]
    /// A club file over the size limit.
    TooLarge {
        /// The path as given.
        path: String,
        /// The limit (bytes).
        max_bytes: u64,
    },
    /// A club path that names a FIFO, a device, a socket or a directory: only regular files are read.
    #[error("club file {path} is {kind}, not a regular file")]
    NotRegularFile {
        /// The path as given.
        path: String,
        /// What it names instead (`a FIFO`, `a directory`, ...).
        kind: &'static str,
    },
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
    #[allow(clippy::needless_range_loop)]
    fn presets_match_the_seed_tables() {
        let text = include_str!("../../../../tests/data/seed-tables.toml");
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
