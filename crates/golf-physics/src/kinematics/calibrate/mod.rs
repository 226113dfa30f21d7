//! Calibration from static trials: a marker set from where its markers sit (`body_set`), the lab frame in the
//! world from markers on the floor and the target line or a stated target axis ([`lab`]), and the tracked body
//! in the club frame from the club at address: the face located by face markers, by a pointer's touches
//! ([`pointer`](mod@pointer)), by a marker set that states it, or assumed soled square ([`club`]); shaft markers
//! give the address shaft lean and lie ([`shaft`]). Marker positions come in averaged over a trial's frames and
//! checked still ([`static_check`]) (lab frame, m).
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
    /// The markers given do not make a marker set.
    #[error("{0}")]
    MarkerSet(#[from] MarkerSetError),
    /// Too few markers for one step of the calibration.
    #[error("{what} needs at least {need} markers, got {got}")]
    TooFew {
        /// What needs them (`floor`, `face`, `a pointer with its tip on its axis`, ...).
        what: &'static str,
        /// The fewest it needs.
        need: usize,
        /// The markers given.
        got: usize,
    },
    /// Markers placed so that they fix no frame (too close together, on one line, off the club file's face, ...):
    /// the text says which and what to do.
    #[error("{0}")]
    Geometry(String),
    /// A marker of a static trial moved more than the limit over the frames averaged.
    #[error(
        "the trial is not static: marker `{label}` moved {moved_mm:.1} mm from its mean position (at frame \
         {frame}) over the {frames} frames averaged, more than the {limit_mm:.1} mm a static trial allows \
         (choose still frames with --frame/--frames, or widen the limit with --static-mm)"
    )]
    NotStatic {
        /// The marker that moved most.
        label: String,
        /// Its largest distance from its mean position (mm).
        moved_mm: Real,
        /// The frame it sat furthest from its mean in (its index in the capture).
        frame: u64,
        /// The frames averaged.
        frames: usize,
        /// The most a marker may move, the static limit (mm).
        limit_mm: Real,
    },
    /// A marker asked for is valid in none of the frames averaged.
    #[error("marker `{0}` is not valid in any of the frames asked for")]
    NeverSeen(String),
    /// Floor markers too near one line to give the floor's tilt.
    #[error(
        "the floor markers are nearly on one line: they spread {spread_mm:.1} mm (RMS) across their best-fit line, \
         under the {min_mm:.0} mm that gives the floor's tilt: add floor markers away from that line (a triangle \
         at least 20 cm on a side)"
    )]
    FloorCollinear {
        /// The floor markers' RMS distance from their best-fit line (mm).
        spread_mm: Real,
        /// The least spread accepted, [`lab::MIN_FLOOR_SPREAD_M`] (mm).
        min_mm: Real,
    },
    /// A floor marker off the floor's plane.
    #[error(
        "floor marker `{label}` is {off_mm:.1} mm off the plane of the floor markers (at most {max_mm:.0} mm): it \
         is not on the floor (a foot, a mat's edge?); leave it out of --floor"
    )]
    FloorNotFlat {
        /// The floor marker furthest off the plane.
        label: String,
        /// Its distance from the plane of the floor markers (mm).
        off_mm: Real,
        /// The furthest a floor marker may sit off it, [`lab::MAX_FLOOR_OFF_M`] (mm).
        max_mm: Real,
    },
    /// A stated up axis that the capture contradicts.
    #[error(
        "--lab-up {stated} disagrees with the capture: the floor's normal on the side {evidence} is ({:.3}, \
         {:.3}, {:.3}) in the lab, nearest {nearest}, {angle_deg:.0} deg from the stated {stated}: give --lab-up \
         {nearest} or leave it out",
        measured.x, measured.y, measured.z
    )]
    LabUpDisagrees {
        /// The lab axis nearest the stated up axis (`x`, `-y`, ...).
        stated: String,
        /// The lab axis nearest the measured up axis.
        nearest: String,
        /// The measured up axis: the floor's normal on the side the evidence says is up (lab, unit).
        measured: Vector3,
        /// The angle between the stated and the measured up axes (deg).
        angle_deg: Real,
        /// What fixed the measured side, in words: where the markers off the floor stand, or the stated axis.
        evidence: String,
    },
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
