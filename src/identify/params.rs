//! Each model's identifiable parameters, with bounds (seed section 3.1.3: "unique parameters that will affect
//! the predicted launch conditions").
//!
//! - adjusted (Danaei, Table 3.3): the mass added to the head `Δm` and the ball-CG shift `Δ` in the impact frame
//!   (x′ normal, y′ up the face, z′ toe); four numbers.
//! - slip (Cross and Dewhurst, Table 3.4): the tangential restitutions `e_y`, `e_z` of eq. 3.11-3.12.
//! - continuous (two-layer volumetric, Table 3.5): `k_v`, `d` (eq. 3.14), `μ`, `v_tr` (eq. 3.15), `k_ball`,
//!   `c_ball`, `t_cover`.
//!
//! The optimisers work in the unit cube: a parameter maps linearly (or logarithmically, for those spanning
//! decades) from `[0, 1]` onto its bounds. The parameters live in the club ([`ClubSpec`]'s `impulse` and
//! `continuous`), so a fitted club is a club file `predict` and `run` accept.

use super::IdentifyError;
use crate::equipment::ClubSpec;
use crate::impact::{ContinuousModel, ImpactModel, ImpulseModel, ImpulseVariant};
use crate::math::Real;

/// The models whose parameters can be identified (and compared).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FitModel {
    Impulse(ImpulseVariant),
    Continuous,
}

impl FitModel {
    pub const NAMES: [&'static str; 4] = ["standard", "adjusted", "slip", "continuous"];

    pub fn parse(name: &str) -> Result<Self, IdentifyError> {
        match name {
            "continuous" | "two_layer" => Ok(FitModel::Continuous),
            other => ImpulseVariant::parse(other)
                .map(FitModel::Impulse)
                .ok_or_else(|| IdentifyError::UnknownModel(other.to_string())),
        }
    }

    pub fn name(&self) -> &'static str {
        match self {
            FitModel::Impulse(v) => v.as_str(),
            FitModel::Continuous => "continuous",
        }
    }

    /// The model, reading its parameters from the club.
    pub fn model(&self) -> Box<dyn ImpactModel> {
        match self {
            FitModel::Impulse(v) => Box::new(ImpulseModel::new(*v)),
            FitModel::Continuous => Box::new(ContinuousModel::default()),
        }
    }
}

/// One parameter: where it lives in the club, its bounds (SI) and how to show it.
#[derive(Debug, Clone, Copy)]
pub struct ParamDef {
    /// The name on the command line and in reports.
    pub name: &'static str,
    /// The unit it is shown in, and the factor from SI to that unit.
    pub unit: &'static str,
    pub display_factor: Real,
    pub lo: Real,
    pub hi: Real,
    /// Search in log space (bounds spanning decades).
    pub log: bool,
    pub get: fn(&ClubSpec) -> Real,
    pub set: fn(&mut ClubSpec, Real),
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
}

/// A parameter vector with bounds, read from and written to a club.
pub trait ParamSet {
    fn names(&self) -> Vec<&'static str>;
    /// Bounds in SI.
    fn bounds(&self) -> Vec<(Real, Real)>;
    /// The club's current values (SI).
    fn get(&self, club: &ClubSpec) -> Vec<Real>;
    /// Sets the values (SI) in the club.
    fn set(&self, club: &mut ClubSpec, values: &[Real]);
}

/// A model and the parameters chosen for identification.
#[derive(Debug, Clone)]
pub struct ParamSpace {
    pub model: FitModel,
    pub defs: Vec<ParamDef>,
}

impl ParamSet for ParamSpace {
    fn names(&self) -> Vec<&'static str> {
        self.defs.iter().map(|d| d.name).collect()
    }
    fn bounds(&self) -> Vec<(Real, Real)> {
        self.defs.iter().map(|d| (d.lo, d.hi)).collect()
    }
    fn get(&self, club: &ClubSpec) -> Vec<Real> {
        self.defs.iter().map(|d| (d.get)(club)).collect()
    }
    fn set(&self, club: &mut ClubSpec, values: &[Real]) {
        for (d, v) in self.defs.iter().zip(values) {
            (d.set)(club, *v);
        }
    }
}

macro_rules! def {
    ($name:literal, $unit:literal, $factor:expr, $lo:expr, $hi:expr, $log:expr, |$c:ident| $field:expr) => {
        ParamDef {
            name: $name,
            unit: $unit,
            display_factor: $factor,
            lo: $lo,
            hi: $hi,
            log: $log,
            get: |$c: &ClubSpec| $field,
            set: |$c: &mut ClubSpec, v: Real| $field = v,
        }
    };
}

/// Every parameter of a model, in its table's order.
pub fn all_params(model: FitModel) -> Vec<ParamDef> {
    match model {
        FitModel::Impulse(ImpulseVariant::Standard) => vec![],
        FitModel::Impulse(ImpulseVariant::Adjusted) => vec![
            def!("delta_mass", "g", 1e3, 0.0, 0.030, false, |c| c.impulse.adjusted_delta_mass_kg),
            def!("ball_cg_shift_x", "mm", 1e3, -1.5e-3, 1.5e-3, false, |c| c.impulse.adjusted_ball_cg_shift_m.x),
            def!("ball_cg_shift_y", "mm", 1e3, -1.5e-3, 1.5e-3, false, |c| c.impulse.adjusted_ball_cg_shift_m.y),
            def!("ball_cg_shift_z", "mm", 1e3, -1.5e-3, 1.5e-3, false, |c| c.impulse.adjusted_ball_cg_shift_m.z),
        ],
        FitModel::Impulse(ImpulseVariant::Slip) => vec![
            def!("e_y", "", 1.0, -0.3, 0.3, false, |c| c.impulse.slip_e_y),
            def!("e_z", "", 1.0, -0.3, 0.3, false, |c| c.impulse.slip_e_z),
        ],
        FitModel::Continuous => vec![
            def!("k_v", "N/m^3", 1.0, 1e9, 3e10, true, |c| c.continuous.k_v_n_per_m3),
            def!("d", "ms/m", 1e3, 0.0, 0.03, false, |c| c.continuous.d_s_per_m),
            def!("mu", "", 1.0, 0.05, 1.0, false, |c| c.continuous.mu),
            def!("k_ball", "N m/rad", 1.0, 1.0, 3000.0, true, |c| c.continuous.k_ball_nm_per_rad),
            def!("c_ball", "mN m s/rad", 1e3, 1e-4, 0.3, true, |c| c.continuous.c_ball_nms_per_rad),
            def!("t_cover", "mm", 1e3, 0.5e-3, 5e-3, false, |c| c.continuous.cover_thickness_m),
            def!("v_tr", "m/s", 1.0, 0.05, 3.0, true, |c| c.continuous.v_tr_mps),
        ],
    }
}

impl ParamSpace {
    /// The model's parameters, all of them (`names` empty) or the named ones in the given order.
    pub fn new(model: FitModel, names: &[String]) -> Result<Self, IdentifyError> {
        let all = all_params(model);
        if all.is_empty() {
            return Err(IdentifyError::NothingToFit(model.name().to_string()));
        }
        if names.is_empty() {
            return Ok(ParamSpace { model, defs: all });
        }
        let defs = names
            .iter()
            .map(|n| {
                all.iter().find(|d| d.name == n).copied().ok_or_else(|| IdentifyError::UnknownParam {
                    model: model.name().to_string(),
                    name: n.clone(),
                    known: all.iter().map(|d| d.name).collect::<Vec<_>>().join(", "),
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(ParamSpace { model, defs })
    }

    /// Unit-cube coordinates of SI values.
    pub fn to_unit(&self, values: &[Real]) -> Vec<Real> {
        self.defs.iter().zip(values).map(|(d, v)| d.to_unit(*v)).collect()
    }

    /// SI values of unit-cube coordinates.
    pub fn from_unit(&self, u: &[Real]) -> Vec<Real> {
        self.defs.iter().zip(u).map(|(d, x)| d.from_unit(*x)).collect()
    }

    /// A copy of `club` with the values (SI) set.
    pub fn club_with(&self, club: &ClubSpec, values: &[Real]) -> ClubSpec {
        let mut c = club.clone();
        self.set(&mut c, values);
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn get_set_and_the_unit_cube_round_trip() {
        for name in FitModel::NAMES.into_iter().skip(1) {
            let space = ParamSpace::new(FitModel::parse(name).unwrap(), &[]).unwrap();
            let club = ClubSpec::driver();
            let v = space.get(&club);
            let back = space.from_unit(&space.to_unit(&v));
            for (a, b) in v.iter().zip(&back) {
                assert!((a - b).abs() <= 1e-12 * a.abs().max(1e-6), "{name}: {a} vs {b}");
            }
            let mid = space.from_unit(&vec![0.5; v.len()]);
            assert_eq!(space.get(&space.club_with(&club, &mid)), mid);
        }
        // Table 3.3's driver values are inside the adjusted bounds.
        let adjusted = ParamSpace::new(FitModel::parse("adjusted").unwrap(), &[]).unwrap();
        assert_eq!(adjusted.get(&ClubSpec::driver())[0], 0.00254);
        let err = ParamSpace::new(FitModel::parse("slip").unwrap(), &["e_x".into()]).unwrap_err();
        assert!(err.to_string().contains("e_y, e_z"), "{err}");
        assert!(ParamSpace::new(FitModel::parse("standard").unwrap(), &[]).is_err());
    }
}
