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

/// `v.into_translation()` for building isometries from vectors.
pub trait Translation3Ext {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn skew_is_the_cross_product() {
        let a = Vector3::new(1.0, -2.0, 3.5);
        let b = Vector3::new(-0.5, 4.0, 2.0);
        assert!((skew(&a) * b - a.cross(&b)).norm() < 1e-15);
    }
}
