//! Numeric aliases so the physics reads like the seed's equations.
//!
//! Everything inside the crate is SI (m, s, kg, rad) in `f64`. Vectors are column vectors; transforms are named
//! `a_from_b` so that `p_a = a_from_b * p_b` reads right to left.

/// The scalar type of every physical quantity.
pub type Real = f64;
/// A 3-vector (position, velocity, angular velocity, impulse...).
pub type Vector3 = nalgebra::Vector3<Real>;
/// A point in 3D space.
pub type Point3 = nalgebra::Point3<Real>;
/// A 3x3 matrix (inertia tensors, rotation matrices).
pub type Matrix3 = nalgebra::Matrix3<Real>;
/// A rotation as a unit quaternion.
pub type UnitQuaternion = nalgebra::UnitQuaternion<Real>;
/// A rotation as an orthonormal matrix.
pub type Rotation3 = nalgebra::Rotation3<Real>;
/// A rigid transform (rotation then translation).
pub type Isometry3 = nalgebra::Isometry3<Real>;

/// A translation part of an isometry.
pub type Translation3 = nalgebra::Translation3<Real>;
/// A quaternion, not necessarily of unit length (a rotation's rate, `q̇ = q ω / 2`).
pub type Quaternion = nalgebra::Quaternion<Real>;
/// A 4-vector and a 4x4 matrix (Horn's quaternion fit).
pub type Vector4 = nalgebra::Vector4<Real>;
/// A 4x4 matrix (the quaternion fit's symmetric matrix).
pub type Matrix4 = nalgebra::Matrix4<Real>;
/// Fixed-size matrices and vectors of any shape (a beam element's 12x12 stiffness, a fit's normal equations).
pub type SMatrix<const R: usize, const C: usize> = nalgebra::SMatrix<Real, R, C>;
/// A fixed-size column vector of any length.
pub type SVector<const N: usize> = nalgebra::SVector<Real, N>;
/// Matrices and vectors sized at run time (a shaft's mesh, a least-squares fit).
pub type DMatrix = nalgebra::DMatrix<Real>;
/// A column vector sized at run time.
pub type DVector = nalgebra::DVector<Real>;
/// A complex number (a mode's exact propagator, `e^{λh}`).
pub type Complex = nalgebra::Complex<Real>;
/// A unit-length wrapper (a face normal) and the eigen-decomposition of a symmetric matrix.
pub use nalgebra::{SymmetricEigen, Unit};

/// `v.into_translation()` for building isometries from vectors.
pub trait Translation3Ext {
    /// The translation by this vector.
    fn into_translation(self) -> Translation3;
}

impl Translation3Ext for Vector3 {
    #[inline]
    fn into_translation(self) -> Translation3 {
        Translation3::from(self)
    }
}

/// The cross-product matrix `[a]x` with `[a]x b = a x b`.
#[inline]
pub fn skew(a: &Vector3) -> Matrix3 {
    Matrix3::new(0.0, -a.z, a.y, a.z, 0.0, -a.x, -a.y, a.x, 0.0)
}

/// Rotation about the world/club y axis (up) by `angle_rad`, right-hand rule.
#[inline]
pub fn rot_y(angle_rad: Real) -> Rotation3 {
    Rotation3::from_axis_angle(&Vector3::y_axis(), angle_rad)
}

/// Rotation about the z axis by `angle_rad`, right-hand rule.
#[inline]
pub fn rot_z(angle_rad: Real) -> Rotation3 {
    Rotation3::from_axis_angle(&Vector3::z_axis(), angle_rad)
}

/// The reflection `z -> -z` that turns a right-handed golfer's world into a left-handed golfer's.
#[inline]
pub fn mirror_z(v: &Vector3) -> Vector3 {
    Vector3::new(v.x, v.y, -v.z)
}

/// The reflection of an axial vector (angular velocity, angular momentum) under `z -> -z`.
#[inline]
pub fn mirror_z_axial(w: &Vector3) -> Vector3 {
    Vector3::new(-w.x, -w.y, w.z)
}

/// The reflection of a tensor (inertia) under `z -> -z`: `M I M` with `M = diag(1, 1, -1)`.
#[inline]
pub fn mirror_z_tensor(m: &Matrix3) -> Matrix3 {
    let r = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -1.0));
    r * m * r
}

/// `(sin x, cos x)`: for `|x| ≤ 0.8` rad by their Taylor series to x¹⁸ (truncation below 1e-18, a few times
/// cheaper than the library's general routine), else by `sin_cos`. For the small angles inside a step (a sole's
/// wetted arc, a swing's turn over milliseconds).
#[inline]
pub fn sin_cos_small(x: Real) -> (Real, Real) {
    if x.abs() > 0.8 {
        return x.sin_cos();
    }
    let x2 = x * x;
    // sin x = x (1 − x²/(2·3) (1 − x²/(4·5) (1 − ...))), cos x = 1 − x²/(1·2) (1 − x²/(3·4) (1 − ...)), nested
    // from the innermost factor.
    const SIN: [Real; 8] = [272.0, 210.0, 156.0, 110.0, 72.0, 42.0, 20.0, 6.0];
    const COS: [Real; 9] = [306.0, 240.0, 182.0, 132.0, 90.0, 56.0, 30.0, 12.0, 2.0];
    let s = SIN.iter().fold(1.0, |acc, d| 1.0 - x2 * (1.0 / d) * acc);
    let c = COS.iter().fold(1.0, |acc, d| 1.0 - x2 * (1.0 / d) * acc);
    (x * s, c)
}

/// `Rotation3::new(v)` (the rotation by |v| about v) for the small rotations of an elastic shaft: below 0.1 rad
/// Rodrigues' coefficients `sin θ/θ` and `(1 − cos θ)/θ²` by their series (to rounding; no `sin_cos`).
#[inline]
pub fn small_rotation(v: &Vector3) -> Rotation3 {
    let t2 = v.norm_squared();
    if t2 >= 0.01 {
        return Rotation3::new(*v);
    }
    // sin θ/θ = Σ (−θ²)ᵏ/(2k + 1)!, (1 − cos θ)/θ² = Σ (−θ²)ᵏ/(2k + 2)!; θ² < 0.01 leaves < 1e-17 after 5 terms.
    let a = 1.0 - t2 / 6.0 * (1.0 - t2 / 20.0 * (1.0 - t2 / 42.0 * (1.0 - t2 / 72.0)));
    let b = 0.5 * (1.0 - t2 / 12.0 * (1.0 - t2 / 30.0 * (1.0 - t2 / 56.0 * (1.0 - t2 / 90.0))));
    let k = skew(v);
    Rotation3::from_matrix_unchecked(Matrix3::identity() + k * a + k * k * b)
}

/// `tanh(x) / x` (1 at 0), even in `x`: below 0.1 by its series to x¹⁴ (truncation below 1e-19), else from one
/// exponential, `(1 − e^{−2|x|}) / ((1 + e^{−2|x|}) |x|)` (the library's `tanh` costs an `expm1`). For a
/// regularised friction `μ F_N tanh(v/v_tr) v̂`, written `μ F_N (tanh(x)/x) v / v_tr` with no division by the slip.
#[inline]
pub fn tanh_over_x(x: Real) -> Real {
    let x = x.abs();
    if x < 0.1 {
        // tanh x = x − x³/3 + 2x⁵/15 − 17x⁷/315 + 62x⁹/2835 − 1382x¹¹/155925 + 21844x¹³/6081075 − 929569x¹⁵/638512875
        const C: [Real; 7] = [
            -1.0 / 3.0,
            2.0 / 15.0,
            -17.0 / 315.0,
            62.0 / 2835.0,
            -1382.0 / 155925.0,
            21844.0 / 6081075.0,
            -929569.0 / 638512875.0,
        ];
        let x2 = x * x;
        return 1.0 + x2 * C.iter().rev().fold(0.0, |acc, c| c + x2 * acc);
    }
    let t = (-2.0 * x).exp();
    (1.0 - t) / ((1.0 + t) * x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `tanh_over_x` is the library's `tanh(x) / x` to a few units in the last place, on both sides of the switch
    /// to the exponential (0.1) and far into saturation.
    #[test]
    fn tanh_over_x_is_tanh_divided() {
        assert_eq!(tanh_over_x(0.0), 1.0);
        for i in 1..=4000 {
            let x = if i <= 2000 { i as Real * 1e-4 } else { (i - 2000) as Real * 0.02 };
            let want = x.tanh() / x;
            for x in [x, -x] {
                let got = tanh_over_x(x);
                assert!((got - want).abs() <= 1e-15 * want, "{x}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn skew_is_the_cross_product() {
        let a = Vector3::new(1.0, -2.0, 3.5);
        let b = Vector3::new(-0.5, 4.0, 2.0);
        assert!((skew(&a) * b - a.cross(&b)).norm() < 1e-15);
    }

    /// The series agrees with the library's `sin_cos` to a few units in the last place, and beyond 0.8 rad is it.
    #[test]
    fn small_angle_sin_cos() {
        for i in -1000..=1000 {
            let x = i as Real * 1e-3;
            let (s, c) = sin_cos_small(x);
            assert!((s - x.sin()).abs() <= 4e-16 * x.sin().abs().max(1e-300) + 1e-300, "{x}: sin {s} vs {}", x.sin());
            assert!((c - x.cos()).abs() <= 4e-16, "{x}: cos {c} vs {}", x.cos());
        }
    }

    /// The series rotation is nalgebra's to 1e-15, small and at the switch to the direct form.
    #[test]
    fn small_rotation_is_the_exponential_map() {
        for v in [Vector3::new(1e-9, -2e-9, 0.0), Vector3::new(0.01, -0.03, 0.02), Vector3::new(0.0, 0.0999, 0.0)] {
            let d = (small_rotation(&v).matrix() - Rotation3::new(v).matrix()).norm();
            assert!(d < 1e-15, "{v:?}: {d}");
        }
    }
}
