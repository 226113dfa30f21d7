//! How a Hertzian collision steps on the assembly's stepping, and what it measures at each step.
//!
//! - Steps: `step_s` (the model's), and an eighth of it for a step whose start the law flags near one of its
//!   switches (Arakawa's envelope near eq. 3.23's sign change); the step in which the ball leaves ends where the
//!   overlap closes (the stepping's secant), and the run with it.
//! - Measures at each step's start, from what acted there (the force the law committed at the step before):
//!   contact, peak normal force, the tangential force along the face's initial slip (its reversal), the total
//!   energy (kinetic + Hertz + the law's history) and a trace point every `trace_every` steps.
//! - Stops at a step's start out of contact after a contact (or, never touched, after ten steps); more than
//!   `max_contact_s` in contact is an error naming the model.

use super::HertzTracePoint;
use crate::impact::continuous::assembly::{Assembly, State};
use crate::impact::continuous::ball::{BallPart, RigidBall, RigidBallState};
use crate::impact::continuous::club::{ClubPart, FreeHead, FreeHeadState, Head};
use crate::impact::continuous::ground::NoGround;
use crate::impact::continuous::law::hertz::Tangential;
use crate::impact::continuous::law::hertz_contact::HertzContact;
use crate::impact::continuous::law::ContactLaw;
use crate::impact::continuous::stepping::{Flow, StepPolicy, StepStart};
use crate::impact::ImpactError;
use crate::math::{Real, Vector3};

/// A Hertzian model's parts: eq. 3.16 and a tangential law between a rigid ball and a free head, no ground.
pub(super) type HertzSystem<T> = Assembly<HertzContact<T>, RigidBall, FreeHead, NoGround>;
type HertzStepState = State<FreeHeadState, RigidBallState>;

/// Kinetic energy of both bodies, the Hertz contact's elastic energy and the law's history's (J).
pub(super) fn energy_j<T: Tangential>(asm: &HertzSystem<T>, s: &HertzStepState, history_j: Real) -> Real {
    let head = ClubPart::head(&asm.club, &s.club);
    let ke = ClubPart::energy_j(&asm.club, &s.club) + asm.ball.energy_j(&s.ball);
    let elastic = asm
        .contact(&head, &s.ball)
        .map_or(0.0, |c| asm.law.stored_energy_j(&asm.surface, asm.ball.radius_m, &c.overlap));
    ke + elastic + history_j
}

/// The collision's stepping and what it has measured so far.
pub(super) struct HertzSteps {
    pub step_s: Real,
    /// The step the law's flag asks for (an eighth of `step_s`).
    pub fine_s: Real,
    pub max_contact_s: Real,
    /// The name errors carry.
    pub model: &'static str,
    /// The face's initial slip direction (tangential forces are traced along it) and the axis spin is traced
    /// about (normal x slip).
    pub face_dir: Vector3,
    pub spin_axis: Vector3,
    /// A trace point every this many steps (0: none); with none the energy is followed only in debug builds.
    pub trace_every: usize,
    pub trace: Vec<HertzTracePoint>,
    pub touched: bool,
    pub steps: usize,
    /// The start of the step it stopped at (the ball left there), if it stopped.
    pub stopped_s: Option<Real>,
    pub peak_normal_n: Real,
    /// The largest and smallest tangential force along `face_dir` (N).
    pub ft_max_n: Real,
    pub ft_min_n: Real,
    /// The total energy at the last step's start and its largest increase over a step (J).
    pub energy_j: Real,
    pub max_energy_increase_j: Real,
    /// The law's history at this step's start: stuck rings, stored energy (J).
    stuck_rings: Option<usize>,
    history_j: Real,
}

impl HertzSteps {
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        step_s: Real,
        fine_s: Real,
        max_contact_s: Real,
        model: &'static str,
        face_dir: Vector3,
        spin_axis: Vector3,
        trace_every: usize,
        energy_before_j: Real,
    ) -> Self {
        HertzSteps {
            step_s,
            fine_s,
            max_contact_s,
            model,
            face_dir,
            spin_axis,
            trace_every,
            trace: Vec::new(),
            touched: false,
            steps: 0,
            stopped_s: None,
            peak_normal_n: 0.0,
            ft_max_n: 0.0,
            ft_min_n: 0.0,
            energy_j: energy_before_j,
            max_energy_increase_j: 0.0,
            stuck_rings: None,
            history_j: 0.0,
        }
    }

    /// Whether the energy is followed step by step.
    fn follows_energy(&self) -> bool {
        self.trace_every > 0 || cfg!(debug_assertions)
    }

    /// The law's stored energy in the state it stopped in (J).
    pub fn final_history_j(&self) -> Real {
        if self.stopped_s.is_some() {
            self.history_j
        } else {
            0.0 // released at the separation
        }
    }
}

impl<T: Tangential> StepPolicy<HertzContact<T>, RigidBall, FreeHead, NoGround> for HertzSteps {
    fn step(&self, _: Real, _: &HertzStepState, _: &Head) -> &Real {
        &self.step_s
    }

    fn refined_step(&self) -> Option<&Real> {
        Some(&self.fine_s)
    }

    fn end_at_separation(&self) -> bool {
        true
    }

    fn law_state(&mut self, law: &HertzContact<T>, state: &<HertzContact<T> as ContactLaw>::State) {
        self.stuck_rings = law.stuck_rings(state);
        if self.follows_energy() {
            self.history_j = law.history_energy_j(state);
        }
    }

    fn observe(
        &mut self,
        asm: &HertzSystem<T>,
        t_s: Real,
        _: Real,
        s: &HertzStepState,
        start: &StepStart<Head, ()>,
    ) -> Result<Flow, ImpactError> {
        if self.steps > 0 && self.follows_energy() {
            let e = energy_j(asm, s, self.history_j);
            self.max_energy_increase_j = self.max_energy_increase_j.max(e - self.energy_j);
            self.energy_j = e;
        }
        if let Some(c) = &start.ball {
            self.touched = true;
            self.peak_normal_n = self.peak_normal_n.max(c.normal_n);
            let along = c.friction_n.dot(&self.face_dir);
            self.ft_max_n = self.ft_max_n.max(along);
            self.ft_min_n = self.ft_min_n.min(along);
        }
        if self.trace_every > 0 && self.steps % self.trace_every == 0 {
            let (normal_n, along_n, x_m) = start
                .ball
                .as_ref()
                .map_or((0.0, 0.0, 0.0), |c| (c.normal_n, c.friction_n.dot(&self.face_dir), c.depth_m));
            self.trace.push(HertzTracePoint {
                t_us: t_s * 1e6,
                normal_force_n: normal_n,
                tangential_force_n: along_n,
                ball_spin_rpm: crate::units::radps_to_rpm(asm.ball.spin(&s.ball).dot(&self.spin_axis)),
                compression_mm: x_m * 1e3,
                stuck_rings: self.stuck_rings,
            });
        }
        if start.ball.is_none() && (self.touched || self.steps > 10) {
            self.stopped_s = Some(t_s);
            return Ok(Flow::Stop);
        }
        if t_s >= self.max_contact_s {
            return Err(ImpactError::NotConverged {
                model: self.model,
                reason: format!("still in contact after {:.2} ms", self.max_contact_s * 1e3),
            });
        }
        self.steps += 1;
        Ok(Flow::Continue)
    }
}
