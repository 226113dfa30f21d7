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
//! Two readings of eq. 3.23, chosen by `reading` in the club file's `[arakawa]` section:
//! - `friction` (the default): eq. 3.23 is the size of a friction force that the contact can carry,
//!   `|F| ≤ max(F_T, 0)`, acting against the slip of the contact point (Figure 3.5's tangential axis along the
//!   relative motion). A contact that stops slipping sticks with Mindlin's tangential stiffness `2 G* b_max`
//!   (Johnson eq. 7.40 at the largest contact radius of the elastic Hertz estimate) until the force it needs
//!   exceeds the bound: one ring of Maw's model with Arakawa's bound. The force never drives the slip within a
//!   step (it is a return map on the slip since the step's start), so the energy never increases.
//! - `literal`: eq. 3.23 as printed, signed, along the slip axis at first contact. With Table 3.7's `η` its
//!   second term is 18 kN (driver) and 78 kN (7-iron) at first contact, several times the normal force; the slip
//!   reverses within the compression and the force keeps pushing the same way, so the energy rises (12-14 %,
//!   docs/models.md) and the 7-iron does not converge in the step at 50-55 m/s. Kept for comparison with the
//!   seed's text.

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
    /// How eq. 3.23 becomes a force (module docs).
    #[serde(default)]
    pub reading: ArakawaReading,
}

/// How eq. 3.23's value becomes the tangential force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ArakawaReading {
    /// The bound of a friction force against the slip, with an elastic stick.
    #[default]
    Friction,
    /// eq. 3.23 signed along the slip axis at first contact.
    Literal,
}

impl ArakawaParams {
    /// Table 3.7, driver (E as 15.1 x 10^7 Pa: see `docs/models.md`, "Hertz stiffness").
    pub const DRIVER: ArakawaParams = ArakawaParams {
        e_pa: 151e6,
        nu: 0.407,
        d_s_per_m: 6.35e-3,
        mu: 0.0486,
        eta_n_s_per_m2: 1.32e5,
        reading: ArakawaReading::Friction,
    };
    /// Table 3.7, 7-iron.
    pub const IRON7: ArakawaParams = ArakawaParams {
        e_pa: 146e6,
        nu: 0.418,
        d_s_per_m: 9.89e-3,
        mu: 0.118,
        eta_n_s_per_m2: 2.06e5,
        reading: ArakawaReading::Friction,
    };

    pub fn hertz(&self) -> Hertz {
        Hertz { e_pa: self.e_pa, nu: self.nu, d_s_per_m: self.d_s_per_m }
    }

    pub fn validate(&self) -> Result<(), LawError> {
        self.hertz().validate()?;
        positive("mu", self.mu)?;
        non_negative("eta_n_s_per_m2", self.eta_n_s_per_m2)
    }
}

/// Arakawa's law through one impact: its parameters, the tangential axis (literal reading), the stick
/// stiffness and the committed tangential force on the face (friction reading).
#[derive(Debug, Clone, PartialEq)]
pub struct ArakawaLaw {
    params: ArakawaParams,
    r_eq_m: Real,
    axis: Vector3,
    stick_stiffness_n_per_m: Real,
    force_n: Vector3,
    stuck: bool,
}

impl ArakawaLaw {
    pub fn new(params: &ArakawaParams) -> Self {
        ArakawaLaw {
            params: *params,
            r_eq_m: 0.0,
            axis: Vector3::zeros(),
            stick_stiffness_n_per_m: 0.0,
            force_n: Vector3::zeros(),
            stuck: false,
        }
    }

    /// The friction reading's force on the face at `c` from the committed one, and whether it sticks: the
    /// committed force in the current tangent plane plus the stick stiffness times the slip since the step's
    /// start, scaled back to eq. 3.23's bound when it exceeds it.
    fn friction(&self, c: &ContactKinematics) -> (Vector3, bool) {
        let bound = self.magnitude(c.normal_force_n, c.xdot_mps).max(0.0);
        let n = c.normal;
        let trial = self.force_n - self.force_n.dot(&n) * n + self.stick_stiffness_n_per_m * c.slip_since_step_m;
        let mag2 = trial.norm_squared();
        if mag2 <= bound * bound {
            (trial, true)
        } else {
            (trial * (bound / mag2.sqrt()), false)
        }
    }

    /// eq. 3.23's magnitude along the axis (N).
    pub fn magnitude(&self, normal_force_n: Real, xdot_mps: Real) -> Real {
        let p = &self.params;
        p.mu * normal_force_n + p.mu * p.eta_n_s_per_m2 * std::f64::consts::PI * self.r_eq_m * xdot_mps
    }
}

impl TangentialLaw for ArakawaLaw {
    fn begin(&mut self, slip_dir: Vector3, xdot0_mps: Real, k: Real, r_eq_m: Real, reduced_mass_kg: Real) {
        self.r_eq_m = r_eq_m;
        self.axis = slip_dir;
        // Elastic Hertz: the largest approach x_max = (5 m v² / (4 k))^(2/5), contact radius √(R x_max);
        // Mindlin's tangential stiffness 2 G* b with G* = (G*/E*) E*, E* = 3 k / (4 √R).
        let x_max = (5.0 * reduced_mass_kg * xdot0_mps * xdot0_mps / (4.0 * k)).powf(0.4);
        let e_star = 3.0 * k / (4.0 * r_eq_m.sqrt());
        let ratio = self.params.hertz().tangential_ratio();
        self.stick_stiffness_n_per_m = 2.0 * ratio * e_star * (r_eq_m * x_max).sqrt();
        self.force_n = Vector3::zeros();
        self.stuck = false;
    }

    fn force(&self, c: &ContactKinematics) -> Vector3 {
        if c.x_m < 0.0 {
            return Vector3::zeros();
        }
        if self.params.reading == ArakawaReading::Friction {
            return if c.x_m > 0.0 && c.normal_force_n > 0.0 { -self.friction(c).0 } else { Vector3::zeros() };
        }
        let n = c.normal;
        let t = self.axis - self.axis.dot(&n) * n;
        let norm = t.norm();
        if norm < 1e-12 {
            return Vector3::zeros();
        }
        -self.magnitude(c.normal_force_n, c.xdot_mps) * t / norm
    }

    fn commit(&mut self, c: &ContactKinematics) -> Vector3 {
        if self.params.reading == ArakawaReading::Friction {
            (self.force_n, self.stuck) =
                if c.x_m > 0.0 && c.normal_force_n > 0.0 { self.friction(c) } else { (Vector3::zeros(), false) };
            -self.force_n
        } else {
            self.force(c)
        }
    }

    fn stored_energy_j(&self) -> Real {
        if self.stick_stiffness_n_per_m <= 0.0 {
            return 0.0;
        }
        0.5 * self.force_n.norm_squared() / self.stick_stiffness_n_per_m
    }

    /// The friction reading's contact is one ring: 1 while it sticks.
    fn stuck_rings(&self) -> Option<usize> {
        (self.params.reading == ArakawaReading::Friction).then_some(usize::from(self.stuck))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// eq. 3.23 by hand: μ F_N + μ η π R ẋ = 0.118 * 1000 + 0.118 * 2.06e5 * π * 0.0213 * 10.
    #[test]
    fn eq_3_23() {
        let mut law = ArakawaLaw::new(&ArakawaParams { reading: ArakawaReading::Literal, ..ArakawaParams::IRON7 });
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
        // The friction reading: a slip of 1 m (far past the stick) slides at the bound, against the slip (+y).
        let mut friction = ArakawaLaw::new(&ArakawaParams::IRON7);
        friction.begin(Vector3::y(), 40.0, 1e7, 0.0213, 0.04);
        let slid = ContactKinematics { slip_since_step_m: Vector3::y(), ..c };
        assert!((friction.force(&slid).y + want).abs() < 1e-9 * want);
        // A slip of 1 nm sticks: the stiffness times the slip, against it.
        let small = ContactKinematics { slip_since_step_m: 1e-9 * Vector3::y(), ..c };
        let f = friction.force(&small).y;
        assert!((f + friction.stick_stiffness_n_per_m * 1e-9).abs() < 1e-12 * want, "{f}");
        // A negative bound (fast restitution) carries no force.
        let back = ContactKinematics { xdot_mps: -1e3, ..slid };
        assert_eq!(friction.force(&back), Vector3::zeros());
    }
}
