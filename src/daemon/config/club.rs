//! A rig's club as its configuration makes it: the club (a preset or a club file) loaded, the rig's `soil` as its
//! `[soil]` section, its models built with the rig's `model` and `cor`. What `[[rig]]`, `[rig.clubs]`, a put on
//! `golf/<rig>/club` and a replayed club change all load; an error says which part of the rig it comes from and
//! keeps its cause.

use crate::daemon::config::RigConfig;
use crate::equipment::{EquipmentError, LoadedClub};
use crate::impact::continuous::iron_ground::sections::soil_arg_section;
use crate::impact::registry::{self, BuildOptions};
use crate::impact::ImpactError;
use crate::pipeline::ClubSwitch;

/// Why a rig cannot take a club: the club itself, the rig's soil, or its models.
#[derive(Debug, thiserror::Error)]
pub enum RigClubError {
    /// The club (`what` names where it was asked for) cannot be loaded.
    #[error("{what} `{spec}`: {source}")]
    Club {
        what: String,
        spec: String,
        #[source]
        source: EquipmentError,
    },
    /// The rig's soil: no ground model among the rig's models, or no soil by that name or file.
    #[error("{source}")]
    Soil {
        #[source]
        source: ImpactError,
    },
    /// The rig's models cannot be built for the club `spec`.
    #[error("{spec}: {source}")]
    Model {
        spec: String,
        #[source]
        source: ImpactError,
    },
}

impl RigClubError {
    /// The field of the rig the error comes from: `club`, `soil` or `model`.
    pub fn part(&self) -> &'static str {
        match self {
            RigClubError::Club { .. } => "club",
            RigClubError::Soil { .. } => "soil",
            RigClubError::Model { .. } => "model",
        }
    }
}

/// A rig's `soil`: the club's `[soil]` section, and the model list it implies (`both` with a soil is the impulse
/// model published at once and the ground model when it is ready).
fn soil_model(r: &RigConfig, club: &mut LoadedClub) -> Result<String, ImpactError> {
    let Some(soil) = &r.soil else { return Ok(r.model.clone()) };
    let model = registry::resolve(&r.model, true)?;
    club.sections.insert("soil", soil_arg_section(soil)?);
    Ok(model)
}

impl RigConfig {
    /// The club `spec` (a preset or a club file) ready for this rig: loaded, with the rig's soil, its models built
    /// with the rig's model and COR, and its file's SHA-256. What a put on `golf/<rig>/club` and `[rig.clubs]`
    /// load; `what` names the club's place in errors.
    pub fn prepare_club(&self, spec: &str, what: &str) -> Result<ClubSwitch, RigClubError> {
        let (mut club, bytes) = crate::equipment::load_club_source(spec).map_err(|source| RigClubError::Club {
            what: what.to_string(),
            spec: spec.to_string(),
            source,
        })?;
        let model = soil_model(self, &mut club).map_err(|source| RigClubError::Soil { source })?;
        let options = BuildOptions { cor: self.cor, ..BuildOptions::default() };
        let models = registry::build(&model, &club, &options)
            .map_err(|source| RigClubError::Model { spec: spec.to_string(), source })?;
        let club_ref = crate::wire::ClubRef {
            name: club.club.name.clone(),
            file: spec.to_string(),
            sha256: crate::equipment::sha256_hex(&bytes),
        };
        Ok(ClubSwitch { club: club.club, models, club_ref: Some(club_ref), calibration: None })
    }
}

#[cfg(test)]
mod tests {
    use crate::daemon::{DaemonConfig, DaemonError};
    use crate::equipment::EquipmentError;
    use crate::flight::{ConditionsError, TurfError};
    use crate::impact::ImpactError;
    use crate::wire::LabelsError;

    /// The error a rig file gives, and the causes under it, through `std::error::Error::source`.
    fn refused(rig: &str) -> (DaemonError, Vec<String>) {
        let e = DaemonConfig::parse(&format!("[[rig]]\nname = \"a\"\n{rig}")).unwrap_err();
        let mut causes = Vec::new();
        let mut cause = std::error::Error::source(&e);
        while let Some(c) = cause {
            causes.push(c.to_string());
            cause = c.source();
        }
        (e, causes)
    }

    /// The first cause of type `E` under `e`.
    fn cause<E: std::error::Error + 'static>(e: &DaemonError) -> Option<&E> {
        let mut cause = std::error::Error::source(e);
        while let Some(c) = cause {
            if let Some(found) = c.downcast_ref::<E>() {
                return Some(found);
            }
            cause = c.source();
        }
        None
    }

    /// A bad soil in a rig file: the error names `rig[0].soil` as it always did, and its causes reach the soil's
    /// own error (the turf model's, then the equipment's) instead of ending in text.
    #[test]
    fn a_bad_soil_keeps_the_soil_error_as_its_source() {
        let (e, causes) = refused("club = \"iron7\"\nmodel = \"ground\"\nsoil = \"mud\"");
        assert_eq!(
            e.to_string(),
            "config field `rig[0].soil` model parameter `[soil]` unknown soil 'mud' (expected soft, medium or \
             firm, or a path to a soil .toml file); or none for the ball on a tee"
        );
        assert!(matches!(&e, DaemonError::RigClub { field, .. } if field == "rig[0].soil"), "{e:?}");
        assert!(matches!(cause::<ImpactError>(&e), Some(ImpactError::Soil { .. })), "{causes:?}");
        assert!(matches!(cause::<EquipmentError>(&e), Some(EquipmentError::UnknownSoil(s)) if s == "mud"), "{e:?}");
        // A soil without the ground model is the registry's refusal, kept as it is.
        let (e, _) = refused("club = \"iron7\"\nmodel = \"adjusted\"\nsoil = \"firm\"");
        assert!(e.to_string().starts_with("config field `rig[0].soil` model parameter `soil` needs the ground"));
        assert!(
            matches!(cause::<ImpactError>(&e), Some(ImpactError::InvalidParameter { field, .. }) if field == "soil")
        );
    }

    /// An unknown model and an unknown club (the rig's own, or a body's in `[rig.clubs]`) keep the registry's and
    /// the equipment's errors.
    #[test]
    fn a_bad_model_or_club_keeps_the_registry_or_equipment_error_as_its_source() {
        let (e, _) = refused("model = \"fast\"");
        assert!(e.to_string().starts_with("config field `rig[0].model` driver: unknown model 'fast' (expected "));
        assert!(matches!(cause::<ImpactError>(&e), Some(ImpactError::UnknownModel { name, .. }) if name == "fast"));
        let (e, _) = refused("club = \"putter\"");
        assert!(e.to_string().starts_with("config field `rig[0].club` rig[0].club `putter`: unknown club preset"));
        assert!(matches!(cause::<EquipmentError>(&e), Some(EquipmentError::UnknownPreset(c)) if c == "putter"));
        let (e, _) = refused("[rig.clubs]\nseven = \"putter\"");
        assert!(e.to_string().starts_with("config field `rig[0].clubs.seven` rig[0].clubs.seven `putter`: "));
        assert!(matches!(cause::<EquipmentError>(&e), Some(EquipmentError::UnknownPreset(_))), "{e:?}");
    }

    /// Air and turf out of range keep the flight's own errors; the labels theirs.
    #[test]
    fn bad_conditions_or_labels_keep_the_flight_or_labels_error_as_their_source() {
        let (e, _) = refused("[rig.conditions]\nwind_mps = -1.0");
        assert_eq!(e.to_string(), "config field `rig[0].conditions` `wind_mps` must be within 0 and 40, got -1");
        assert!(matches!(cause::<ConditionsError>(&e), Some(ConditionsError::OutOfRange { field: "wind_mps", .. })));
        let (e, _) = refused("[rig.conditions]\nfirmness = 2.0");
        assert_eq!(e.to_string(), "config field `rig[0].conditions` `firmness` must be within 0 and 1, got 2");
        assert!(cause::<TurfError>(&e).is_some(), "{e:?}");
        let (e, causes) = refused("[rig.conditions]\nhumidity_pct = 150.0");
        assert_eq!(
            e.to_string(),
            "config field `rig[0].conditions` `humidity_pct` is relative humidity in percent, 0-100, got 150"
        );
        assert_eq!(causes.len(), 1, "{causes:?}");
        let tags: Vec<String> = (0..=crate::wire::MAX_TAGS).map(|i| format!("\"t{i}\"")).collect();
        let (e, _) = refused(&format!("[rig.labels]\ntags = [{}]", tags.join(", ")));
        assert_eq!(e.to_string(), "config field `rig[0].labels` field `tags`: more than 32 tags");
        assert!(matches!(cause::<LabelsError>(&e), Some(LabelsError::TooManyTags)), "{e:?}");
    }
}
