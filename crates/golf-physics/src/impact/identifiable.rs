//! Each model's identifiable parameters, with bounds (seed section 3.1.3: "unique parameters that will affect
//! the predicted launch conditions"), read from and written to the model's club-file section. Each is part of
//! its model's entry in the registry (`impact::registry::MODELS`); the identification (`impactd fit`)
//! reads them there.
//!
//! - adjusted (Danaei, Table 3.3), `[adjusted]`: the mass added to the head `Δm` and the ball-CG shift `Δ` in the
//!   impact frame (x′ normal, y′ up the face, z′ toe); four numbers.
//! - slip (Cross and Dewhurst, Table 3.4), `[slip]`: the tangential restitutions `e_y`, `e_z` of eq. 3.11-3.12.
//! - continuous (two-layer volumetric, Table 3.5), `[continuous]`: `k_v`, `d` (eq. 3.14), `μ`, `v_tr` (eq.
//!   3.15), `k_ball`, `c_ball`, `t_cover`.
//! - maw (Table 3.6), `[maw]`: `E`, `ν`, `d`, `μ`; arakawa (Table 3.7), `[arakawa]`: `E`, `d`, `μ`, `η`.
//!
//! The optimisers work in the unit cube: a parameter maps linearly (or logarithmically, for those spanning
//! decades) from `[0, 1]` onto its bounds.

use std::sync::Arc;

use super::continuous::hertzian::HertzModel;
use super::continuous::law::{arakawa::ArakawaParams, maw::MawParams};
use super::continuous::{ContinuousModel, TwoLayerParams, TwoLayerReading};
use super::impulse::ImpulseTuning;
use super::{ImpactError, ImpactModel};
use crate::equipment::{BallSpec, ClubSpec, LoadedClub};
use crate::math::Real;

/// One parameter: where it lives in the model's section, its bounds (SI) and how to show it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamDef {
    /// The name on the command line and in reports.
    pub name: &'static str,
    /// The key in the model's section, and the element of an array key.
    pub key: &'static str,
    /// See `key`.
    pub index: Option<usize>,
    /// The unit it is shown in, and the factor from SI to that unit.
    pub unit: &'static str,
    /// See `unit`.
    pub display_factor: Real,
    /// The smallest value a fit may take (SI).
    pub lo: Real,
    /// The largest value a fit may take (SI).
    pub hi: Real,
    /// Search in log space (bounds spanning decades).
    pub log: bool,
}

impl ParamDef {
    /// The value at `u` in [0, 1].
    pub fn from_unit(&self, u: Real) -> Real {
        let u = u.clamp(0.0, 1.0);
        if self.log {
            (self.lo.ln() + u * (self.hi.ln() - self.lo.ln())).exp()
        } else {
            self.lo + u * (self.hi - self.lo)
        }
    }

    /// Where `value` sits in [0, 1] (clamped to the bounds).
    pub fn to_unit(&self, value: Real) -> Real {
        let u = if self.log {
            (value.max(self.lo).ln() - self.lo.ln()) / (self.hi.ln() - self.lo.ln())
        } else {
            (value - self.lo) / (self.hi - self.lo)
        };
        u.clamp(0.0, 1.0)
    }

    /// The value in a model section `table` (SI).
    pub fn read(&self, table: &toml::Table) -> Option<Real> {
        let v = table.get(self.key)?;
        let v = match self.index {
            Some(i) => v.as_array()?.get(i)?,
            None => v,
        };
        v.as_float().or_else(|| v.as_integer().map(|i| i as Real))
    }

    /// Sets the value (SI) in a model section `table`.
    pub fn write(&self, table: &mut toml::Table, value: Real) {
        match self.index {
            Some(i) => {
                if let Some(a) = table.get_mut(self.key).and_then(toml::Value::as_array_mut) {
                    if let Some(slot) = a.get_mut(i) {
                        *slot = toml::Value::Float(value);
                    }
                }
            }
            None => {
                table.insert(self.key.to_string(), toml::Value::Float(value));
            }
        }
    }
}

/// A model whose parameters can be identified: its registry name, club-file section and parameters.
#[derive(Debug)]
pub struct FitModel {
    /// The model's registry name.
    pub name: &'static str,
    /// Its club-file section.
    pub section: &'static str,
    /// The section's values when the club file has none (the seed's, per club).
    pub defaults: fn(&ClubSpec) -> toml::Table,
    /// The parameters a fit may vary.
    pub params: &'static [ParamDef],
    /// The model at a coarser integration step, for the global search of a model resolved in time (`None`: the
    /// model is cheap, or has no step).
    pub coarse: Option<BuildFn>,
}

/// Builds a model from a club's sections.
pub type BuildFn = fn(&LoadedClub, &BallSpec) -> Result<Arc<dyn ImpactModel>, ImpactError>;

/// How much coarser the global search integrates: 4 x 0.6 us = 2.4 us moves the 7-iron's launch by at most
/// 0.006 mph, 0.009 deg and 10 rpm of backspin from the 0.6 us step (200 shots of Table 3.5's 7-iron), far
/// inside the launch monitor's noise, at a quarter of the cost.
pub const COARSE_STEP_FACTOR: Real = 4.0;

fn continuous_coarse(club: &LoadedClub, ball: &BallSpec) -> Result<Arc<dyn ImpactModel>, ImpactError> {
    let exact = ContinuousModel::default();
    let params = TwoLayerParams::from_sections(&club.sections, &club.club, ball)?;
    // A fixed step, as it was measured (above): the stiffness-bounded step grows from the default step only.
    Ok(Arc::new(ContinuousModel { params, step_s: COARSE_STEP_FACTOR * exact.step_s, max_step_growth: 1.0, ..exact }))
}

/// Maw's and Arakawa's global search: the exact model on the subsample of a model resolved in time (their steps
/// cannot be coarsened: the stick/slip switches of the rings make the step error first order, research/maw-arakawa.md).
/// (Their rigid ball is the seed's, whatever the fit's ball: as the registry builds them.)
fn maw_global(club: &LoadedClub, _: &BallSpec) -> Result<Arc<dyn ImpactModel>, ImpactError> {
    Ok(Arc::new(HertzModel::maw_from_sections(&club.sections)?))
}

fn arakawa_global(club: &LoadedClub, _: &BallSpec) -> Result<Arc<dyn ImpactModel>, ImpactError> {
    Ok(Arc::new(HertzModel::arakawa_from_sections(&club.sections)?))
}

fn maw_defaults(club: &ClubSpec) -> toml::Table {
    toml::Table::try_from(if club.is_wood() { MawParams::DRIVER } else { MawParams::IRON7 }).unwrap_or_default()
}

fn arakawa_defaults(club: &ClubSpec) -> toml::Table {
    toml::Table::try_from(if club.is_wood() { ArakawaParams::DRIVER } else { ArakawaParams::IRON7 }).unwrap_or_default()
}

const fn p(name: &'static str, key: &'static str, index: Option<usize>, unit: &'static str, f: Real) -> ParamDef {
    ParamDef { name, key, index, unit, display_factor: f, lo: 0.0, hi: 1.0, log: false }
}

const fn bounded(d: ParamDef, lo: Real, hi: Real, log: bool) -> ParamDef {
    ParamDef { lo, hi, log, ..d }
}

fn adjusted_defaults(club: &ClubSpec) -> toml::Table {
    let t = ImpulseTuning::seed_for(club);
    let s = t.adjusted_ball_cg_shift_m;
    let mut table = toml::Table::new();
    table.insert("delta_mass_kg".into(), t.adjusted_delta_mass_kg.into());
    table.insert("ball_cg_shift_m".into(), toml::Value::Array(vec![s.x.into(), s.y.into(), s.z.into()]));
    table
}

fn slip_defaults(club: &ClubSpec) -> toml::Table {
    let t = ImpulseTuning::seed_for(club);
    let mut table = toml::Table::new();
    table.insert("e_y".into(), t.slip_e_y.into());
    table.insert("e_z".into(), t.slip_e_z.into());
    table
}

fn continuous_defaults(club: &ClubSpec) -> toml::Table {
    toml::Table::try_from(TwoLayerParams::preset(club, TwoLayerReading::OneCycle)).unwrap_or_default()
}

/// The adjusted model's identifiable parameters.
pub const ADJUSTED: FitModel = FitModel {
    name: "adjusted",
    section: "adjusted",
    defaults: adjusted_defaults,
    coarse: None,
    params: &[
        bounded(p("delta_mass", "delta_mass_kg", None, "g", 1e3), 0.0, 0.030, false),
        bounded(p("ball_cg_shift_x", "ball_cg_shift_m", Some(0), "mm", 1e3), -1.5e-3, 1.5e-3, false),
        bounded(p("ball_cg_shift_y", "ball_cg_shift_m", Some(1), "mm", 1e3), -1.5e-3, 1.5e-3, false),
        bounded(p("ball_cg_shift_z", "ball_cg_shift_m", Some(2), "mm", 1e3), -1.5e-3, 1.5e-3, false),
    ],
};

/// The slip model's identifiable parameters.
pub const SLIP: FitModel = FitModel {
    name: "slip",
    section: "slip",
    defaults: slip_defaults,
    coarse: None,
    params: &[
        bounded(p("e_y", "e_y", None, "", 1.0), -0.3, 0.3, false),
        bounded(p("e_z", "e_z", None, "", 1.0), -0.3, 0.3, false),
    ],
};

/// The continuous model's identifiable parameters.
pub const CONTINUOUS: FitModel = FitModel {
    name: "continuous",
    section: "continuous",
    defaults: continuous_defaults,
    coarse: Some(continuous_coarse),
    params: &[
        bounded(p("k_v", "k_v_n_per_m3", None, "N/m^3", 1.0), 1e9, 3e10, true),
        bounded(p("d", "d_s_per_m", None, "ms/m", 1e3), 0.0, 0.03, false),
        bounded(p("mu", "mu", None, "", 1.0), 0.05, 1.0, false),
        bounded(p("k_ball", "k_ball_nm_per_rad", None, "N m/rad", 1.0), 1.0, 3000.0, true),
        bounded(p("c_ball", "c_ball_nms_per_rad", None, "mN m s/rad", 1e3), 1e-4, 0.3, true),
        bounded(p("t_cover", "cover_thickness_m", None, "mm", 1e3), 0.5e-3, 5e-3, false),
        bounded(p("v_tr", "v_tr_mps", None, "m/s", 1.0), 0.05, 3.0, true),
    ],
};

/// The maw model's identifiable parameters.
pub const MAW: FitModel = FitModel {
    name: "maw",
    section: "maw",
    defaults: maw_defaults,
    coarse: Some(maw_global),
    params: &[
        bounded(p("e", "e_pa", None, "MPa", 1e-6), 20e6, 2e9, true),
        bounded(p("nu", "nu", None, "", 1.0), 0.2, 0.49, false),
        bounded(p("d", "d_s_per_m", None, "ms/m", 1e3), 0.0, 0.03, false),
        bounded(p("mu", "mu", None, "", 1.0), 0.05, 1.5, false),
    ],
};

/// The arakawa model's identifiable parameters.
pub const ARAKAWA: FitModel = FitModel {
    name: "arakawa",
    section: "arakawa",
    defaults: arakawa_defaults,
    coarse: Some(arakawa_global),
    params: &[
        bounded(p("e", "e_pa", None, "MPa", 1e-6), 20e6, 2e9, true),
        bounded(p("d", "d_s_per_m", None, "ms/m", 1e3), 0.0, 0.03, false),
        bounded(p("mu", "mu", None, "", 1.0), 0.01, 1.0, true),
        bounded(p("eta", "eta_n_s_per_m2", None, "N s/m^2", 1.0), 1e3, 1e7, true),
    ],
};
