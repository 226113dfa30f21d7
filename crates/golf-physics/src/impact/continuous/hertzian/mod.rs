//! The seed's Hertzian continuous models (section 3.2.2 Maw, section 3.2.3 Arakawa): a rigid ball against a free
//! clubhead, eq. 3.16's normal force along the contact normal and a tangential law in the tangent plane, both
//! applied at one contact point, equal and opposite on the two free bodies (section 3.2.2, last paragraph).
//!
//! - Contact geometry: the ball against the face plane (irons) or the face sphere of the geometric-mean radius
//!   of bulge and roll (drivers), as the two-layer model; the approach `x` is the overlap along the normal,
//!   the contact point sits `R` from the ball's centre, the small-strain arm of Maw, Barber and Fawcett's theory
//!   (`contact_arm = "mid_overlap"` in the section: `R − x/2`; [`super::law::hertz::ContactArm`]).
//! - Stiffness eq. 3.17 with eq. 3.18's equivalent radius; tangential law [`MawRings`] or [`ArakawaLaw`].
//! - Integration: the shared [`Assembly`](super::Assembly) of a free head, a rigid ball and no ground with eq.
//!   3.16 and the tangential law as one contact law ([`HertzContact`](super::law::hertz_contact::HertzContact)),
//!   on the assembly's stepping (`Assembly::run_stepped`, classical RK4 at a fixed step: default 2 µs for Maw,
//!   1 µs for Arakawa) from first contact until the bodies separate, the contact's slip integrated beside.
//!   The ring states are history variables: inside a step each ring follows the slip since the step's start
//!   (its own stick/slip test at every stage) and the step's end is committed; the committed force is the next
//!   step's first stage. Steps the law flags near one of its switches (Arakawa's envelope near eq. 3.23's sign
//!   change) are split in eight, and the step in which the ball leaves ends where the overlap closes
//!   (`policy.rs`). Both bodies feel equal and opposite forces at the same point, so linear and angular
//!   momentum are conserved to rounding.
//!
//! Assumptions: a rigid ball (its spin is the launch spin), no gravity or shaft in the half millisecond of
//! contact, the contact never reaches the face's edges.

mod policy;
mod run;
#[cfg(test)]
mod tests;

use super::law::{
    arakawa::{ArakawaLaw, ArakawaParams},
    maw::{MawParams, MawRings},
};
use super::{ContinuousResult, TracePoint};
use crate::impact::{Equipment, ImpactError, ImpactModel, ImpactState, Launch, ModelRun, RunOptions};
use crate::math::{Real, Vector3};

/// One sample of a trace.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct HertzTracePoint {
    /// Time from first contact (µs).
    pub t_us: Real,
    /// The Hertz normal force (N, eq. 3.16).
    pub normal_force_n: Real,
    /// Tangential force on the ball along the face's initial slip relative to the ball (N): positive while it
    /// drives the ball's contact point along with the face, negative once it has reversed.
    pub tangential_force_n: Real,
    /// The ball's spin (rpm) about the axis normal x initial slip (positive: the spin the face imparts).
    pub ball_spin_rpm: Real,
    /// The normal compression (mm).
    pub compression_mm: Real,
    /// Maw: rings stuck.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stuck_rings: Option<usize>,
}

/// What a run gives besides the launch.
#[derive(Debug, Clone, PartialEq)]
pub struct HertzResult {
    /// The ball and the club as the ball leaves.
    pub launch: Launch,
    /// From first contact until the ball leaves (s).
    pub contact_time_s: Real,
    /// The largest normal force (N).
    pub peak_normal_force_n: Real,
    /// The tangential force along the initial axis took both signs (each beyond 1 % of its largest size).
    pub tangential_reversal: bool,
    /// Steps taken.
    pub steps: usize,
    /// The contact's course, when asked for.
    pub trace: Vec<HertzTracePoint>,
    /// Total energy (kinetic + Hertz + rings) before the contact (J).
    pub energy_before_j: Real,
    /// Total energy after it (J).
    pub energy_after_j: Real,
    /// Largest increase of the total energy (kinetic + Hertz + rings) over any step (J).
    pub max_energy_increase_j: Real,
    /// Linear and angular momentum (about the world origin) of both bodies before and after.
    pub momentum_before: (Vector3, Vector3),
    /// See `momentum_before`.
    pub momentum_after: (Vector3, Vector3),
}

/// Which tangential law, with its parameters (`None`: the club's preset, driver's for a curved face).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HertzLaw {
    /// Maw's rings (seed section 3.2.2; `None`: the club's preset).
    Maw(Option<MawParams>),
    /// Arakawa's contact-area friction (seed section 3.2.3, eq. 3.19-3.23; `None`: the club's preset).
    Arakawa(Option<ArakawaParams>),
}

/// Maw's or Arakawa's model on a free head.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzModel {
    /// The tangential law.
    pub law: HertzLaw,
    /// Integration step (s).
    pub step_s: Real,
    /// Give up after this long in contact (s).
    pub max_contact_s: Real,
}

impl HertzModel {
    /// Maw's rings with a 2 µs step: halving it moves ball speed < 2e-7 and spin < 2e-5 (both clubs, 35-55 m/s,
    /// centred and off-centre; crates/golf-physics/tests/maw_arakawa.rs asserts 1e-4 and 1e-3). The rings reached within a step feel
    /// the slip since they entered ([`MawRings`]), which makes the spin converge faster than first order.
    pub fn maw() -> Self {
        HertzModel { law: HertzLaw::Maw(None), step_s: 2e-6, max_contact_s: 3e-3 }
    }

    /// Arakawa's law with a 1 µs step: halving it moves ball speed < 4e-6 and spin < 3e-4 (both clubs,
    /// 35-55 m/s, crates/golf-physics/tests/maw_arakawa.rs).
    pub fn arakawa() -> Self {
        HertzModel { law: HertzLaw::Arakawa(None), step_s: 1e-6, ..Self::maw() }
    }

    /// `maw` or `arakawa`.
    pub fn law_name(&self) -> &'static str {
        match self.law {
            HertzLaw::Maw(_) => "maw",
            HertzLaw::Arakawa(_) => "arakawa",
        }
    }

    /// Maw's model with the club file's `[maw]` section (Table 3.6's preset without one).
    pub fn maw_from_sections(sections: &crate::equipment::ModelSections) -> Result<Self, ImpactError> {
        let p = crate::impact::impulse::section::<MawParams>(sections, "maw")?;
        if let Some(p) = &p {
            p.validate().map_err(|e| bad_section("maw", e))?;
        }
        Ok(HertzModel { law: HertzLaw::Maw(p), ..Self::maw() })
    }

    /// Arakawa's model with the club file's `[arakawa]` section (Table 3.7's preset without one).
    pub fn arakawa_from_sections(sections: &crate::equipment::ModelSections) -> Result<Self, ImpactError> {
        let p = crate::impact::impulse::section::<ArakawaParams>(sections, "arakawa")?;
        if let Some(p) = &p {
            p.validate().map_err(|e| bad_section("arakawa", e))?;
        }
        Ok(HertzModel { law: HertzLaw::Arakawa(p), ..Self::arakawa() })
    }

    /// An error naming this model as the registry does.
    pub(crate) fn not_converged(&self, reason: String) -> ImpactError {
        ImpactError::NotConverged { model: self.law_name(), reason }
    }

    /// Runs the collision, recording a trace every `trace_every` steps (0: none).
    pub fn simulate(
        &self,
        state: &ImpactState,
        eq: &Equipment,
        trace_every: usize,
    ) -> Result<HertzResult, ImpactError> {
        let curved = eq.club.face.shape.is_curved();
        match self.law {
            HertzLaw::Maw(p) => {
                let p = p.unwrap_or(if curved { MawParams::DRIVER } else { MawParams::IRON7 });
                p.validate().map_err(|e| bad_section("maw", e))?;
                run::run(self, state, eq, (p.hertz(), p.contact_arm), |b| MawRings::new(&p, b), trace_every)
            }
            HertzLaw::Arakawa(p) => {
                let p = p.unwrap_or(if curved { ArakawaParams::DRIVER } else { ArakawaParams::IRON7 });
                p.validate().map_err(|e| bad_section("arakawa", e))?;
                run::run(self, state, eq, (p.hertz(), p.contact_arm), |b| ArakawaLaw::new(&p, b), trace_every)
            }
        }
    }
}

impl ImpactModel for HertzModel {
    fn name(&self) -> &'static str {
        self.law_name()
    }

    fn run(&self, state: &ImpactState, equipment: &Equipment, o: &RunOptions) -> Result<ModelRun, ImpactError> {
        self.simulate(state, equipment, o.trace_every).map(|r| r.into_continuous().into_run(o))
    }
}

impl HertzResult {
    /// The same run in the continuous models' terms (the rigid ball's cover turns with it).
    pub fn into_continuous(self) -> ContinuousResult {
        ContinuousResult {
            launch: self.launch,
            contact_time_s: self.contact_time_s,
            peak_normal_force_n: self.peak_normal_force_n,
            steps: self.steps,
            trace: self
                .trace
                .iter()
                .map(|p| TracePoint {
                    t_us: p.t_us,
                    normal_force_n: p.normal_force_n,
                    tangential_force_n: p.tangential_force_n,
                    ball_spin_rpm: p.ball_spin_rpm,
                    cover_spin_rpm: p.ball_spin_rpm,
                    compression_mm: p.compression_mm,
                    stuck_rings: p.stuck_rings,
                })
                .collect(),
            energy_before_j: self.energy_before_j,
            energy_after_j: self.energy_after_j,
            max_energy_increase_j: self.max_energy_increase_j,
            momentum_before: self.momentum_before,
            momentum_after: self.momentum_after,
        }
    }
}

fn bad_section(section: &str, e: super::law::hertz::LawError) -> ImpactError {
    let super::law::hertz::LawError::OutOfRange { field, .. } = &e;
    ImpactError::InvalidParameter { field: format!("{section}.{field}"), reason: e.to_string() }
}
