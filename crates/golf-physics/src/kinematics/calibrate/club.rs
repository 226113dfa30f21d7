//! `club_from_body` from the club at address: the face located by face markers, by a pointer's touches or by a
//! marker set that states it, or else assumed soled square behind the ball (reported as an assumption). Each
//! gives the face's centre, normal and toe axis in the body frame; the club file's loft turns that triad into
//! the club frame's axes and its CG offset places the frame's origin.

use crate::equipment::ClubSpec;
use crate::math::{Isometry3, Matrix3, Real, Rotation3, Translation3, UnitQuaternion, Vector3};

use super::pointer::{face_from_touches, FaceInBody, Touches};
use super::{fit_plane, CalibrationError};

/// Face markers of a club calibration (lab frame, m, marker centres, stuck on the face).
#[derive(Debug, Clone, PartialEq)]
pub struct FaceMarkers {
    /// The marker at the heel end of a score line.
    pub heel_m: Vector3,
    /// The marker at the toe end of the same score line.
    pub toe_m: Vector3,
    /// Further markers on the face (at least one, off the heel-toe line).
    pub others_m: Vec<Vector3>,
    /// A marker on the face centre; without one, the face markers' centroid is taken as the face centre.
    pub centre_m: Option<Vector3>,
    /// The markers' radius (m): their centres sit this far off the face along its normal.
    pub marker_radius_m: Real,
}

/// How the face was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaceFrom {
    /// Not measured: the club taken as soled square behind the ball at the club file's loft and lie.
    Assumed,
    /// Face markers.
    Markers,
    /// A pointer's touches.
    Pointer,
    /// The marker set's `[face]`; `toe_measured` when shaft markers fixed its turn about the normal, else the toe
    /// was taken as level at address (the club file's lie).
    MarkerSet {
        /// Shaft markers fixed the face's turn about its normal.
        toe_measured: bool,
    },
}

/// What a club calibration found, in the body frame and at address in the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClubCalibration {
    /// The tracked body's pose in the club frame (origin at the head's CG; m): the rig's calibration.
    pub club_from_body: Isometry3,
    /// The club file's face centre in the body frame (m).
    pub face_centre_body_m: Vector3,
    /// The club file's face normal `n0` in the body frame (unit).
    pub face_normal_body: Vector3,
    /// How the face was found.
    pub face: FaceFrom,
    /// At address (world frame): the face normal's elevation (loft), the toe axis's elevation (toe up +, 0 at the
    /// club file's lie) and the face normal's heading right of the target line (face angle, + toward +z). Measured when
    /// the face is; the assumption's own values (the club file's loft, 0, 0) when it is assumed.
    pub loft_deg: Real,
    /// The toe axis's elevation at address (deg, toe up +; see `loft_deg`).
    pub toe_up_deg: Real,
    /// The face normal's heading right of the target line at address (deg, + toward +z; see `loft_deg`).
    pub face_angle_deg: Real,
}

/// From the club soled square behind the ball at its specified lie, the face centre against the ball: the club
/// frame is the world's axes there and the face centre is a ball radius behind the ball's centre along `n0`.
pub fn club_soled_square(
    lab_from_body: &Isometry3,
    world_from_lab: &Isometry3,
    club: &ClubSpec,
    ball_position_m: &Vector3,
    ball_radius_m: Real,
) -> ClubCalibration {
    let n0 = club.face.n0();
    let face_centre_world = ball_position_m - n0 * ball_radius_m;
    let world_from_club =
        Isometry3::from_parts(Translation3::from(face_centre_world - club.face.center_m), UnitQuaternion::identity());
    let club_from_body = world_from_club.inverse() * world_from_lab * lab_from_body;
    report(club_from_body, world_from_lab * lab_from_body, club, FaceFrom::Assumed)
}

/// From face markers: the face plane gives the normal, the heel-to-toe line the toe axis, the club file's loft
/// the rest of the club's orientation; the face centre and the club file's CG offset give its position.
pub fn club_from_face(
    lab_from_body: &Isometry3,
    world_from_lab: &Isometry3,
    face: &FaceMarkers,
    club: &ClubSpec,
) -> Result<ClubCalibration, CalibrationError> {
    let mut points = vec![face.heel_m, face.toe_m];
    points.extend_from_slice(&face.others_m);
    let centroid = points.iter().sum::<Vector3>() / points.len() as Real;
    // The face looks away from the marker cluster on the head (the body's origin sits behind the face).
    let n = fit_plane(&points, "face")?.normal_toward(&(centroid - lab_from_body.translation.vector));
    let heel_toe = face.toe_m - face.heel_m;
    let t = heel_toe - n * heel_toe.dot(&n);
    if t.norm() < 0.02 {
        return Err(CalibrationError::Geometry("the heel and toe face markers are under 2 cm apart".into()));
    }
    // Stickers: their centres sit a marker radius off the face.
    let centre = face.centre_m.unwrap_or(centroid) - n * face.marker_radius_m;
    let body_from_lab = lab_from_body.inverse();
    let in_body = FaceInBody {
        centre_m: (body_from_lab * crate::math::Point3::from(centre)).coords,
        normal: body_from_lab.rotation * n,
        toe: body_from_lab.rotation * t.normalize(),
    };
    Ok(from_face(&in_body, world_from_lab * lab_from_body, club, FaceFrom::Markers))
}

/// From a pointer's three touches (body frame): [`face_from_touches`].
pub fn club_from_touches(
    touches: &Touches,
    world_from_body: Isometry3,
    club: &ClubSpec,
) -> Result<ClubCalibration, CalibrationError> {
    let face = face_from_touches(touches, &club.face)?;
    Ok(from_face(&face, world_from_body, club, FaceFrom::Pointer))
}

/// From a face stated in the body frame (centre, outward normal): its turn about the normal from the shaft's
/// direction in the body frame (the club file's lie puts the shaft at `(0, sin lie, -cos lie)` in the club frame),
/// or, without one, with the toe level at address.
pub fn club_from_face_in_body(
    centre_m: &Vector3,
    normal: &Vector3,
    shaft_up_body: Option<&Vector3>,
    world_from_body: Isometry3,
    club: &ClubSpec,
) -> Result<ClubCalibration, CalibrationError> {
    let n = normal.normalize();
    let (toe, toe_measured) = match shaft_up_body {
        Some(s) => {
            // The toe axis in the club frame, from n0 and the shaft's part across it; then the same in the body.
            let (n0, s0, t0) = (club.face.n0(), club.shaft_axis_up(), club.face.t0());
            let across = |s: &Vector3, n: &Vector3| (s - n * s.dot(n)).normalize();
            let (a0, a) = (across(&s0, &n0), across(s, &n));
            // t0 in the basis (n0, a0, n0 x a0), carried to (n, a, n x a).
            let t = n * t0.dot(&n0) + a * t0.dot(&a0) + n.cross(&a) * t0.dot(&n0.cross(&a0));
            (t, true)
        }
        None => {
            let n_world = world_from_body.rotation * n;
            let t_world = n_world.cross(&Vector3::y());
            if t_world.norm() < 0.1 {
                return Err(CalibrationError::Geometry(
                    "the stated face normal points nearly straight up at address: give --shaft to fix the toe axis"
                        .into(),
                ));
            }
            (world_from_body.inverse_transform_vector(&t_world.normalize()), false)
        }
    };
    let face = FaceInBody { centre_m: *centre_m, normal: n, toe: (toe - n * toe.dot(&n)).normalize() };
    Ok(from_face(&face, world_from_body, club, FaceFrom::MarkerSet { toe_measured }))
}

/// `club_from_body` from the face's triad in the body frame: the measured (n, u, t) are the club file's
/// (n0, u0, t0), and the face centre is the club file's `face.center_m`.
fn from_face(face: &FaceInBody, world_from_body: Isometry3, club: &ClubSpec, from: FaceFrom) -> ClubCalibration {
    let (n, t) = (face.normal, face.toe);
    let u = t.cross(&n);
    let measured = Matrix3::from_columns(&[n, u, t]);
    let design = Matrix3::from_columns(&[club.face.n0(), club.face.u0(), club.face.t0()]);
    // Both triads are orthonormal, so their product is a rotation as it stands.
    let rotation =
        UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(design * measured.transpose()));
    let translation = club.face.center_m - rotation * face.centre_m;
    report(Isometry3::from_parts(Translation3::from(translation), rotation), world_from_body, club, from)
}

fn report(club_from_body: Isometry3, world_from_body: Isometry3, club: &ClubSpec, face: FaceFrom) -> ClubCalibration {
    let world_from_club = world_from_body * club_from_body.inverse();
    let n = world_from_club.rotation * club.face.n0();
    let t = world_from_club.rotation * club.face.t0();
    ClubCalibration {
        club_from_body,
        face_centre_body_m: club_from_body.inverse_transform_point(&club.face.center_m.into()).coords,
        face_normal_body: club_from_body.inverse_transform_vector(&club.face.n0()),
        face,
        loft_deg: n.y.clamp(-1.0, 1.0).asin().to_degrees(),
        // The toe rises at a flatter-than-specified lie (toe up), positive here.
        toe_up_deg: t.y.clamp(-1.0, 1.0).asin().to_degrees(),
        face_angle_deg: n.z.atan2(n.x).to_degrees(),
    }
}
