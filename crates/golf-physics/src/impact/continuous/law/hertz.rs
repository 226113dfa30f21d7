//! Hertz contact with Hunt-Crossley damping (seed section 3.2.2, eq. 3.16-3.19), the normal force of both the
//! Maw and the Arakawa model, and the interface their tangential laws share.
//!
//! - eq. 3.16: `F_N = k x^{3/2} + d x^{3/2} ẋ`, `x` the normal approach (overlap) and `ẋ` its rate (positive while
//!   compressing). Never negative: the contact does not pull.
//! - eq. 3.17: `k = 4 G √R / (3 (1 − ν))`, `G = E / (2 (1 + ν))` the effective shear modulus from the effective
//!   Young's modulus `E` and Poisson's ratio `ν` (the parameters of Tables 3.6 and 3.7). This is Hertz's
//!   `k = (4/3) E* √R` with `E* = G / (1 − ν)`, the contact modulus of two bodies of the same material.
//! - eq. 3.18: `1/r_eq = 1/r_ball + 1/r_club`; for a face with different bulge and roll radii the Hertz
//!   equivalent radius `r_eq = 1 / √((1/r_ball + 1/r_bulge)(1/r_ball + 1/r_roll))`, which is eq. 3.18 when the
//!   radii are equal; a flat face (irons) gives `r_eq = r_ball`.
//! - eq. 3.19: the contact radius `b = √(R x)`.
//!
//! The elastic part stores `(2/5) k x^{5/2}`; the damping part only takes energy out (`ẋ` and the force it adds
//! have the same sign).

use crate::face::FaceShape;
use crate::math::{Real, Vector3};

/// A contact-law parameter is out of its range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LawError {
    /// A parameter outside its range.
    #[error("`{field}` must be {expected}, got {value}")]
    OutOfRange {
        /// The parameter.
        field: &'static str,
        /// The range it must be in.
        expected: &'static str,
        /// What it was.
        value: Real,
    },
}

/// Checks that `value` is finite and positive.
pub fn positive(field: &'static str, value: Real) -> Result<(), LawError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(LawError::OutOfRange { field, expected: "positive", value })
    }
}

/// Checks that `value` is finite and not negative.
pub fn non_negative(field: &'static str, value: Real) -> Result<(), LawError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(LawError::OutOfRange { field, expected: "finite and not negative", value })
    }
}

/// Where the Hertzian models apply the contact force on the ball: its lever arm about the ball's centre.
///
/// Maw, Barber and Fawcett's theory (the seed's section 3.2.2 extends it and compares against it in Figure 3.4)
/// is a small-strain theory: the tangential traction acts at the undeformed radius `R`. With the seed's stiffness
/// read as a golf ball's (157-163 MPa) the approach reaches about 7 mm, a third of the radius, and an arm of
/// `R − x/2` (the middle of the overlap) shortens the lever by that much: Figure 3.4's plate then leaves at 1.51
/// times rolling where the theory's arm gives 1.085 (research/maw-arakawa.md, "Maw's backspin: the lever arm").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactArm {
    /// `R`, the theory's (default).
    #[default]
    Radius,
    /// `R − x/2`, the middle of the overlap.
    MidOverlap,
}

impl ContactArm {
    /// The arm (m) at approach `x_m` for a ball of radius `r_m`.
    pub fn arm_m(self, r_m: Real, x_m: Real) -> Real {
        match self {
            ContactArm::Radius => r_m,
            ContactArm::MidOverlap => r_m - 0.5 * x_m,
        }
    }
}

/// The normal law's material parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    /// Effective Young's modulus `E` (Pa).
    pub e_pa: Real,
    /// Effective Poisson's ratio `ν`.
    pub nu: Real,
    /// Hunt-Crossley damping `d` (s/m); 0 gives the original elastic Hertz law.
    pub d_s_per_m: Real,
}

impl Hertz {
    /// Checks the modulus, Poisson's ratio and damping, naming a bad one.
    pub fn validate(&self) -> Result<(), LawError> {
        positive("e_pa", self.e_pa)?;
        non_negative("d_s_per_m", self.d_s_per_m)?;
        if !(self.nu.is_finite() && (0.0..0.5).contains(&self.nu)) {
            return Err(LawError::OutOfRange { field: "nu", expected: "within 0 and 0.5", value: self.nu });
        }
        Ok(())
    }

    /// Shear modulus `G = E / (2 (1 + ν))` (Pa).
    pub fn shear_modulus_pa(&self) -> Real {
        self.e_pa / (2.0 * (1.0 + self.nu))
    }

    /// Contact modulus `E* = G / (1 − ν)` (Pa), so that eq. 3.17 reads `k = (4/3) E* √R`.
    pub fn contact_modulus_pa(&self) -> Real {
        self.shear_modulus_pa() / (1.0 - self.nu)
    }

    /// Tangential contact modulus over the normal one, `G*/E* = 2 (1 − ν) / (2 − ν)` (Mindlin; Johnson ch. 7).
    pub fn tangential_ratio(&self) -> Real {
        2.0 * (1.0 - self.nu) / (2.0 - self.nu)
    }

    /// eq. 3.17: `k = 4 G √R / (3 (1 − ν))` (N/m^1.5) for the equivalent radius `r_eq_m`.
    pub fn stiffness(&self, r_eq_m: Real) -> Real {
        4.0 * self.shear_modulus_pa() * r_eq_m.sqrt() / (3.0 * (1.0 - self.nu))
    }
}

/// eq. 3.18: the equivalent radius of the ball against the face (m).
pub fn equivalent_radius(ball_radius_m: Real, face: &FaceShape) -> Real {
    match *face {
        FaceShape::Plane => ball_radius_m,
        FaceShape::Torus { bulge_radius_m, roll_radius_m } => {
            let a = 1.0 / ball_radius_m + 1.0 / bulge_radius_m;
            let b = 1.0 / ball_radius_m + 1.0 / roll_radius_m;
            1.0 / (a * b).sqrt()
        }
    }
}

/// eq. 3.16: the normal force (N) at approach `x_m` and approach rate `xdot_mps`; 0 when apart or when the
/// damping would pull.
#[inline]
pub fn normal_force(k: Real, d_s_per_m: Real, x_m: Real, xdot_mps: Real) -> Real {
    if x_m <= 0.0 {
        return 0.0;
    }
    (k * x_m * x_m.sqrt() * (1.0 + d_s_per_m * xdot_mps)).max(0.0)
}

/// The elastic energy stored by eq. 3.16's first term, `(2/5) k x^{5/2}` (J).
pub fn elastic_energy(k: Real, x_m: Real) -> Real {
    if x_m <= 0.0 {
        0.0
    } else {
        0.4 * k * x_m * x_m * x_m.sqrt()
    }
}

/// eq. 3.19: contact radius `b = √(R x)` (m).
pub fn contact_radius(r_eq_m: Real, x_m: Real) -> Real {
    (r_eq_m * x_m.max(0.0)).sqrt()
}

/// The contact at one instant, as a tangential law sees it (world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactKinematics {
    /// Unit normal from the face toward the ball.
    pub normal: Vector3,
    /// Normal approach `x` (m) and its rate `ẋ` (m/s, positive while compressing).
    pub x_m: Real,
    /// See `x_m`.
    pub xdot_mps: Real,
    /// The normal force of eq. 3.16 (N).
    pub normal_force_n: Real,
    /// Velocity of the ball's contact point relative to the face's, in the tangent plane (m/s).
    pub slip_velocity_mps: Vector3,
    /// Tangential displacement of the ball's contact point relative to the face's since the start of the
    /// current integration step (m, in the tangent plane).
    pub slip_since_step_m: Vector3,
}

impl ContactKinematics {
    /// Out of contact (no approach, no force, no slip), along `normal`.
    pub fn at_rest(normal: Vector3) -> Self {
        ContactKinematics {
            normal,
            x_m: 0.0,
            xdot_mps: 0.0,
            normal_force_n: 0.0,
            slip_velocity_mps: Vector3::zeros(),
            slip_since_step_m: Vector3::zeros(),
        }
    }
}

/// What a tangential law is set up from at first contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Begin {
    /// Unit direction of the ball's initial slip relative to the face (tangent plane).
    pub slip_dir: Vector3,
    /// The initial approach rate (m/s).
    pub xdot0_mps: Real,
    /// The Hertz stiffness of eq. 3.17 (N/m^1.5).
    pub k: Real,
    /// eq. 3.18's equivalent radius (m).
    pub r_eq_m: Real,
    /// The normal reduced mass (kg).
    pub reduced_mass_kg: Real,
}

impl Begin {
    /// Elastic Hertz: the largest approach `x_max = (5 m v² / (4 k))^(2/5)` (m).
    pub fn max_approach_m(&self) -> Real {
        (5.0 * self.reduced_mass_kg * self.xdot0_mps * self.xdot0_mps / (4.0 * self.k)).powf(0.4)
    }
}

/// A tangential contact law (Maw's rings; Arakawa's eq. 3.23), set up for one impact ([`Begin`]), its history in
/// [`Self::State`]; `HertzContact` pairs it with eq. 3.16 as a contact law.
pub trait Tangential {
    /// The law's history over one impact (Maw's rings' slips; none for Arakawa's).
    type State: Clone + Default + std::fmt::Debug;
    /// The state at first contact.
    fn initial_state(&self) -> Self::State;
    /// The tangential force on the ball (N, in the tangent plane) at an intermediate stage of a step.
    fn force(&self, c: &ContactKinematics, state: &Self::State) -> Vector3;
    /// Accepts the end of a step as the new reference state; returns the tangential force on the ball there
    /// (what [`Self::force`] gives at the same instant with no slip since the step's start, up to rounding).
    fn commit(&self, c: &ContactKinematics, state: &mut Self::State) -> Vector3;
    /// Elastic energy the law stores (J).
    fn stored_energy_j(&self, state: &Self::State) -> Real;
    /// How many rings are stuck (Maw), if the law has rings.
    fn stuck_rings(&self, state: &Self::State) -> Option<usize>;
    /// Whether the step starting at `c` (the committed state) is near a switch of the law that a full step
    /// would resolve only to first order, so it should be split.
    fn refine(&self, _c: &ContactKinematics, _state: &Self::State) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// eq. 3.17 is Hertz's `(4/3) E* √R` with `E* = G/(1 − ν)`.
    #[test]
    fn stiffness_is_hertz() {
        let h = Hertz { e_pa: 157e6, nu: 0.407, d_s_per_m: 0.0 };
        let r: Real = 0.0213;
        let want = 4.0 / 3.0 * h.contact_modulus_pa() * r.sqrt();
        assert!((h.stiffness(r) - want).abs() < 1e-9 * want);
        // 157e6 / (2 * 1.407) / 0.593 * 4/3 * sqrt(0.0213) = 5.5792e7 / 0.593 * 1.33333 * 0.145945 = 1.8308e7 N/m^1.5.
        assert!((h.stiffness(r) - 1.8308e7).abs() < 2e3, "{}", h.stiffness(r));
    }

    /// eq. 3.18 with equal radii, and the flat face.
    #[test]
    fn equivalent_radius_eq_3_18() {
        let r = equivalent_radius(0.0213, &FaceShape::Torus { bulge_radius_m: 0.3, roll_radius_m: 0.3 });
        assert!((1.0 / r - (1.0 / 0.0213 + 1.0 / 0.3)).abs() < 1e-9);
        assert_eq!(equivalent_radius(0.0213, &FaceShape::Plane), 0.0213);
    }

    /// The damping term adds while compressing and takes away while restoring; no pull.
    #[test]
    fn damping_sign() {
        let f0 = normal_force(1e7, 0.0, 1e-3, 10.0);
        assert!(normal_force(1e7, 0.01, 1e-3, 10.0) > f0);
        assert!(normal_force(1e7, 0.01, 1e-3, -10.0) < f0);
        assert_eq!(normal_force(1e7, 0.2, 1e-3, -10.0), 0.0);
        assert_eq!(normal_force(1e7, 0.01, -1e-3, 10.0), 0.0);
    }
}
