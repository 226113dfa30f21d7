//! The two-layer model's stepping: each step as long as the friction's stiffness allows, and what a
//! [`ContinuousResult`] reports measured as it steps (the trace, the contact time, the peak force, energy and
//! momentum).
//!
//! The step: classical Runge-Kutta is stable on a decaying mode of rate `λ` while `h λ <= 2.78`, and the
//! regularised friction (eq. 3.15) makes the slip at the contact such a mode, `λ = (∂F_t/∂v_t) ·
//! slip_compliance_per_kg`. Each step is `clamp(h_lambda / λ, step_s, growth · step_s)`, `λ` bounded over the slips
//! the longest step can reach from its start (`ContactLaw::slip_stiffness`); out of contact it is the longest.
//! Without a bound every step is `step_s`.
//!
//! It stops at the first step's start out of contact after a contact (or, never touched, after ten steps: the
//! face moves off); still in contact after `max_contact_s` is an error naming the model.

use super::{Flow, StepPolicy, StepStart, SteppedState};
use crate::impact::continuous::assembly::{Assembly, ContinuousResult, Integration, State, TracePoint};
use crate::impact::continuous::ball::BallPart;
use crate::impact::continuous::club::{ClubPart, Head, SteppedClub};
use crate::impact::continuous::ground::SampledGround;
use crate::impact::continuous::law::{Contact, ContactForce, ContactLaw};
use crate::impact::{ImpactError, ImpactState, Launch};
use crate::math::{Real, Vector3};
use crate::units::radps_to_rpm;

/// How far the friction's stiffness lets a step grow (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StiffnessBound {
    /// The largest step as a multiple of `step_s`.
    pub growth: Real,
    /// The largest `h λ` a step may take.
    pub h_lambda: Real,
    /// How fast a tangential force changes the slip at the contact (1/kg): an upper bound of
    /// `1/m_ball + R²/I_surface + 1/m_club + |r_club|² / I_club,min`.
    pub slip_compliance_per_kg: Real,
}

/// The steps of a ball's contact with the face and what they measure (module docs).
#[derive(Debug, Clone)]
pub struct StiffnessStep<S> {
    integration: Integration,
    bound: Option<StiffnessBound>,
    /// The longest step and its size (s).
    long: S,
    long_s: Real,
    /// The direction traces measure the tangential force along.
    slip0: Vector3,
    max_steps: usize,
    steps: usize,
    touched: bool,
    contact_time_s: Real,
    peak_normal_force_n: Real,
    trace: Vec<TracePoint>,
    energy_before_j: Real,
    energy_j: Real,
    max_energy_increase_j: Real,
    momentum_before: (Vector3, Vector3),
}

impl<S> StiffnessStep<S> {
    /// Steps of `integration.step_s`, growing up to `growth` times it as `bound` allows (`None`: fixed); `slip0`
    /// the direction traces measure the tangential force along.
    pub fn new<C: SteppedClub<Step = S>>(
        club: &C,
        integration: Integration,
        bound: Option<StiffnessBound>,
        slip0: Vector3,
    ) -> Self {
        let long_s = integration.step_s * bound.map_or(1.0, |b| b.growth.max(1.0));
        StiffnessStep {
            integration,
            bound,
            long: club.step(long_s),
            long_s,
            slip0,
            max_steps: (integration.max_contact_s / integration.step_s).ceil() as usize,
            steps: 0,
            touched: false,
            contact_time_s: 0.0,
            peak_normal_force_n: 0.0,
            trace: Vec::new(),
            energy_before_j: 0.0,
            energy_j: 0.0,
            max_energy_increase_j: 0.0,
            momentum_before: (Vector3::zeros(), Vector3::zeros()),
        }
    }

    /// Runs `asm`'s collision from `state`, the ball at rest with its centre at `ball_centre_m` (world), with
    /// these steps: the launch and what was measured.
    pub fn run<L, B, C, G>(
        mut self,
        asm: &Assembly<L, B, C, G>,
        state: &ImpactState,
        ball_centre_m: Vector3,
    ) -> Result<ContinuousResult, ImpactError>
    where
        L: ContactLaw,
        B: BallPart,
        C: SteppedClub<Step = S> + ClubPart<State = <C as SteppedClub>::State>,
        G: SampledGround,
    {
        let s0 = State { club: ClubPart::initial(&asm.club, state), ball: asm.ball.at_rest(ball_centre_m) };
        let (s, _) = asm.run_stepped(s0, 0.0, &mut self)?;
        if !self.touched {
            return Err(ImpactError::NotConverged {
                model: self.integration.model,
                reason: "the face never pressed the ball".into(),
            });
        }
        let head = ClubPart::head(&asm.club, &s.club);
        let (_, v_b) = B::centre(&s.ball);
        Ok(ContinuousResult {
            launch: Launch {
                ball_velocity_mps: v_b,
                ball_spin_radps: asm.ball.spin(&s.ball),
                club_velocity_mps: head.velocity_mps,
                club_angular_velocity_radps: head.angular_velocity_radps,
                impulse_n_s: asm.ball.mass_kg() * v_b,
            },
            contact_time_s: self.contact_time_s,
            peak_normal_force_n: self.peak_normal_force_n,
            steps: self.steps,
            trace: self.trace,
            energy_before_j: self.energy_before_j,
            energy_after_j: asm.energy_j(&s),
            max_energy_increase_j: self.max_energy_increase_j,
            momentum_before: self.momentum_before,
            momentum_after: asm.momentum(&s),
        })
    }
}

impl<L, B, C, G> StepPolicy<L, B, C, G> for StiffnessStep<C::Step>
where
    L: ContactLaw,
    B: BallPart,
    C: SteppedClub + ClubPart<State = <C as SteppedClub>::State>,
    G: SampledGround,
{
    #[inline]
    fn step(&self, _: Real, _: &SteppedState<B, C>, _: &Head) -> &C::Step {
        &self.long
    }

    #[inline]
    fn contact_step_s(&self, asm: &Assembly<L, B, C, G>, contact: &Contact, force: &ContactForce) -> Option<Real> {
        let b = self.bound.as_ref()?;
        let k = b.slip_compliance_per_kg;
        let lambda = k * asm.law.slip_stiffness(contact, force.normal_n, self.long_s * k);
        (self.long_s * lambda > b.h_lambda).then(|| (b.h_lambda / lambda).max(self.integration.step_s))
    }

    fn observe(
        &mut self,
        asm: &Assembly<L, B, C, G>,
        t_s: Real,
        _: Real,
        s: &SteppedState<B, C>,
        start: &StepStart<C::Motion, G::Forces>,
    ) -> Result<Flow, ImpactError> {
        let trace_every = self.integration.trace_every;
        if self.steps == 0 {
            self.energy_before_j = asm.energy_j(s);
            self.energy_j = self.energy_before_j;
            self.momentum_before = asm.momentum(s);
        } else if trace_every > 0 || cfg!(debug_assertions) {
            let e = asm.energy_j(s);
            self.max_energy_increase_j = self.max_energy_increase_j.max(e - self.energy_j);
            self.energy_j = e;
        }
        let cf = start.ball.unwrap_or_default();
        if trace_every > 0 && self.steps % trace_every == 0 {
            self.trace.push(TracePoint {
                t_us: t_s * 1e6,
                normal_force_n: cf.normal_n,
                tangential_force_n: cf.friction_n.dot(&self.slip0),
                ball_spin_rpm: radps_to_rpm(asm.ball.spin(&s.ball).norm()),
                cover_spin_rpm: radps_to_rpm(B::cover_spin(&s.ball).norm()),
                compression_mm: cf.depth_m * 1e3,
                stuck_rings: None,
            });
        }
        self.peak_normal_force_n = self.peak_normal_force_n.max(cf.normal_n);
        if cf.in_contact {
            self.touched = true;
        } else if self.touched || self.steps > 10 {
            if self.touched {
                self.contact_time_s = t_s;
            }
            return Ok(Flow::Stop);
        }
        if self.steps >= self.max_steps || t_s >= self.integration.max_contact_s {
            return Err(ImpactError::NotConverged {
                model: self.integration.model,
                reason: format!("still in contact after {:.2} ms", self.integration.max_contact_s * 1e3),
            });
        }
        self.steps += 1;
        Ok(Flow::Continue)
    }
}
