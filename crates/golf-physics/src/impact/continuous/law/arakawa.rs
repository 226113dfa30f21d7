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
//! Three readings of eq. 3.23, chosen by `reading` in the club file's `[arakawa]` section:
//! - `envelope` (the default): eq. 3.23, signed along the slip axis at first contact (Figure 3.5's tangential
//!   axis), is the envelope of a stick-slip force: while the contact area grows (`F_T > 0`) the contact can carry
//!   a force against the initial slip up to `F_T`; once it shrinks fast enough that `F_T < 0` (the seed, section
//!   2.2.3: "in this phase dA/dt is negative, which produces the friction reversal"), only a reversed force, up to
//!   `|F_T|`. Inside that half disc the force is an elastic stick with Mindlin's stiffness `2 G* b` at the current
//!   contact radius `b = √(R x)` (eq. 3.19: the area of eq. 3.21 sets the stiffness as its rate sets the bound):
//!   area newly gained carries no traction, a shrinking contact releases its share (as Maw's rings do). The
//!   force is the closest point of the half disc to the elastic trial (a return map on the slip since the step's
//!   start); the half disc holds the origin, so the projection never adds stick energy and the energy never
//!   increases. The reversal comes from the ball's spin overshooting rolling while stuck, as in real impacts.
//!   Steps where eq. 3.23 is within twice the carried force (it sweeps through zero a few µs after the largest
//!   compression) are split in eight.
//! - `friction`: eq. 3.23 is the size of a friction force that the contact can carry, `|F| ≤ max(F_T, 0)`,
//!   acting against the slip of the contact point. A contact that stops slipping sticks with Mindlin's
//!   tangential stiffness `2 G* b_max` (Johnson eq. 7.40 at the largest contact radius of the elastic Hertz
//!   estimate). It cannot reverse: the bound is positive only while `ẋ > −F_N/(η π R)`, i.e. until a few µs after
//!   the largest compression (7-iron: `η π R` = 13.8 kN s/m against `F_N` ≈ 9 kN), and a stuck contact's force
//!   stays forward for half the tangential period `π √(m_t / k_t)`, which for elastic Hertz contact with
//!   Mindlin's stiffness at the largest radius is `(π / √(2 G*/E*)) / 1.425 · √(m_t / m_n)` = 1.03 times the
//!   compression time (ball on the free 7-iron head, ν = 0.418; independent of speed, E, μ and η); damping only
//!   shortens the compression.
//! - `literal`: eq. 3.23 as printed, signed, along the slip axis at first contact. With Table 3.7's `η` its
//!   second term is 18 kN (driver) and 78 kN (7-iron) at first contact, several times the normal force; the slip
//!   reverses within the compression and the force keeps pushing the same way, so the energy rises (12-14 %,
//!   research/maw-arakawa.md) and the 7-iron does not converge in the step at 50-55 m/s. Kept for comparison with the
//!   seed's text.

use super::hertz::{non_negative, positive, Begin, ContactKinematics, Hertz, LawError, Tangential};
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
    /// The contact force's lever arm on the ball (as Maw's: `"radius"` by default, or `"mid_overlap"`).
    #[serde(default)]
    pub contact_arm: super::hertz::ContactArm,
}

/// How eq. 3.23's value becomes the tangential force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ArakawaReading {
    /// The bound of a friction force against the slip, with an elastic stick.
    Friction,
    /// eq. 3.23 signed along the slip axis bounds an elastic stick-slip force between 0 and its value: forward
    /// while the contact grows, reversed while it shrinks.
    #[default]
    Envelope,
    /// eq. 3.23 signed along the slip axis at first contact.
    Literal,
}

impl ArakawaParams {
    /// Table 3.7, driver (E as 15.1 x 10^7 Pa: see `research/maw-arakawa.md`, "Hertz stiffness").
    pub const DRIVER: ArakawaParams = ArakawaParams {
        e_pa: 151e6,
        nu: 0.407,
        d_s_per_m: 6.35e-3,
        mu: 0.0486,
        eta_n_s_per_m2: 1.32e5,
        reading: ArakawaReading::Envelope,
        contact_arm: super::hertz::ContactArm::Radius,
    };
    /// Table 3.7, 7-iron.
    pub const IRON7: ArakawaParams = ArakawaParams {
        e_pa: 146e6,
        nu: 0.418,
        d_s_per_m: 9.89e-3,
        mu: 0.118,
        eta_n_s_per_m2: 2.06e5,
        reading: ArakawaReading::Envelope,
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
        non_negative("eta_n_s_per_m2", self.eta_n_s_per_m2)
    }
}

/// Arakawa's law for one impact, set up at first contact ([`Begin`]): its parameters, the tangential axis and
/// the stick stiffness.
#[derive(Debug, Clone, PartialEq)]
pub struct ArakawaLaw {
    params: ArakawaParams,
    r_eq_m: Real,
    axis: Vector3,
    stick_stiffness_n_per_m: Real,
    /// Mindlin's `2 G*` (N/m²): the envelope reading's stick stiffness is this times the contact radius.
    stick_modulus_n_per_m2: Real,
}

/// Arakawa's law's history: the committed tangential force on the face (friction and envelope readings).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ArakawaState {
    /// The contact radius (m) and stick stiffness (N/m) at the committed state.
    radius_m: Real,
    committed_stiffness_n_per_m: Real,
    force_n: Vector3,
    stuck: bool,
}

impl ArakawaLaw {
    /// The law for an impact beginning as `b` says: the stick stiffness is Mindlin's `2 G* b` with
    /// `G* = (G*/E*) E*`, `E* = 3 k / (4 √R)`, at the largest contact radius `√(R x_max)` of the elastic Hertz
    /// estimate (friction reading) or at the current radius (envelope).
    pub fn new(params: &ArakawaParams, b: &Begin) -> Self {
        let e_star = 3.0 * b.k / (4.0 * b.r_eq_m.sqrt());
        let ratio = params.hertz().tangential_ratio();
        let stick_modulus_n_per_m2 = 2.0 * ratio * e_star;
        ArakawaLaw {
            params: *params,
            r_eq_m: b.r_eq_m,
            axis: b.slip_dir,
            stick_stiffness_n_per_m: stick_modulus_n_per_m2 * (b.r_eq_m * b.max_approach_m()).sqrt(),
            stick_modulus_n_per_m2,
        }
    }

    /// The friction reading's force on the face at `c` from the committed one, and whether it sticks: the
    /// committed force in the current tangent plane plus the stick stiffness times the slip since the step's
    /// start, scaled back to eq. 3.23's bound when it exceeds it.
    ///
    /// The envelope reading bounds the same trial force by the half disc `|f| ≤ |F_T|` on the side of the slip
    /// axis that eq. 3.23's sign gives (forward, against the initial slip, while `F_T > 0`; reversed while
    /// `F_T < 0`): the closest point of that set, which holds the origin, so the stick spring's energy never
    /// grows by the projection.
    fn friction(&self, c: &ContactKinematics, st: &ArakawaState) -> (Vector3, bool) {
        let signed = self.magnitude(c.normal_force_n, c.xdot_mps);
        let n = c.normal;
        let carried = st.force_n - st.force_n.dot(&n) * n;
        let mut stuck = true;
        let (mut trial, bound) = if self.params.reading == ArakawaReading::Envelope {
            // The stick spring follows the contact (eq. 3.19): 2 G* b; area newly gained carries no traction and
            // a shrinking contact releases its share.
            let b = (self.r_eq_m * c.x_m.max(0.0)).sqrt();
            let kept = if b < st.radius_m { b / st.radius_m } else { 1.0 };
            // The stiffness over the step at the mean radius (second order in the step).
            let k = self.stick_modulus_n_per_m2 * 0.5 * (b + st.radius_m);
            (kept * carried + k * c.slip_since_step_m, signed.abs())
        } else {
            (carried + self.stick_stiffness_n_per_m * c.slip_since_step_m, signed.max(0.0))
        };
        if self.params.reading == ArakawaReading::Envelope {
            let a = self.axis - self.axis.dot(&n) * n;
            let a2 = a.norm_squared();
            let along = trial.dot(&a);
            if a2 > 1e-24 && along * signed < 0.0 {
                // The force on the face along the slip axis must have eq. 3.23's sign: drop the other part.
                trial -= (along / a2) * a;
                stuck = false;
            }
        }
        let mag2 = trial.norm_squared();
        if mag2 <= bound * bound {
            (trial, stuck)
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

impl Tangential for ArakawaLaw {
    type State = ArakawaState;

    fn initial_state(&self) -> ArakawaState {
        ArakawaState {
            radius_m: 0.0,
            committed_stiffness_n_per_m: self.stick_stiffness_n_per_m,
            force_n: Vector3::zeros(),
            stuck: false,
        }
    }

    fn force(&self, c: &ContactKinematics, st: &ArakawaState) -> Vector3 {
        if c.x_m < 0.0 {
            return Vector3::zeros();
        }
        if self.params.reading != ArakawaReading::Literal {
            return if c.x_m > 0.0 && c.normal_force_n > 0.0 { -self.friction(c, st).0 } else { Vector3::zeros() };
        }
        let n = c.normal;
        let t = self.axis - self.axis.dot(&n) * n;
        let norm = t.norm();
        if norm < 1e-12 {
            return Vector3::zeros();
        }
        -self.magnitude(c.normal_force_n, c.xdot_mps) * t / norm
    }

    fn commit(&self, c: &ContactKinematics, st: &mut ArakawaState) -> Vector3 {
        if self.params.reading != ArakawaReading::Literal {
            (st.force_n, st.stuck) =
                if c.x_m > 0.0 && c.normal_force_n > 0.0 { self.friction(c, st) } else { (Vector3::zeros(), false) };
            if self.params.reading == ArakawaReading::Envelope {
                st.radius_m = (self.r_eq_m * c.x_m.max(0.0)).sqrt();
                st.committed_stiffness_n_per_m = self.stick_modulus_n_per_m2 * st.radius_m;
            }
            -st.force_n
        } else {
            self.force(c, st)
        }
    }

    fn stored_energy_j(&self, st: &ArakawaState) -> Real {
        if st.committed_stiffness_n_per_m <= 0.0 {
            return 0.0;
        }
        0.5 * st.force_n.norm_squared() / st.committed_stiffness_n_per_m
    }

    /// The envelope reading near its bound: eq. 3.23 within twice the committed force (the bound sweeps
    /// through zero within microseconds of the largest compression).
    fn refine(&self, c: &ContactKinematics, st: &ArakawaState) -> bool {
        let f_t = self.magnitude(c.normal_force_n, c.xdot_mps).abs();
        self.params.reading == ArakawaReading::Envelope
            && f_t < 2.0 * st.force_n.norm()
            && f_t < 2.0 * self.params.mu * c.normal_force_n
    }

    /// The friction reading's contact is one ring: 1 while it sticks.
    fn stuck_rings(&self, st: &ArakawaState) -> Option<usize> {
        (self.params.reading != ArakawaReading::Literal).then_some(usize::from(st.stuck))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// First contact at 40 m/s along +y, k = 1e7 N/m^1.5, R = 21.3 mm, a 40 g reduced mass.
    const BEGIN: Begin =
        Begin { slip_dir: Vector3::new(0.0, 1.0, 0.0), xdot0_mps: 40.0, k: 1e7, r_eq_m: 0.0213, reduced_mass_kg: 0.04 };

    /// eq. 3.23 by hand: μ F_N + μ η π R ẋ = 0.118 * 1000 + 0.118 * 2.06e5 * π * 0.0213 * 10.
    #[test]
    fn eq_3_23() {
        let law = ArakawaLaw::new(&ArakawaParams { reading: ArakawaReading::Literal, ..ArakawaParams::IRON7 }, &BEGIN);
        let st = law.initial_state();
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
        let f = law.force(&c, &st);
        assert!((f.y + want).abs() < 1e-9 * want && f.x.abs() < 1e-12);
        // The friction reading: a slip of 1 m (far past the stick) slides at the bound, against the slip (+y).
        let friction =
            ArakawaLaw::new(&ArakawaParams { reading: ArakawaReading::Friction, ..ArakawaParams::IRON7 }, &BEGIN);
        let fst = friction.initial_state();
        let slid = ContactKinematics { slip_since_step_m: Vector3::y(), ..c };
        assert!((friction.force(&slid, &fst).y + want).abs() < 1e-9 * want);
        // A slip of 1 nm sticks: the stiffness times the slip, against it.
        let small = ContactKinematics { slip_since_step_m: 1e-9 * Vector3::y(), ..c };
        let f = friction.force(&small, &fst).y;
        assert!((f + friction.stick_stiffness_n_per_m * 1e-9).abs() < 1e-12 * want, "{f}");
        // A negative bound (fast restitution) carries no force.
        let back = ContactKinematics { xdot_mps: -1e3, ..slid };
        assert_eq!(friction.force(&back, &fst), Vector3::zeros());
    }

    /// The envelope reading: while eq. 3.23 is positive the contact carries a force against the initial slip
    /// (+y) up to F_T; once it is negative (the contact shrinking) only a reversed one, up to |F_T|.
    #[test]
    fn envelope_half_discs() {
        let law = ArakawaLaw::new(&ArakawaParams::IRON7, &BEGIN);
        let st = law.initial_state();
        assert_eq!(ArakawaParams::IRON7.reading, ArakawaReading::Envelope);
        let c = |xdot_mps: Real, slip_m: Real| ContactKinematics {
            normal: Vector3::x(),
            x_m: 1e-3,
            xdot_mps,
            normal_force_n: 1000.0,
            slip_velocity_mps: Vector3::zeros(),
            slip_since_step_m: Vector3::new(0.0, slip_m, 0.0),
        };
        // Growing (F_T = 3.3 kN at 10 m/s): a forward slip of 1 m slides at F_T, a backward one carries nothing.
        let grow = law.magnitude(1000.0, 10.0);
        assert!((law.force(&c(10.0, 1.0), &st).y + grow).abs() < 1e-9 * grow);
        assert_eq!(law.force(&c(10.0, -1.0), &st).y, 0.0);
        // Shrinking (F_T = -3.1 kN at -10 m/s): the other way round, bounded by |F_T|.
        let shrink = law.magnitude(1000.0, -10.0);
        assert!(shrink < 0.0);
        assert_eq!(law.force(&c(-10.0, 1.0), &st).y, 0.0);
        assert!((law.force(&c(-10.0, -1.0), &st).y + shrink).abs() < 1e-9 * grow);
        // A small slip sticks with Mindlin's 2 G* b at the mean of the committed (0) and current radius.
        let b = (0.0213 * 1e-3 as Real).sqrt();
        let f = law.force(&c(10.0, 1e-9), &st).y;
        assert!((f + law.stick_modulus_n_per_m2 * 0.5 * b * 1e-9).abs() < 1e-9 * f.abs(), "{f}");
    }
}
