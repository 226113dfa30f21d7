//! One collision of [`super::HertzModel`]: the ball placed against the face, eq. 3.16 and the tangential law set
//! up at first contact ([`Begin`]), the parts assembled (a free head, a rigid ball, no ground) and stepped on the
//! assembly's stepping ([`super::policy`]).

use super::policy::{energy_j, HertzSteps, HertzSystem};
use super::{HertzModel, HertzResult};
use crate::impact::continuous::assembly::{Assembly, State};
use crate::impact::continuous::ball::{BallPart, RigidBall};
use crate::impact::continuous::club::{ClubPart, FreeHead};
use crate::impact::continuous::ground::NoGround;
use crate::impact::continuous::law::hertz::{equivalent_radius, Begin, ContactArm, Hertz, Tangential};
use crate::impact::continuous::law::hertz_contact::HertzContact;
use crate::impact::continuous::law::ContactLaw;
use crate::impact::continuous::surface::FaceSurface;
use crate::impact::{Equipment, ImpactError, ImpactState, Launch};
use crate::math::Real;

/// A step the tangential law flags ([`ContactLaw::refine`]) is split into this many.
const REFINE: usize = 8;

fn positive(field: &str, value: Real) -> Result<(), ImpactError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(ImpactError::InvalidParameter { field: field.into(), reason: format!("{value} s must be positive") })
    }
}

/// Runs the collision of the ball (at rest against the face) and the club (moving as `state` says) with eq. 3.16
/// (`hertz`, the force on the ball at `contact_arm`) and the tangential law `law` builds at first contact.
pub(super) fn run<T: Tangential>(
    model: &HertzModel,
    state: &ImpactState,
    eq: &Equipment,
    (hertz, contact_arm): (Hertz, ContactArm),
    law: impl FnOnce(&Begin) -> T,
    trace_every: usize,
) -> Result<HertzResult, ImpactError> {
    let club = &eq.club;
    if !club.on_face(state.impact_h_m, state.impact_v_m) {
        return Err(ImpactError::OffFace { h_mm: state.impact_h_m * 1e3, v_mm: state.impact_v_m * 1e3 });
    }
    positive("step_s", model.step_s)?;
    positive("max_contact_s", model.max_contact_s)?;
    let surface = FaceSurface::of_club(club);
    let r_eq = equivalent_radius(eq.ball.radius_m, &club.face.shape);
    let k = hertz.stiffness(r_eq);
    let (club_part, ball_part) = (FreeHead::new(club), RigidBall::new(&eq.ball));
    let contact = club.face.contact(state.impact_h_m, state.impact_v_m)?;
    let ball_club = match surface {
        FaceSurface::Plane { .. } => contact.point_m + eq.ball.radius_m * contact.normal,
        FaceSurface::Sphere { centre, radius_m } => {
            centre + (radius_m + eq.ball.radius_m) * (contact.point_m - centre).normalize()
        }
    };
    let iso = state.world_from_club;
    let rot = iso.rotation;
    let s = State { club: club_part.initial(state), ball: ball_part.at_rest(iso.translation.vector + rot * ball_club) };
    let n0 = (RigidBall::centre(&s.ball).0 - iso.translation.vector - rot * contact.point_m).normalize();
    let v_face0 = state.cg_velocity_mps + state.angular_velocity_radps.cross(&(rot * contact.point_m));
    let xdot0 = v_face0.dot(&n0);
    if xdot0 <= 0.0 {
        return Err(ImpactError::NotApproaching);
    }
    // The ball slips against the face's tangential motion; Figure 3.5's tangential axis.
    let face_t = v_face0 - xdot0 * n0;
    let face_dir = if face_t.norm() > 1e-9 { face_t.normalize() } else { rot * club.face.u0() };
    let m_b_kg = ball_part.mass_kg;
    let reduced_mass_kg = m_b_kg * club.mass_kg / (m_b_kg + club.mass_kg);
    let begin = Begin { slip_dir: -face_dir, xdot0_mps: xdot0, k, r_eq_m: r_eq, reduced_mass_kg };
    let asm: HertzSystem<T> = Assembly {
        law: HertzContact { k, d_s_per_m: hertz.d_s_per_m, contact_arm, tangential: law(&begin) },
        ball: ball_part,
        club: club_part,
        ground: NoGround,
        surface,
    };
    let energy_before = energy_j(&asm, &s, asm.law.history_energy_j(&asm.law.initial_state()));
    let momentum = |s: &State<_, _>| {
        let (lc, ac) = ClubPart::momentum(&asm.club, &s.club);
        let (lb, ab) = asm.ball.momentum(&s.ball);
        (lc + lb, ac + ab)
    };
    let momentum_before = momentum(&s);
    let mut policy = HertzSteps::new(
        model.step_s,
        model.step_s / REFINE as Real,
        model.max_contact_s,
        model.law_name(),
        face_dir,
        face_dir.cross(&n0),
        trace_every,
        energy_before,
    );
    let (s, t_s) = asm.run_stepped(s, 0.0, &mut policy)?;
    if !policy.touched {
        return Err(model.not_converged("the face never pressed the ball".into()));
    }
    let head = ClubPart::head(&asm.club, &s.club);
    let size = policy.ft_max_n.max(-policy.ft_min_n);
    let v_b = s.ball.velocity_mps;
    Ok(HertzResult {
        launch: Launch {
            ball_velocity_mps: v_b,
            ball_spin_radps: asm.ball.spin(&s.ball),
            club_velocity_mps: head.velocity_mps,
            club_angular_velocity_radps: head.angular_velocity_radps,
            impulse_n_s: m_b_kg * v_b,
        },
        contact_time_s: t_s,
        peak_normal_force_n: policy.peak_normal_n,
        tangential_reversal: policy.ft_max_n > 0.01 * size && policy.ft_min_n < -0.01 * size,
        steps: policy.steps,
        energy_before_j: energy_before,
        energy_after_j: energy_j(&asm, &s, policy.final_history_j()),
        max_energy_increase_j: policy.max_energy_increase_j,
        momentum_before,
        momentum_after: momentum(&s),
        trace: policy.trace,
    })
}
