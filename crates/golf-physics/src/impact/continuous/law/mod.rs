//! Contact laws: the normal and tangential force between the ball and the face at one instant, from the contact's
//! geometry and relative motion, with the law's own state where it needs one (a memoryless law has `()`).
//!
//! - [`volumetric`]: eq. 3.14-3.15, the two-layer model's law (volume of intersection, tanh friction).
//! - [`hertz`]: eq. 3.16-3.19, Hertz with Hunt-Crossley damping, and [`hertz_contact::HertzContact`], that normal force
//!   with a tangential law in the tangent plane as one [`ContactLaw`]: [`maw`]'s rings or [`arakawa`]'s eq. 3.23.
//!   Their history (ring forces, a stuck force) is their [`ContactLaw::State`]; they ask for the slip since a
//!   step's start ([`ContactLaw::TRACKS_SLIP`]), place the force on the ball's radius (their own
//!   [`ContactLaw::contact`]), start each step from the force they committed and may split a step
//!   ([`ContactLaw::refine`]).

pub mod arakawa;
pub mod hertz;
pub mod hertz_contact;
pub mod maw;
pub mod volumetric;

use super::club::Head;
use super::surface::{FaceSurface, Overlap};
use crate::math::{Real, Vector3};

/// The contact at one instant, as every law sees it (world frame unless said).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Geometry of the overlap in the club frame (depth, volume, centroid, normal).
    pub overlap: Overlap,
    /// Unit normal out of the face toward the ball.
    pub normal: Vector3,
    /// Club CG -> the point where the force acts.
    pub r_club_m: Vector3,
    /// Ball centre -> the point where the force acts.
    pub r_ball_m: Vector3,
    /// Normal approach velocity `ẋ = (v_club − v_ball)·n` at the point (m/s, + while compressing).
    pub approach_mps: Real,
    /// Tangential velocity of the ball's surface relative to the face at the point (m/s).
    pub slip_mps: Vector3,
    /// The tangential displacement of the ball's surface relative to the face at the point since the start of
    /// the current step (m, in the tangent plane): the integral of `slip_mps`, for a law that asks for it
    /// ([`ContactLaw::TRACKS_SLIP`]); zero otherwise.
    pub slip_since_step_m: Vector3,
}

/// The ball as a contact sees it: its centre's position (m) and velocity (m/s), the spin of its surface (rad/s)
/// and its radius (m), world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallAt {
    /// Centre (m).
    pub centre_m: Vector3,
    /// Centre velocity (m/s).
    pub velocity_mps: Vector3,
    /// Angular velocity of the surface in contact (rad/s).
    pub surface_spin_radps: Vector3,
    /// Radius (m).
    pub radius_m: Real,
}

/// The force of a law on the ball: `normal_n` along the contact normal and `friction_n` in the tangent plane.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactForce {
    /// Along the contact normal, toward the ball (N).
    pub normal_n: Real,
    /// In the tangent plane (N).
    pub friction_n: Vector3,
}

/// A contact law. Forces on the ball; the face gets the opposite at the same point.
pub trait ContactLaw {
    /// History the law carries from step to step (stuck rings, a tangential displacement).
    type State: Clone + Default + std::fmt::Debug;
    /// Whether the law reads [`Contact::slip_since_step_m`]: the stepping then integrates the contact's slip
    /// beside the parts' state (a law that does not pays nothing).
    const TRACKS_SLIP: bool = false;
    /// The state at the first contact (the law's own start: a slip axis, ring widths from the approach speed).
    fn initial_state(&self) -> Self::State {
        Self::State::default()
    }
    /// The contact of `ball` with the face `surface` (club frame) of the head at `head`, if they touch: by
    /// default the overlap's volume, its centroid as the point the force acts at (the volumetric law's).
    #[inline(always)]
    fn contact(&self, surface: &FaceSurface, head: &Head, ball: &BallAt) -> Option<Contact> {
        let rot = &head.world_from_club;
        let overlap =
            surface.overlap(&rot.inverse_transform_vector(&(ball.centre_m - head.position_m)), ball.radius_m)?;
        let normal = rot * overlap.normal;
        let r_club_m = rot * overlap.centroid_m;
        let r_ball_m = head.position_m + r_club_m - ball.centre_m;
        let v_club = head.velocity_mps + head.angular_velocity_radps.cross(&r_club_m);
        let v_ball = ball.velocity_mps + ball.surface_spin_radps.cross(&r_ball_m);
        let v_rel = v_ball - v_club;
        Some(Contact {
            overlap,
            normal,
            r_club_m,
            r_ball_m,
            approach_mps: -v_rel.dot(&normal),
            slip_mps: v_rel - v_rel.dot(&normal) * normal,
            slip_since_step_m: Vector3::zeros(),
        })
    }
    /// The force at this instant; within a Runge-Kutta step the state is the one at the step's start.
    fn force(&self, contact: &Contact, state: &Self::State) -> ContactForce;
    /// The force at a step's start (its first stage): [`Self::force`], unless the law found it when it committed
    /// the step before (the same instant) and keeps it in its state.
    #[inline(always)]
    fn start_force(&self, contact: &Contact, state: &Self::State) -> ContactForce {
        self.force(contact, state)
    }
    /// Updates the state after an accepted step of `h` seconds ending at `contact` (`None`: out of contact).
    fn commit(&self, _contact: Option<&Contact>, _state: &mut Self::State, _h: Real) {}
    /// Whether the step starting at `contact` (the committed state) is near a switch of the law that a full step
    /// would resolve only to first order, so the stepping should take its policy's finer step.
    fn refine(&self, _contact: &Contact, _state: &Self::State) -> bool {
        false
    }
    /// An upper bound of the friction's stiffness `∂F_t/∂v_t` (N s/m) at this contact under `normal_n`, over
    /// the slips the coming step can reach: `slip_per_n_mps` is how much a newton of tangential force held over
    /// that step changes the slip (m/s per N). A step-size bound for explicit integration; 0 if the law has none.
    fn slip_stiffness(&self, _contact: &Contact, _normal_n: Real, _slip_per_n_mps: Real) -> Real {
        0.0
    }
    /// Elastic energy stored in the contact at this overlap (J), for the energy balance.
    fn stored_energy_j(&self, surface: &FaceSurface, ball_radius_m: Real, overlap: &Overlap) -> Real;
    /// Elastic energy the law's history holds besides (stuck rings' springs, J).
    fn history_energy_j(&self, _state: &Self::State) -> Real {
        0.0
    }
}
