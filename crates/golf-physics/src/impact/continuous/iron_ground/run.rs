//! One shot of the iron-plus-ground model: the ball placed, the parts assembled, the strike stepped on the
//! assembly's multi-rate stepping ([`super::policy`]) and its measures gathered.

use super::measures::Measures;
use super::placement::{classify, first_ground_contact_s, Strike};
use super::policy::{StrikeSteps, StrikeSystem};
use super::{GroundResult, PreparedGround};
use crate::impact::continuous::assembly::{Assembly, State};
use crate::impact::continuous::ball::BallPart;
use crate::impact::continuous::club::{ShaftClub, ShaftClubState};
use crate::impact::continuous::ground::{GroundForces, SampledGround, SoilGround};
use crate::impact::continuous::shaft::grip::ConstantTwist;
use crate::impact::continuous::surface::FaceSurface;
use crate::impact::continuous::{TwoLayerContact, TwoLayerParams, TwoLayerReading};
use crate::impact::{ImpactError, ImpactState};
use crate::math::Real;
use crate::units::MPS_PER_MPH;

pub(super) fn simulate<G: SampledGround<Forces = GroundForces>>(
    p: &PreparedGround,
    state: &ImpactState,
    trace_every: usize,
    follow_s: Real,
    with: impl FnOnce(SoilGround) -> G,
) -> Result<GroundResult, ImpactError> {
    let model = &p.model;
    let club = &p.equipment.club;
    let params = model.params.unwrap_or_else(|| TwoLayerParams::preset(club, TwoLayerReading::default()));
    let TwoLayerContact { law, ball, surface } = params.contact(club, &p.equipment.ball)?;
    let mut ground = p.ground_for(state)?;
    let motion = ConstantTwist {
        world_from_club: state.world_from_club,
        cg_velocity_mps: state.cg_velocity_mps,
        angular_velocity_radps: state.angular_velocity_radps,
    };
    let FaceSurface::Plane { point: face_point, normal: face_normal } = surface else {
        return Err(ImpactError::InvalidParameter {
            field: "club".into(),
            reason: format!("must have a flat (iron) face for the ground model ({}'s is curved)", club.name),
        });
    };
    let contact = club.face.contact(state.impact_h_m, state.impact_v_m)?;
    let v_contact0 =
        state.cg_velocity_mps + state.angular_velocity_radps.cross(&(state.world_from_club.rotation * contact.point_m));
    let approach0 = v_contact0.dot(&(state.world_from_club.rotation * contact.normal));
    if approach0 <= 0.0 {
        return Err(ImpactError::NotApproaching);
    }
    let first_ground =
        if model.with_ground { first_ground_contact_s(&ground, &motion, -0.03, model.follow_s) } else { None };
    if !model.with_ground {
        ground.ground_y_m = Real::NEG_INFINITY;
    }
    // The sole's first touch is an event: a fat strike starts there (nothing acts on the club before it), and a
    // later touch ends a step at it (below).
    let t0 = match first_ground {
        Some(t) if t < 0.0 => t,
        _ => 0.0,
    };
    let shaft_club = ShaftClub {
        modal: &p.modal,
        motion,
        twist: motion.prepared(),
        elastic_frame: motion.world_from_club(t0).rotation.to_rotation_matrix(),
        head_mass_kg: club.mass_kg,
        shaft_mass_kg: model.shaft.mass_kg,
        shaft_cg_m: p.shaft_cg_m,
    };
    let asm: StrikeSystem<G> = Assembly { law, ball, club: shaft_club, ground: with(ground), surface };
    let ball_centre = super::placement::ball_centre_m(state, club, &p.equipment.ball)?;
    let s0 = State { club: ShaftClubState::default(), ball: asm.ball.at_rest(ball_centre) };
    let momentum_start = asm.club.momentum_n_s(&s0.club, t0);
    let mut policy = StrikeSteps {
        model,
        club,
        ladder: &p.steps,
        face_point_m: face_point,
        face_normal,
        ball_radius_m: p.equipment.ball.radius_m,
        approach_mps: approach0,
        first_ground_s: first_ground,
        follow_s,
        trace_every,
        out: Measures::default(),
        trace: Vec::new(),
        launch: None,
        steps: 0,
        next_trace_s: Real::NEG_INFINITY,
    };
    let (s, t_s) = asm.run_stepped(s0, t0, &mut policy)?;
    let StrikeSteps { out, trace, launch, steps, .. } = policy;
    let launch = launch.ok_or_else(|| ImpactError::NotConverged { model: "ground", reason: "no launch".into() })?;
    Ok(GroundResult {
        launch,
        strike: if model.with_ground { classify(first_ground) } else { Strike::Teed },
        ground_contact_before_ball_ms: out.first_ground_s.map(|t| (out.t_ball_s - t) * 1e3),
        club_speed_loss_mph: out.speed_loss_mps / MPS_PER_MPH,
        face_angle_change_deg: out.face_change_deg,
        dynamic_loft_change_deg: out.loft_change_deg,
        divot_depth_mm: out.max_sinkage_m * 1e3,
        divot_length_mm: out.divot_length_m * 1e3,
        peak_ground_force_n: out.peak_ground_n,
        ground_contact_ms: out.ground_time_s * 1e3,
        ball_contact_us: out.ball_time_s * 1e6,
        club_momentum_start_n_s: momentum_start,
        club_momentum_end_n_s: asm.club.momentum_n_s(&s.club, t_s),
        ball_impulse_n_s: s.club.j_ball_n_s,
        ground_impulse_before_ball_n_s: out.ground_impulse_before_ball_n_s,
        ground_impulse_n_s: s.club.j_ground_n_s,
        grip_impulse_n_s: s.club.j_grip_n_s,
        steps,
        trace,
    })
}
