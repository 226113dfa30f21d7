//! How a strike steps on the assembly's multi-rate stepping, and what it measures at each step.
//!
//! - Steps: `ground_step_s` while only the ground acts and after the ball leaves, `ball_step_s` from the ball's
//!   contact until it leaves; approaching the ball, each step covers at most half the time the face needs to
//!   reach it at its first approach speed, so the steps shrink by halves from the one to the other and the
//!   contact starts within one ball step (the head only slows in the turf).
//! - Events: the sole's first touch on the undisturbed swing (a long step ends there), the end of the
//!   follow-through.
//! - The ground's forces are held over `ground_hold_s` during the ball's contact.
//! - It stops once the ground contact is over after the ball left, or at the end of the follow-through.

use super::measures::{GroundSample, Measures};
use super::{GroundModel, GroundTracePoint};
use crate::equipment::ClubSpec;
use crate::impact::continuous::assembly::{Assembly, State};
use crate::impact::continuous::ball::{BallPart, TwoLayerBall, TwoLayerBallState};
use crate::impact::continuous::club::{Head, ShaftClub, ShaftClubState, ShaftMotion};
use crate::impact::continuous::ground::{GroundForces, GroundPhase, SampledGround, SoilGround};
use crate::impact::continuous::law::volumetric::Volumetric;
use crate::impact::continuous::shaft::exponential::ModalStepper;
use crate::impact::continuous::stepping::{Flow, StepLadder, StepPolicy, StepStart};
use crate::impact::{ImpactError, Launch};
use crate::math::{Real, Vector3};

/// The iron-plus-ground system on the assembly, on the soil (`G = SoilGround`) or on a ground computing the same
/// forces another way ([`super::PreparedGround::simulate_with`]).
pub(super) type StrikeSystem<'a, G = SoilGround> = Assembly<Volumetric, TwoLayerBall, ShaftClub<'a>, G>;

/// At most this many steps before giving up.
const MAX_STEPS: usize = 2_000_000;

/// Face angle (open +) and dynamic loft (deg) of a head whose face normal is `n0` in its frame.
fn face_angles_deg(head: &Head, n0: &Vector3) -> (Real, Real) {
    let n = head.world_from_club * n0;
    (n.z.atan2(n.x).to_degrees(), n.y.clamp(-1.0, 1.0).asin().to_degrees())
}

/// The strike's stepping and what it has measured so far.
pub(super) struct StrikeSteps<'a> {
    pub model: &'a GroundModel,
    pub club: &'a ClubSpec,
    pub ladder: &'a StepLadder<ModalStepper>,
    /// The flat face's point and outward normal (club frame), the ball's radius (m) and the face's first
    /// approach speed toward the ball (m/s).
    pub face_point_m: Vector3,
    pub face_normal: Vector3,
    pub ball_radius_m: Real,
    pub approach_mps: Real,
    /// The sole's first touch on the undisturbed swing (s from the ball's first contact).
    pub first_ground_s: Option<Real>,
    /// How long to follow the ground contact after the ball leaves (s).
    pub follow_s: Real,
    /// A trace point every this many ball steps of time (0: none).
    pub trace_every: usize,
    pub out: Measures,
    pub trace: Vec<GroundTracePoint>,
    pub launch: Option<Launch>,
    pub steps: usize,
    pub next_trace_s: Real,
}

impl<'a, G: SampledGround<Forces = GroundForces>> StepPolicy<Volumetric, TwoLayerBall, ShaftClub<'a>, G>
    for StrikeSteps<'_>
{
    fn step(&self, _t_s: Real, s: &State<ShaftClubState, TwoLayerBallState>, head: &Head) -> &ModalStepper {
        if self.launch.is_some() {
            return self.ladder.long();
        }
        if self.out.ball_touched {
            return self.ladder.short();
        }
        let ball_club = head.world_from_club.inverse_transform_vector(&(s.ball.centre_m - head.position_m));
        let gap = self.face_normal.dot(&(ball_club - self.face_point_m)) - self.ball_radius_m;
        self.ladder.at_most(0.5 * gap / self.approach_mps)
    }

    fn events(&self, _t_s: Real, h_s: Real) -> impl IntoIterator<Item = Real> {
        let touch = self.first_ground_s.filter(|_| self.out.first_ground_s.is_none() && h_s > self.model.ball_step_s);
        let follow_end = self.launch.is_some().then_some(self.out.t_separation_s + self.follow_s);
        [touch, follow_end].into_iter().flatten()
    }

    fn ground_hold_s(&self, h_s: Real) -> Option<Real> {
        let near_ball = self.launch.is_none() && h_s <= self.model.ball_step_s;
        (near_ball && self.model.with_ground).then_some(self.model.ground_hold_s)
    }

    fn observe(
        &mut self,
        asm: &StrikeSystem<'a, G>,
        t_s: Real,
        h_s: Real,
        s: &State<ShaftClubState, TwoLayerBallState>,
        start: &StepStart<ShaftMotion, GroundForces>,
    ) -> Result<Flow, ImpactError> {
        let (head, ground, out) = (&start.motion.head, &start.ground, &mut self.out);
        // Measures at the step's start (the ground's over the interval since the last step's start).
        let f_ground = ground.force_n();
        let clear = ground.phase == GroundPhase::Clear;
        let sample = GroundSample {
            t_s,
            sinkage_m: ground.sole.max_sinkage_m,
            edge_depth_m: if clear { ground.sole.max_sinkage_m } else { ground.face.leading_edge_depth_m },
            horizontal_speed_mps: head.velocity_mps.x.hypot(head.velocity_mps.z),
        };
        out.ground(sample, f_ground.norm());
        let n0 = self.club.face.n0();
        if let Some(c) = start.ball {
            if !out.ball_touched {
                out.ball_touched = true;
                out.t_ball_s = t_s;
                out.ground_impulse_before_ball_n_s = s.club.j_ground_n_s;
                let fc = self.club.face.center_m;
                let v_fc =
                    |b: &Head| (b.velocity_mps + b.angular_velocity_radps.cross(&(b.world_from_club * fc))).norm();
                let rigid = asm.club.undisturbed_head(&s.club, t_s);
                out.speed_loss_mps = v_fc(&rigid) - v_fc(head);
                let (fa, dl) = face_angles_deg(head, &n0);
                let (fa0, dl0) = face_angles_deg(&rigid, &n0);
                out.face_change_deg = fa - fa0;
                out.loft_change_deg = dl - dl0;
            }
            out.ball_time_s += h_s;
            out.peak_ball_n = out.peak_ball_n.max(c.normal_n);
        } else if out.ball_touched && self.launch.is_none() {
            let b = &asm.ball;
            self.launch = Some(Launch {
                ball_velocity_mps: s.ball.velocity_mps,
                ball_spin_radps: b.spin(&s.ball),
                club_velocity_mps: head.velocity_mps,
                club_angular_velocity_radps: head.angular_velocity_radps,
                impulse_n_s: b.mass_kg * s.ball.velocity_mps,
            });
            out.t_separation_s = t_s;
        }
        // A trace point every `trace_every` ball steps of time (at every step where the steps are longer).
        if self.trace_every > 0 && t_s >= self.next_trace_s {
            self.next_trace_s = t_s + (self.trace_every as Real - 0.5) * self.model.ball_step_s;
            let (fa, dl) = face_angles_deg(head, &n0);
            let horizontal = |v: Vector3| v.x.hypot(v.z);
            let sole = ground.sole.pressure_n + ground.sole.shear_n;
            self.trace.push(GroundTracePoint {
                t_ms: t_s * 1e3,
                sole_vertical_n: sole.y,
                sole_horizontal_n: horizontal(sole),
                face_horizontal_n: horizontal(ground.face.force_n),
                ground_vertical_n: f_ground.y,
                ground_horizontal_n: horizontal(f_ground),
                ball_normal_n: start.ball.map_or(0.0, |c| c.normal_n),
                face_angle_deg: fa,
                dynamic_loft_deg: dl,
                phase: ground.phase,
            });
        }
        self.steps += 1;
        let out = &self.out;
        if self.launch.is_some() {
            let ground_done = out.first_ground_s.is_some()
                && ground.phase == GroundPhase::Clear
                && t_s > out.first_ground_s.unwrap_or(0.0);
            if !self.model.with_ground || ground_done || t_s >= out.t_separation_s + self.follow_s - 1e-9 {
                return Ok(Flow::Stop);
            }
        } else if (!out.ball_touched && t_s > 0.05) || self.steps >= MAX_STEPS {
            return Err(ImpactError::NotConverged {
                model: "ground",
                reason: "the face never released the ball".into(),
            });
        }
        Ok(Flow::Continue)
    }
}
