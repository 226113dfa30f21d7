//! The impulse-momentum family (seed section 3.1): standard, adjusted (Danaei et al., section 3.1.1, Table 3.3)
//! and slip (Cross and Dewhurst, section 3.1.2, Table 3.4), one solver with three parameter sets.
//!
//! Assumptions (seed 3.1): the collision is instantaneous, neither body moves during it, contact is at one
//! point, both bodies are free, the ball is at rest. Equations, with `P` the impulse on the ball:
//!
//! - eq. 3.1  `P = ∫ F dt`
//! - eq. 3.2  `m_c v_c,i − P = m_c v_c,f`            eq. 3.3  `I_c ω_c,i − r_c × P = I_c ω_c,f`
//! - eq. 3.4  `m_b v_b,i + P = m_b v_b,f`            eq. 3.5  `I_b ω_b,i + r_b × P = I_b ω_b,f`
//! - eq. 3.6  `e = −(v_imp,c,f − v_imp,b,f)·i′ / (v_imp,c,i − v_imp,b,i)·i′`   (COR along the face normal)
//! - eq. 3.7  `v_imp,c = v_c + ω_c × r_c`             eq. 3.8  `v_imp,b = v_b + ω_b × r_b`
//! - eq. 3.9, 3.10 (rolling) `(v_imp,c,f − v_imp,b,f)·j′ = 0`, `·k′ = 0`
//! - eq. 3.11, 3.12 (slip) `e_y = −(…)_f·j′ / (…)_i·j′`, `e_z = −(…)_f·k′ / (…)_i·k′`
//!
//! The 15 scalar equations reduce to one 3×3 solve. The relative contact velocity `u = v_imp,c − v_imp,b`
//! changes by `−K P` with
//! `K = (1/m_c + 1/m_b) I − [r_c]× I_c⁻¹ [r_c]× − [r_b]× I_b⁻¹ [r_b]×`,
//! and eq. 3.6 and 3.9–3.12 fix the final `u′ = −F E Fᵀ u` (`F` = the impact frame, `E = diag(e, e_y, e_z)`), so
//! `P = K⁻¹ (I + F E Fᵀ) u`. Rolling is `e_y = e_z = 0`.
//!
//! Energetic consistency: Newton's restitution along the normal (eq. 3.6) with rolling can create kinetic energy
//! when the inertia couples the normal and tangential directions and `e` is close to 1 (up to 1.4e-4 relative at
//! `e = 1` over the test spread). Where the seed's law would add energy, the normal restitution is lowered to the
//! largest value that does not (the energy change `−½ P·(u + u′)` is then zero); everywhere else, including every
//! preset at the default COR, eq. 3.6 holds exactly.
//!
//! The adjusted variant adds `Δm` to `m_c` (not to the inertia) and moves the ball's CG by `Δ` (impact frame),
//! so `r_b = −R n − F Δ`. The COR is a constant (default 0.83, the rules limit, seed-tables `[cor]`).
//!
//! The slip variant's `e_y` and `e_z` may rise with the strike's obliquity to one grip value (Cross's tangential
//! restitution of a ball that grips the face; the club file's `[slip]` `oblique_*` fields, `oblique.rs`): the
//! obliquity is the angle between the contact point's closing velocity and the face normal, taken before the 3×3
//! solve, which is otherwise unchanged.

mod oblique;
mod tuning;

pub use oblique::ObliqueRise;
pub(crate) use tuning::section;
pub use tuning::ImpulseTuning;

use super::{ContactGeometry, Equipment, ImpactError, ImpactModel, ImpactState, Launch, ModelRun, RunOptions};
use crate::math::{skew, Matrix3, Real, Vector3};

/// The default coefficient of restitution.
pub const DEFAULT_COR: Real = 0.83;

/// Which parameter set of the family.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ImpulseVariant {
    /// Seed section 3.1, Table 3.2: rolling, no adjustments.
    Standard,
    /// Danaei et al. (seed 3.1.1, Table 3.3): added head mass, shifted ball CG, rolling.
    Adjusted,
    /// Cross and Dewhurst (seed 3.1.2, Table 3.4): tangential restitution e_y, e_z.
    Slip,
}

impl ImpulseVariant {
    /// Every variant, in the registry's order.
    pub const ALL: [ImpulseVariant; 3] = [ImpulseVariant::Standard, ImpulseVariant::Adjusted, ImpulseVariant::Slip];

    /// The variant's name in the registry (`standard`, `adjusted`, `slip`).
    pub fn as_str(&self) -> &'static str {
        match self {
            ImpulseVariant::Standard => "standard",
            ImpulseVariant::Adjusted => "adjusted",
            ImpulseVariant::Slip => "slip",
        }
    }

    /// The variant of that name.
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|v| v.as_str() == name)
    }
}

/// The numbers the solver needs, resolved from a variant and a club.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpulseParams {
    /// The normal coefficient of restitution `e` (eq. 3.6).
    pub cor: Real,
    /// Mass added to the head (kg; the adjusted variant's, Table 3.3; else 0).
    pub delta_mass_kg: Real,
    /// Shift of the ball's CG in the impact frame (m; the adjusted variant's, Table 3.3; else 0).
    pub ball_cg_shift_m: Vector3,
    /// Tangential restitution up the face (eq. 3.11; the slip variant's, Table 3.4; 0, rolling, otherwise).
    pub e_y: Real,
    /// Tangential restitution toward the toe (eq. 3.12; as `e_y`).
    pub e_z: Real,
    /// The slip variant's rise of `e_y` and `e_z` with the impact's obliquity, if the club file gives one.
    pub oblique: Option<ObliqueRise>,
}

/// An impulse-momentum model: a variant, a COR and the variant's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpulseModel {
    /// Which parameter set.
    pub variant: ImpulseVariant,
    /// The coefficient of restitution.
    pub cor: Real,
    /// The adjusted and slip parameters; `None` uses the seed's for the club ([`ImpulseTuning::seed_for`]).
    pub tuning: Option<ImpulseTuning>,
}

impl ImpulseModel {
    /// The variant with [`DEFAULT_COR`] and the seed's parameters for the club.
    pub fn new(variant: ImpulseVariant) -> Self {
        ImpulseModel { variant, cor: DEFAULT_COR, tuning: None }
    }

    /// With these adjusted and slip parameters instead of the seed's.
    pub fn with_tuning(mut self, tuning: ImpulseTuning) -> Self {
        self.tuning = Some(tuning);
        self
    }

    /// With this coefficient of restitution.
    pub fn with_cor(mut self, cor: Real) -> Self {
        self.cor = cor;
        self
    }

    /// The parameters of this variant for `equipment`'s club.
    pub fn params(&self, equipment: &Equipment) -> ImpulseParams {
        let t = self.tuning.unwrap_or_else(|| ImpulseTuning::seed_for(&equipment.club));
        let mut p = ImpulseParams {
            cor: self.cor,
            delta_mass_kg: 0.0,
            ball_cg_shift_m: Vector3::zeros(),
            e_y: 0.0,
            e_z: 0.0,
            oblique: None,
        };
        match self.variant {
            ImpulseVariant::Standard => {}
            ImpulseVariant::Adjusted => {
                p.delta_mass_kg = t.adjusted_delta_mass_kg;
                p.ball_cg_shift_m = t.adjusted_ball_cg_shift_m;
            }
            ImpulseVariant::Slip => {
                p.e_y = t.slip_e_y;
                p.e_z = t.slip_e_z;
                p.oblique = t.slip_oblique;
            }
        }
        p
    }
}

/// One two-body point collision in the world frame: everything [`solve`] needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactProblem {
    /// The head's mass (kg).
    pub club_mass_kg: Real,
    /// Inverse inertia of the head about its CG, world frame.
    pub club_inertia_inv: Matrix3,
    /// The ball's mass (kg).
    pub ball_mass_kg: Real,
    /// Inverse inertia of the ball about its CG, world frame.
    pub ball_inertia_inv: Matrix3,
    /// Club CG -> contact (m).
    pub r_club_m: Vector3,
    /// Ball CG -> contact (m).
    pub r_ball_m: Vector3,
    /// The impact frame in the world (columns x′, y′, z′).
    pub world_from_impact: Matrix3,
    /// The head's CG velocity before (m/s, world).
    pub club_velocity_mps: Vector3,
    /// The head's angular velocity before (rad/s, world).
    pub club_angular_velocity_radps: Vector3,
    /// The ball's velocity before (m/s, world).
    pub ball_velocity_mps: Vector3,
    /// The ball's angular velocity before (rad/s, world).
    pub ball_angular_velocity_radps: Vector3,
    /// `(e, e_y, e_z)`.
    pub restitution: Vector3,
}

/// Velocities after the collision and the impulse on the ball.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSolution {
    /// The impulse on the ball (N s, world).
    pub impulse_n_s: Vector3,
    /// The head's CG velocity after (m/s, world).
    pub club_velocity_mps: Vector3,
    /// The head's angular velocity after (rad/s, world).
    pub club_angular_velocity_radps: Vector3,
    /// The ball's velocity after (m/s, world).
    pub ball_velocity_mps: Vector3,
    /// The ball's angular velocity after (rad/s, world).
    pub ball_angular_velocity_radps: Vector3,
}

impl ContactProblem {
    /// Velocity of the club's material point at the contact, eq. 3.7.
    pub fn club_contact_velocity(&self, v: &Vector3, w: &Vector3) -> Vector3 {
        v + w.cross(&self.r_club_m)
    }
    /// Velocity of the ball's material point at the contact, eq. 3.8.
    pub fn ball_contact_velocity(&self, v: &Vector3, w: &Vector3) -> Vector3 {
        v + w.cross(&self.r_ball_m)
    }
}

/// Solves eq. 3.2-3.12 for one collision.
#[inline]
pub fn solve(p: &ContactProblem) -> Result<ContactSolution, ImpactError> {
    let rc = skew(&p.r_club_m);
    let rb = skew(&p.r_ball_m);
    let k = Matrix3::from_diagonal_element(1.0 / p.club_mass_kg + 1.0 / p.ball_mass_kg)
        - rc * p.club_inertia_inv * rc
        - rb * p.ball_inertia_inv * rb;
    let u = p.club_contact_velocity(&p.club_velocity_mps, &p.club_angular_velocity_radps)
        - p.ball_contact_velocity(&p.ball_velocity_mps, &p.ball_angular_velocity_radps);
    let u_impact = p.world_from_impact.transpose() * u;
    let chol = k.cholesky();
    let impulse_for = |restitution: &Vector3| {
        // u - u' = F (I + E) F^T u
        let du = p.world_from_impact * u_impact.component_mul(&(Vector3::repeat(1.0) + restitution));
        chol.as_ref().map(|c| c.solve(&du)).or_else(|| k.lu().solve(&du))
    };
    // Kinetic energy change of an impulse P that takes u to u': −½ P·(u + u').
    let energy_change = |impulse: &Vector3| {
        let u_after = u - k * impulse;
        -0.5 * impulse.dot(&(u + u_after))
    };
    let mut impulse = impulse_for(&p.restitution).ok_or(ImpactError::Singular)?;
    if energy_change(&impulse) > 0.0 {
        // Energetic consistency: the largest normal restitution that creates no energy (bisection; rare).
        let (mut lo, mut hi) = (0.0, p.restitution.x);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            let trial =
                impulse_for(&Vector3::new(mid, p.restitution.y, p.restitution.z)).ok_or(ImpactError::Singular)?;
            if energy_change(&trial) > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        impulse = impulse_for(&Vector3::new(lo, p.restitution.y, p.restitution.z)).ok_or(ImpactError::Singular)?;
    }
    Ok(ContactSolution {
        impulse_n_s: impulse,
        club_velocity_mps: p.club_velocity_mps - impulse / p.club_mass_kg,
        club_angular_velocity_radps: p.club_angular_velocity_radps - p.club_inertia_inv * p.r_club_m.cross(&impulse),
        ball_velocity_mps: p.ball_velocity_mps + impulse / p.ball_mass_kg,
        ball_angular_velocity_radps: p.ball_angular_velocity_radps + p.ball_inertia_inv * p.r_ball_m.cross(&impulse),
    })
}

impl ImpulseModel {
    /// The contact problem for a state on the given equipment, with this model's parameters.
    pub fn problem(&self, state: &ImpactState, equipment: &Equipment) -> Result<ContactProblem, ImpactError> {
        self.problem_at(state, &state.contact(&equipment.club)?, equipment)
    }

    /// [`problem`](Self::problem) with the state's contact geometry at hand.
    pub fn problem_at(
        &self,
        state: &ImpactState,
        g: &ContactGeometry,
        equipment: &Equipment,
    ) -> Result<ContactProblem, ImpactError> {
        let params = self.params(equipment);
        let closing_mps = g.contact_velocity_mps.dot(&g.world_from_impact.column(0));
        if closing_mps.is_nan() || closing_mps <= 0.0 {
            return Err(ImpactError::NotApproaching);
        }
        let rot = g.world_from_club;
        let ball = &equipment.ball;
        // The obliquity: the closing velocity of the contact point against the face normal (oblique.rs).
        let (e_y, e_z) = match params.oblique {
            Some(rise) => {
                let u = g.contact_velocity_mps;
                let cos = (u.dot(&g.world_from_impact.column(0)) / u.norm()).clamp(-1.0, 1.0);
                let theta_deg = cos.acos().to_degrees();
                (rise.at(params.e_y, theta_deg), rise.at(params.e_z, theta_deg))
            }
            None => (params.e_y, params.e_z),
        };
        let r_ball_m = -ball.radius_m * g.world_from_impact.column(0) - g.world_from_impact * params.ball_cg_shift_m;
        Ok(ContactProblem {
            club_mass_kg: equipment.club.mass_kg + params.delta_mass_kg,
            club_inertia_inv: rot * equipment.club.inertia_inv_kg_m2 * rot.transpose(),
            ball_mass_kg: ball.mass_kg,
            ball_inertia_inv: Matrix3::from_diagonal_element(1.0 / ball.inertia_kg_m2),
            r_club_m: g.r_club_m,
            r_ball_m,
            world_from_impact: g.world_from_impact,
            club_velocity_mps: state.cg_velocity_mps,
            club_angular_velocity_radps: state.angular_velocity_radps,
            ball_velocity_mps: Vector3::zeros(),
            ball_angular_velocity_radps: Vector3::zeros(),
            restitution: Vector3::new(params.cor, e_y, e_z),
        })
    }
}

impl ImpactModel for ImpulseModel {
    fn name(&self) -> &'static str {
        match self.variant {
            ImpulseVariant::Standard => "standard",
            ImpulseVariant::Adjusted => "adjusted",
            ImpulseVariant::Slip => "slip",
        }
    }

    fn run(&self, state: &ImpactState, equipment: &Equipment, _: &RunOptions) -> Result<ModelRun, ImpactError> {
        self.predict(state, equipment).map(ModelRun::launch_only)
    }

    fn linearises_itself(&self) -> bool {
        true
    }

    fn predict(&self, state: &ImpactState, equipment: &Equipment) -> Result<Launch, ImpactError> {
        self.predict_at(state, &state.contact(&equipment.club)?, equipment)
    }

    fn predict_at(
        &self,
        state: &ImpactState,
        contact: &ContactGeometry,
        equipment: &Equipment,
    ) -> Result<Launch, ImpactError> {
        let s = solve(&self.problem_at(state, contact, equipment)?)?;
        Ok(Launch {
            ball_velocity_mps: s.ball_velocity_mps,
            ball_spin_radps: s.ball_angular_velocity_radps,
            club_velocity_mps: s.club_velocity_mps,
            club_angular_velocity_radps: s.club_angular_velocity_radps,
            impulse_n_s: s.impulse_n_s,
        })
    }
}

#[cfg(test)]
mod closed_forms;
#[cfg(test)]
mod tests;
