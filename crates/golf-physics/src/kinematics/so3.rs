//! SO(3) helpers: exponential and logarithm maps and the right Jacobian, for fitting orientations in a tangent
//! space (`R(t) = R_ref Exp(θ(t))`, body-frame angular velocity `ω_b = J_r(θ) θ'`).

use crate::math::{skew, Matrix3, Real, UnitQuaternion, Vector3};

/// Exp: rotation vector -> rotation.
#[inline]
pub fn exp(theta: &Vector3) -> UnitQuaternion {
    UnitQuaternion::from_scaled_axis(*theta)
}

/// Log: rotation -> rotation vector (angle < π).
#[inline]
pub fn log(q: &UnitQuaternion) -> Vector3 {
    q.scaled_axis()
}

/// Right Jacobian `J_r(θ) = I − (1 − cos|θ|)/|θ|² [θ]× + (|θ| − sin|θ|)/|θ|³ [θ]×²`, so that
/// `d/dt Exp(θ(t)) = Exp(θ) [J_r(θ) θ']×`.
pub fn right_jacobian(theta: &Vector3) -> Matrix3 {
    let a2 = theta.norm_squared();
    let k = skew(theta);
    let (c1, c2): (Real, Real) = if a2 < 1e-8 {
        (0.5 - a2 / 24.0, 1.0 / 6.0 - a2 / 120.0)
    } else {
        let a = a2.sqrt();
        ((1.0 - a.cos()) / a2, (a - a.sin()) / (a2 * a))
    };
    Matrix3::identity() - c1 * k + c2 * k * k
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Finite-difference check of the body angular velocity of Exp(θ(t)).
    #[test]
    fn right_jacobian_gives_the_body_rate() {
        let theta = |t: Real| Vector3::new(0.3 + 2.0 * t, -0.2 + 0.5 * t * t, 0.1 - t);
        let dtheta = |t: Real| Vector3::new(2.0, t, -1.0);
        let t = 0.4;
        let h = 1e-6;
        let r0 = exp(&theta(t));
        let r1 = exp(&theta(t + h));
        let w_fd = log(&(r0.inverse() * r1)) / h;
        let w = right_jacobian(&theta(t)) * dtheta(t);
        assert!((w - w_fd).norm() < 1e-5, "{w} vs {w_fd}");
    }
}
