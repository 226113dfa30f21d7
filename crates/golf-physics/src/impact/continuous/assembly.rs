//! One continuous model = a ball, a contact law, a club and (optionally) the ground, integrated together from
//! first contact until the ball leaves the face, on the assembly's multi-rate stepping (`Assembly::run_stepped`,
//! a policy choosing each step).
//!
//! The contact's geometry comes from the face [`surface`](super::surface); the law turns it into forces on the
//! ball, applied equal and opposite to the head at the same point, so linear momentum is conserved to rounding
//! at every Runge-Kutta stage. This file holds the parts, the contact between ball and face, the bodies' energy
//! and momentum, and what a run gives ([`ContinuousResult`]).

use super::ball::BallPart;
use super::club::{ClubPart, Head};
use super::law::{BallAt, Contact, ContactLaw};
use super::surface::FaceSurface;
use crate::impact::Launch;
use crate::math::{Real, Vector3};

/// The parts of a continuous model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Assembly<L, B, C, G> {
    /// The contact law between ball and face ([`super::law`]).
    pub law: L,
    /// The ball ([`super::ball`]).
    pub ball: B,
    /// The club: a free head or a head on its shaft ([`super::club`]).
    pub club: C,
    /// The ground under the head ([`super::ground`]; `NoGround` for a ball on a tee).
    pub ground: G,
    /// The face the ball touches, in the club frame.
    pub surface: FaceSurface,
}

/// How to integrate: the base step and the longest contact before giving up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Integration {
    /// The base step (s).
    pub step_s: Real,
    /// The longest contact before the run gives up (s).
    pub max_contact_s: Real,
    /// Record a trace point every this many steps (0: none).
    pub trace_every: usize,
    /// The name errors carry.
    pub model: &'static str,
}

/// The club's and the ball's state together.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State<CS, BS> {
    /// The club's state.
    pub club: CS,
    /// The ball's state.
    pub ball: BS,
}

/// The forces at one instant, for traces.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactForces {
    /// The normal force on the ball (N, ≥ 0).
    pub normal_n: Real,
    /// Friction on the ball (N, world).
    pub friction_n: Vector3,
    /// Whether ball and face touch.
    pub in_contact: bool,
    /// How deep the ball is pressed into the face (m; the law's compression).
    pub depth_m: Real,
}

/// One sample of a trace.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TracePoint {
    /// Time from first contact (µs).
    pub t_us: Real,
    /// The normal force on the ball (N).
    pub normal_force_n: Real,
    /// Friction on the ball along the initial slip direction's opposite (N): positive while it drives the ball's
    /// cover against the slip, negative once it has reversed.
    pub tangential_force_n: Real,
    /// The ball's total spin (rpm) and the cover's (rpm).
    pub ball_spin_rpm: Real,
    /// See `ball_spin_rpm`.
    pub cover_spin_rpm: Real,
    /// The ball's compression (mm).
    pub compression_mm: Real,
    /// Maw's model: how many of its rings are stuck.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stuck_rings: Option<usize>,
}

/// What a continuous run gives besides the launch.
#[derive(Debug, Clone, PartialEq)]
pub struct ContinuousResult {
    /// The ball and the club as the ball leaves.
    pub launch: Launch,
    /// From first contact until the ball leaves (s).
    pub contact_time_s: Real,
    /// The largest normal force (N).
    pub peak_normal_force_n: Real,
    /// Steps taken.
    pub steps: usize,
    /// The contact's course, when asked for (`Integration::trace_every`).
    pub trace: Vec<TracePoint>,
    /// Total mechanical energy (kinetic + spring + contact) before and after (J).
    pub energy_before_j: Real,
    /// See `energy_before_j`.
    pub energy_after_j: Real,
    /// Largest increase of the total mechanical energy over any step (J).
    pub max_energy_increase_j: Real,
    /// Linear momentum (N s) and angular momentum about the world origin (N m s) of both bodies, before and
    /// after.
    pub momentum_before: (Vector3, Vector3),
    /// See `momentum_before`.
    pub momentum_after: (Vector3, Vector3),
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

impl<L: ContactLaw, B: BallPart, C: ClubPart, G> Assembly<L, B, C, G> {
    /// Linear momentum (N s) and angular momentum about the world origin (N m s) of both bodies.
    pub(super) fn momentum(&self, s: &State<C::State, B::State>) -> (Vector3, Vector3) {
        let (lc, ac) = self.club.momentum(&s.club);
        let (lb, ab) = self.ball.momentum(&s.ball);
        (lc + lb, ac + ab)
    }

    /// Total mechanical energy: kinetic, the bodies' springs and the contact's (J).
    pub(super) fn energy_j(&self, s: &State<C::State, B::State>) -> Real {
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
}
