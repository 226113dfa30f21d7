//! A registry model's identifiable parameters by name ([`FitModel::parse`]), and the model built from a club whose
//! section holds them ([`FitModel::build`]). Beside [`identifiable`](super::identifiable), which defines the
//! parameter sets: these go through the [`registry`](super::registry), which holds them.

use std::sync::Arc;

use super::identifiable::FitModel;
use super::registry::{self, BuildOptions};
use super::{ImpactError, ImpactModel};
use crate::equipment::{BallSpec, LoadedClub};

/// Why a model name has no parameter set to identify.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum FitModelError {
    /// No model of the registry has this name.
    #[error("no parameter set for model `{name}` (fit: {fittable})")]
    UnknownModel {
        /// The name as given.
        name: String,
        /// The models that have one, comma-separated.
        fittable: String,
    },
    /// The model has no identifiable parameters.
    #[error("model `{0}` has no parameters to identify")]
    NothingToFit(String),
}

impl FitModel {
    /// The identifiable parameters of the registry's model `name`.
    pub fn parse(name: &str) -> Result<&'static FitModel, FitModelError> {
        match registry::entry(name) {
            Some(e) => e.fit.as_ref().ok_or_else(|| FitModelError::NothingToFit(name.to_string())),
            None => Err(FitModelError::UnknownModel {
                name: name.to_string(),
                fittable: registry::fit_models().map(|m| m.name).collect::<Vec<_>>().join(", "),
            }),
        }
    }

    /// The model with its parameters from `club`'s sections, through the registry.
    pub fn build(&self, club: &LoadedClub, ball: &BallSpec) -> Result<Arc<dyn ImpactModel>, ImpactError> {
        registry::build_one(self.name, club, &BuildOptions { ball: *ball, ..Default::default() })
    }

    /// The club's section for this model, or its defaults.
    pub fn section_of(&self, club: &LoadedClub) -> toml::Table {
        club.sections.get(self.section).cloned().unwrap_or_else(|| (self.defaults)(&club.club))
    }
}
