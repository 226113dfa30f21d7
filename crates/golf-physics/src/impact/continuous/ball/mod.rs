//! The ball side of a continuous model.
//!
//! - [`TwoLayerBall`]: core and cover with a rotary spring-damper between them (seed section 3.2.1, Table 3.5).
//! - [`RigidBall`]: one rigid sphere.

mod rigid;
mod two_layer;

pub use rigid::{RigidBall, RigidBallState};
pub use two_layer::{TwoLayerBall, TwoLayerBallState};

use crate::math::{Real, Vector3};

/// The ball part of a continuous model. The ball starts at rest.
pub trait BallPart {
    /// The ball's state (centre, velocity, spins).
    type State: Copy;
    /// The state's rate of change.
    type Rate: Copy;
    /// The ball's mass (kg).
    fn mass_kg(&self) -> Real;
    /// The ball's radius (m).
    fn radius_m(&self) -> Real;
    /// At rest with its centre at `centre_m`.
    fn at_rest(&self, centre_m: Vector3) -> Self::State;
    /// Centre position (m) and velocity (m/s).
    fn centre(s: &Self::State) -> (Vector3, Vector3);
    /// Angular velocity of the surface in contact (the cover of a layered ball), rad/s.
    fn surface_spin(s: &Self::State) -> Vector3;
    /// The spin the ball flies with: total angular momentum over total inertia (rad/s).
    fn spin(&self, s: &Self::State) -> Vector3;
    /// The rate under a force (N) acting at `r_m` from the centre (world).
    fn rate(&self, s: &Self::State, force_n: Vector3, r_m: Vector3) -> Self::Rate;
    /// Explicit Euler: `s + r h`.
    fn advance(s: &Self::State, r: &Self::Rate, h: Real) -> Self::State;
    /// The classical Runge-Kutta step from its four stage rates: `s + (h/6) (k1 + 2 k2 + 2 k3 + k4)`.
    fn advance_rk4(s: &Self::State, k: [&Self::Rate; 4], h: Real) -> Self::State;
    /// The same step as [`Self::advance_rk4`] rounded as the assembly's multi-rate stepping rounds it,
    /// `s + (k1 + 2 k2 + 2 k3 + k4) (h/6)`: each system keeps its own floating-point order
    /// ([`crate::integrate`]). [`Self::advance_rk4`] unless a part says otherwise.
    fn advance_rk4_scaled(s: &Self::State, k: [&Self::Rate; 4], h: Real) -> Self::State {
        Self::advance_rk4(s, k, h)
    }
    /// Linear momentum and angular momentum about the world origin.
    fn momentum(&self, s: &Self::State) -> (Vector3, Vector3);
    /// Kinetic and internal elastic energy (J).
    fn energy_j(&self, s: &Self::State) -> Real;
    /// The cover's spin for traces (the ball's spin for a one-layer ball).
    fn cover_spin(s: &Self::State) -> Vector3 {
        Self::surface_spin(s)
    }
}

#[inline]
pub(crate) fn rk4_mean(a: Vector3, b: Vector3, c: Vector3, d: Vector3) -> Vector3 {
    (a + 2.0 * b + 2.0 * c + d) / 6.0
}
