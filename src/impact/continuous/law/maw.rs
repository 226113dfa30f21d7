//! Maw's stick-slip contact (seed section 3.2.2, Table 3.6; Maw, Barber and Fawcett 1976 and 1981): the contact
//! circle divided into annular rings, each stuck or slipping.
//!
//! - Normal force: eq. 3.16 with eq. 3.17's stiffness (see [`super::hertz`]); the Hertz pressure
//!   `p(r) = p₀ √(1 − r²/b²)` over the contact radius `b = √(R x)` (eq. 3.19).
//! - Tangential: each ring carries a tangential traction `q` that follows the relative tangential displacement
//!   of the bodies while `|q| ≤ μ p` (stuck) and slides at `|q| = μ p` (slipping), Mindlin's tangential
//!   compliance giving the stiffness `G* = (G*/E*) E*`, `G*/E* = 2 (1 − ν)/(2 − ν)`. Area newly gained as the
//!   contact grows is laid down free of traction; rings the shrinking contact leaves are released.
//! - The rings are resolved with the method of dimensionality reduction (Popov and Heß): ring `i` at radius
//!   `r_i` is a tangential spring of stiffness `2 G* Δr` whose normal load is `E* (x − r_i²/R) 2 Δr`, which is
//!   exact for Cattaneo-Mindlin loading with any history of normal and tangential load (the stick radius equals
//!   the 3D one); the ring loads are scaled to sum to eq. 3.16's `F_N`, so full sliding gives `μ F_N`.
//! - 2D model in the normal-tangential frame of Figure 3.5, applied in 3D: each ring's displacement is a vector
//!   in the tangent plane (along the relative motion at the contact point while the slip keeps its direction),
//!   re-projected as the normal turns.
//!
//! The ring width is the expected largest contact radius (elastic Hertz estimate from the approach speed)
//! over the ring count; the contact may grow past it by up to the same again.

use super::hertz::{positive, ContactKinematics, Hertz, LawError, TangentialLaw};
use crate::math::{Real, Vector3};

/// The parameters of Table 3.6.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MawParams {
    /// Effective Young's modulus `E` (Pa).
    pub e_pa: Real,
    /// Effective Poisson's ratio `ν`.
    pub nu: Real,
    /// Hunt-Crossley damping `d` (s/m).
    pub d_s_per_m: Real,
    /// Friction coefficient `μ`.
    pub mu: Real,
    /// Rings across the largest contact radius (the seed uses 20).
    #[serde(default = "default_rings")]
    pub rings: usize,
}

fn default_rings() -> usize {
    20
}

impl MawParams {
    /// Table 3.6, driver (E as 15.7 x 10^7 Pa: see `docs/models.md`, "Hertz stiffness").
    pub const DRIVER: MawParams = MawParams { e_pa: 157e6, nu: 0.407, d_s_per_m: 6.50e-3, mu: 0.860, rings: 20 };
    /// Table 3.6, 7-iron.
    pub const IRON7: MawParams = MawParams { e_pa: 163e6, nu: 0.418, d_s_per_m: 11.5e-3, mu: 0.519, rings: 20 };

    pub fn hertz(&self) -> Hertz {
        Hertz { e_pa: self.e_pa, nu: self.nu, d_s_per_m: self.d_s_per_m }
    }

    pub fn validate(&self) -> Result<(), LawError> {
        self.hertz().validate()?;
        positive("mu", self.mu)?;
        if !(1..=1000).contains(&self.rings) {
            return Err(LawError::OutOfRange {
                field: "rings",
                expected: "within 1 and 1000",
                value: self.rings as Real,
            });
        }
        Ok(())
    }
}

/// The rings' state through one impact.
#[derive(Debug, Clone, PartialEq)]
pub struct MawRings {
    mu: Real,
    rings: usize,
    tangential_ratio: Real,
    r_eq_m: Real,
    /// Ring width Δr (m) and tangential stiffness of one ring, `2 G* Δr` (N/m).
    width_m: Real,
    ring_stiffness_n_per_m: Real,
    /// Committed tangential force each ring carries on the face (N, tangent plane); minus it acts on the ball.
    force_n: Vec<Vector3>,
    /// The previous step's forces, reused as the next step's buffer.
    scratch: Vec<Vector3>,
    stuck: usize,
}

impl MawRings {
    pub fn new(params: &MawParams) -> Self {
        MawRings {
            mu: params.mu,
            rings: params.rings,
            tangential_ratio: params.hertz().tangential_ratio(),
            r_eq_m: 0.0,
            width_m: 0.0,
            ring_stiffness_n_per_m: 0.0,
            force_n: Vec::new(),
            scratch: Vec::new(),
            stuck: 0,
        }
    }

    /// The rings' forces at `c` from the committed state, and how many are stuck. Calls `each(i, force)` for
    /// the rings in contact; the others carry nothing.
    #[inline]
    fn evaluate(&self, c: &ContactKinematics, mut each: impl FnMut(usize, Vector3)) -> (Vector3, usize) {
        let n = c.normal;
        let mut total = Vector3::zeros();
        if c.x_m <= 0.0 || c.normal_force_n <= 0.0 {
            return (total, 0);
        }
        // Rings in contact: r_i = (i + 1/2) Δr < √(R x); their normal loads E* (x − r_i²/R) 2 Δr, scaled to sum
        // to F_N: Σ (x − r_i²/R) = n x − (Δr²/R)(n³/3 − n/12).
        let b = (self.r_eq_m * c.x_m).sqrt();
        let active = ((b / self.width_m + 0.5).ceil() as usize).saturating_sub(1).min(self.force_n.len());
        if active == 0 {
            return (total, 0);
        }
        let nf = active as Real;
        let dr2_r = self.width_m * self.width_m / self.r_eq_m;
        let sum_w = nf * c.x_m - dr2_r * (nf * nf * nf / 3.0 - nf / 12.0);
        let scale = self.mu * c.normal_force_n / sum_w;
        let step = self.ring_stiffness_n_per_m * c.slip_since_step_m;
        let mut stuck = 0;
        for (i, f0) in self.force_n[..active].iter().enumerate() {
            let r = i as Real + 0.5;
            let limit = scale * (c.x_m - r * r * dr2_r);
            let trial = f0 - f0.dot(&n) * n + step;
            let mag2 = trial.norm_squared();
            let f = if mag2 <= limit * limit {
                stuck += 1;
                trial
            } else {
                trial * (limit / mag2.sqrt())
            };
            total += f;
            each(i, f);
        }
        (-total, stuck)
    }

    /// The ring width (m).
    pub fn ring_width_m(&self) -> Real {
        self.width_m
    }
}

impl TangentialLaw for MawRings {
    fn begin(&mut self, _slip_dir: Vector3, xdot0_mps: Real, k: Real, r_eq_m: Real, reduced_mass_kg: Real) {
        // Elastic Hertz: the largest approach x_max = (5 m v² / (4 k))^(2/5), contact radius √(R x_max).
        let x_max = (5.0 * reduced_mass_kg * xdot0_mps * xdot0_mps / (4.0 * k)).powf(0.4);
        let b_max = (r_eq_m * x_max).sqrt();
        self.r_eq_m = r_eq_m;
        self.width_m = b_max / self.rings as Real;
        let e_star = 3.0 * k / (4.0 * r_eq_m.sqrt());
        self.ring_stiffness_n_per_m = 2.0 * self.tangential_ratio * e_star * self.width_m;
        self.force_n = vec![Vector3::zeros(); 2 * self.rings];
        self.stuck = 0;
    }

    fn force(&self, c: &ContactKinematics) -> Vector3 {
        self.evaluate(c, |_, _| {}).0
    }

    fn commit(&mut self, c: &ContactKinematics) {
        let mut next = std::mem::take(&mut self.scratch);
        next.clear();
        next.resize(self.force_n.len(), Vector3::zeros());
        let (_, stuck) = self.evaluate(c, |i, f| next[i] = f);
        self.scratch = std::mem::replace(&mut self.force_n, next);
        self.stuck = stuck;
    }

    fn stored_energy_j(&self) -> Real {
        if self.ring_stiffness_n_per_m <= 0.0 {
            return 0.0;
        }
        self.force_n.iter().map(|f| 0.5 * f.norm_squared() / self.ring_stiffness_n_per_m).sum()
    }

    fn stuck_rings(&self) -> Option<usize> {
        Some(self.stuck)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kin(x_m: Real, normal_force_n: Real, slip: Real) -> ContactKinematics {
        ContactKinematics {
            normal: Vector3::x(),
            x_m,
            xdot_mps: 0.0,
            normal_force_n,
            slip_velocity_mps: Vector3::zeros(),
            slip_since_step_m: Vector3::new(0.0, slip, 0.0),
        }
    }

    /// Cattaneo-Mindlin under a constant normal load: the initial tangential stiffness is `2 G* b` (Johnson
    /// eq. 7.40: `8 G b / (2 − ν)` for one elastic body, `G* = 4G/(2 − ν)`), and a large displacement slides
    /// every ring at `μ F_N`.
    #[test]
    fn mindlin_stiffness_and_gross_slip() {
        let p = MawParams { e_pa: 157e6, nu: 0.4, d_s_per_m: 0.0, mu: 0.5, rings: 400 };
        let h = p.hertz();
        let r = 0.0213;
        let k = h.stiffness(r);
        let mut rings = MawRings::new(&p);
        rings.begin(Vector3::y(), 40.0, k, r, 0.04);
        let x: Real = 3e-3;
        let f_n = k * x.powf(1.5);
        let b = (r * x).sqrt();
        let e_star = 3.0 * k / (4.0 * r.sqrt());
        let k_t = 2.0 * h.tangential_ratio() * e_star * b;
        let small = 1e-9;
        let f = rings.force(&kin(x, f_n, small));
        assert!((f.y / (-k_t * small) - 1.0).abs() < 0.02, "{} vs {}", f.y, -k_t * small);
        let f = rings.force(&kin(x, f_n, 1.0));
        assert!((f.y + 0.5 * f_n).abs() < 1e-9 * f_n, "{} vs {}", f.y, -0.5 * f_n);
    }

    /// Mindlin's force-displacement curve (Johnson eq. 7.42): `F = μP (1 − (1 − δ/δ_slip)^{3/2})` with
    /// `δ_slip = μ P / (2 G* b) · 3/2`.
    #[test]
    fn mindlin_curve() {
        let p = MawParams { e_pa: 157e6, nu: 0.4, d_s_per_m: 0.0, mu: 0.5, rings: 400 };
        let h = p.hertz();
        let r = 0.0213;
        let k = h.stiffness(r);
        let mut rings = MawRings::new(&p);
        rings.begin(Vector3::y(), 40.0, k, r, 0.04);
        let x: Real = 3e-3;
        let f_n = k * x.powf(1.5);
        let b = (r * x).sqrt();
        let e_star = 3.0 * k / (4.0 * r.sqrt());
        let delta_slip = 1.5 * p.mu * f_n / (2.0 * h.tangential_ratio() * e_star * b);
        for frac in [0.2, 0.5, 0.9] {
            let f = -rings.force(&kin(x, f_n, frac * delta_slip)).y;
            let want = p.mu * f_n * (1.0 - (1.0 - frac).powf(1.5));
            assert!((f - want).abs() < 0.01 * want, "{frac}: {f} vs {want}");
        }
    }
}
