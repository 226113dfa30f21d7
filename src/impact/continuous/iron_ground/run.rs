//! One shot of the iron-plus-ground model: placement, stepping and the measures of the strike.

use super::dynamics::{State, System};
use super::measures::{GroundSample, Measures};
use super::placement::{classify, first_ground_contact_s, Strike};
use super::{GroundResult, GroundTracePoint, PreparedGround};
use crate::impact::continuous::ball::TwoLayerBall;
use crate::impact::continuous::club::Head as BodyMotion;
use crate::impact::continuous::ground::{GroundForces, GroundPhase};
use crate::impact::continuous::shaft::exponential::ModalStepper;
use crate::impact::continuous::shaft::grip::ConstantTwist;
use crate::impact::continuous::shaft::modal::ModalState;
use crate::impact::continuous::surface::FaceSurface;
use crate::impact::continuous::{TwoLayerParams, TwoLayerReading};
use crate::impact::{ImpactError, ImpactState, Launch};
use crate::math::{Real, Vector3};
use crate::units::MPS_PER_MPH;

/// Face angle (open +) and dynamic loft (deg) of a head whose face normal is `n0` in its frame.
fn face_angles_deg(head: &BodyMotion, n0: &Vector3) -> (Real, Real) {
    let n = head.world_from_club * n0;
    (n.z.atan2(n.x).to_degrees(), n.y.clamp(-1.0, 1.0).asin().to_degrees())
}

pub(super) fn simulate(
    p: &PreparedGround,
    state: &ImpactState,
    trace_every: usize,
    follow_s: Real,
) -> Result<GroundResult, ImpactError> {
    let model = &p.model;
    let club = &p.equipment.club;
    let params = model.params.unwrap_or_else(|| TwoLayerParams::preset(club, TwoLayerReading::default()));
    params.validate(&p.equipment.ball)?;
    let mut ground = p.ground_for(state)?;
    let motion = ConstantTwist {
        world_from_club: state.world_from_club,
        cg_velocity_mps: state.cg_velocity_mps,
        angular_velocity_radps: state.angular_velocity_radps,
    };
    let surface = FaceSurface::of_club(club);
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
    let sys = System {
        params,
        ball: TwoLayerBall::new(
            &p.equipment.ball,
            params.cover_thickness_m,
            params.k_ball_nm_per_rad,
            params.c_ball_nms_per_rad,
        ),
        surface,
        modal: &p.modal,
        ground: &ground,
        motion,
        twist: motion.prepared(),
        elastic_frame: motion.world_from_club(t0).rotation.to_rotation_matrix(),
        head_mass_kg: club.mass_kg,
        shaft_mass_kg: model.shaft.mass_kg,
        shaft_cg_m: p.shaft_cg_m,
    };
    let ball_centre = super::placement::ball_centre_m(state, club, &p.equipment.ball)?;
    let mut s = State {
        t_s: t0,
        shaft: ModalState::default(),
        p_b_m: ball_centre,
        v_b_mps: Vector3::zeros(),
        w_core_radps: Vector3::zeros(),
        w_cover_radps: Vector3::zeros(),
        theta_rad: Vector3::zeros(),
        j_ball_ns: Vector3::zeros(),
        j_ground_ns: Vector3::zeros(),
        j_grip_ns: Vector3::zeros(),
    };
    let momentum_start = sys.club_momentum(&s);
    let r_ball = p.equipment.ball.radius_m;
    let mut out = Measures::default();
    let mut trace = Vec::new();
    let mut launch: Option<Launch> = None;
    let mut steps = 0usize;
    let mut next_trace_s = Real::NEG_INFINITY;
    let max_steps = 2_000_000;
    // The ground's forces held during the ball's contact, and when they were evaluated.
    let mut held: Option<(GroundForces, Real)> = None;
    let steppers = &p.steps;
    loop {
        let head_and_rigid = sys.head_and_rigid(&s);
        let head = &head_and_rigid.0;
        let ball_club = head.world_from_club.inverse_transform_vector(&(s.p_b_m - head.position_m));
        let gap = face_normal.dot(&(ball_club - face_point)) - r_ball;
        // The ball's contact is an event: approaching it, each step covers at most half the time the face
        // needs to reach the ball at its first approach speed, so the steps shrink geometrically from the
        // ground's to the ball's and the contact starts within one ball step (the head only slows in the turf).
        let stepper = if launch.is_some() {
            steppers.ground()
        } else if out.ball_touched {
            steppers.ball()
        } else {
            steppers.at_most(0.5 * gap / approach0)
        };
        // Events inside a long step end it there: the sole's first touch on the undisturbed swing, the end of
        // the follow-through.
        let touch = first_ground.filter(|_| out.first_ground_s.is_none() && stepper.h_s > model.ball_step_s);
        let follow_end = launch.is_some().then_some(out.t_separation_s + follow_s);
        let event = [touch, follow_end]
            .into_iter()
            .flatten()
            .filter(|t| *t > s.t_s + 1e-9 && *t < s.t_s + stepper.h_s - 1e-9)
            .reduce(Real::min);
        let one_off;
        let stepper = match event {
            Some(t) => {
                one_off = ModalStepper::new(&p.modal, t - s.t_s);
                &one_off
            }
            None => stepper,
        };
        let h = stepper.h_s;
        let near_ball = launch.is_none() && h <= model.ball_step_s;
        // During the ball's contact the ground's forces are held over `ground_hold_s` (they change over
        // milliseconds, the ball's over microseconds).
        let hold = near_ball && model.with_ground;
        let reuse = held.filter(|(_, t)| hold && s.t_s - t < model.ground_hold_s - 0.5 * h).map(|(g, _)| g);
        let (next, e) = sys.step_held(&s, head_and_rigid, stepper, hold, reuse.as_ref());
        if reuse.is_none() {
            held = hold.then_some((e.ground, s.t_s));
        }
        // Measures at the step's start (the ground's over the interval since the last step's start).
        let f_ground = e.ground.force_n();
        let clear = e.ground.phase == GroundPhase::Clear;
        let sample = GroundSample {
            t_s: s.t_s,
            sinkage_m: e.ground.sole.max_sinkage_m,
            edge_depth_m: if clear { e.ground.sole.max_sinkage_m } else { e.ground.face.leading_edge_depth_m },
            horizontal_speed_mps: e.head.velocity_mps.x.hypot(e.head.velocity_mps.z),
        };
        out.ground(sample, f_ground.norm());
        if let Some(c) = e.ball {
            if !out.ball_touched {
                out.ball_touched = true;
                out.t_ball_s = s.t_s;
                out.ground_impulse_before_ball = s.j_ground_ns;
                let fc = club.face.center_m;
                let v_fc = |b: &BodyMotion| {
                    (b.velocity_mps + b.angular_velocity_radps.cross(&(b.world_from_club * fc))).norm()
                };
                let rigid = sys.head(&State { shaft: ModalState::default(), ..s });
                out.speed_loss_mps = v_fc(&rigid) - v_fc(&e.head);
                let (fa, dl) = face_angles_deg(&e.head, &club.face.n0());
                let (fa0, dl0) = face_angles_deg(&rigid, &club.face.n0());
                out.face_change_deg = fa - fa0;
                out.loft_change_deg = dl - dl0;
            }
            out.ball_time_s += h;
            out.peak_ball_n = out.peak_ball_n.max(c.normal_n);
        } else if out.ball_touched && launch.is_none() {
            let b = &sys.ball;
            let spin = (b.core_inertia_kg_m2 * s.w_core_radps + b.cover_inertia_kg_m2 * s.w_cover_radps)
                / (b.core_inertia_kg_m2 + b.cover_inertia_kg_m2);
            launch = Some(Launch {
                ball_velocity_mps: s.v_b_mps,
                ball_spin_radps: spin,
                club_velocity_mps: e.head.velocity_mps,
                club_angular_velocity_radps: e.head.angular_velocity_radps,
                impulse_ns: b.mass_kg * s.v_b_mps,
            });
            out.t_separation_s = s.t_s;
        }
        // A trace point every `trace_every` ball steps of time (at every step where the steps are longer).
        if trace_every > 0 && s.t_s >= next_trace_s {
            next_trace_s = s.t_s + (trace_every as Real - 0.5) * model.ball_step_s;
            let (fa, dl) = face_angles_deg(&e.head, &club.face.n0());
            let horizontal = |v: Vector3| v.x.hypot(v.z);
            let sole = e.ground.sole.pressure_n + e.ground.sole.shear_n;
            trace.push(GroundTracePoint {
                t_ms: s.t_s * 1e3,
                sole_vertical_n: sole.y,
                sole_horizontal_n: horizontal(sole),
                face_horizontal_n: horizontal(e.ground.face.force_n),
                ground_vertical_n: f_ground.y,
                ground_horizontal_n: horizontal(f_ground),
                ball_normal_n: e.ball.map_or(0.0, |c| c.normal_n),
                face_angle_deg: fa,
                dynamic_loft_deg: dl,
                phase: e.ground.phase,
            });
        }
        steps += 1;
        if launch.is_some() {
            let ground_done = out.first_ground_s.is_some()
                && e.ground.phase == GroundPhase::Clear
                && s.t_s > out.first_ground_s.unwrap_or(0.0);
            if !model.with_ground || ground_done || s.t_s >= out.t_separation_s + follow_s - 1e-9 {
                break;
            }
        } else if (!out.ball_touched && s.t_s > 0.05) || steps >= max_steps {
            return Err(ImpactError::NotConverged {
                model: "ground",
                reason: "the face never released the ball".into(),
            });
        }
        s = next;
    }
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
        club_momentum_start: momentum_start,
        club_momentum_end: sys.club_momentum(&s),
        ball_impulse_ns: s.j_ball_ns,
        ground_impulse_before_ball_ns: out.ground_impulse_before_ball,
        ground_impulse_ns: s.j_ground_ns,
        grip_impulse_ns: s.j_grip_ns,
        steps,
        trace,
    })
}
