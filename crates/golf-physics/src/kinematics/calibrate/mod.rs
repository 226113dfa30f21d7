//! Calibration from static trials: a marker set from where its markers sit (`body_set`), the lab frame in the
//! world from markers on the floor and the target line or a stated target axis ([`lab`]), and the tracked body
//! in the club frame from the club at address: the face located by face markers, by a pointer's touches
//! ([`pointer`]), by a marker set that states it, or assumed soled square ([`club`]); shaft markers give the
//! address shaft lean and lie ([`shaft`]). Marker positions come in averaged over a trial's frames and checked
//! still ([`static_check`]) (lab frame, m).
//!
//! The world frame (ARCHITECTURE.md section 2) has its origin at the resting ball's centre, x toward the target, y
//! up, z right of the target line. The club frame at a square address has the world's axes; its face normal is
//! `n0 = (cos L, sin L, 0)`, up-the-face `u0 = (-sin L, cos L, 0)`, toe `t0 = (0, 0, 1)` for static loft L.

pub mod club;
pub mod lab;
pub mod plane;
pub mod pointer;
pub mod shaft;
pub mod static_check;

pub use club::{
    club_from_face, club_from_face_in_body, club_from_touches, club_soled_square, ClubCalibration, FaceFrom,
    FaceMarkers,
};
pub use lab::{world_from_lab, BallAt, LabCalibration, LabMarkers, Target, UpFrom};
pub use plane::{fit_plane, PlaneFit};
pub use pointer::{pointer_tip, FaceInBody, TipOffset, Touches};
pub use shaft::{shaft_reading, ShaftReading};
pub use static_check::{static_markers, StaticMarker, DEFAULT_STATIC_LIMIT_M};

use crate::math::{Real, Vector3};

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
    /// A marker of a static trial moved more than the limit over the frames averaged.
    #[error(
        "the trial is not static: marker `{label}` moved {moved_mm:.1} mm from its mean position (at frame \
         {frame}) over the {frames} frames averaged, more than the {limit_mm:.1} mm a static trial allows \
         (choose still frames with --frame/--frames, or widen the limit with --static-mm)"
    )]
    NotStatic { label: String, moved_mm: Real, frame: u64, frames: usize, limit_mm: Real },
    /// A marker asked for is valid in none of the frames averaged.
    #[error("marker `{0}` is not valid in any of the frames asked for")]
    NeverSeen(String),
    /// Floor markers too near one line to give the floor's tilt.
    #[error(
        "the floor markers are nearly on one line: they spread {spread_mm:.1} mm (RMS) across their best-fit line, \
         under the {min_mm:.0} mm that gives the floor's tilt: add floor markers away from that line (a triangle \
         at least 20 cm on a side)"
    )]
    FloorCollinear { spread_mm: Real, min_mm: Real },
    /// A floor marker off the floor's plane.
    #[error(
        "floor marker `{label}` is {off_mm:.1} mm off the plane of the floor markers (at most {max_mm:.0} mm): it \
         is not on the floor (a foot, a mat's edge?); leave it out of --floor"
    )]
    FloorNotFlat { label: String, off_mm: Real, max_mm: Real },
    /// A stated up axis that the capture contradicts.
    #[error(
        "--lab-up {stated} disagrees with the capture: the floor's normal on the side {evidence} is ({:.3}, \
         {:.3}, {:.3}) in the lab, nearest {nearest}, {angle_deg:.0} deg from the stated {stated}: give --lab-up \
         {nearest} or leave it out",
        measured.x, measured.y, measured.z
    )]
    LabUpDisagrees { stated: String, nearest: String, measured: Vector3, angle_deg: Real, evidence: String },
}

/// The name of the lab axis nearest `v` (`+x`, `-y`, ...) and the angle to it (deg).
pub fn nearest_axis(v: &Vector3) -> (String, Real) {
    let mut best = (String::new(), Real::INFINITY);
    for (i, name) in ["x", "y", "z"].iter().enumerate() {
        for sign in [1.0, -1.0] {
            let mut axis = Vector3::zeros();
            axis[i] = sign;
            let angle = v.normalize().dot(&axis).clamp(-1.0, 1.0).acos().to_degrees();
            if angle < best.1 {
                best = (format!("{}{name}", if sign > 0.0 { "+" } else { "-" }), angle);
            }
        }
    }
    best
}

/// A marker set whose body frame has its origin at the markers' centroid and the lab's axes.
pub fn body_set(markers: &[(String, Vector3)]) -> Result<MarkerSet, CalibrationError> {
    let n = markers.len().max(1) as Real;
    let centroid = markers.iter().map(|(_, p)| p).sum::<Vector3>() / n;
    Ok(MarkerSet::new(markers.iter().map(|(l, p)| (l.clone(), p - centroid)))?)
}
