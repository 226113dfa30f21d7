//! Clubface geometry: the contact point and outward normal for an impact location, and the impact frame.
//!
//! Conventions (ARCHITECTURE.md section 2). In the club frame (origin at the head's CG, x forward, y up, z toward the
//! toe) the face-centre normal is `n0 = (cos L, sin L, 0)` for static loft `L`, up-the-face `u0 = (-sin L, cos L,
//! 0)` and toe `t0 = (0, 0, 1)`. An impact location `(h, v)` is the contact point's offset from the face centre
//! `c` measured in the tangent plane at `c`: `h` toward the toe, `v` up the face.
//!
//! - Planar face (irons): contact `c + h t0 + v u0`, normal `n0`.
//! - Torus (drivers, the seed's bulge and roll, section 3.1 and Danaei et al.): the tube of radius `R_roll` lies
//!   in the `n0`-`u0` plane centred at `c - R_roll n0` and is revolved about the axis through `c - R_bulge n0`
//!   parallel to `u0`. With `psi = asin(v / R_roll)` and `phi = asin(h / rho)`, `rho = R_bulge - R_roll + R_roll
//!   cos psi`, the contact is `c - R_bulge n0 + rho (cos phi n0 + sin phi t0) + R_roll sin psi u0` and the normal
//!   `n = cos psi (cos phi n0 + sin phi t0) + sin psi u0`. Equal radii give a sphere, infinite radii a plane.
//!
//! The impact frame (seed eq. 3.6-3.12) has its origin at the contact point: `x'` is the outward face normal
//! (toward the ball), `z'` the club's toe axis projected onto the tangent plane, `y' = z' x x'` (up the face).

use crate::math::{Matrix3, Real, Vector3};

/// The shape of a clubface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FaceShape {
    /// A flat face (irons).
    Plane,
    /// A torus with horizontal (bulge) and vertical (roll) radii of curvature (drivers, woods).
    Torus {
        /// Horizontal (toe-heel) radius of curvature (m).
        bulge_radius_m: Real,
        /// Vertical radius of curvature (m).
        roll_radius_m: Real,
    },
}

impl FaceShape {
    /// The shape for the given radii: infinite radii on both axes make a plane.
    pub fn from_radii(bulge_radius_m: Real, roll_radius_m: Real) -> Self {
        if bulge_radius_m.is_infinite() && roll_radius_m.is_infinite() {
            FaceShape::Plane
        } else {
            FaceShape::Torus { bulge_radius_m, roll_radius_m }
        }
    }

    /// Whether the face is curved.
    pub fn is_curved(&self) -> bool {
        matches!(self, FaceShape::Torus { .. })
    }
}

/// The clubface of one club, in its club frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Face {
    /// Face centre relative to the CG, club frame (m).
    pub center_m: Vector3,
    /// Static loft (rad).
    pub loft_rad: Real,
    /// Plane or torus.
    pub shape: FaceShape,
}

/// A contact point on the face with its outward normal, both in the club frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceContact {
    /// Contact point relative to the club CG (m), club frame.
    pub point_m: Vector3,
    /// Outward unit normal at the contact point, club frame.
    pub normal: Vector3,
}

/// Why an impact location has no point on the face.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum FaceError {
    #[error("impact location ({h_mm:.1} mm, {v_mm:.1} mm) is outside the face's curvature (bulge/roll radius)")]
    /// The impact location (toward the toe, up the face) has no point on the curved face.
    OutsideCurvature {
        /// Toward the toe (mm).
        h_mm: Real,
        /// Up the face (mm).
        v_mm: Real,
    },
}

impl Face {
    /// Face-centre normal `n0`.
    #[inline]
    pub fn n0(&self) -> Vector3 {
        Vector3::new(self.loft_rad.cos(), self.loft_rad.sin(), 0.0)
    }

    /// Up-the-face direction at the face centre `u0`.
    #[inline]
    pub fn u0(&self) -> Vector3 {
        Vector3::new(-self.loft_rad.sin(), self.loft_rad.cos(), 0.0)
    }

    /// Toe direction `t0`.
    #[inline]
    pub fn t0(&self) -> Vector3 {
        Vector3::z()
    }

    /// Contact point and normal for the impact location `(h_m, v_m)`.
    pub fn contact(&self, h_m: Real, v_m: Real) -> Result<FaceContact, FaceError> {
        let (n0, u0, t0) = (self.n0(), self.u0(), self.t0());
        match self.shape {
            FaceShape::Plane => Ok(FaceContact { point_m: self.center_m + h_m * t0 + v_m * u0, normal: n0 }),
            FaceShape::Torus { bulge_radius_m, roll_radius_m } => {
                let outside = || FaceError::OutsideCurvature { h_mm: h_m * 1e3, v_mm: v_m * 1e3 };
                // Infinite roll (or bulge) reduces to a cylinder; handle the limit without inf*0.
                let (sin_psi, cos_psi, v_arc) = if roll_radius_m.is_finite() {
                    let s = v_m / roll_radius_m;
                    if s.abs() >= 1.0 {
                        return Err(outside());
                    }
                    let c = (1.0 - s * s).sqrt();
                    (s, c, roll_radius_m * (1.0 - c))
                } else {
                    (0.0, 1.0, 0.0)
                };
                let (sin_phi, cos_phi, h_arc) = if bulge_radius_m.is_finite() {
                    // rho = R_bulge - R_roll (1 - cos psi)
                    let rho = bulge_radius_m - v_arc;
                    let s = h_m / rho;
                    if rho.is_nan() || rho <= 0.0 || s.abs() >= 1.0 {
                        return Err(outside());
                    }
                    let c = (1.0 - s * s).sqrt();
                    (s, c, rho * (1.0 - c))
                } else {
                    (0.0, 1.0, 0.0)
                };
                // Depth behind the tangent plane at c: v_arc from the roll, h_arc from the bulge.
                let point_m = self.center_m - (v_arc + h_arc) * n0 + h_m * t0 + v_m * u0;
                let normal = cos_psi * (cos_phi * n0 + sin_phi * t0) + sin_psi * u0;
                Ok(FaceContact { point_m, normal })
            }
        }
    }
}

/// Where a point (a ball's centre) stands relative to the face surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceGap {
    /// Distance from the point to the face surface along the surface normal, positive in front of the face (m).
    pub distance_m: Real,
    /// Impact location of the surface point nearest the point (m): toward the toe, up the face.
    pub h_m: Real,
    /// Up the face (m).
    pub v_m: Real,
}

impl Face {
    /// The gap between `point_m` (club frame) and the face surface, and the location of the nearest surface
    /// point. A sphere of radius `r` centred there touches the face when `distance_m == r`, at `(h_m, v_m)`.
    ///
    /// Plane: `distance = n0 . (p - c)`, `h = t0 . (p - c)`, `v = u0 . (p - c)`. Torus: the nearest point of the
    /// tube circle in the point's meridian plane (the revolution axis passes through `c - R_bulge n0` along
    /// `u0`); `distance = |p - tube centre| - R_roll`.
    pub fn gap(&self, point_m: &Vector3) -> FaceGap {
        let (n0, u0, t0) = (self.n0(), self.u0(), self.t0());
        let d = point_m - self.center_m;
        match self.shape {
            FaceShape::Torus { bulge_radius_m, roll_radius_m }
                if bulge_radius_m.is_finite() && roll_radius_m.is_finite() =>
            {
                // Coordinates about the revolution axis.
                let a = d + bulge_radius_m * n0; // from the axis point
                let y = a.dot(&u0);
                let radial = a - y * u0; // in the n0-t0 plane
                let (rn, rt) = (radial.dot(&n0), radial.dot(&t0));
                let phi = rt.atan2(rn);
                let e = phi.cos() * n0 + phi.sin() * t0;
                let tube_centre = (bulge_radius_m - roll_radius_m) * e;
                let w = a - tube_centre; // from the tube centre, in the (e, u0) plane
                let (we, wy) = (w.dot(&e), w.dot(&u0));
                let psi = wy.atan2(we);
                let rho = bulge_radius_m - roll_radius_m + roll_radius_m * psi.cos();
                FaceGap {
                    distance_m: we.hypot(wy) - roll_radius_m,
                    h_m: rho * phi.sin(),
                    v_m: roll_radius_m * psi.sin(),
                }
            }
            _ => FaceGap { distance_m: d.dot(&n0), h_m: d.dot(&t0), v_m: d.dot(&u0) },
        }
    }
}

/// The impact frame: columns `x'` (normal, toward the ball), `y'` (up the face), `z'` (toward the toe).
///
/// `normal` and `toe` are in the same frame (world or club); the result is in that frame.
#[inline]
pub fn impact_frame(normal: &Vector3, toe: &Vector3) -> Matrix3 {
    let x = *normal;
    let z = (toe - toe.dot(&x) * x).normalize();
    let y = z.cross(&x);
    Matrix3::from_columns(&[x, y, z])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn driver_face() -> Face {
        Face {
            center_m: Vector3::new(0.0408, 0.0114, 0.001),
            loft_rad: 9.8_f64.to_radians(),
            shape: FaceShape::Torus { bulge_radius_m: 0.305, roll_radius_m: 0.305 },
        }
    }

    /// Closed form: equal bulge and roll radii make a sphere of radius R centred at c - R n0; every contact point
    /// lies on it and its normal points away from the centre.
    #[test]
    fn equal_radii_make_a_sphere() {
        let face = driver_face();
        let centre = face.center_m - 0.305 * face.n0();
        for &(h, v) in &[(0.0, 0.0), (0.02, 0.0), (-0.03, 0.015), (0.04, -0.02)] {
            let c = face.contact(h, v).unwrap();
            let r = c.point_m - centre;
            assert!((r.norm() - 0.305).abs() < 1e-12, "radius {}", r.norm());
            assert!((r.normalize() - c.normal).norm() < 1e-12);
            // Tangent-plane coordinates are h and v by definition.
            let d = c.point_m - face.center_m;
            assert!((d.dot(&face.t0()) - h).abs() < 1e-12);
            assert!((d.dot(&face.u0()) - v).abs() < 1e-12);
        }
    }

    #[test]
    fn toe_hit_normal_points_toward_the_toe() {
        let c = driver_face().contact(0.02, 0.0).unwrap();
        assert!(c.normal.z > 0.0);
        let c = driver_face().contact(0.0, 0.02).unwrap();
        // Above centre the normal tilts up the face (more loft).
        assert!(c.normal.y > driver_face().n0().y);
    }

    #[test]
    fn plane_is_flat() {
        let face = Face { center_m: Vector3::zeros(), loft_rad: 0.5, shape: FaceShape::Plane };
        let c = face.contact(0.01, -0.02).unwrap();
        assert!((c.normal - face.n0()).norm() < 1e-15);
        assert!(c.point_m.dot(&face.n0()).abs() < 1e-15);
    }

    #[test]
    fn impact_frame_is_right_handed() {
        let f = impact_frame(&Vector3::new(0.9, 0.3, 0.1).normalize(), &Vector3::z());
        assert!((f.determinant() - 1.0).abs() < 1e-12);
        assert!((f.transpose() * f - Matrix3::identity()).norm() < 1e-12);
    }

    /// A point placed at distance r along the normal of a contact point reports that distance and location.
    #[test]
    fn gap_inverts_contact() {
        for face in [
            driver_face(),
            Face { center_m: Vector3::new(0.004, 0.005, 0.001), loft_rad: 0.53, shape: FaceShape::Plane },
        ] {
            for &(h, v) in &[(0.0, 0.0), (0.02, -0.01), (-0.035, 0.012)] {
                let c = face.contact(h, v).unwrap();
                let g = face.gap(&(c.point_m + 0.0213 * c.normal));
                assert!((g.distance_m - 0.0213).abs() < 1e-12, "{g:?}");
                assert!((g.h_m - h).abs() < 1e-12 && (g.v_m - v).abs() < 1e-12, "{g:?}");
            }
        }
    }

    #[test]
    fn off_the_curvature_is_an_error() {
        assert!(driver_face().contact(0.0, 0.4).is_err());
    }
}
