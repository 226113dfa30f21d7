//! The model registry: one list of every impact model, by the name users type (`--model`, `model = "..."` in
//! the daemon's config), with the club-file section its parameters load from.
//!
//! Adding a model is one new file behind [`ImpactModel`] plus one entry in [`MODELS`]. `predict`, `map`, `bench`,
//! the evaluation and the daemon all build their models here.

use std::sync::Arc;

use super::continuous::hertzian::HertzModel;
use super::continuous::{ContinuousModel, TwoLayerParams};
use super::identifiable::{self, FitModel};
use super::impulse::{ImpulseModel, ImpulseTuning, ImpulseVariant};
use super::{ImpactError, ImpactModel};
use crate::equipment::{BallSpec, LoadedClub};
use crate::math::Real;

/// Options every model build takes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BuildOptions {
    /// The impulse-momentum models' coefficient of restitution.
    pub cor: Real,
    /// The ball (the seed's by default).
    pub ball: BallSpec,
}

impl Default for BuildOptions {
    fn default() -> Self {
        BuildOptions { cor: super::impulse::DEFAULT_COR, ball: BallSpec::SEED }
    }
}

/// A registered model.
pub struct ModelEntry {
    /// The name users type.
    pub name: &'static str,
    /// One line for `--help` and errors.
    pub summary: &'static str,
    /// The club-file sections its parameters load from.
    pub sections: &'static [&'static str],
    /// Whether it resolves the contact in time (and so has a trace of forces).
    pub resolved_in_time: bool,
    /// Its identifiable parameters (`impactd fit`), if it has any.
    pub fit: Option<FitModel>,
    build: BuildFn,
}

/// How an entry builds its model from a club and the options.
type BuildFn = fn(&LoadedClub, &BuildOptions) -> Result<Arc<dyn ImpactModel>, ImpactError>;

fn impulse(variant: ImpulseVariant, club: &LoadedClub, o: &BuildOptions) -> Result<Arc<dyn ImpactModel>, ImpactError> {
    let tuning = ImpulseTuning::from_sections(&club.club, &club.sections)?;
    Ok(Arc::new(ImpulseModel::new(variant).with_cor(o.cor).with_tuning(tuning)))
}

/// The iron-plus-ground model, its soil, sole and shaft from the `[soil]`, `[sole]` and `[shaft]` sections (firm
/// soil of Table 4.3 by default), its ball from the `[continuous]` section.
fn ground(club: &LoadedClub, o: &BuildOptions) -> Result<Arc<dyn ImpactModel>, ImpactError> {
    let mut model = super::continuous::iron_ground::GroundModel::from_sections(&club.sections, club.club.lie_deg)?;
    model.params = TwoLayerParams::from_sections(&club.sections, &club.club, &o.ball)?;
    let equipment = super::Equipment { club: club.club.clone(), ball: o.ball };
    Ok(Arc::new(model.prepare(&equipment)?))
}

fn continuous(club: &LoadedClub, o: &BuildOptions) -> Result<Arc<dyn ImpactModel>, ImpactError> {
    let params = TwoLayerParams::from_sections(&club.sections, &club.club, &o.ball)?;
    Ok(Arc::new(ContinuousModel { params, ..ContinuousModel::default() }))
}

/// Every model.
pub const MODELS: &[ModelEntry] = &[
    ModelEntry {
        name: "standard",
        summary: "impulse-momentum, rolling (seed 3.1, Table 3.2)",
        sections: &[],
        resolved_in_time: false,
        fit: None,
        build: |c, o| impulse(ImpulseVariant::Standard, c, o),
    },
    ModelEntry {
        name: "adjusted",
        summary: "impulse-momentum with Danaei's added mass and ball-CG shift (seed 3.1.1, Table 3.3)",
        sections: &["adjusted"],
        resolved_in_time: false,
        fit: Some(identifiable::ADJUSTED),
        build: |c, o| impulse(ImpulseVariant::Adjusted, c, o),
    },
    ModelEntry {
        name: "slip",
        summary: "impulse-momentum with Cross and Dewhurst's tangential restitution (seed 3.1.2, Table 3.4)",
        sections: &["slip"],
        resolved_in_time: false,
        fit: Some(identifiable::SLIP),
        build: |c, o| impulse(ImpulseVariant::Slip, c, o),
    },
    ModelEntry {
        name: "continuous",
        summary: "two-layer ball, volumetric contact, free head, in time (seed 3.2.1, Table 3.5 read for one \
                  force reversal per contact)",
        sections: &["continuous"],
        resolved_in_time: true,
        fit: Some(identifiable::CONTINUOUS),
        build: continuous,
    },
    ModelEntry {
        name: "maw",
        summary:
            "rigid ball, Hertz normal force and Maw's stick-slip rings, free head, in time (seed 3.2.2, Table 3.6)",
        sections: &["maw"],
        resolved_in_time: true,
        fit: Some(identifiable::MAW),
        build: |c, _| Ok(Arc::new(HertzModel::maw_from_sections(&c.sections)?)),
    },
    ModelEntry {
        name: "arakawa",
        summary: "rigid ball, Hertz normal force and Arakawa's contact-area friction, free head, in time (seed 3.2.3, \
                  Table 3.7)",
        sections: &["arakawa"],
        resolved_in_time: true,
        fit: Some(identifiable::ARAKAWA),
        build: |c, _| Ok(Arc::new(HertzModel::arakawa_from_sections(&c.sections)?)),
    },
    ModelEntry {
        name: "ground",
        summary: "two-layer ball on an iron head on a flexible shaft, the ball on the turf (firm unless --soil): \
                  sole and face ground reaction (seed chapter 4, Tables 4.1-4.3)",
        sections: &["continuous", "soil", "sole", "shaft"],
        resolved_in_time: true,
        fit: None,
        build: ground,
    },
];

/// Names that stand for several models, published in order.
pub const GROUPS: &[(&str, &[&str])] = &[("both", &["adjusted", "continuous"])];

/// The model names and groups, for help texts and errors: `standard, adjusted, slip, continuous, both`.
pub fn names() -> String {
    MODELS.iter().map(|m| m.name).chain(GROUPS.iter().map(|g| g.0)).collect::<Vec<_>>().join(", ")
}

/// The identifiable parameters of every model that has them, in the registry's order.
pub fn fit_models() -> impl Iterator<Item = &'static FitModel> {
    MODELS.iter().filter_map(|m| m.fit.as_ref())
}

/// The entry of a single model.
pub fn entry(name: &str) -> Option<&'static ModelEntry> {
    MODELS.iter().find(|m| m.name == name)
}

/// The models a name stands for: one model, a group (`both`), or a comma-separated list (`adjusted,continuous`),
/// in the order their predictions are published, each with its parameters from the club's sections. A section
/// that belongs to no model is an error (a typo would otherwise be ignored).
pub fn build(name: &str, club: &LoadedClub, options: &BuildOptions) -> Result<Vec<Arc<dyn ImpactModel>>, ImpactError> {
    check_sections(club)?;
    let names: Vec<&str> = match GROUPS.iter().find(|g| g.0 == name) {
        Some((_, members)) => members.to_vec(),
        None => name.split(',').map(str::trim).collect(),
    };
    names
        .iter()
        .map(|n| {
            let e =
                entry(n).ok_or_else(|| ImpactError::UnknownModel { name: n.to_string(), expected: self::names() })?;
            (e.build)(club, options)
        })
        .collect()
}

/// One model by name (not a group).
pub fn build_one(name: &str, club: &LoadedClub, options: &BuildOptions) -> Result<Arc<dyn ImpactModel>, ImpactError> {
    check_sections(club)?;
    let e = entry(name).ok_or_else(|| ImpactError::UnknownModel { name: name.to_string(), expected: self::names() })?;
    (e.build)(club, options)
}

fn check_sections(club: &LoadedClub) -> Result<(), ImpactError> {
    for section in club.sections.names() {
        if !MODELS.iter().any(|m| m.sections.contains(&section)) {
            let known: Vec<&str> = MODELS.iter().flat_map(|m| m.sections.iter().copied()).collect();
            return Err(ImpactError::UnknownSection { section: section.to_string(), known: known.join(", ") });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::load_club;

    #[test]
    fn every_name_builds_and_groups_expand_in_order() {
        let club = load_club("iron7").unwrap();
        for m in MODELS {
            assert_eq!(build(m.name, &club, &BuildOptions::default()).unwrap().len(), 1, "{}", m.name);
        }
        let both = build("both", &club, &BuildOptions::default()).unwrap();
        assert_eq!(both.iter().map(|m| m.name()).collect::<Vec<_>>(), ["impulse/adjusted", "continuous/two_layer"]);
        let list = build("slip, standard", &club, &BuildOptions::default()).unwrap();
        assert_eq!(list.iter().map(|m| m.name()).collect::<Vec<_>>(), ["impulse/slip", "impulse/standard"]);
        let e = build("nosuch", &club, &BuildOptions::default()).unwrap_err().to_string();
        assert!(e.contains("nosuch") && e.contains("adjusted"), "{e}");
    }
}
