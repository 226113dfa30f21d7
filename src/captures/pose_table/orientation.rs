//! A pose table's orientation columns as a rotation (`lab_from_body`'s): a quaternion (scalar last or first), a
//! rotation matrix (row-major, its columns the body's axes in the lab), or a named Euler sequence (SciPy's
//! naming: `XYZ` upper-case for intrinsic rotations, about the body's axes as they turn; `xyz` lower-case for
//! extrinsic, about the lab's fixed axes; the first angle about the first axis named).

use crate::math::{Matrix3, Rotation3, UnitQuaternion, Vector3};

/// How the orientation is written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum OrientationKind {
    /// Four columns: `x, y, z, w` when `scalar_last`, else `w, x, y, z`.
    Quaternion { scalar_last: bool },
    /// Nine columns, row-major: `r11, r12, r13, r21, ..., r33`.
    Matrix,
    /// Three angles about `axes` (0 x, 1 y, 2 z), intrinsic or extrinsic, in units of `radians_per_unit`.
    Euler { axes: [usize; 3], intrinsic: bool, radians_per_unit: f64 },
}

impl OrientationKind {
    /// The number of columns it takes.
    pub fn columns(&self) -> usize {
        match self {
            OrientationKind::Quaternion { .. } => 4,
            OrientationKind::Matrix => 9,
            OrientationKind::Euler { .. } => 3,
        }
    }

    /// An Euler sequence from its name (`ZYX`, `xyz`, `ZXZ`, ...), or why it is not one.
    pub fn euler(sequence: &str, radians_per_unit: f64) -> Result<Self, String> {
        let chars: Vec<char> = sequence.chars().collect();
        let intrinsic = chars.iter().all(|c| c.is_ascii_uppercase());
        let extrinsic = chars.iter().all(|c| c.is_ascii_lowercase());
        let axis = |c: &char| match c.to_ascii_lowercase() {
            'x' => Some(0),
            'y' => Some(1),
            'z' => Some(2),
            _ => None,
        };
        let axes: Option<Vec<usize>> = chars.iter().map(axis).collect();
        match axes {
            Some(a) if a.len() == 3 && (intrinsic || extrinsic) && a[0] != a[1] && a[1] != a[2] => {
                Ok(OrientationKind::Euler { axes: [a[0], a[1], a[2]], intrinsic, radians_per_unit })
            }
            _ => Err(format!(
                "`{sequence}` is not an Euler sequence: three of x, y, z, no axis twice in a row, all upper-case \
                 (intrinsic) or all lower-case (extrinsic), e.g. ZYX or xyz"
            )),
        }
    }

    /// The rotation of one row's values (as many as [`OrientationKind::columns`]), or why they are none.
    pub fn rotation(&self, v: &[f64]) -> Result<UnitQuaternion, String> {
        match *self {
            OrientationKind::Quaternion { scalar_last } => {
                let xyzw = if scalar_last { [v[0], v[1], v[2], v[3]] } else { [v[1], v[2], v[3], v[0]] };
                crate::kinematics::sample::unit_quaternion(&xyzw, 1e-3).ok_or_else(|| {
                    let norm = xyzw.iter().map(|c| c * c).sum::<f64>().sqrt();
                    format!("the quaternion's norm is {norm:.6}, not 1 (within 0.001)")
                })
            }
            OrientationKind::Matrix => {
                let m = Matrix3::from_row_slice(&v[..9]);
                let off = (m.transpose() * m - Matrix3::identity()).abs().max();
                if off > 1e-3 || m.determinant() < 0.0 {
                    return Err(format!(
                        "the rotation matrix is not a rotation (|R^T R - I| = {off:.2e}, det = {:.4})",
                        m.determinant()
                    ));
                }
                Ok(UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix(&m)))
            }
            OrientationKind::Euler { axes, intrinsic, radians_per_unit } => {
                let turn = |i: usize| UnitQuaternion::from_axis_angle(&unit_axis(axes[i]), v[i] * radians_per_unit);
                Ok(if intrinsic { turn(0) * turn(1) * turn(2) } else { turn(2) * turn(1) * turn(0) })
            }
        }
    }
}

fn unit_axis(i: usize) -> nalgebra::Unit<Vector3> {
    match i {
        0 => Vector3::x_axis(),
        1 => Vector3::y_axis(),
        _ => Vector3::z_axis(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_three_forms_give_one_rotation() {
        let q = UnitQuaternion::from_euler_angles(0.3, -0.2, 1.1);
        let quat = OrientationKind::Quaternion { scalar_last: false };
        let wxyz = [q.w, q.i, q.j, q.k];
        assert!(quat.rotation(&wxyz).unwrap().angle_to(&q) < 1e-12);
        let m = q.to_rotation_matrix();
        let rows: Vec<f64> = (0..3).flat_map(|r| (0..3).map(move |c| m[(r, c)])).collect();
        assert!(OrientationKind::Matrix.rotation(&rows).unwrap().angle_to(&q) < 1e-9);
        // nalgebra's euler angles (roll, pitch, yaw) are extrinsic x, y, z: intrinsic Z, Y, X of (yaw, pitch, roll).
        let deg = std::f64::consts::PI / 180.0;
        let (r, p, y) = (0.3 / deg, -0.2 / deg, 1.1 / deg);
        let extrinsic = OrientationKind::euler("xyz", deg).unwrap();
        assert!(extrinsic.rotation(&[r, p, y]).unwrap().angle_to(&q) < 1e-12);
        let intrinsic = OrientationKind::euler("ZYX", deg).unwrap();
        assert!(intrinsic.rotation(&[y, p, r]).unwrap().angle_to(&q) < 1e-12);
        assert!(OrientationKind::euler("XXY", deg).is_err() && OrientationKind::euler("Xyz", deg).is_err());
        assert!(quat.rotation(&[0.5, 0.5, 0.5, 0.0]).unwrap_err().contains("norm is 0.866"));
        let mut skew = rows.clone();
        skew[1] += 0.1;
        assert!(OrientationKind::Matrix.rotation(&skew).unwrap_err().contains("not a rotation"));
    }
}
