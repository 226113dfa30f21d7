//! A pointer (a wand of markers with a known tip) touching the face: at the face centre, then at the heel and
//! toe ends of the leading edge. Expressed in the club body's frame, the three touches give the face centre,
//! the toe axis (along the leading edge) and the face's plane (through the centre and the leading edge), the
//! face's bulge and roll from the club file taken off: the leading edge lies behind the plane tangent at the
//! centre by the face's curvature.

use crate::face::Face;
use crate::math::{Real, Vector3};

use super::CalibrationError;

/// Where a wand's tip is relative to its markers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TipOffset {
    /// On the wand's axis, this far (m) beyond its first marker, away from its last: `first + d (first - last) /
    /// |first - last|` (two or more markers on one line).
    Along(Real),
    /// In the wand's frame (m): origin at the first marker, x toward the second, y in the plane of the first three
    /// toward the third, z = x cross y (three or more markers, not on one line).
    InFrame(Vector3),
}

/// The wand's tip from its markers' positions (any frame, m).
pub fn pointer_tip(markers: &[Vector3], tip: &TipOffset) -> Result<Vector3, CalibrationError> {
    match tip {
        TipOffset::Along(d) => {
            let [first, .., last] = markers else {
                return Err(CalibrationError::TooFew {
                    what: "a pointer with its tip on its axis",
                    need: 2,
                    got: markers.len(),
                });
            };
            let axis = first - last;
            if axis.norm() < 0.02 {
                return Err(CalibrationError::Geometry(
                    "the pointer's first and last markers are under 2 cm apart".into(),
                ));
            }
            Ok(first + axis.normalize() * *d)
        }
        TipOffset::InFrame(offset) => {
            let [o, a, b, ..] = markers else {
                return Err(CalibrationError::TooFew {
                    what: "a pointer with its tip in its frame",
                    need: 3,
                    got: markers.len(),
                });
            };
            let x = a - o;
            let y = (b - o) - x.normalize() * (b - o).dot(&x.normalize());
            if x.norm() < 0.02 || y.norm() < 0.01 {
                return Err(CalibrationError::Geometry(
                    "the pointer's first three markers are too near one line to give its frame (the third must sit \
                     at least 1 cm off the line of the first two)"
                        .into(),
                ));
            }
            let (x, y) = (x.normalize(), y.normalize());
            Ok(o + x * offset.x + y * offset.y + x.cross(&y) * offset.z)
        }
    }
}

/// The three touches of the pointer's tip, in the club body's frame (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Touches {
    /// The touch at the face centre.
    pub centre_m: Vector3,
    /// The touch at the leading edge's heel end.
    pub heel_m: Vector3,
    /// The touch at the leading edge's toe end.
    pub toe_m: Vector3,
}

/// The face located in the club body's frame: its centre, its outward normal and its toe axis (unit vectors).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceInBody {
    /// The face centre (m).
    pub centre_m: Vector3,
    /// The face's outward normal at the centre (unit): the club file's `n0`, seen in the body frame.
    pub normal: Vector3,
    /// The toe axis (unit, across the normal): the club file's `t0`, seen in the body frame.
    pub toe: Vector3,
}

/// The face from the pointer's touches: the toe axis along the leading edge, up-the-face from the leading edge
/// toward the centre, the normal `n = u x t`. The touched edge points are brought forward onto the plane tangent
/// at the centre by their depth behind it on the club file's face (none for a flat face), and the frame refound,
/// a few times over.
pub fn face_from_touches(touches: &Touches, face: &Face) -> Result<FaceInBody, CalibrationError> {
    let heel = touches.heel_m - touches.centre_m;
    let toe = touches.toe_m - touches.centre_m;
    if (toe - heel).norm() < 0.03 {
        return Err(CalibrationError::Geometry(format!(
            "the leading edge's heel and toe touches are {:.0} mm apart: touch its two ends (at least 3 cm apart)",
            (toe - heel).norm() * 1e3
        )));
    }
    let (mut h_plane, mut t_plane) = (heel, toe);
    let mut frame = (Vector3::zeros(), Vector3::zeros(), Vector3::zeros());
    for _ in 0..4 {
        let t = (t_plane - h_plane).normalize();
        // From the leading-edge line up to the centre (the centre is the origin here).
        let foot = h_plane - t * h_plane.dot(&t);
        if foot.norm() < 0.005 {
            return Err(CalibrationError::Geometry(format!(
                "the face-centre touch is {:.1} mm from the leading edge's line: touch the face's centre and the \
                 leading edge's ends",
                foot.norm() * 1e3
            )));
        }
        let u = -foot.normalize();
        let n = u.cross(&t);
        frame = (n, u, t);
        // Each edge touch's depth behind the tangent plane at its place on the face, added back along n.
        let depth = |p: &Vector3| -> Result<Real, CalibrationError> {
            let c = face.contact(p.dot(&t), p.dot(&u)).map_err(|e| {
                CalibrationError::Geometry(format!("a leading-edge touch is off the club file's face: {e}"))
            })?;
            Ok(-(c.point_m - face.center_m).dot(&face.n0()))
        };
        h_plane = heel + n * depth(&heel)?;
        t_plane = toe + n * depth(&toe)?;
    }
    let (normal, _, toe_axis) = frame;
    Ok(FaceInBody { centre_m: touches.centre_m, normal, toe: toe_axis })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::ClubSpec;
    use crate::math::{Isometry3, Point3};

    #[test]
    fn touches_on_a_curved_face_give_its_centre_frame() {
        for club in [ClubSpec::driver(), ClubSpec::iron7()] {
            let body_from_club = Isometry3::new(Vector3::new(0.02, -0.05, 0.01), Vector3::new(0.3, -0.7, 0.2));
            let at =
                |h: Real, v: Real| (body_from_club * Point3::from(club.face.contact(h, v).unwrap().point_m)).coords;
            // Edge touches unevenly either side, both 25 mm below the centre (the leading edge along the toe axis).
            let touches = Touches { centre_m: at(0.0, 0.0), heel_m: at(-0.035, -0.025), toe_m: at(0.045, -0.025) };
            let face = face_from_touches(&touches, &club.face).unwrap();
            let n = body_from_club.rotation * club.face.n0();
            let t = body_from_club.rotation * club.face.t0();
            let (dn, dt) = (face.normal.angle(&n).to_degrees(), face.toe.angle(&t).to_degrees());
            assert!(dn < 0.01 && dt < 0.01, "{}: normal {dn} deg, toe {dt} deg off", club.name);
        }
    }

    #[test]
    fn a_tip_along_the_wand_and_in_its_frame() {
        let m = [Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 0.0, 0.1), Vector3::new(0.05, 0.0, 0.2)];
        let along = pointer_tip(&[m[0], m[1]], &TipOffset::Along(0.12)).unwrap();
        assert!((along - Vector3::new(0.0, 0.0, -0.12)).norm() < 1e-12);
        let framed = pointer_tip(&m, &TipOffset::InFrame(Vector3::new(-0.12, 0.0, 0.01))).unwrap();
        // x = +z, y = +x, z = x cross y = +y.
        assert!((framed - Vector3::new(0.0, 0.01, -0.12)).norm() < 1e-12, "{framed}");
    }
}
