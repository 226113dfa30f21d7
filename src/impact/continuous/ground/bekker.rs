//! Ground reaction on an iron's head (seed section 4.2): the sole in Bekker soil ([`super::sole`], eq. 4.3-4.9)
//! and the passive earth pressure on the face below the surface ([`super::face_pressure`], eq. 4.10-4.13).
//!
//! The ground is the plane `y = y_ground` (world; for a ball resting on the turf `y_ground = y_ball − r_ball`,
//! DESIGN.md section 2). Contact has two phases (seed 4.2): compression, while only the sole is below the
//! surface and the soil is pressed down; and the divot, once the leading edge is below the surface and the
//! face pushes soil forward. The sole's forces act in both phases, the face's only in the second.

use crate::equipment::soil::SoilSpec;
use crate::equipment::sole::{SoleArc, SoleSpec};
use crate::equipment::ClubSpec;
use crate::math::{Isometry3, Real, Rotation3, Vector3};

use super::face_pressure::{face_forces, FacePressure};
use super::sole::{sole_forces, SoleContact};

/// The most Gauss points of a rule.
pub const MAX_GAUSS: usize = 16;

/// A Gauss-Legendre rule on [0, 1].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussRule {
    pub n: usize,
    pub x: [Real; MAX_GAUSS],
    pub w: [Real; MAX_GAUSS],
}

impl GaussRule {
    /// The `n`-point rule (1 ≤ n ≤ 16), roots of the Legendre polynomial by Newton's method.
    pub fn new(n: usize) -> Self {
        let n = n.clamp(1, MAX_GAUSS);
        let mut rule = GaussRule { n, x: [0.0; MAX_GAUSS], w: [0.0; MAX_GAUSS] };
        for i in 0..n {
            let mut t = (std::f64::consts::PI * (i as Real + 0.75) / (n as Real + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, t);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as Real * t * p1 - (k - 1) as Real * p0) / k as Real;
                    p0 = p1;
                    p1 = p2;
                }
                let p = if n == 1 { t } else { p1 };
                let pm1 = if n == 1 { 1.0 } else { p0 };
                dp = n as Real * (t * p - pm1) / (t * t - 1.0);
                let dt = p / dp;
                t -= dt;
                if dt.abs() < 1e-15 {
                    break;
                }
            }
            rule.x[i] = 0.5 * (1.0 - t);
            rule.w[i] = 1.0 / ((1.0 - t * t) * dp * dp);
        }
        rule
    }
}

/// The sole's cylinder placed in the world at one instant, with the ground's height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoleArcWorld {
    /// The head's CG (world).
    pub cg_m: Vector3,
    /// The sole cylinder's axes in the world: forward, up, toe (the cylinder's axis); the club frame's for a
    /// level sole.
    pub ex: Vector3,
    pub ey: Vector3,
    pub ez: Vector3,
    /// The cylinder's axis point at the sole's heel-toe middle (world).
    pub centre_m: Vector3,
    pub radius_m: Real,
    pub theta_te_rad: Real,
    pub theta_le_rad: Real,
    pub half_length_m: Real,
    pub ground_y_m: Real,
    /// The sinkage's form `A(s) + R ρ cos(θ − θ₀)`, computed once: `(A(0), slope of A in s, ρ, θ₀)`.
    form: (Real, Real, Real, Real),
}

impl SoleArcWorld {
    pub fn new(arc: &SoleArc, world_from_club: &Isometry3, ground_y_m: Real) -> Self {
        Self::at(arc, &world_from_club.rotation.to_rotation_matrix(), &world_from_club.translation.vector, ground_y_m)
    }

    /// [`Self::new`] with the pose as a rotation matrix and the CG's position (no quaternion on the way).
    pub fn at(arc: &SoleArc, world_from_club: &Rotation3, cg_m: &Vector3, ground_y_m: Real) -> Self {
        let r = world_from_club * arc.axes.to_rotation_matrix();
        let (ex, ey, ez) = (r.matrix().column(0).into_owned(), r.matrix().column(1).into_owned(), r.matrix().column(2).into_owned());
        let centre_m = cg_m + world_from_club * arc.centre_m;
        SoleArcWorld {
            cg_m: *cg_m,
            ex,
            ey,
            ez,
            centre_m,
            radius_m: arc.radius_m,
            theta_te_rad: arc.theta_te_rad,
            theta_le_rad: arc.theta_le_rad,
            half_length_m: 0.5 * arc.length_m,
            ground_y_m,
            form: (ground_y_m - centre_m.y, -ez.y, ex.y.hypot(ey.y), (-ex.y).atan2(ey.y)),
        }
    }

    /// The sole point at angle θ, given `sin θ` and `cos θ`, and heel-toe offset s (world).
    #[inline]
    pub fn point_sc(&self, sin: Real, cos: Real, s_m: Real) -> Vector3 {
        self.centre_m + self.radius_m * (sin * self.ex - cos * self.ey) + s_m * self.ez
    }

    /// The sole point at angle θ and heel-toe offset s (world).
    #[inline]
    pub fn point(&self, theta: Real, s_m: Real) -> Vector3 {
        self.centre_m + self.radius_m * (theta.sin() * self.ex - theta.cos() * self.ey) + s_m * self.ez
    }

    /// Sinkage `A(s) + R ρ cos(θ − θ₀)`: returns `(A(0), slope of A in s, ρ, θ₀)`.
    #[inline]
    fn sinkage_form(&self) -> (Real, Real, Real, Real) {
        self.form
    }

    /// The deepest sinkage of any sole point (m; negative when the sole is clear of the ground).
    pub fn max_sinkage_m(&self) -> Real {
        let (a0, slope, rho, theta0) = self.sinkage_form();
        let th = theta0.clamp(self.theta_te_rad, self.theta_le_rad);
        a0 + slope.abs() * self.half_length_m + self.radius_m * rho * (th - theta0).cos()
    }

    /// The heel-toe range of the sole with some point below the surface.
    pub fn wetted_heel_toe(&self) -> Option<(Real, Real)> {
        let (a0, slope, rho, theta0) = self.sinkage_form();
        let th = theta0.clamp(self.theta_te_rad, self.theta_le_rad);
        let top = a0 + self.radius_m * rho * (th - theta0).cos();
        linear_positive(top, slope, self.half_length_m)
    }

    /// The wetted arc `[θ_a, θ_b]` of the strip at heel-toe offset s.
    pub fn wetted_arc(&self, s_m: Real) -> Option<(Real, Real)> {
        let (a0, slope, rho, theta0) = self.sinkage_form();
        let a = a0 + slope * s_m;
        let c = -a / (self.radius_m * rho);
        if c >= 1.0 {
            return None;
        }
        let delta = if c <= -1.0 { std::f64::consts::PI } else { c.acos() };
        let lo = self.theta_te_rad.max(theta0 - delta);
        let hi = self.theta_le_rad.min(theta0 + delta);
        (hi > lo).then_some((lo, hi))
    }

    /// The leading edge's depth below the surface at heel-toe offset s (m; negative above).
    pub fn leading_edge_depth_m(&self, s_m: Real) -> Real {
        self.ground_y_m - self.point(self.theta_le_rad, s_m).y
    }
}

/// The range of s in [−half, half] where `top + slope s > 0`.
fn linear_positive(top: Real, slope: Real, half: Real) -> Option<(Real, Real)> {
    if slope.abs() < 1e-14 {
        return (top > 0.0).then_some((-half, half));
    }
    let root = -top / slope;
    let (lo, hi) = if slope > 0.0 { (root.max(-half), half) } else { (-half, root.min(half)) };
    (hi > lo).then_some((lo, hi))
}

/// The contact phase (seed 4.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum GroundPhase {
    Clear,
    /// Only the sole below the surface.
    Compression,
    /// The leading edge below the surface: the face cuts a divot.
    Divot,
}

/// Every ground force at one instant (world frame; moments about the head's CG).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundForces {
    pub sole: SoleContact,
    pub face: FacePressure,
    pub phase: GroundPhase,
}

impl GroundForces {
    /// The resultant force (N).
    pub fn force_n(&self) -> Vector3 {
        self.sole.pressure_n + self.sole.shear_n + self.face.force_n
    }

    /// The resultant moment about the CG (N m).
    pub fn torque_nm(&self) -> Vector3 {
        self.sole.torque_nm + self.face.torque_nm
    }
}

/// The ground under an iron: soil, the sole's geometry and the surface's height.
#[derive(Debug, Clone, PartialEq)]
pub struct SoilGround {
    pub soil: SoilSpec,
    pub sole: SoleSpec,
    pub arc: SoleArc,
    /// Outward face normal and up-the-face direction, club frame.
    pub face_normal: Vector3,
    pub up_face: Vector3,
    pub ground_y_m: Real,
    /// Shear smoothing speed (m/s).
    pub slip_regularisation_mps: Real,
    pub strips: GaussRule,
    pub along_arc: GaussRule,
    pub along_edge: GaussRule,
    /// World-frame multipliers of every force component (ones: the seed's model); see [`super::sole_forces`].
    pub force_mask: Vector3,
}

impl SoilGround {
    /// The ground `y = ground_y_m` under `club` with `sole` in `soil`; default quadrature (3 strips heel to toe,
    /// 5 points along the arc; 3 along the leading edge, exact for eq. 4.13's quadratic pressure and its moment).
    pub fn new(soil: SoilSpec, sole: SoleSpec, club: &ClubSpec, ground_y_m: Real) -> Self {
        let arc = sole.arc(&club.face.center_m, club.face.loft_rad);
        SoilGround {
            soil,
            sole,
            arc,
            face_normal: club.face.n0(),
            up_face: club.face.u0(),
            ground_y_m,
            slip_regularisation_mps: 0.05,
            strips: GaussRule::new(3),
            along_arc: GaussRule::new(5),
            along_edge: GaussRule::new(3),
            force_mask: Vector3::repeat(1.0),
        }
    }

    /// The sole placed at `world_from_club`.
    pub fn placed(&self, world_from_club: &Isometry3) -> SoleArcWorld {
        SoleArcWorld::new(&self.arc, world_from_club, self.ground_y_m)
    }

    /// Every ground force on the head at pose `world_from_club`, CG velocity `v_cg` and angular velocity `w`.
    pub fn forces(&self, world_from_club: &Isometry3, v_cg: &Vector3, w: &Vector3) -> GroundForces {
        let rotation = world_from_club.rotation.to_rotation_matrix();
        self.forces_at(&rotation, &world_from_club.translation.vector, v_cg, w)
    }

    /// [`Self::forces`] with the pose as a rotation matrix and the CG's position.
    pub fn forces_at(&self, world_from_club: &Rotation3, cg_m: &Vector3, v_cg: &Vector3, w: &Vector3) -> GroundForces {
        let placed = SoleArcWorld::at(&self.arc, world_from_club, cg_m, self.ground_y_m);
        let sole = sole_forces(
            &placed,
            &self.soil,
            v_cg,
            w,
            self.slip_regularisation_mps,
            &self.strips,
            &self.along_arc,
            &self.force_mask,
        );
        if sole.max_sinkage_m <= 0.0 {
            return GroundForces { sole, face: FacePressure::default(), phase: GroundPhase::Clear };
        }
        let r = world_from_club;
        let face = face_forces(
            &placed,
            &(r * self.face_normal),
            &(r * self.up_face),
            &self.soil,
            v_cg,
            w,
            self.slip_regularisation_mps,
            &self.along_edge,
            &self.force_mask,
        );
        let phase = if face.leading_edge_depth_m > 0.0 { GroundPhase::Divot } else { GroundPhase::Compression };
        GroundForces { sole, face, phase }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An n-point Gauss-Legendre rule integrates polynomials of degree 2n − 1 exactly: ∫₀¹ x^k dx = 1/(k + 1).
    #[test]
    fn gauss_rules_are_exact_to_degree_2n_minus_1() {
        for n in [1, 2, 3, 6, 8, 16] {
            let g = GaussRule::new(n);
            assert!((g.w[..n].iter().sum::<Real>() - 1.0).abs() < 1e-14);
            for k in 0..2 * n {
                let got: Real = (0..n).map(|i| g.w[i] * g.x[i].powi(k as i32)).sum();
                assert!((got - 1.0 / (k as Real + 1.0)).abs() < 1e-13, "n {n} k {k}: {got}");
            }
        }
    }

    /// A delofted, open, toe-down sole in firm soil moving along a descending path: the default quadrature
    /// (3 x 5) is within 0.5 % of 16 x 16 in force and moment.
    #[test]
    fn quadrature_converges_on_a_tilted_sole() {
        let club = ClubSpec::iron7();
        let mut ground = SoilGround::new(SoilSpec::firm(), SoleSpec::IRON7, &club, 0.0);
        let rot = crate::math::UnitQuaternion::from_euler_angles(0.03, -0.05, -0.08);
        let probe = Isometry3::from_parts(nalgebra::Translation3::identity(), rot);
        let lowest = -ground.placed(&probe).max_sinkage_m();
        let pose = Isometry3::from_parts(nalgebra::Translation3::new(0.0, -lowest - 0.006, 0.0), rot);
        let (v, w) = (Vector3::new(34.0, -2.5, 1.0), Vector3::new(2.0, -5.0, -30.0));
        let coarse = ground.forces(&pose, &v, &w);
        ground.strips = GaussRule::new(16);
        ground.along_arc = GaussRule::new(16);
        let fine = ground.forces(&pose, &v, &w);
        let df = (coarse.force_n() - fine.force_n()).norm() / fine.force_n().norm();
        let dt = (coarse.torque_nm() - fine.torque_nm()).norm() / fine.torque_nm().norm();
        assert!(df < 5e-3 && dt < 5e-3, "force {df}, torque {dt}");
        assert!((fine.sole.max_sinkage_m - 0.006).abs() < 1e-12);
    }
}
