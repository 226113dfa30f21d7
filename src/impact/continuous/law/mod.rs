//! Contact laws: the normal and tangential force between the ball and the face at one instant, from the contact's
//! geometry and relative motion, with the law's own state where it needs one (a memoryless law has `()`).
//!
//! - [`volumetric`]: eq. 3.14-3.15, the two-layer model's law (volume of intersection, tanh friction).
//! - [`hertz`]: eq. 3.16-3.19, Hertz with Hunt-Crossley damping; [`maw`]: Maw's rings; [`arakawa`]: eq. 3.23.
//!   These three run in `continuous::hertzian` with their own stage-wise slip (their rings need the slip since a
//!   step's start), not yet behind [`ContactLaw`].

pub mod arakawa;
pub mod hertz;
pub mod maw;
pub mod volumetric;

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
}

/// The force of a law on the ball: `normal_n` along the contact normal and `friction_n` in the tangent plane.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactForce {
    pub normal_n: Real,
    pub friction_n: Vector3,
}

/// A contact law. Forces on the ball; the face gets the opposite at the same point.
pub trait ContactLaw {
    /// History the law carries from step to step (stuck rings, a tangential displacement).
    type State: Clone + Default + std::fmt::Debug;
    /// The force at this instant; within a Runge-Kutta step the state is the one at the step's start.
    fn force(&self, contact: &Contact, state: &Self::State) -> ContactForce;
    /// Updates the state after an accepted step of `h` seconds ending at `contact` (`None`: out of contact).
    fn commit(&self, _contact: Option<&Contact>, _state: &mut Self::State, _h: Real) {}
    /// An upper bound of the friction's stiffness `∂F_t/∂v_t` (N s/m) at this contact under `normal_n`, over
    /// the slips the coming step can reach: `slip_per_n_mps` is how much a newton of tangential force held over
    /// that step changes the slip (m/s per N). A step-size bound for explicit integration; 0 if the law has none.
    fn slip_stiffness(&self, _contact: &Contact, _normal_n: Real, _slip_per_n_mps: Real) -> Real {
        0.0
    }
    /// Elastic energy stored in the contact at this overlap (J), for the energy balance.
    fn stored_energy_j(&self, surface: &FaceSurface, ball_radius_m: Real, overlap: &Overlap) -> Real;
}
