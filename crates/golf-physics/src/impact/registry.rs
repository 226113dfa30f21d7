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
    /// How it builds.
    pub build: BuildFn,
}

/// How an entry builds its model from a club and the options.
pub type BuildFn = fn(&LoadedClub, &BuildOptions) -> Result<Arc<dyn ImpactModel>, ImpactError>;

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

#[doc = include_str!("model_examples.md")]
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
                  force reversal per contact; `reading = \"table\"`: as printed)",
        sections: &["continuous"],
        resolved_in_time: true,
        fit: Some(identifiable::CONTINUOUS),
        build: continuous,
    },
    ModelEntry {
        name: "maw",
        summary: "rigid ball, Hertz + Hunt-Crossley normal force and Maw's stick-slip rings with Mindlin \
                  compliance, free head, in time (seed 3.2.2, eq. 3.16-3.18, Table 3.6)",
        sections: &["maw"],
        resolved_in_time: true,
        fit: Some(identifiable::MAW),
        build: |c, _| Ok(Arc::new(HertzModel::maw_from_sections(&c.sections)?)),
    },
    ModelEntry {
        name: "arakawa",
        summary: "rigid ball, Hertz normal force and Arakawa's contact-area friction F_T = mu F_N + mu eta pi R \
                  xdot bounding an elastic stick, free head, in time (seed 3.2.3, eq. 3.19-3.23, Table 3.7)",
        sections: &["arakawa"],
        resolved_in_time: true,
        fit: Some(identifiable::ARAKAWA),
        build: |c, _| Ok(Arc::new(HertzModel::arakawa_from_sections(&c.sections)?)),
    },
    ModelEntry {
        name: "ground",
        summary: "continuous's two-layer ball on an iron head on a flexible shaft, the ball on the turf (firm \
                  unless --soil; none: on a tee): sole and face ground reaction (seed chapter 4, Tables 4.1-4.3)",
        sections: &["continuous", "soil", "sole", "shaft"],
        resolved_in_time: true,
        fit: None,
        build: ground,
    },
];

/// A name that stands for several models, published in order: one list for a ball on a tee, one for a ball on
/// the turf (a rig or command with a soil).
pub struct Group {
    /// The name that stands for the group (`both`, ...).
    pub name: &'static str,
    /// Its models for a ball on a tee, in publication order.
    pub members: &'static [&'static str],
    /// Its models for a ball on the turf.
    pub on_turf: &'static [&'static str],
}

/// The names models were published under before each was published under its registry name, as
/// `(former, current)`: recordings and messages made before carry them, and every reader takes them through
/// [`current_name`] (docs/topics.md).
pub const FORMER_NAMES: &[(&str, &str)] = &[
    ("impulse/standard", "standard"),
    ("impulse/adjusted", "adjusted"),
    ("impulse/slip", "slip"),
    ("continuous/two_layer", "continuous"),
    ("continuous/maw", "maw"),
    ("continuous/arakawa", "arakawa"),
];

/// A published model name as it is published today: a former name mapped to its model's registry name, any
/// other name unchanged.
pub fn current_name(name: &str) -> &str {
    FORMER_NAMES.iter().find(|(former, _)| *former == name).map_or(name, |(_, current)| current)
}

/// The model that stands on the turf: the one a soil (`--soil`, `soil = ...`) is for.
pub const TURF_MODEL: &str = "ground";

/// Whether `name` (a model or a group) takes a soil: the turf model, or a group whose turf members include it.
pub fn takes_soil(name: &str) -> bool {
    name == TURF_MODEL || GROUPS.iter().any(|g| g.name == name && g.on_turf.contains(&TURF_MODEL))
}

/// The model a rig, `predict` and `map` run when none is named: Cross and Dewhurst's slip model (seed 3.1.2).
///
/// The thesis names the adjusted model the best for its driver (section 5.1.1) and notes that the slip model
/// spins an iron's ball more (5.1.2), each fitted to the one club and session it was identified on. On launch
/// monitors' sessions it was never fitted to, the slip model generalises best: iron spin within 600 rpm on every
/// session where the adjusted misses three (730-1,070 rpm), a lower iron ball-speed error, and half the
/// adjusted's spin and spin-axis error on drives (research/offcentre-monitors.md). It is as fast (under 1 us a strike); `model = "adjusted"` runs the thesis'
/// choice.
pub const DEFAULT_MODEL: &str = "slip";

/// Every group.
pub const GROUPS: &[Group] =
    &[Group { name: "both", members: &[DEFAULT_MODEL, "continuous"], on_turf: &[DEFAULT_MODEL, "ground"] }];

/// The models a configured name (or a comma-separated list of names) stands for, comma-separated: the one place
/// groups are resolved. A group expands to its members, on the turf (`on_turf`: a soil is given) to its turf
/// members; on the turf the list must then include the ground model.
pub fn resolve(name: &str, on_turf: bool) -> Result<String, ImpactError> {
    let list = name
        .split(',')
        .map(str::trim)
        .map(|item| match GROUPS.iter().find(|g| g.name == item) {
            Some(g) => (if on_turf { g.on_turf } else { g.members }).join(","),
            None => item.to_string(),
        })
        .collect::<Vec<_>>()
        .join(",");
    for n in list.split(',').map(str::trim) {
        if entry(n).is_none() {
            return Err(ImpactError::UnknownModel { name: n.to_string(), expected: names() });
        }
    }
    if on_turf && !list.split(',').any(|m| m.trim() == TURF_MODEL) {
        return Err(ImpactError::InvalidParameter {
            field: "soil".into(),
            reason: format!("needs the ground model (model ground or both), not {name}"),
        });
    }
    Ok(list)
}

/// The model names and groups, for help texts and errors, in the registry's order (`standard, adjusted, ...,
/// both`).
pub fn names() -> String {
    MODELS.iter().map(|m| m.name).chain(GROUPS.iter().map(|g| g.name)).collect::<Vec<_>>().join(", ")
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
    build_from(MODELS, &resolve(name, false)?, club, options)
}

/// The comma-separated models `list` (groups already resolved) built from `entries`: [`build`] over [`MODELS`],
/// or over a registry of one's own (a model tried before its entry joins [`MODELS`]).
pub fn build_from(
    entries: &[ModelEntry],
    list: &str,
    club: &LoadedClub,
    options: &BuildOptions,
) -> Result<Vec<Arc<dyn ImpactModel>>, ImpactError> {
    check_sections(entries, club)?;
    list.split(',')
        .map(str::trim)
        .map(|n| {
            let e = entries.iter().find(|m| m.name == n).ok_or_else(|| ImpactError::UnknownModel {
                name: n.to_string(),
                expected: entries.iter().map(|m| m.name).collect::<Vec<_>>().join(", "),
            })?;
            (e.build)(club, options)
        })
        .collect()
}

/// One model by name (not a group).
pub fn build_one(name: &str, club: &LoadedClub, options: &BuildOptions) -> Result<Arc<dyn ImpactModel>, ImpactError> {
    check_sections(MODELS, club)?;
    let e = entry(name).ok_or_else(|| ImpactError::UnknownModel { name: name.to_string(), expected: self::names() })?;
    (e.build)(club, options)
}

fn check_sections(entries: &[ModelEntry], club: &LoadedClub) -> Result<(), ImpactError> {
    for section in club.sections.names() {
        if !entries.iter().any(|m| m.sections.contains(&section)) {
            let mut known: Vec<&str> = Vec::new();
            for s in entries.iter().flat_map(|m| m.sections.iter().copied()) {
                if !known.contains(&s) {
                    known.push(s);
                }
            }
            return Err(ImpactError::UnknownSection { section: section.to_string(), known: known.join(", ") });
        }
    }
    Ok(())
}

/// The models as a Markdown list (the README's "Models" section is this, `impactd models`).
pub fn models_markdown() -> String {
    let mut out = String::new();
    for m in MODELS {
        out.push_str(&format!("- `{}`: {}", m.name, m.summary));
        if let Some(fit) = &m.fit {
            let params: Vec<&str> = fit.params.iter().map(|p| p.name).collect();
            out.push_str(&format!("; `fit` identifies {}", params.join(", ")));
        }
        out.push_str(".\n");
    }
    for g in GROUPS {
        out.push_str(&format!(
            "- `{}`: {} together (with a soil: {}).\n",
            g.name,
            g.members.iter().map(|m| format!("`{m}`")).collect::<Vec<_>>().join(" and "),
            g.on_turf.iter().map(|m| format!("`{m}`")).collect::<Vec<_>>().join(" and ")
        ));
    }
    out
}

/// The club-file sections and the models that read them, as the TOML comment block of docs/club-files.md
/// (`impactd models --sections`).
pub fn sections_markdown() -> String {
    let mut out = String::new();
    for s in super::club_sections::SECTIONS {
        let readers: Vec<String> =
            MODELS.iter().filter(|m| m.sections.contains(&s.name)).map(|m| format!("`{}`", m.name)).collect();
        let head = format!("[{}]", s.name);
        for (i, line) in s.fields.iter().enumerate() {
            let text = if i == 0 { format!("read by {}: {line}", readers.join(" and ")) } else { line.to_string() };
            let left = if i == 0 { head.as_str() } else { "" };
            out.push_str(&format!("{left:<27}# {text}\n"));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::{presets, EquipmentError, LoadedClub};

    fn load_club(preset: &str) -> Result<LoadedClub, EquipmentError> {
        presets::find(preset).ok_or_else(|| EquipmentError::UnknownPreset(preset.into()))?.load()
    }

    #[test]
    fn every_name_builds_and_groups_expand_in_order() {
        let club = load_club("iron7").unwrap();
        for m in MODELS {
            assert_eq!(build(m.name, &club, &BuildOptions::default()).unwrap().len(), 1, "{}", m.name);
        }
        let both = build("both", &club, &BuildOptions::default()).unwrap();
        assert_eq!(both.iter().map(|m| m.name()).collect::<Vec<_>>(), ["slip", "continuous"]);
        let list = build("slip, standard", &club, &BuildOptions::default()).unwrap();
        assert_eq!(list.iter().map(|m| m.name()).collect::<Vec<_>>(), ["slip", "standard"]);
        let e = build("nosuch", &club, &BuildOptions::default()).unwrap_err().to_string();
        // One name per model: each publishes under its registry name, and each former name maps to one.
        for m in MODELS {
            assert_eq!(build_one(m.name, &club, &BuildOptions::default()).unwrap().name(), m.name);
            if let Some(fit) = &m.fit {
                assert_eq!(fit.name, m.name, "the identifiable parameters name their entry's model");
            }
        }
        // A soil goes with the turf model and the groups that stand on the turf, nothing else.
        assert!(takes_soil("ground") && takes_soil("both"));
        assert!(!takes_soil("adjusted") && !takes_soil("continuous"));
        for (former, current) in FORMER_NAMES {
            assert!(entry(current).is_some() && entry(former).is_none(), "{former} -> {current}");
            assert_eq!(current_name(former), *current);
        }
        assert_eq!(current_name("ground"), "ground");
        // Every section a model reads is documented, and every documented section is read.
        for m in MODELS {
            for s in m.sections {
                assert!(super::super::club_sections::SECTIONS.iter().any(|d| d.name == *s), "[{s}] undocumented");
            }
        }
        for d in super::super::club_sections::SECTIONS {
            assert!(MODELS.iter().any(|m| m.sections.contains(&d.name)), "[{}] read by no model", d.name);
        }
        assert!(e.contains("nosuch") && e.contains("adjusted"), "{e}");
    }

    /// Regression: a section no model reads was refused with `continuous` twice among the known sections (the
    /// ground model reads it too).
    #[test]
    fn an_unknown_section_names_each_known_section_once() {
        let mut club = load_club("iron7").unwrap();
        club.sections.insert("foo", toml::Table::new());
        let e = build("standard", &club, &BuildOptions::default()).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(e.contains("[foo]"), "{e}");
        let known = e.split("known sections: ").nth(1).unwrap_or_default().trim_end_matches(')');
        let names: Vec<&str> = known.split(", ").collect();
        for (i, n) in names.iter().enumerate() {
            assert!(!names[..i].contains(n), "[{n}] named twice: {e}");
        }
        assert!(names.contains(&"continuous") && names.contains(&"shaft"), "{e}");
    }
}
