//! From a DataStream frame to a clubhead sample: a subject's segment (its root unless named), or a marker set
//! fitted to the subject's labelled markers.
//!
//! A sample keeps Vicon's world frame (the rig's `world_from_lab` maps it to impactd's world): the translation
//! (mm) in metres and the row-major rotation matrix as a quaternion. Its `frame` is the SDK's frame number
//! (`FrameInfo`'s id plus one, what every DataStream SDK program prints); its `t_ns` the frame's start on Vicon's
//! 135 MHz master clock, id x period (`StreamInfo`), in nanoseconds since the system's frame 0. A segment absent
//! from the frame is published `occluded: true` with the origin and the identity orientation.

use super::frame::Frame;
use super::items::SubjectDef;
use crate::kinematics::MarkerFitter;
use crate::math::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use crate::mocap::track::{BadPose, BodySample, UNIT_TOL};

/// Where a route's pose is in the stream, resolved against the current `SubjectInfo`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RouteIds {
    /// A segment of a subject.
    Segment { subject_id: u32, segment_id: u32 },
    /// A marker set fitted to a subject's labelled markers: each set marker's id in the subject.
    Markers { subject_id: u32, marker_ids: Vec<u32> },
}

/// Why a route does not resolve; [`Unresolved::reason`] is the key its frames are counted under.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Unresolved {
    #[error("subject `{0}` is not among the server's subjects")]
    NoSubject(String),
    #[error("subject `{subject}` has no segment `{segment}`")]
    NoSegment { subject: String, segment: String },
    #[error("subject `{0}` has no root segment")]
    NoRoot(String),
    #[error("marker `{marker}` of the marker set is not among subject `{subject}`'s markers")]
    NoMarker { subject: String, marker: String },
}

impl Unresolved {
    pub fn reason(&self) -> &'static str {
        match self {
            Unresolved::NoSubject(_) => "body_not_in_model",
            Unresolved::NoSegment { .. } | Unresolved::NoRoot(_) => "segment_not_in_model",
            Unresolved::NoMarker { .. } => "markers_not_in_model",
        }
    }
}

fn subject<'a>(frame: &'a Frame, name: &str) -> Result<&'a SubjectDef, Unresolved> {
    frame.subject(name).ok_or_else(|| Unresolved::NoSubject(name.to_string()))
}

/// A subject's segment: `segment`, or the root when `None`.
pub fn resolve_segment(frame: &Frame, subject_name: &str, segment: Option<&str>) -> Result<RouteIds, Unresolved> {
    let s = subject(frame, subject_name)?;
    let seg = match segment {
        Some(name) => s
            .segment(name)
            .ok_or_else(|| Unresolved::NoSegment { subject: subject_name.into(), segment: name.into() })?,
        None => s.root().ok_or_else(|| Unresolved::NoRoot(subject_name.into()))?,
    };
    Ok(RouteIds::Segment { subject_id: s.subject_id, segment_id: seg.segment_id })
}

/// A marker set's markers among a subject's (matched by name).
pub fn resolve_markers(frame: &Frame, subject_name: &str, fitter: &MarkerFitter) -> Result<RouteIds, Unresolved> {
    let s = subject(frame, subject_name)?;
    let names: Vec<&str> = s.markers.iter().map(|m| m.name.as_str()).collect();
    let indices = fitter
        .set
        .indices_in(&names)
        .map_err(|marker| Unresolved::NoMarker { subject: subject_name.into(), marker })?;
    Ok(RouteIds::Markers {
        subject_id: s.subject_id,
        marker_ids: indices.iter().map(|&i| s.markers[i].marker_id).collect(),
    })
}

/// The frame's number and time, or `None` before a `FrameInfo` and a positive `StreamInfo` period arrived.
fn stamp(frame: &Frame) -> Option<BodySample> {
    Some(BodySample {
        frame: frame.sdk_frame_number()?,
        t_ns: frame.t_ns()?,
        position_m: [0.0; 3],
        orientation_xyzw: [0.0, 0.0, 0.0, 1.0],
        occluded: true,
        exposure_t_ns: None,
        fit_residual_m: None,
        system_latency_us: frame.latency_total_s().map(|s| s * 1e6),
    })
}

/// A segment's sample in this frame (`None`: the frame has no number or time yet). A pose that is not finite or
/// not a rotation is published occluded and says why.
pub fn segment_sample(frame: &Frame, subject_id: u32, segment_id: u32) -> Option<(BodySample, Option<BadPose>)> {
    let mut s = stamp(frame)?;
    let Some(pose) = frame.segment_pose(subject_id, segment_id) else { return Some((s, None)) };
    let p = pose.translation_mm.map(|v| v * 1e-3);
    if p.iter().chain(pose.rotation.iter()).any(|v| !v.is_finite()) {
        return Some((s, Some(BadPose::NotFinite)));
    }
    let m = Matrix3::from_row_slice(&pose.rotation);
    let off = (m.transpose() * m - Matrix3::identity()).abs().max();
    if off > UNIT_TOL || m.determinant() < 0.0 {
        return Some((s, Some(BadPose::NotRotation)));
    }
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m));
    s.position_m = p;
    s.orientation_xyzw = [q.i, q.j, q.k, q.w];
    s.occluded = false;
    Some((s, None))
}

/// A marker set fitted to a subject's labelled markers in this frame (`marker_ids` from [`resolve_markers`]);
/// fewer than three usable markers is occluded. `lab_m` is reused.
pub fn fitted_sample(
    frame: &Frame,
    fitter: &MarkerFitter,
    subject_id: u32,
    marker_ids: &[u32],
    lab_m: &mut Vec<Option<Vector3>>,
) -> Option<BodySample> {
    let mut s = stamp(frame)?;
    lab_m.clear();
    lab_m.extend(marker_ids.iter().map(|&id| {
        let p = frame.marker_mm(subject_id, id)?.map(|v| v * 1e-3);
        p.iter().all(|v| v.is_finite()).then(|| Vector3::from(p))
    }));
    if let Ok(fit) = fitter.fit(lab_m) {
        let p = fit.lab_from_body.translation.vector;
        let q = fit.lab_from_body.rotation;
        s.position_m = [p.x, p.y, p.z];
        s.orientation_xyzw = [q.i, q.j, q.k, q.w];
        s.fit_residual_m = Some(fit.residual_m);
        s.occluded = false;
    }
    Some(s)
}
