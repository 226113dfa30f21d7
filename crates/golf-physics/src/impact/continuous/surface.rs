//! Volumetric contact geometry (seed section 3.2.1, Figure 3.2; Gonthier and McPhee): the volume of
//! intersection `V` between the ball and the face, its centroid (where the contact force acts) and the contact
//! normal.
//!
//! - Sphere-plane (irons, Figure 3.2b): a spherical cap of height `δ = R − n·(c_ball − c_face)`,
//!   `V = π δ² (3R − δ) / 3`; its centroid lies on the normal through the ball's centre, `3 (2R − δ)² / (4 (3R − δ))`
//!   from the centre. The normal is the face normal.
//! - Sphere-sphere (drivers, Figure 3.2a): the lens between the ball (radius `R₁`) and the face sphere (radius
//!   `R₂`, centred `R₂` behind the face centre along `n0`) at centre distance `d`:
//!   `V = π (R₁ + R₂ − d)² (d² + 2d(R₁ + R₂) − 3(R₁ − R₂)²) / (12 d)`, the sum of two caps whose heights follow
//!   from the plane of intersection; the normal is along the line of centres.
//!
//! The potential energy of the elastic part `kV` is `k ∫ V dδ` over the overlap `δ`; [`overlap_energy`] gives it
//! in closed form for the energy balance.

use crate::equipment::ClubSpec;
use crate::face::FaceShape;
use crate::math::{Real, Vector3};

/// The contact between the ball and the face, in the club frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Overlap {
    /// Volume of intersection (m³).
    pub volume_m3: Real,
    /// Centroid of the intersection (club frame, m).
    pub centroid_m: Vector3,
    /// Unit normal from the face toward the ball (club frame).
    pub normal: Vector3,
    /// Overlap depth along the normal (m).
    pub depth_m: Real,
}

/// A face the ball can press into.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FaceSurface {
    /// A plane through `point` with outward `normal` (club frame).
    Plane {
        /// A point of the plane (m).
        point: Vector3,
        /// Its outward unit normal.
        normal: Vector3,
    },
    /// A sphere (centre, radius) whose outside is the face (club frame).
    Sphere {
        /// The sphere's centre (m).
        centre: Vector3,
        /// Its radius (m).
        radius_m: Real,
    },
}

/// Volume and centroid distance (from the sphere's centre) of a cap of height `h` of a sphere of radius `r`.
#[inline]
fn cap(r: Real, h: Real) -> (Real, Real) {
    let v = std::f64::consts::PI * h * h * (3.0 * r - h) / 3.0;
    let z = 3.0 * (2.0 * r - h).powi(2) / (4.0 * (3.0 * r - h));
    (v, z)
}

/// Volume and first moment `V z` about the sphere's centre of a cap of height `h` of a sphere of radius `r`:
/// [`cap`]'s `V · z = π h² (2r − h)² / 4`, with no division.
#[inline]
fn cap_moment(r: Real, h: Real) -> (Real, Real) {
    let v = std::f64::consts::PI * h * h * (3.0 * r - h) / 3.0;
    let w = h * (2.0 * r - h);
    (v, std::f64::consts::FRAC_PI_4 * w * w)
}

impl FaceSurface {
    /// The surface of a club's face for the contact: the plane for a flat face, the face sphere for a curved one
    /// (a face whose bulge and roll differ is taken as a sphere of their geometric-mean radius).
    pub fn of_club(club: &ClubSpec) -> Self {
        let face = &club.face;
        match face.shape {
            FaceShape::Plane => FaceSurface::Plane { point: face.center_m, normal: face.n0() },
            FaceShape::Torus { bulge_radius_m, roll_radius_m } => {
                let radius_m = if bulge_radius_m.is_finite() && roll_radius_m.is_finite() {
                    (bulge_radius_m * roll_radius_m).sqrt()
                } else {
                    bulge_radius_m.min(roll_radius_m)
                };
                FaceSurface::Sphere { centre: face.center_m - radius_m * face.n0(), radius_m }
            }
        }
    }

    /// The overlap's depth along the normal with a ball of radius `r` centred at `ball_m` (club frame), negative
    /// when apart (m).
    #[inline]
    pub fn signed_depth_m(&self, ball_m: &Vector3, r: Real) -> Real {
        match *self {
            FaceSurface::Plane { point, normal } => r - normal.dot(&(ball_m - point)),
            FaceSurface::Sphere { centre, radius_m } => r + radius_m - (ball_m - centre).norm(),
        }
    }

    /// The overlap with a ball of radius `r` centred at `ball_m` (club frame), if any.
    #[inline]
    pub fn overlap(&self, ball_m: &Vector3, r: Real) -> Option<Overlap> {
        match *self {
            FaceSurface::Plane { point, normal } => {
                let depth = r - normal.dot(&(ball_m - point));
                if depth <= 0.0 {
                    return None;
                }
                let depth = depth.min(2.0 * r);
                let (v, z) = cap(r, depth);
                Some(Overlap { volume_m3: v, centroid_m: ball_m - z * normal, normal, depth_m: depth })
            }
            FaceSurface::Sphere { centre, radius_m: r2 } => {
                let delta = ball_m - centre;
                let d = delta.norm();
                let depth = r + r2 - d;
                if depth <= 0.0 || d <= (r2 - r).abs() {
                    return None;
                }
                let normal = delta / d;
                // Plane of intersection at distance a from the face sphere's centre.
                let a = (d * d + r2 * r2 - r * r) / (2.0 * d);
                let h_face = r2 - a; // cap of the face sphere, toward the ball
                let h_ball = r - (d - a); // cap of the ball, toward the face
                let (v_face, m_face) = cap_moment(r2, h_face);
                let (v_ball, m_ball) = cap_moment(r, h_ball);
                let volume = v_face + v_ball;
                // The caps' centroids lie on the line of centres: the face cap's `z_face` from the face sphere's
                // centre toward the ball (`d − z_face` behind the ball's centre), the ball's `z_ball` from the
                // ball's centre toward the face; their volume-weighted mean from the ball's centre along `normal`.
                let along = (m_face - v_face * d - m_ball) / volume;
                Some(Overlap { volume_m3: volume, centroid_m: ball_m + along * normal, normal, depth_m: depth })
            }
        }
    }
}

/// Potential energy `∫₀^δ V(s) ds` of the elastic contact per unit stiffness (m⁴) at overlap `depth`.
pub fn overlap_energy(surface: &FaceSurface, r: Real, depth: Real) -> Real {
    if depth <= 0.0 {
        return 0.0;
    }
    match *surface {
        // V(s) = π (R s² − s³/3)  =>  ∫ = π (R δ³/3 − δ⁴/12)
        FaceSurface::Plane { .. } => std::f64::consts::PI * (r * depth.powi(3) / 3.0 - depth.powi(4) / 12.0),
        // Numerically (Simpson) along the centre distance; the lens volume is smooth in the overlap.
        FaceSurface::Sphere { radius_m: r2, .. } => {
            let v = |s: Real| {
                if s <= 0.0 {
                    return 0.0;
                }
                let d = r + r2 - s;
                std::f64::consts::PI * s * s * (d * d + 2.0 * d * (r + r2) - 3.0 * (r - r2).powi(2)) / (12.0 * d)
            };
            let n = 200;
            let h = depth / n as Real;
            let mut sum = v(0.0) + v(depth);
            for i in 1..n {
                sum += v(i as Real * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
            }
            sum * h / 3.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sphere-sphere lens with a huge face sphere tends to the sphere-plane cap.
    #[test]
    fn lens_tends_to_cap() {
        let r = 0.0213;
        let depth = 0.004;
        let plane = FaceSurface::Plane { point: Vector3::zeros(), normal: Vector3::x() };
        let ball = Vector3::new(r - depth, 0.0, 0.0);
        let a = plane.overlap(&ball, r).unwrap();
        let big = 1e6; // the lens differs from the cap by O(r / R), 2e-8 here
        let sphere = FaceSurface::Sphere { centre: Vector3::new(-big, 0.0, 0.0), radius_m: big };
        let b = sphere.overlap(&ball, r).unwrap();
        assert!((a.volume_m3 - b.volume_m3).abs() < 1e-6 * a.volume_m3, "{} {}", a.volume_m3, b.volume_m3);
        assert!((a.centroid_m - b.centroid_m).norm() < 1e-6);
    }

    /// The cap's moment is its volume times its centroid's distance.
    #[test]
    fn cap_moment_is_volume_times_centroid() {
        for (r, h) in [(0.0213, 1e-5), (0.0213, 0.004), (0.3, 0.002), (0.02, 0.039)] {
            let (v, z) = cap(r, h);
            let (v2, m) = cap_moment(r, h);
            assert_eq!(v, v2);
            assert!((m - v * z).abs() <= 1e-14 * m, "{r} {h}: {m} vs {}", v * z);
        }
    }

    /// Closed form: the lens volume of two equal spheres of radius R at distance d is
    /// π (4R + d)(2R − d)² / 12.
    #[test]
    fn equal_spheres_lens() {
        let r = 0.02;
        let d = 0.035;
        let s = FaceSurface::Sphere { centre: Vector3::zeros(), radius_m: r };
        let o = s.overlap(&Vector3::new(d, 0.0, 0.0), r).unwrap();
        let want = std::f64::consts::PI * (4.0 * r + d) * (2.0 * r - d).powi(2) / 12.0;
        assert!((o.volume_m3 - want).abs() < 1e-12 * want.max(1e-12) + 1e-18);
        assert!((o.centroid_m.x - d / 2.0).abs() < 1e-12);
    }

    /// The overlap energy's derivative is the volume.
    #[test]
    fn energy_derivative_is_volume() {
        let r = 0.0213;
        for surface in [
            FaceSurface::Plane { point: Vector3::zeros(), normal: Vector3::x() },
            FaceSurface::Sphere { centre: Vector3::new(-0.305, 0.0, 0.0), radius_m: 0.305 },
        ] {
            let depth = 0.003;
            let h = 1e-7;
            let dv = (overlap_energy(&surface, r, depth + h) - overlap_energy(&surface, r, depth - h)) / (2.0 * h);
            let ball = match surface {
                FaceSurface::Plane { .. } => Vector3::new(r - depth, 0.0, 0.0),
                FaceSurface::Sphere { .. } => Vector3::new(r - depth, 0.0, 0.0),
            };
            let v = surface.overlap(&ball, r).unwrap().volume_m3;
            assert!((dv - v).abs() < 1e-6 * v, "{dv} vs {v}");
        }
    }
}
