//! The club side of a continuous model: the head's motion under the contact (and ground) forces.
//!
//! - [`FreeHead`]: a free 6-DOF rigid body (the seed's section 3.2 models: no shaft, no gravity during the half
//!   millisecond of contact).

mod free_head;

pub use free_head::{FreeHead, FreeHeadState};

use crate::impact::ImpactState;
use crate::math::{Real, Rotation3, Vector3};

/// The head's pose and motion at an instant (world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Head {
    /// CG position (m).
    pub position_m: Vector3,
    pub world_from_club: Rotation3,
    /// CG velocity (m/s).
    pub velocity_mps: Vector3,
    pub angular_velocity_radps: Vector3,
}

/// The club part of a continuous model.
pub trait ClubPart {
    type State: Copy;
    type Rate: Copy;
    /// The state at first contact.
    fn initial(&self, state: &ImpactState) -> Self::State;
    /// The head's pose and motion in a state.
    fn head(&self, s: &Self::State) -> Head;
    /// The rate under a force on the head (N, world) and its moment about the head's CG (N m, world).
    fn rate(&self, s: &Self::State, head: &Head, force_n: Vector3, torque_nm: Vector3) -> Self::Rate;
    /// `s + h r`.
    fn advance(s: &Self::State, r: &Self::Rate, h: Real) -> Self::State;
    /// `s + h (k1 + 2 k2 + 2 k3 + k4) / 6`, then any constraint restored (a unit quaternion).
    fn advance_rk4(s: &Self::State, k: [&Self::Rate; 4], h: Real) -> Self::State;
    /// Linear momentum (N s) and angular momentum about the world origin (N m s).
    fn momentum(&self, s: &Self::State) -> (Vector3, Vector3);
    /// Kinetic (and elastic) energy (J).
    fn energy_j(&self, s: &Self::State) -> Real;
}
