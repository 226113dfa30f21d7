//! The sole's cylinder placed in the world at one instant (seed section 4.2, Figure 4.3) and the Gauss-Legendre
//! rule the sole's and the face's soil forces are integrated with along the sole (eq. 4.3-4.13).

use crate::equipment::sole::SoleArc;
use crate::math::{Isometry3, Real, Rotation3, Vector3};

/// The most Gauss points of a rule.
pub const MAX_GAUSS: usize = 16;

/// A Gauss-Legendre rule on [0, 1].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussRule {
    /// Its number of points (≤ [`MAX_GAUSS`]).
    pub n: usize,
    /// Its nodes on [0, 1] (the first `n`).
    pub x: [Real; MAX_GAUSS],
    /// Its weights, summing to 1 (the first `n`).
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
    /// See `ex`.
    pub ey: Vector3,
    /// See `ex`.
    pub ez: Vector3,
    /// The cylinder's axis point at the sole's heel-toe middle (world).
    pub centre_m: Vector3,
    /// The sole's radius of curvature (m, seed Figure 4.8's `R`).
    pub radius_m: Real,
    /// The trailing edge's angle on the cylinder (rad, from straight down, toward the leading edge +).
    pub theta_te_rad: Real,
    /// The leading edge's angle on the cylinder (rad).
    pub theta_le_rad: Real,
    /// Half the sole's heel-toe length (m).
    pub half_length_m: Real,
    /// The undisturbed playing surface's height `y_ground` (m, world).
    pub ground_y_m: Real,
    /// The sinkage's form `A(s) + R ρ cos(θ − θ₀)`, computed once: `(A(0), slope of A in s, ρ, θ₀)`.
    form: (Real, Real, Real, Real),
}

impl SoleArcWorld {
    /// The sole `arc` on a head at `world_from_club`, over the ground `y = ground_y_m`.
    pub fn new(arc: &SoleArc, world_from_club: &Isometry3, ground_y_m: Real) -> Self {
        Self::at(arc, &world_from_club.rotation.to_rotation_matrix(), &world_from_club.translation.vector, ground_y_m)
    }

    /// [`Self::new`] with the pose as a rotation matrix and the CG's position (no quaternion on the way).
    pub fn at(arc: &SoleArc, world_from_club: &Rotation3, cg_m: &Vector3, ground_y_m: Real) -> Self {
        let r = world_from_club * arc.axes.to_rotation_matrix();
        let m = r.matrix();
        let (ex, ey, ez) = (m.column(0).into_owned(), m.column(1).into_owned(), m.column(2).into_owned());
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
