//! One continuous model = a ball, a contact law, a club and (optionally) the ground, integrated together from
//! first contact until the ball leaves the face.
//!
//! The contact's geometry comes from the face [`surface`](super::surface); the law turns it into forces on the
//! ball, applied equal and opposite to the head at the same point, so linear momentum is conserved to rounding
//! at every Runge-Kutta stage (the shared [`rk4_step`](crate::integrate::rk4_step)), by a fixed step or one
//! bounded by the friction's stiffness ([`StepSize`]). The law's own state (if any) is held through a step and
//! committed after it.

use super::ball::BallPart;
use super::club::{ClubPart, Head};
use super::ground::GroundReaction;
use super::law::{BallAt, Contact, ContactForce, ContactLaw};
use super::surface::FaceSurface;
use crate::impact::{ImpactError, ImpactState, Launch};
use crate::integrate::{rk4_step, Ode};
use crate::math::{Real, Vector3};

/// The parts of a continuous model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Assembly<L, B, C, G> {
    pub law: L,
    pub ball: B,
    pub club: C,
    pub ground: G,
    /// The face the ball touches, in the club frame.
    pub surface: FaceSurface,
}

/// How to integrate: the step and the longest contact before giving up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Integration {
    pub step_s: Real,
    pub max_contact_s: Real,
    /// Record a trace point every this many steps (0: none).
    pub trace_every: usize,
    /// The name errors carry.
    pub model: &'static str,
}

/// How the step is chosen within [`Integration`]'s bounds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub enum StepSize {
    /// Every step `step_s`.
    #[default]
    Fixed,
    /// From `step_s` up to `growth` times it, as far as the friction's stiffness allows: classical Runge-Kutta is
    /// stable for a decaying mode of rate `λ` while `h λ <= 2.78`, and the regularised friction (eq. 3.15) makes
    /// the slip at the contact such a mode, `λ = (∂F_t/∂v_t) · slip_compliance_per_kg`. Each step is
    /// `clamp(h_lambda / λ, step_s, growth · step_s)`, `λ` bounded over the step from its start ([`ContactLaw::slip_stiffness`]).
    Stiffness {
        /// The largest step as a multiple of `step_s`.
        growth: Real,
        /// The largest `h λ` a step may take.
        h_lambda: Real,
        /// How fast a tangential force changes the slip at the contact (1/kg): an upper bound of
        /// `1/m_ball + R²/I_surface + 1/m_club + |r_club|² / I_club,min`.
        slip_compliance_per_kg: Real,
    },
}

/// The club's and the ball's state together.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State<CS, BS> {
    pub club: CS,
    pub ball: BS,
}

/// The forces at one instant, for traces.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactForces {
    pub normal_n: Real,
    /// Friction on the ball (N, world).
    pub friction_n: Vector3,
    pub in_contact: bool,
    pub depth_m: Real,
}

/// One sample of a trace.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TracePoint {
    pub t_us: Real,
    pub normal_force_n: Real,
    /// Friction on the ball along the initial slip direction's opposite (N): positive while it drives the ball's
    /// cover against the slip, negative once it has reversed.
    pub tangential_force_n: Real,
    /// The ball's total spin (rpm) and the cover's (rpm).
    pub ball_spin_rpm: Real,
    pub cover_spin_rpm: Real,
    pub compression_mm: Real,
    /// Maw's model: how many of its rings are stuck.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stuck_rings: Option<usize>,
}

/// What a continuous run gives besides the launch.
#[derive(Debug, Clone, PartialEq)]
pub struct ContinuousResult {
    pub launch: Launch,
    pub contact_time_s: Real,
    pub peak_normal_force_n: Real,
    pub steps: usize,
    pub trace: Vec<TracePoint>,
    /// Total mechanical energy (kinetic + spring + contact) before and after (J).
    pub energy_before_j: Real,
    pub energy_after_j: Real,
    /// Largest increase of the total mechanical energy over any step (J).
    pub max_energy_increase_j: Real,
    /// Linear momentum (N s) and angular momentum about the world origin (N m s) of both bodies, before and
    /// after.
    pub momentum_before: (Vector3, Vector3),
    pub momentum_after: (Vector3, Vector3),
}

/// The rate of the whole system, with the contact forces it was computed from.
#[derive(Debug, Clone, Copy)]
pub struct Rate<CR, BR> {
    club: CR,
    ball: BR,
    forces: ContactForces,
}

/// The assembly with the law's state frozen for one step: the ODE the integrator sees.
struct Stage<'a, L: ContactLaw, B, C, G> {
    asm: &'a Assembly<L, B, C, G>,
    law_state: &'a L::State,
}

impl<L: ContactLaw, B: BallPart, C, G> Assembly<L, B, C, G> {
    /// The contact between ball and face in a state, if they touch (as the law places it).
    #[inline(always)]
    pub(super) fn contact(&self, head: &Head, ball: &B::State) -> Option<Contact> {
        let (centre_m, velocity_mps) = B::centre(ball);
        let at = BallAt {
            centre_m,
            velocity_mps,
            surface_spin_radps: B::surface_spin(ball),
            radius_m: self.ball.radius_m(),
        };
        self.law.contact(&self.surface, head, &at)
    }
}

impl<L: ContactLaw, B: BallPart, C: ClubPart, G: GroundReaction> Assembly<L, B, C, G> {
    #[inline]
    fn rate_with(&self, s: &State<C::State, B::State>, law_state: &L::State) -> Rate<C::Rate, B::Rate> {
        self.rate_and_step::<false>(s, law_state, &StepSize::Fixed, 0.0).0
    }

    /// The rate, and with `STEP` the next step by `step_size` from a base step `step_s` (else `step_s`).
    #[inline(always)]
    fn rate_and_step<const STEP: bool>(
        &self,
        s: &State<C::State, B::State>,
        law_state: &L::State,
        step_size: &StepSize,
        step_s: Real,
    ) -> (Rate<C::Rate, B::Rate>, Real) {
        let head = self.club.head(&s.club);
        let mut h = match *step_size {
            StepSize::Fixed => step_s,
            StepSize::Stiffness { growth, .. } => growth.max(1.0) * step_s,
        };
        let (mut force_club, mut torque_club, mut force_ball, mut r_ball, mut forces) =
            (Vector3::zeros(), Vector3::zeros(), Vector3::zeros(), Vector3::zeros(), ContactForces::default());
        if let Some(c) = self.contact(&head, &s.ball) {
            let ContactForce { normal_n, friction_n } = self.law.force(&c, law_state);
            if STEP {
                if let StepSize::Stiffness { h_lambda, slip_compliance_per_kg, .. } = *step_size {
                    h = self.stiff_step(&c, normal_n, h, step_s, h_lambda, slip_compliance_per_kg);
                }
            }
            force_ball = normal_n * c.normal + friction_n;
            r_ball = c.r_ball_m;
            force_club = -force_ball;
            torque_club = c.r_club_m.cross(&force_club);
            forces = ContactForces { normal_n, friction_n, in_contact: true, depth_m: c.overlap.depth_m };
        }
        if G::PRESENT {
            let g = self.ground.wrench(&head);
            force_club += g.force_n;
            torque_club += g.torque_nm;
        }
        let rate = Rate {
            club: self.club.rate(&s.club, &head, force_club, torque_club),
            ball: self.ball.rate(&s.ball, force_ball, r_ball),
            forces,
        };
        (rate, h)
    }

    /// The longest step up to `h_max` (and at least `step_s`) whose `h λ` stays within `h_lambda`, `λ` the slip
    /// mode's rate bounded over the slips a step of `h_max` can reach (a shorter step reaches fewer).
    #[inline]
    fn stiff_step(&self, c: &Contact, normal_n: Real, h_max: Real, step_s: Real, h_lambda: Real, k: Real) -> Real {
        let lambda = k * self.law.slip_stiffness(c, normal_n, h_max * k);
        if h_max * lambda <= h_lambda {
            h_max
        } else {
            (h_lambda / lambda).max(step_s)
        }
    }

    fn momentum(&self, s: &State<C::State, B::State>) -> (Vector3, Vector3) {
        let (lc, ac) = self.club.momentum(&s.club);
        let (lb, ab) = self.ball.momentum(&s.ball);
        (lc + lb, ac + ab)
    }

    fn energy_j(&self, s: &State<C::State, B::State>) -> Real {
        let head = self.club.head(&s.club);
        let (p_b, _) = B::centre(&s.ball);
        let r = self.ball.radius_m();
        let contact = self
            .surface
            .overlap(&head.world_from_club.inverse_transform_vector(&(p_b - head.position_m)), r)
            .map(|o| self.law.stored_energy_j(&self.surface, r, &o))
            .unwrap_or(0.0);
        self.club.energy_j(&s.club) + self.ball.energy_j(&s.ball) + contact
    }

    /// Runs the collision from `state` with the ball at rest with its centre at `ball_centre_m` (world); `slip0`
    /// is the direction traces measure the tangential force along.
    pub fn simulate(
        &self,
        state: &ImpactState,
        ball_centre_m: Vector3,
        slip0: Vector3,
        integration: &Integration,
    ) -> Result<ContinuousResult, ImpactError> {
        self.simulate_with_step(state, ball_centre_m, slip0, integration, &StepSize::Fixed)
    }

    /// [`Self::simulate`] with the step chosen by `step_size`.
    pub fn simulate_with_step(
        &self,
        state: &ImpactState,
        ball_centre_m: Vector3,
        slip0: Vector3,
        integration: &Integration,
        step_size: &StepSize,
    ) -> Result<ContinuousResult, ImpactError> {
        let mut s = State { club: self.club.initial(state), ball: self.ball.at_rest(ball_centre_m) };
        let mut law_state = L::State::default();
        let energy_before = self.energy_j(&s);
        let momentum_before = self.momentum(&s);
        let step_s = integration.step_s;
        let trace_every = integration.trace_every;
        let max_steps = (integration.max_contact_s / step_s).ceil() as usize;
        let mut trace = Vec::new();
        let (mut peak, mut touched, mut steps, mut max_increase) = (0.0f64, false, 0, 0.0f64);
        let mut energy = energy_before;
        let (mut t_s, mut contact_time) = (0.0, 0.0);
        loop {
            let stage = Stage { asm: self, law_state: &law_state };
            let (k1, h) = match step_size {
                StepSize::Fixed => (stage.rate(&s), step_s),
                StepSize::Stiffness { .. } => self.rate_and_step::<true>(&s, &law_state, step_size, step_s),
            };
            let cf = k1.forces;
            if trace_every > 0 && steps % trace_every == 0 {
                let spin = self.ball.spin(&s.ball);
                trace.push(TracePoint {
                    t_us: t_s * 1e6,
                    normal_force_n: cf.normal_n,
                    tangential_force_n: cf.friction_n.dot(&slip0),
                    ball_spin_rpm: crate::units::radps_to_rpm(spin.norm()),
                    cover_spin_rpm: crate::units::radps_to_rpm(B::cover_spin(&s.ball).norm()),
                    compression_mm: cf.depth_m * 1e3,
                    stuck_rings: None,
                });
            }
            peak = peak.max(cf.normal_n);
            if cf.in_contact {
                touched = true;
            } else if touched || steps > 10 {
                // Separated (or, after a few steps, never in contact: the face moves off).
                if touched {
                    contact_time = t_s;
                }
                break;
            }
            if steps >= max_steps || t_s >= integration.max_contact_s {
                return Err(ImpactError::NotConverged {
                    model: integration.model,
                    reason: format!("still in contact after {:.2} ms", integration.max_contact_s * 1e3),
                });
            }
            s = rk4_step(&stage, &s, &k1, h);
            if std::mem::size_of::<L::State>() > 0 {
                let head = self.club.head(&s.club);
                let c = self.contact(&head, &s.ball);
                self.law.commit(c.as_ref(), &mut law_state, h);
            }
            steps += 1;
            t_s = match *step_size {
                StepSize::Fixed => steps as Real * step_s,
                StepSize::Stiffness { .. } => t_s + h,
            };
            if trace_every > 0 || cfg!(debug_assertions) {
                let e = self.energy_j(&s);
                max_increase = max_increase.max(e - energy);
                energy = e;
            }
        }
        if !touched {
            return Err(ImpactError::NotConverged {
                model: integration.model,
                reason: "the face never pressed the ball".into(),
            });
        }
        let head = self.club.head(&s.club);
        let (_, v_b) = B::centre(&s.ball);
        Ok(ContinuousResult {
            launch: Launch {
                ball_velocity_mps: v_b,
                ball_spin_radps: self.ball.spin(&s.ball),
                club_velocity_mps: head.velocity_mps,
                club_angular_velocity_radps: head.angular_velocity_radps,
                impulse_ns: self.ball.mass_kg() * v_b,
            },
            contact_time_s: contact_time,
            peak_normal_force_n: peak,
            steps,
            trace,
            energy_before_j: energy_before,
            energy_after_j: self.energy_j(&s),
            max_energy_increase_j: max_increase,
            momentum_before,
            momentum_after: self.momentum(&s),
        })
    }
}

impl<L: ContactLaw, B: BallPart, C: ClubPart, G: GroundReaction> Ode for Stage<'_, L, B, C, G> {
    type State = State<C::State, B::State>;
    type Rate = Rate<C::Rate, B::Rate>;

    #[inline]
    fn rate(&self, s: &Self::State) -> Self::Rate {
        self.asm.rate_with(s, self.law_state)
    }

    #[inline]
    fn advance(s: &Self::State, r: &Self::Rate, h: Real) -> Self::State {
        State { club: C::advance(&s.club, &r.club, h), ball: B::advance(&s.ball, &r.ball, h) }
    }

    #[inline]
    fn advance_rk4(s: &Self::State, k: [&Self::Rate; 4], h: Real) -> Self::State {
        State {
            club: C::advance_rk4(&s.club, [&k[0].club, &k[1].club, &k[2].club, &k[3].club], h),
            ball: B::advance_rk4(&s.ball, [&k[0].ball, &k[1].ball, &k[2].ball, &k[3].ball], h),
        }
    }
}
