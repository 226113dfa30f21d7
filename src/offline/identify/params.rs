//! The parameters chosen for identification ([`ParamSpace`]) of a model whose registry entry has identifiable
//! parameters ([`FitModel`], seed section 3.1.3).
//!
//! A model's parameter set is part of its registry entry ([`crate::impact::identifiable`]): its section, the
//! section's defaults for a club and its parameters (each a key of the section, or an element of an array key).
//! The model itself is built through [`crate::impact::registry`] from the club with the section written, so a
//! fitted club is a club file `predict` and `run` accept.
//!
//! The optimisers work in the unit cube: a parameter maps linearly (or logarithmically, for those spanning
//! decades) from `[0, 1]` onto its bounds.

use super::IdentifyError;
use crate::equipment::LoadedClub;
pub use crate::impact::identifiable::{BuildFn, FitModel, ParamDef, COARSE_STEP_FACTOR};
use crate::math::Real;

/// A model and the parameters chosen for identification.
#[derive(Debug, Clone)]
pub struct ParamSpace {
    pub model: &'static FitModel,
    pub defs: Vec<ParamDef>,
}

impl ParamSpace {
    /// The model's parameters, all of them (`names` empty) or the named ones in the given order.
    pub fn new(model: &'static FitModel, names: &[String]) -> Result<Self, IdentifyError> {
        if names.is_empty() {
            return Ok(ParamSpace { model, defs: model.params.to_vec() });
        }
        let defs = names
            .iter()
            .map(|n| {
                model.params.iter().find(|d| d.name == n).copied().ok_or_else(|| IdentifyError::UnknownParam {
                    model: model.name.to_string(),
                    name: n.clone(),
                    known: model.params.iter().map(|d| d.name).collect::<Vec<_>>().join(", "),
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(ParamSpace { model, defs })
    }

    pub fn names(&self) -> Vec<&'static str> {
        self.defs.iter().map(|d| d.name).collect()
    }

    /// The club's current values (SI).
    pub fn get(&self, club: &LoadedClub) -> Vec<Real> {
        let table = self.model.section_of(club);
        self.defs.iter().map(|d| d.read(&table).unwrap_or(Real::NAN)).collect()
    }

    /// A copy of `club` with the values (SI) set in the model's section.
    pub fn club_with(&self, club: &LoadedClub, values: &[Real]) -> LoadedClub {
        let mut table = self.model.section_of(club);
        for (d, v) in self.defs.iter().zip(values) {
            d.write(&mut table, *v);
        }
        let mut out = club.clone();
        out.sections.insert(self.model.section, table);
        out
    }

    /// Unit-cube coordinates of SI values.
    pub fn to_unit(&self, values: &[Real]) -> Vec<Real> {
        self.defs.iter().zip(values).map(|(d, v)| d.to_unit(*v)).collect()
    }

    /// SI values of unit-cube coordinates.
    pub fn from_unit(&self, u: &[Real]) -> Vec<Real> {
        self.defs.iter().zip(u).map(|(d, x)| d.from_unit(*x)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::{BallSpec, ClubSpec, ModelSections};
    use crate::impact::{registry, FitModelError};

    fn preset(club: ClubSpec) -> LoadedClub {
        LoadedClub { club, sections: ModelSections::default() }
    }

    #[test]
    fn get_set_and_the_unit_cube_round_trip() {
        for model in registry::fit_models() {
            let space = ParamSpace::new(model, &[]).unwrap();
            let club = preset(ClubSpec::driver());
            let v = space.get(&club);
            let back = space.from_unit(&space.to_unit(&v));
            for (a, b) in v.iter().zip(&back) {
                assert!((a - b).abs() <= 1e-12 * a.abs().max(1e-6), "{}: {a} vs {b}", model.name);
            }
            let mid = space.from_unit(&vec![0.5; v.len()]);
            let with = space.club_with(&club, &mid);
            assert_eq!(space.get(&with), mid);
            // The registry builds the model from the written section.
            assert!(model.build(&with, &BallSpec::SEED).is_ok(), "{}", model.name);
        }
        // Table 3.3's driver values (tests/data/seed-tables.toml) are the starting point.
        let adjusted = ParamSpace::new(FitModel::parse("adjusted").unwrap(), &[]).unwrap();
        assert_eq!(adjusted.get(&preset(ClubSpec::driver())), vec![0.00254, 0.0, -0.482e-3, -0.068e-3]);
        let err = ParamSpace::new(FitModel::parse("slip").unwrap(), &["e_x".into()]).unwrap_err();
        assert!(err.to_string().contains("e_y, e_z"), "{err}");
        assert!(matches!(FitModel::parse("standard"), Err(FitModelError::NothingToFit(_))));
        assert!(matches!(FitModel::parse("nope"), Err(FitModelError::UnknownModel { .. })));
    }
}
