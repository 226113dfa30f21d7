//! `world_from_lab` from a static trial: the floor's plane gives the up axis (on the side the other markers
//! stand, or a stated side that the capture must not contradict), the target line or a stated lab axis the
//! target direction, and the ball's centre the origin.

use crate::math::{Isometry3, Matrix3, Real, Rotation3, Translation3, UnitQuaternion, Vector3};

use super::{fit_plane, nearest_axis, CalibrationError};

/// The floor markers must spread at least this far (RMS) across their best-fit line (m): at 0.2 mm of noise or
/// unevenness, 50 mm leaves the floor's tilt uncertain by at most about 0.2 deg from one frame of three markers.
pub const MIN_FLOOR_SPREAD_M: Real = 0.05;
/// A floor marker further than this from the floor markers' plane is not on the floor (m).
pub const MAX_FLOOR_OFF_M: Real = 0.01;
/// A marker further than this from the floor stands on one side of it and tells which side is up (m).
pub const OFF_FLOOR_M: Real = 0.02;
/// A stated up axis further than this from the capture's up (deg) disagrees with it.
pub const MAX_UP_DISAGREEMENT_DEG: Real = 45.0;
/// The ball's centre at rest or on a tee sits this far above the floor at most (m).
pub const MAX_BALL_HEIGHT_M: Real = 0.15;

/// Where the target is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// Two markers on the target line: the one nearer the golfer, and the one toward the target.
    Line {
        /// The marker nearer the golfer (lab, m).
        rear_m: Vector3,
        /// The marker toward the target (lab, m).
        front_m: Vector3,
    },
    /// A lab axis (unit vector) toward the target, laid into the floor.
    Axis(Vector3),
}

/// Where the ball is in a lab calibration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BallAt {
    /// The ball's centre at this lab point (a taped-ball marker, a static ball trial, or stated).
    Centre(Vector3),
    /// On the floor where the rear target-line marker stands.
    RearMarker,
}

/// The markers of a lab calibration (lab frame, m, marker centres).
#[derive(Debug, Clone, PartialEq)]
pub struct LabMarkers {
    /// Where the target is.
    pub target: Target,
    /// On the floor (at least 3, spread off one line; may include the target-line markers), with their labels.
    pub floor: Vec<(String, Vector3)>,
    /// Every other marker of the trial (the club's, the ball's, ...): those off the floor tell its up side.
    pub others: Vec<(String, Vector3)>,
    /// The stated up axis, if any: a check on the capture, or the side when no marker stands off the floor.
    pub lab_up: Option<Vector3>,
    /// Where the ball is: the world's origin.
    pub ball: BallAt,
    /// The markers' radius (m): the floor lies this far below the plane of the floor markers' centres.
    pub marker_radius_m: Real,
    /// The ball's radius (m): its centre's height above the floor for [`BallAt::RearMarker`].
    pub ball_radius_m: Real,
}

/// How the up side of the floor was found.
#[derive(Debug, Clone, PartialEq)]
pub enum UpFrom {
    /// From `count` markers off the floor, all on one side; `highest` is the furthest (label, m).
    Markers {
        /// The markers off the floor on its up side (more than [`OFF_FLOOR_M`] from its plane).
        count: usize,
        /// The one furthest from the floor markers' plane: its label and that distance (m).
        highest: (String, Real),
    },
    /// From the stated axis: no marker stood off the floor to say.
    Stated,
}

/// What a lab calibration found.
#[derive(Debug, Clone, PartialEq)]
pub struct LabCalibration {
    /// The lab frame's pose in the world: y up the floor's normal, x toward the target, origin at the ball's centre.
    pub world_from_lab: Isometry3,
    /// The up axis (the floor's normal) in the lab.
    pub up_lab: Vector3,
    /// How the up side of the floor was found.
    pub up_from: UpFrom,
    /// The floor markers' spread across their best-fit line (RMS, m).
    pub floor_spread_m: Real,
    /// The floor markers' largest distance off their plane (m).
    pub floor_off_max_m: Real,
    /// The ball's centre above the floor (m).
    pub ball_height_m: Real,
}

/// `world_from_lab`: y along the floor's normal, x toward the target in the floor, origin at the ball.
pub fn world_from_lab(m: &LabMarkers) -> Result<LabCalibration, CalibrationError> {
    let points: Vec<Vector3> = m.floor.iter().map(|(_, p)| *p).collect();
    let fit = fit_plane(&points, "floor")?;
    if fit.line_spread_m < MIN_FLOOR_SPREAD_M {
        return Err(CalibrationError::FloorCollinear {
            spread_mm: fit.line_spread_m * 1e3,
            min_mm: MIN_FLOOR_SPREAD_M * 1e3,
        });
    }
    let (worst, off) =
        fit.off_plane_m.iter().enumerate().fold((0, 0.0), |b, (i, d)| if d.abs() > b.1 { (i, d.abs()) } else { b });
    if off > MAX_FLOOR_OFF_M {
        return Err(CalibrationError::FloorNotFlat {
            label: m.floor[worst].0.clone(),
            off_mm: off * 1e3,
            max_mm: MAX_FLOOR_OFF_M * 1e3,
        });
    }
    let (up, up_from) = up_side(m, &fit.centroid, &fit.normal)?;
    let along = match m.target {
        Target::Line { rear_m, front_m } => {
            let along = front_m - rear_m;
            let x = along - up * along.dot(&up);
            if x.norm() < 0.05 {
                return Err(CalibrationError::Geometry(format!(
                    "the target-line markers are {:.1} mm apart along the floor: put them at least 5 cm apart",
                    x.norm() * 1e3
                )));
            }
            x
        }
        Target::Axis(a) => {
            let x = a - up * a.dot(&up);
            if x.norm() < 0.5 {
                return Err(CalibrationError::Geometry(format!(
                    "the target axis is {:.0} deg from the floor's normal: it must lie near the floor (a lab axis \
                     across the floor, not the up axis)",
                    a.normalize().dot(&up).clamp(-1.0, 1.0).acos().to_degrees()
                )));
            }
            x
        }
    };
    let x = along.normalize();
    let z = x.cross(&up);
    // The floor is the plane of the marker centres lowered by a marker radius.
    let floor_at = |p: &Vector3| (p - fit.centroid).dot(&up) + m.marker_radius_m;
    let ball_m =
        match (m.ball, m.target) {
            (BallAt::Centre(p), _) => p,
            (BallAt::RearMarker, Target::Line { rear_m, .. }) => rear_m - up * floor_at(&rear_m) + up * m.ball_radius_m,
            (BallAt::RearMarker, Target::Axis(_)) => return Err(CalibrationError::Geometry(
                "no ball: with a target axis and no target-line markers, give a ball marker, a static ball trial or \
                 the ball's position"
                    .into(),
            )),
        };
    let ball_height_m = floor_at(&ball_m);
    if !(-0.005..=MAX_BALL_HEIGHT_M).contains(&ball_height_m) {
        return Err(CalibrationError::Geometry(format!(
            "the ball's centre is {:.1} mm above the floor: a ball at rest or on a tee is {:.0}-{:.0} mm above it \
             (are its coordinates in the lab's axes, in the units asked for?)",
            ball_height_m * 1e3,
            m.ball_radius_m * 1e3,
            MAX_BALL_HEIGHT_M * 1e3
        )));
    }
    // Rows: the world axes in lab coordinates, so R p_lab gives world components.
    let rotation =
        Rotation3::from_matrix_unchecked(Matrix3::from_rows(&[x.transpose(), up.transpose(), z.transpose()]));
    let rotation = UnitQuaternion::from_rotation_matrix(&rotation);
    Ok(LabCalibration {
        world_from_lab: Isometry3::from_parts(Translation3::from(-(rotation * ball_m)), rotation),
        up_lab: up,
        up_from,
        floor_spread_m: fit.line_spread_m,
        floor_off_max_m: off,
        ball_height_m,
    })
}

/// The floor's normal on its up side: where the markers off the floor stand, checked against a stated axis; or
/// the stated axis's side when none stands off it.
fn up_side(m: &LabMarkers, centroid: &Vector3, normal: &Vector3) -> Result<(Vector3, UpFrom), CalibrationError> {
    let off: Vec<(&String, Real)> =
        m.others.iter().map(|(l, p)| (l, (p - centroid).dot(normal))).filter(|(_, d)| d.abs() > OFF_FLOOR_M).collect();
    let above = off.iter().filter(|(_, d)| *d > 0.0).count();
    let below = off.len() - above;
    let stated_name = |v: &Vector3| nearest_axis(v).0;
    let (up, up_from, evidence) = if off.is_empty() {
        let Some(stated) = m.lab_up else {
            return Err(CalibrationError::Geometry(format!(
                "no marker stands more than {:.0} mm off the floor to tell which side of it is up: give --lab-up",
                OFF_FLOOR_M * 1e3
            )));
        };
        let up = if normal.dot(&stated) < 0.0 { -normal } else { *normal };
        (up, UpFrom::Stated, "of the stated axis".to_string())
    } else {
        if above == below {
            return Err(CalibrationError::Geometry(format!(
                "{above} markers stand on each side of the floor: its up side is unclear (a ghost below the floor?): \
                 give --lab-up"
            )));
        }
        let sign = if above > below { 1.0 } else { -1.0 };
        let up = normal * sign;
        let mine: Vec<&(&String, Real)> = off.iter().filter(|(_, d)| d * sign > 0.0).collect();
        let highest =
            mine.iter().fold((String::new(), 0.0), |b, (l, d)| if d.abs() > b.1 { ((*l).clone(), d.abs()) } else { b });
        let evidence = format!(
            "where {} of the {} markers off it stand (`{}` {:.0} mm from it)",
            mine.len(),
            off.len(),
            highest.0,
            highest.1 * 1e3
        );
        (up, UpFrom::Markers { count: mine.len(), highest }, evidence)
    };
    if let Some(stated) = m.lab_up {
        let angle_deg = stated.normalize().dot(&up).clamp(-1.0, 1.0).acos().to_degrees();
        if angle_deg > MAX_UP_DISAGREEMENT_DEG {
            let (nearest, _) = nearest_axis(&up);
            return Err(CalibrationError::LabUpDisagrees {
                stated: stated_name(&stated).trim_start_matches('+').to_string(),
                nearest: nearest.trim_start_matches('+').to_string(),
                measured: up,
                angle_deg,
                evidence,
            });
        }
    }
    Ok((up, up_from))
}
