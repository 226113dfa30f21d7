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
//!   kept in a basis that turns with the normal.
//! - A ring the growing contact reaches within an integration step feels only the slip since it entered, not the
//!   whole step's: the approach taken as linear over the step, the share `(x − r_i²/R)/(x − x₀)` of the slip
//!   since the step's start (`x₀` the approach at the step's start). Without it each entering ring that sticks
//!   carries an error of the order of the step for the rest of the contact, which made the spin converge only to
//!   first order in the step (research/maw-arakawa.md, "Maw's step").
//!
//! The ring width is the expected largest contact radius (elastic Hertz estimate from the approach speed)
//! over the ring count; the contact may grow past it by up to the same again.

use super::hertz::{positive, Begin, ContactKinematics, Hertz, LawError, Tangential};
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
    /// The contact force's lever arm on the ball (`contact_arm = "radius"` by default, or `"mid_overlap"`).
    #[serde(default)]
    pub contact_arm: super::hertz::ContactArm,
}

fn default_rings() -> usize {
    20
}

impl MawParams {
    /// Table 3.6, driver (E as 15.7 x 10^7 Pa: see `research/maw-arakawa.md`, "Hertz stiffness").
    pub const DRIVER: MawParams = MawParams {
        e_pa: 157e6,
        nu: 0.407,
        d_s_per_m: 6.50e-3,
        mu: 0.860,
        rings: 20,
        contact_arm: super::hertz::ContactArm::Radius,
    };
    /// Table 3.6, 7-iron.
    pub const IRON7: MawParams = MawParams {
        e_pa: 163e6,
        nu: 0.418,
        d_s_per_m: 11.5e-3,
        mu: 0.519,
        rings: 20,
        contact_arm: super::hertz::ContactArm::Radius,
    };

    /// The normal law (eq. 3.16-3.17) of these parameters.
    pub fn hertz(&self) -> Hertz {
        Hertz { e_pa: self.e_pa, nu: self.nu, d_s_per_m: self.d_s_per_m }
    }

    /// Checks every parameter, naming a bad one.
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

/// The rings of one impact, laid out at first contact ([`Begin`]).
///
/// Each ring's committed tangential force ([`MawState`]) is kept as two coordinates in a basis of the tangent
/// plane, `t1` the initial slip axis projected onto the plane and `t2 = n × t1`, so the forces follow the plane as
/// the normal turns (the rings are carried with the surface) and a stage costs a few operations per ring.
#[derive(Debug, Clone, PartialEq)]
pub struct MawRings {
    mu: Real,
    r_eq_m: Real,
    /// Ring width Δr (m) and tangential stiffness of one ring, `2 G* Δr` (N/m).
    width_m: Real,
    ring_stiffness_n_per_m: Real,
    /// The initial slip axis, from which the tangent basis is built.
    axis: Vector3,
    /// Each ring's `r_i² / R` (m): its normal load is proportional to `x − r_i²/R`.
    depth_m: Vec<Real>,
}

/// The rings' history through one impact.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MawState {
    /// Committed tangential force each ring carries on the face (N), along `t1` and `t2`; minus it acts on the
    /// ball.
    force_t1_n: Vec<Real>,
    force_t2_n: Vec<Real>,
    stuck: usize,
    /// The approach (m) and the number of rings in contact at the committed state: rings past it entered within
    /// the current step.
    x_committed_m: Real,
    active_committed: usize,
}

/// The rings in contact at `c` and the slip limit per unit of `x − r_i²/R`.
struct Sweep {
    active: usize,
    /// Rings `kept..active` entered within the step.
    kept: usize,
    scale: Real,
    t1: Vector3,
    t2: Vector3,
    step1: Real,
    step2: Real,
}

/// The share of the step's slip a ring that entered within the step has felt: the approach is taken as linear
/// over the step from `x_committed_m`, so the ring entered where it passed the ring's depth.
#[inline(always)]
fn entered_share(x_committed_m: Real, x_m: Real, depth_m: Real) -> Real {
    if x_m <= x_committed_m {
        1.0
    } else {
        ((x_m - depth_m) / (x_m - x_committed_m)).clamp(0.0, 1.0)
    }
}

/// One ring's force from its committed one plus the spring's step, scaled back to its slip limit; and whether
/// it sticks.
#[inline(always)]
fn ring(f1: Real, f2: Real, step1: Real, step2: Real, limit: Real) -> (Real, Real, bool) {
    let (a, b) = (f1 + step1, f2 + step2);
    let mag2 = a * a + b * b;
    if mag2 <= limit * limit {
        (a, b, true)
    } else {
        let s = limit / mag2.sqrt();
        (a * s, b * s, false)
    }
}

impl MawRings {
    /// The rings for an impact beginning as `b` says: the ring width is the elastic Hertz estimate of the
    /// largest contact radius, `√(R x_max)`, over the ring count; rings reach twice as far.
    pub fn new(params: &MawParams, b: &Begin) -> Self {
        let b_max = (b.r_eq_m * b.max_approach_m()).sqrt();
        let width_m = b_max / params.rings as Real;
        let e_star = 3.0 * b.k / (4.0 * b.r_eq_m.sqrt());
        let dr2_r = width_m * width_m / b.r_eq_m;
        MawRings {
            mu: params.mu,
            r_eq_m: b.r_eq_m,
            width_m,
            ring_stiffness_n_per_m: 2.0 * params.hertz().tangential_ratio() * e_star * width_m,
            axis: b.slip_dir,
            depth_m: (0..2 * params.rings)
                .map(|i| {
                    let r = i as Real + 0.5;
                    r * r * dr2_r
                })
                .collect(),
        }
    }

    /// The tangent basis at normal `n`: the slip axis projected onto the plane, and `n × t1`.
    #[inline]
    fn basis(&self, n: &Vector3) -> (Vector3, Vector3) {
        let mut t1 = self.axis - self.axis.dot(n) * *n;
        let norm2 = t1.norm_squared();
        if norm2 < 1e-12 {
            // The axis along the normal (never in a golf impact): any tangent direction.
            t1 = n.cross(&if n.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() });
            t1.normalize_mut();
        } else {
            t1 /= norm2.sqrt();
        }
        (t1, n.cross(&t1))
    }

    /// The rings in contact at `c`, `None` when out of contact.
    #[inline]
    fn sweep(&self, c: &ContactKinematics, st: &MawState) -> Option<Sweep> {
        if c.x_m <= 0.0 || c.normal_force_n <= 0.0 {
            return None;
        }
        // Rings in contact: r_i = (i + 1/2) Δr < √(R x); their normal loads E* (x − r_i²/R) 2 Δr, scaled to sum
        // to F_N: Σ (x − r_i²/R) = n x − (Δr²/R)(n³/3 − n/12).
        let b = (self.r_eq_m * c.x_m).sqrt();
        let active = ((b / self.width_m + 0.5).ceil() as usize).saturating_sub(1).min(self.depth_m.len());
        if active == 0 {
            return None;
        }
        let nf = active as Real;
        let dr2_r = self.width_m * self.width_m / self.r_eq_m;
        let sum_w = nf * c.x_m - dr2_r * (nf * nf * nf / 3.0 - nf / 12.0);
        let (t1, t2) = self.basis(&c.normal);
        let step = self.ring_stiffness_n_per_m * c.slip_since_step_m;
        Some(Sweep {
            active,
            kept: st.active_committed.min(active),
            scale: self.mu * c.normal_force_n / sum_w,
            t1,
            t2,
            step1: step.dot(&t1),
            step2: step.dot(&t2),
        })
    }

    /// The ring width (m).
    pub fn ring_width_m(&self) -> Real {
        self.width_m
    }
}

impl Tangential for MawRings {
    type State = MawState;

    fn initial_state(&self) -> MawState {
        let n = self.depth_m.len();
        MawState {
            force_t1_n: vec![0.0; n],
            force_t2_n: vec![0.0; n],
            stuck: 0,
            x_committed_m: 0.0,
            active_committed: 0,
        }
    }

    fn force(&self, c: &ContactKinematics, st: &MawState) -> Vector3 {
        let Some(w) = self.sweep(c, st) else { return Vector3::zeros() };
        let (mut a1, mut a2) = (0.0, 0.0);
        let rings = st.force_t1_n[..w.active].iter().zip(&st.force_t2_n[..w.active]).zip(&self.depth_m);
        for (i, ((&f1, &f2), &depth)) in rings.enumerate() {
            let share = if i < w.kept { 1.0 } else { entered_share(st.x_committed_m, c.x_m, depth) };
            // ring() without the branch: the slip factor min(1, limit/|trial|) (1 when the trial is zero).
            let (g1, g2) = (f1 + share * w.step1, f2 + share * w.step2);
            let factor = (w.scale * (c.x_m - depth) / (g1 * g1 + g2 * g2).sqrt()).min(1.0);
            a1 += g1 * factor;
            a2 += g2 * factor;
        }
        -(a1 * w.t1 + a2 * w.t2)
    }

    fn commit(&self, c: &ContactKinematics, st: &mut MawState) -> Vector3 {
        let Some(w) = self.sweep(c, st) else {
            st.force_t1_n.fill(0.0);
            st.force_t2_n.fill(0.0);
            st.stuck = 0;
            st.x_committed_m = c.x_m.max(0.0);
            st.active_committed = 0;
            return Vector3::zeros();
        };
        let (mut a1, mut a2, mut stuck) = (0.0, 0.0, 0);
        let x_committed_m = st.x_committed_m;
        let (t1s, t2s) = (&mut st.force_t1_n[..w.active], &mut st.force_t2_n[..w.active]);
        for (i, ((f1, f2), &depth)) in t1s.iter_mut().zip(t2s.iter_mut()).zip(&self.depth_m).enumerate() {
            let share = if i < w.kept { 1.0 } else { entered_share(x_committed_m, c.x_m, depth) };
            let (g1, g2, s) = ring(*f1, *f2, share * w.step1, share * w.step2, w.scale * (c.x_m - depth));
            (*f1, *f2) = (g1, g2);
            a1 += g1;
            a2 += g2;
            stuck += usize::from(s);
        }
        // Rings the contact has left are released.
        st.force_t1_n[w.active..].fill(0.0);
        st.force_t2_n[w.active..].fill(0.0);
        st.stuck = stuck;
        st.x_committed_m = c.x_m;
        st.active_committed = w.active;
        -(a1 * w.t1 + a2 * w.t2)
    }

    fn stored_energy_j(&self, st: &MawState) -> Real {
        if self.ring_stiffness_n_per_m <= 0.0 {
            return 0.0;
        }
        let sum: Real = st.force_t1_n.iter().zip(&st.force_t2_n).map(|(a, b)| a * a + b * b).sum();
        0.5 * sum / self.ring_stiffness_n_per_m
    }

    fn stuck_rings(&self, st: &MawState) -> Option<usize> {
        Some(st.stuck)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// First contact at 40 m/s along +y, a 40 g reduced mass.
    fn begin(k: Real, r_eq_m: Real) -> Begin {
        Begin { slip_dir: Vector3::y(), xdot0_mps: 40.0, k, r_eq_m, reduced_mass_kg: 0.04 }
    }

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
        let p =
            MawParams { e_pa: 157e6, nu: 0.4, d_s_per_m: 0.0, mu: 0.5, rings: 400, contact_arm: Default::default() };
        let h = p.hertz();
        let r = 0.0213;
        let k = h.stiffness(r);
        let rings = MawRings::new(&p, &begin(k, r));
        let mut st = rings.initial_state();
        let x: Real = 3e-3;
        let f_n = k * x.powf(1.5);
        let b = (r * x).sqrt();
        let e_star = 3.0 * k / (4.0 * r.sqrt());
        let k_t = 2.0 * h.tangential_ratio() * e_star * b;
        // The normal load first (no slip), then the tangential displacement at that load.
        rings.commit(&kin(x, f_n, 0.0), &mut st);
        let small = 1e-9;
        let f = rings.force(&kin(x, f_n, small), &st);
        assert!((f.y / (-k_t * small) - 1.0).abs() < 0.02, "{} vs {}", f.y, -k_t * small);
        let f = rings.force(&kin(x, f_n, 1.0), &st);
        assert!((f.y + 0.5 * f_n).abs() < 1e-9 * f_n, "{} vs {}", f.y, -0.5 * f_n);
    }

    /// Mindlin's force-displacement curve (Johnson eq. 7.42): `F = μP (1 − (1 − δ/δ_slip)^{3/2})` with
    /// `δ_slip = μ P / (2 G* b) · 3/2`.
    #[test]
    fn mindlin_curve() {
        let p =
            MawParams { e_pa: 157e6, nu: 0.4, d_s_per_m: 0.0, mu: 0.5, rings: 400, contact_arm: Default::default() };
        let h = p.hertz();
        let r = 0.0213;
        let k = h.stiffness(r);
        let rings = MawRings::new(&p, &begin(k, r));
        let mut st = rings.initial_state();
        let x: Real = 3e-3;
        let f_n = k * x.powf(1.5);
        let b = (r * x).sqrt();
        let e_star = 3.0 * k / (4.0 * r.sqrt());
        let delta_slip = 1.5 * p.mu * f_n / (2.0 * h.tangential_ratio() * e_star * b);
        rings.commit(&kin(x, f_n, 0.0), &mut st);
        for frac in [0.2, 0.5, 0.9] {
            let f = -rings.force(&kin(x, f_n, frac * delta_slip), &st).y;
            let want = p.mu * f_n * (1.0 - (1.0 - frac).powf(1.5));
            assert!((f - want).abs() < 0.01 * want, "{frac}: {f} vs {want}");
        }
    }

    /// Rings reached within a step feel the slip since they entered: with every ring stuck (μ large), approach and
    /// slip growing linearly, each ring carries its stiffness times the slip since the contact reached it, so one
    /// step from 1 mm to 3 mm gives the same force as 64 steps over the same path (to 1e-9; 0.906 N for a
    /// 1 µm slip), where charging the entering rings with the whole step's slip gave 1.128 N in one step.
    #[test]
    fn rings_entering_within_a_step_feel_the_slip_since_entry() {
        let p = MawParams { e_pa: 157e6, nu: 0.4, d_s_per_m: 0.0, mu: 1e6, rings: 20, contact_arm: Default::default() };
        let r = 0.0213;
        let k = p.hertz().stiffness(r);
        let run = |steps: usize| {
            let rings = MawRings::new(&p, &begin(k, r));
            let mut st = rings.initial_state();
            let (x0, x1, slip) = (1e-3, 3e-3, 1e-6);
            rings.commit(&kin(x0, k * x0 * Real::sqrt(x0), 0.0), &mut st);
            let mut f = Vector3::zeros();
            for i in 1..=steps {
                let x = x0 + (x1 - x0) * i as Real / steps as Real;
                f = rings.commit(&kin(x, k * x * x.sqrt(), slip / steps as Real), &mut st);
            }
            f.y
        };
        let (one, fine) = (run(1), run(64));
        assert!(fine < 0.0 && (one / fine - 1.0).abs() < 1e-9, "one step {one}, 64 steps {fine}");
    }
}
