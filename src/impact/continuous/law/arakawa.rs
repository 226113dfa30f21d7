//! Arakawa's contact-area friction (seed section 3.2.3, eq. 3.19-3.23, Table 3.7): the tangential force grows
//! with the normal force and with the rate the contact area grows.
//!
//! - eq. 3.19-3.21: Hertz's contact radius `b = √(R x)`, area `a = π b² = π R x`.
//! - eq. 3.22: `da/dt = π R ẋ`.
//! - eq. 3.23: `F_T = μ F_N + μ η π R ẋ`, `μ` and `η` contact parameters (`μ` is not a friction coefficient),
//!   with eq. 3.16 for `F_N`. While the contact grows (`ẋ > 0`) the second term adds to the first; while it
//!   shrinks it subtracts, and the tangential force reverses once `η π R |ẋ| > F_N`. Over a whole contact the
//!   second term's impulse is `μ η π R (x_end − x_start) = 0`.
//! - 2D model in the normal-tangential frame of Figure 3.5: the tangential axis is the direction of the ball's
//!   slip relative to the face at first contact (kept in the tangent plane as the normal turns); `F_T` acts on
//!   the ball against it. `R` is eq. 3.18's equivalent radius (the ball's radius for a flat face).
//!
//! The law stores no energy; it is not dissipative by construction (the force keeps its axis whatever the
//! slip does), so the energy balance is checked, not assumed.

use super::hertz::{non_negative, positive, ContactKinematics, Hertz, LawError, TangentialLaw};
use crate::math::{Real, Vector3};

/// The parameters of Table 3.7.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArakawaParams {
    /// Effective Young's modulus `E` (Pa).
    pub e_pa: Real,
    /// Effective Poisson's ratio `ν` (not in Table 3.7: Table 3.6's for the same club).
    pub nu: Real,
    /// Hunt-Crossley damping `d` (s/m).
    pub d_s_per_m: Real,
    /// Contact parameter `μ`.
    pub mu: Real,
    /// Contact parameter `η` (N s/m²).
    pub eta_n_s_per_m2: Real,
}

impl ArakawaParams {
    /// Table 3.7, driver (E as 15.1 x 10^7 Pa: see `docs/models.md`, "Hertz stiffness").
    pub const DRIVER: ArakawaParams =
        ArakawaParams { e_pa: 151e6, nu: 0.407, d_s_per_m: 6.35e-3, mu: 0.0486, eta_n_s_per_m2: 1.32e5 };
    /// Table 3.7, 7-iron.
    pub const IRON7: ArakawaParams =
        ArakawaParams { e_pa: 146e6, nu: 0.418, d_s_per_m: 9.89e-3, mu: 0.118, eta_n_s_per_m2: 2.06e5 };

    pub fn hertz(&self) -> Hertz {
        Hertz { e_pa: self.e_pa, nu: self.nu, d_s_per_m: self.d_s_per_m }
    }

    pub fn validate(&self) -> Result<(), LawError> {
        self.hertz().validate()?;
        positive("mu", self.mu)?;
        non_negative("eta_n_s_per_m2", self.eta_n_s_per_m2)
    }
}

/// Arakawa's law through one impact: its parameters and the tangential axis.
#[derive(Debug, Clone, PartialEq)]
pub struct ArakawaLaw {
    params: ArakawaParams,
    r_eq_m: Real,
    axis: Vector3,
}

impl ArakawaLaw {
    pub fn new(params: &ArakawaParams) -> Self {
        ArakawaLaw { params: *params, r_eq_m: 0.0, axis: Vector3::zeros() }
    }

    /// eq. 3.23's magnitude along the axis (N).
    pub fn magnitude(&self, normal_force_n: Real, xdot_mps: Real) -> Real {
        let p = &self.params;
        p.mu * normal_force_n + p.mu * p.eta_n_s_per_m2 * std::f64::consts::PI * self.r_eq_m * xdot_mps
    }
}

impl TangentialLaw for ArakawaLaw {
    fn begin(&mut self, slip_dir: Vector3, _xdot0_mps: Real, _k: Real, r_eq_m: Real, _reduced_mass_kg: Real) {
        self.r_eq_m = r_eq_m;
        self.axis = slip_dir;
    }

    fn force(&self, c: &ContactKinematics) -> Vector3 {
        if c.x_m < 0.0 {
            return Vector3::zeros();
        }
        let n = c.normal;
        let t = self.axis - self.axis.dot(&n) * n;
        let norm = t.norm();
        if norm < 1e-12 {
            return Vector3::zeros();
        }
        -self.magnitude(c.normal_force_n, c.xdot_mps) * t / norm
    }

    fn commit(&mut self, _c: &ContactKinematics) {}

    fn stored_energy_j(&self) -> Real {
        0.0
    }

    fn stuck_rings(&self) -> Option<usize> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// eq. 3.23 by hand: μ F_N + μ η π R ẋ = 0.118 * 1000 + 0.118 * 2.06e5 * π * 0.0213 * 10.
    #[test]
    fn eq_3_23() {
        let mut law = ArakawaLaw::new(&ArakawaParams::IRON7);
        law.begin(Vector3::y(), 40.0, 1e7, 0.0213, 0.04);
        let want = 0.118 * 1000.0 + 0.118 * 2.06e5 * std::f64::consts::PI * 0.0213 * 10.0;
        assert!((law.magnitude(1000.0, 10.0) - want).abs() < 1e-9 * want);
        let c = ContactKinematics {
            normal: Vector3::x(),
            x_m: 1e-3,
            xdot_mps: 10.0,
            normal_force_n: 1000.0,
            slip_velocity_mps: Vector3::y(),
            slip_since_step_m: Vector3::zeros(),
        };
        let f = law.force(&c);
        assert!((f.y + want).abs() < 1e-9 * want && f.x.abs() < 1e-12);
    }
}
