//! The volumetric contact law of the two-layer model (seed section 3.2.1; Gonthier and McPhee, Brown and McPhee).
//!
//! - Normal force, eq. 3.14: `F_N = kV + d ẋ kV` along the contact normal, `V` the volume of intersection
//!   (sphere-plane for irons, sphere-sphere with the face sphere for drivers, see [`surface`](super::super::surface)),
//!   `ẋ` the normal approach velocity, applied at the centroid of the intersection. Never negative (no adhesion).
//! - Friction, eq. 3.15 (and 2.8): `F_f = μ F_N tanh(4 v_t / v_tr)` against the relative tangential velocity `v_t`
//!   of the ball's cover at the contact.
//!
//! Its elastic energy is `k ∫ V dδ` over the overlap ([`overlap_energy`]).

use super::{Contact, ContactForce, ContactLaw};
use crate::impact::continuous::surface::{overlap_energy, FaceSurface, Overlap};
use crate::math::{tanh_over_x, Real};

/// Eq. 3.14-3.15 with their Table 3.5 parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Volumetric {
    /// Volumetric stiffness `k` (N/m³).
    pub k_v_n_per_m3: Real,
    /// Hunt-Crossley damping `d` (s/m).
    pub d_s_per_m: Real,
    /// Dynamic friction coefficient `μ`.
    pub mu: Real,
    /// Friction transition velocity `v_tr` (m/s).
    pub v_tr_mps: Real,
}

impl ContactLaw for Volumetric {
    type State = ();

    #[inline]
    fn force(&self, c: &Contact, _: &()) -> ContactForce {
        // eq. 3.14
        let normal_n = (self.k_v_n_per_m3 * c.overlap.volume_m3 * (1.0 + self.d_s_per_m * c.approach_mps)).max(0.0);
        // eq. 3.15: μ F_N tanh(x) v̂_t = μ F_N (4 / v_tr) (tanh(x) / x) v_t with x = 4 |v_t| / v_tr
        let scale = 4.0 / self.v_tr_mps;
        let x = scale * c.slip_mps.norm();
        let friction_n = -(self.mu * normal_n * scale * tanh_over_x(x)) * c.slip_mps;
        ContactForce { normal_n, friction_n }
    }

    /// `μ F_N ∂tanh(4 v_t / v_tr)/∂v_t` along the slip is largest at zero slip, `4 μ F_N / v_tr`; across it
    /// `μ F_N tanh(4 v_t / v_tr) / v_t`, never more. Along the slip it is taken at the smallest slip the step
    /// can reach, `v_t − μ F_N · slip_per_n_mps`.
    fn slip_stiffness(&self, c: &Contact, normal_n: Real, slip_per_n_mps: Real) -> Real {
        let scale = 4.0 / self.v_tr_mps;
        let speed_t = c.slip_mps.norm();
        let closest = scale * (speed_t - self.mu * normal_n * slip_per_n_mps);
        let most = if closest <= 0.0 {
            1.0
        } else {
            let tanh_closest = closest * tanh_over_x(closest);
            (1.0 - tanh_closest * tanh_closest).max(tanh_over_x(scale * speed_t))
        };
        self.mu * normal_n * scale * most
    }

    fn stored_energy_j(&self, surface: &FaceSurface, ball_radius_m: Real, overlap: &Overlap) -> Real {
        self.k_v_n_per_m3 * overlap_energy(surface, ball_radius_m, overlap.depth_m)
    }
}
