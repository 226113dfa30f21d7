//! Calibration from static trials: a marker set from where its markers sit (`body`), the lab frame in the world
//! from markers on the target line and the floor (`lab`), and the tracked body in the club frame from the club
//! at address (`club`). Marker positions come in already averaged over the trial's frames (lab frame, m).
//!
//! The world frame (ARCHITECTURE.md section 2) has its origin at the resting ball's centre, x toward the target, y up,
//! z right of the target line. The club frame at a square address has the world's axes; its face normal is
//! `n0 = (cos L, sin L, 0)`, up-the-face `u0 = (-sin L, cos L, 0)`, toe `t0 = (0, 0, 1)` for static loft L.

use crate::equipment::ClubSpec;
use crate::math::{Isometry3, Matrix3, Real, Rotation3, Translation3, UnitQuaternion, Vector3};

use super::marker_set::{MarkerSet, MarkerSetError};

/// Why a calibration could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CalibrationError {
    #[error("{0}")]
    MarkerSet(#[from] MarkerSetError),
    #[error("{what} needs at least {need} markers, got {got}")]
    TooFew { what: &'static str, need: usize, got: usize },
    #[error("{0}")]
    Geometry(String),
}

/// A marker set whose body frame has its origin at the markers' centroid and the lab's axes.
pub fn body_set(markers: &[(String, Vector3)]) -> Result<MarkerSet, CalibrationError> {
    let n = markers.len().max(1) as Real;
    let centroid = markers.iter().map(|(_, p)| p).sum::<Vector3>() / n;
    Ok(MarkerSet::new(markers.iter().map(|(l, p)| (l.clone(), p - centroid)))?)
}

/// The floor or face plane through marker centres: (centroid, unit normal), the normal the one with a
/// positive component along `hint`.
pub fn plane(points: &[Vector3], hint: &Vector3, what: &'static str) -> Result<(Vector3, Vector3), CalibrationError> {
    if points.len() < 3 {
        return Err(CalibrationError::TooFew { what, need: 3, got: points.len() });
    }
    let centroid = points.iter().sum::<Vector3>() / points.len() as Real;
    let mut cov = Matrix3::zeros();
    for p in points {
        cov += (p - centroid) * (p - centroid).transpose();
    }
    let eigen = crate::math::SymmetricEigen::new(cov);
    let mut order = [0, 1, 2];
    order.sort_by(|a, b| eigen.eigenvalues[*a].total_cmp(&eigen.eigenvalues[*b]));
    // The two larger spreads must be real: markers on one line leave the plane's tilt open.
    if eigen.eigenvalues[order[1]].max(0.0).sqrt() < 1e-3 {
        return Err(CalibrationError::Geometry(format!("the {what} markers lie on one line: they give no plane")));
    }
    let mut normal: Vector3 = eigen.eigenvectors.column(order[0]).into_owned();
    if normal.dot(hint) < 0.0 {
        normal = -normal;
    }
    Ok((centroid, normal.normalize()))
}

/// Where the ball is in a lab calibration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BallAt {
    /// A marker whose centre is the ball's centre (a ball covered in retro-reflective tape).
    Marker(Vector3),
    /// On the floor where the rear target-line marker stands.
    RearMarker,
}

/// The markers of a lab calibration (lab frame, m, marker centres).
#[derive(Debug, Clone, PartialEq)]
pub struct LabMarkers {
    /// On the target line: the one nearer the golfer, and the one toward the target.
    pub rear_m: Vector3,
    pub front_m: Vector3,
    /// On the floor (at least 3, not on one line; may include the target-line markers).
    pub floor_m: Vec<Vector3>,
    /// The lab's approximate up direction (the floor normal's sign).
    pub lab_up: Vector3,
    pub ball: BallAt,
    pub marker_radius_m: Real,
    pub ball_radius_m: Real,
}

/// `world_from_lab`: y along the floor's normal, x along the target line in the floor, origin at the ball.
pub fn world_from_lab(m: &LabMarkers) -> Result<Isometry3, CalibrationError> {
    let (floor_centroid, up) = plane(&m.floor_m, &m.lab_up, "floor")?;
    let along = m.front_m - m.rear_m;
    let x = along - up * along.dot(&up);
    if x.norm() < 0.05 {
        return Err(CalibrationError::Geometry(format!(
            "the target-line markers are {:.1} mm apart along the floor: put them at least 5 cm apart",
            x.norm() * 1e3
        )));
    }
    let x = x.normalize();
    let z = x.cross(&up);
    let ball_m = match m.ball {
        BallAt::Marker(p) => p,
        BallAt::RearMarker => {
            // The floor is the plane of the marker centres lowered by a marker radius; the ball rests on it.
            let above_plane = (m.rear_m - floor_centroid).dot(&up);
            m.rear_m - up * (above_plane + m.marker_radius_m) + up * m.ball_radius_m
        }
    };
    // Rows: the world axes in lab coordinates, so R p_lab gives world components.
    let rotation =
        Rotation3::from_matrix_unchecked(Matrix3::from_rows(&[x.transpose(), up.transpose(), z.transpose()]));
    let rotation = UnitQuaternion::from_rotation_matrix(&rotation);
    Ok(Isometry3::from_parts(Translation3::from(-(rotation * ball_m)), rotation))
}

/// Face markers of a club calibration (lab frame, m, marker centres, stuck on the face).
#[derive(Debug, Clone, PartialEq)]
pub struct FaceMarkers {
    /// Along a score line: the heel end and the toe end.
    pub heel_m: Vector3,
    pub toe_m: Vector3,
    /// Further markers on the face (at least one, off the heel-toe line).
    pub others_m: Vec<Vector3>,
    /// A marker on the face centre; without one, the face markers' centroid is taken as the face centre.
    pub centre_m: Option<Vector3>,
    pub marker_radius_m: Real,
}

/// What a club calibration found, in the body frame and against the club file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClubCalibration {
    pub club_from_body: Isometry3,
    pub face_centre_body_m: Vector3,
    pub face_normal_body: Vector3,
    /// The face's loft and lie as measured at address (world frame), and their residuals against the club
    /// file's loft and its lie (the toe axis level at the specified lie).
    pub loft_deg: Real,
    pub loft_residual_deg: Real,
    pub lie_residual_deg: Real,
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
    let loft = club.face.loft_rad;
    let n0 = Vector3::new(loft.cos(), loft.sin(), 0.0);
    let face_centre_world = ball_position_m - n0 * ball_radius_m;
    let world_from_club =
        Isometry3::from_parts(Translation3::from(face_centre_world - club.face.center_m), UnitQuaternion::identity());
    let club_from_body = world_from_club.inverse() * world_from_lab * lab_from_body;
    report(club_from_body, world_from_lab * lab_from_body, club)
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
    let (_, n) = plane(&points, &(centroid - lab_from_body.translation.vector), "face")?;
    let heel_toe = face.toe_m - face.heel_m;
    let t = heel_toe - n * heel_toe.dot(&n);
    if t.norm() < 0.02 {
        return Err(CalibrationError::Geometry("the heel and toe face markers are under 2 cm apart".into()));
    }
    let t = t.normalize();
    let u = t.cross(&n);
    let loft = club.face.loft_rad;
    let (n0, u0, t0) =
        (Vector3::new(loft.cos(), loft.sin(), 0.0), Vector3::new(-loft.sin(), loft.cos(), 0.0), Vector3::z());
    let measured = Matrix3::from_columns(&[n, u, t]);
    let design = Matrix3::from_columns(&[n0, u0, t0]);
    // Both triads are orthonormal, so their product is a rotation as it stands.
    let rotation =
        UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(measured * design.transpose()));
    // Stickers: their centres sit a marker radius off the face.
    let centre = face.centre_m.unwrap_or(centroid) - n * face.marker_radius_m;
    let lab_from_club = Isometry3::from_parts(Translation3::from(centre - rotation * club.face.center_m), rotation);
    let club_from_body = lab_from_club.inverse() * lab_from_body;
    Ok(report(club_from_body, world_from_lab * lab_from_body, club))
}

fn report(club_from_body: Isometry3, world_from_body: Isometry3, club: &ClubSpec) -> ClubCalibration {
    let world_from_club = world_from_body * club_from_body.inverse();
    let loft = club.face.loft_rad;
    let n = world_from_club.rotation * Vector3::new(loft.cos(), loft.sin(), 0.0);
    let t = world_from_club.rotation * Vector3::z();
    let loft_deg = n.y.clamp(-1.0, 1.0).asin().to_degrees();
    ClubCalibration {
        club_from_body,
        face_centre_body_m: club_from_body.inverse_transform_point(&club.face.center_m.into()).coords,
        face_normal_body: club_from_body.inverse_transform_vector(&Vector3::new(loft.cos(), loft.sin(), 0.0)),
        loft_deg,
        loft_residual_deg: loft_deg - club.loft_deg(),
        // The toe rises at a flatter-than-specified lie (toe up), positive here.
        lie_residual_deg: t.y.clamp(-1.0, 1.0).asin().to_degrees(),
        face_angle_deg: n.z.atan2(n.x).to_degrees(),
    }
}
