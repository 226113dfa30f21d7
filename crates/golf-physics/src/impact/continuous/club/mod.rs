//! The club side of a continuous model: the head's motion under the contact (and ground) forces.
//!
//! - [`FreeHead`]: a free 6-DOF rigid body (the seed's section 3.2 models: no shaft, no gravity during the half
//!   millisecond of contact).
//! - [`ShaftClub`]: the head on a flexible shaft whose grip follows the swing (seed section 4.1), its modes
//!   stepped by exponential time differencing ([`SteppedClub`]).
//!
//! [`ClubPart`] is a part the plain fixed-step Runge-Kutta advances; [`SteppedClub`] one that advances over each
//! step its own way on the same four stages, for the assembly's multi-rate stepping.

mod free_head;
mod on_shaft;

pub use free_head::{FreeHead, FreeHeadState};
pub use on_shaft::{ShaftClub, ShaftClubRate, ShaftClubState, ShaftMotion};

use crate::impact::ImpactState;
use crate::math::{Real, Rotation3, Vector3};

/// The head's pose and motion at an instant (world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Head {
    /// CG position (m).
    pub position_m: Vector3,
    /// The club frame's orientation in the world.
    pub world_from_club: Rotation3,
    /// CG velocity (m/s).
    pub velocity_mps: Vector3,
    /// Angular velocity (rad/s).
    pub angular_velocity_radps: Vector3,
}

/// The club part of a continuous model.
pub trait ClubPart {
    /// The club's state.
    type State: Copy;
    /// The state's rate of change.
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

/// The forces on the head during a step's stage, told apart: the ball's (N, world) with the lever from the head's
/// CG to where it acts (m), and the ground's resultant with its moment about the CG.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClubLoad {
    /// The ball's force on the head (N, world).
    pub ball_force_n: Vector3,
    /// From the head's CG to where the ball's force acts (m, world).
    pub ball_lever_m: Vector3,
    /// The ground's resultant force on the head (N, world).
    pub ground_force_n: Vector3,
    /// Its moment about the head's CG (N m, world).
    pub ground_torque_nm: Vector3,
}

/// A club part that advances over a whole step its own way on classical Runge-Kutta's four stages (the stages at
/// `t`, `t + h/2`, `t + h/2`, `t + h`): a shaft's modes by exponential time differencing, so the step follows
/// the forces rather than the stiffest mode. Its state is advanced only by the step's own coefficients
/// ([`Self::Step`]), built once per step size.
pub trait SteppedClub {
    /// The club's state.
    type State: Copy;
    /// The state's rate of change at one stage.
    type Rate: Copy;
    /// The head's motion at an instant with whatever the part derives beside it (the rigid frame a shaft rides
    /// on).
    type Motion: Copy;
    /// The coefficients of one step size.
    type Step;
    /// What stages two and three share (a free motion over half a step).
    type Half;
    /// The coefficients of steps of `h_s` (may cost as much as many steps: keep them).
    fn step(&self, h_s: Real) -> Self::Step;
    /// A step's size (s).
    fn step_s(step: &Self::Step) -> Real;
    /// The motion in state `s` at time `t_s` (the grip's drive runs on time).
    fn motion(&self, s: &Self::State, t_s: Real) -> Self::Motion;
    /// The head's pose and motion in a [`Self::Motion`].
    fn head(m: &Self::Motion) -> Head;
    /// The rate under the load on the head.
    fn rate(&self, s: &Self::State, m: &Self::Motion, load: &ClubLoad) -> Self::Rate;
    /// The part of stages two and three that depends on the step's start alone.
    fn free_half(&self, step: &Self::Step, s: &Self::State) -> Self::Half;
    /// Stage two (three) from the step's start along the rate of stage one (two).
    fn half(&self, step: &Self::Step, s: &Self::State, free: &Self::Half, k: &Self::Rate) -> Self::State;
    /// Stage four from the step's start, stage two and the rates of stages one and three.
    fn fourth(
        &self,
        step: &Self::Step,
        s: &Self::State,
        s2: &Self::State,
        k1: &Self::Rate,
        k3: &Self::Rate,
    ) -> Self::State;
    /// The step's end from its start and the four stages' rates.
    fn finish(&self, step: &Self::Step, s: &Self::State, k: [&Self::Rate; 4]) -> Self::State;
}
