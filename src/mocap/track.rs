//! From a motion-capture frame to a clubhead sample: units, the NaN and occlusion rules, and each body's frame
//! numbering (dropped, out of order, restarted), counted the way `MocapInputStatus` reports them.
//!
//! A sample keeps the server's lab frame (the rig's `world_from_lab` maps it to the world): NatNet's position
//! (m) and quaternion as sent; QTM's position (mm) in metres and its column-major rotation matrix as a
//! quaternion. An untracked body is published `occluded: true`; where its numbers are not finite (QTM sends NaN,
//! JSON has none) the sample carries the origin and the identity orientation instead.

use crate::math::{Matrix3, Rotation3, UnitQuaternion};
use crate::wire::{ClubheadSampleMsg, MocapInputStatus, QuaternionMsg};

use super::qtm::{Body6d, Frame6d};

/// A frame number this far behind the last one is a server restart, not a late frame.
pub const RESTART_FRAMES: u64 = 1000;

/// The tolerance on a quaternion's norm, and on a rotation matrix's orthonormality, for a tracked body.
pub const UNIT_TOL: f64 = 1e-3;

/// A sample before it is addressed to a rig.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodySample {
    pub frame: u64,
    pub t_ns: u64,
    pub position_m: [f64; 3],
    pub orientation_xyzw: [f64; 4],
    pub occluded: bool,
    pub exposure_t_ns: Option<u64>,
    /// A pose fitted from markers: the fit's RMS residual (m).
    pub fit_residual_m: Option<f64>,
    /// The motion-capture system's own latency for this frame, as it reports it (us; Vicon's `LatencyInfo`).
    pub system_latency_us: Option<f64>,
}

impl BodySample {
    pub fn to_msg(&self, rig: &str) -> ClubheadSampleMsg {
        let [x, y, z, w] = self.orientation_xyzw;
        ClubheadSampleMsg {
            rig: rig.to_string(),
            frame: self.frame,
            t_ns: self.t_ns,
            position_m: self.position_m,
            orientation: QuaternionMsg { x, y, z, w },
            occluded: self.occluded,
            exposure_t_ns: self.exposure_t_ns,
            fit_residual_m: self.fit_residual_m,
            system_latency_us: self.system_latency_us,
            body: None,
        }
    }

    /// The body as a tracked ball (its origin the ball's centre): a sample for `mocap/<rig>/ball`.
    pub fn to_ball_msg(&self, rig: &str) -> crate::wire::BallSampleMsg {
        crate::wire::BallSampleMsg {
            rig: rig.to_string(),
            frame: self.frame,
            t_ns: self.t_ns,
            position_m: self.position_m,
            occluded: self.occluded,
        }
    }
}

/// Why a body's frame was published occluded although the server said it was tracked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BadPose {
    /// A position or orientation number is NaN or infinite.
    NotFinite,
    /// The quaternion is not of unit norm, or the matrix not a rotation.
    NotRotation,
}

impl BadPose {
    pub fn reason(self) -> &'static str {
        match self {
            BadPose::NotFinite => "nan_pose",
            BadPose::NotRotation => "bad_rotation",
        }
    }
}

pub fn placeholder(s: &mut BodySample) {
    s.position_m = [0.0; 3];
    s.orientation_xyzw = [0.0, 0.0, 0.0, 1.0];
}

/// Seconds to integer nanoseconds (0 for a negative or non-finite time).
pub fn s_to_ns(t_s: f64) -> u64 {
    if t_s.is_finite() && t_s > 0.0 {
        (t_s * 1e9).round() as u64
    } else {
        0
    }
}

/// A QTM 6D body of `frame` as a sample: NaN position means not tracked.
/// A marker set fitted to a QTM frame's labelled markers: `indices[k]` is marker `k` of the set among the 3D
/// labels; a frame with fewer than 3 of them valid (seen, and not rejected by their residual) is occluded. The fit's residual is the
/// caller's to count.
pub fn qtm_fitted_sample(
    fitter: &crate::kinematics::MarkerFitter,
    indices: &[usize],
    frame: &Frame6d,
    lab_m: &mut Vec<Option<crate::math::Vector3>>,
) -> BodySample {
    let t_ns = u64::try_from(frame.timestamp_us).unwrap_or(0).saturating_mul(1000);
    lab_m.clear();
    lab_m.extend(indices.iter().map(|&i| {
        let p = frame.markers_mm.get(i)?.map(|v| f64::from(v) * 1e-3);
        p.iter().all(|v| v.is_finite()).then(|| crate::math::Vector3::from(p))
    }));
    let mut s = BodySample {
        frame: u64::from(frame.frame_number),
        t_ns,
        position_m: [0.0; 3],
        orientation_xyzw: [0.0, 0.0, 0.0, 1.0],
        occluded: false,
        exposure_t_ns: Some(t_ns),
        fit_residual_m: None,
        system_latency_us: None,
    };
    match fitter.fit(lab_m) {
        Ok(fit) => {
            let p = fit.lab_from_body.translation.vector;
            let q = fit.lab_from_body.rotation;
            s.position_m = [p.x, p.y, p.z];
            s.orientation_xyzw = [q.i, q.j, q.k, q.w];
            s.fit_residual_m = Some(fit.residual_m);
        }
        Err(_) => {
            placeholder(&mut s);
            s.occluded = true;
        }
    }
    s
}

pub fn qtm_sample(body: &Body6d, frame: &Frame6d) -> (BodySample, Option<BadPose>) {
    let t_ns = u64::try_from(frame.timestamp_us).unwrap_or(0).saturating_mul(1000);
    let mut s = BodySample {
        frame: u64::from(frame.frame_number),
        t_ns,
        position_m: body.position_mm.map(|v| f64::from(v) * 1e-3),
        orientation_xyzw: [0.0, 0.0, 0.0, 1.0],
        occluded: false,
        exposure_t_ns: Some(t_ns),
        fit_residual_m: None,
        system_latency_us: None,
    };
    if body.position_mm.iter().any(|v| v.is_nan()) {
        placeholder(&mut s);
        s.occluded = true;
        return (s, None);
    }
    let r = body.rotation.map(f64::from);
    if s.position_m.iter().chain(r.iter()).any(|v| !v.is_finite()) {
        placeholder(&mut s);
        s.occluded = true;
        return (s, Some(BadPose::NotFinite));
    }
    let m = Matrix3::from_column_slice(&r);
    let off = (m.transpose() * m - Matrix3::identity()).abs().max();
    if off > UNIT_TOL || m.determinant() < 0.0 {
        placeholder(&mut s);
        s.occluded = true;
        return (s, Some(BadPose::NotRotation));
    }
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m));
    s.orientation_xyzw = [q.i, q.j, q.k, q.w];
    (s, None)
}

/// One body's frame numbering and counts.
#[derive(Debug, Clone, Default)]
pub struct BodyTrack {
    last_frame: Option<u64>,
}

/// What to do with a body's frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sequence {
    Publish,
    /// At or before the last published frame: counted, not published.
    Late,
}

impl BodyTrack {
    /// Counts a frame of the body into `status` and says whether to publish it.
    pub fn on_frame(&mut self, sample: &BodySample, bad: Option<BadPose>, status: &mut MocapInputStatus) -> Sequence {
        status.frames += 1;
        if let Some(last) = self.last_frame {
            if sample.frame <= last && last - sample.frame < RESTART_FRAMES {
                status.out_of_order += 1;
                return Sequence::Late;
            }
            if sample.frame <= last {
                status.restarts += 1;
            } else {
                status.dropped += sample.frame - last - 1;
            }
        }
        self.last_frame = Some(sample.frame);
        if let Some(b) = bad {
            *status.rejected.entry(b.reason().to_string()).or_default() += 1;
        }
        if sample.occluded {
            status.occluded += 1;
        }
        status.published += 1;
        Sequence::Publish
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbering_counts_drops_late_frames_and_restarts() {
        let mut t = BodyTrack::default();
        let mut st = MocapInputStatus::default();
        let s = |frame| BodySample {
            frame,
            t_ns: 0,
            position_m: [0.0; 3],
            orientation_xyzw: [0.0, 0.0, 0.0, 1.0],
            occluded: false,
            exposure_t_ns: None,
            fit_residual_m: None,
            system_latency_us: None,
        };
        assert_eq!(t.on_frame(&s(5000), None, &mut st), Sequence::Publish);
        assert_eq!(t.on_frame(&s(5003), None, &mut st), Sequence::Publish);
        assert_eq!(t.on_frame(&s(5002), None, &mut st), Sequence::Late);
        assert_eq!(t.on_frame(&s(5003), None, &mut st), Sequence::Late);
        assert_eq!(t.on_frame(&s(1), None, &mut st), Sequence::Publish);
        assert_eq!((st.frames, st.dropped, st.out_of_order, st.restarts, st.published), (5, 2, 2, 1, 3));
    }

    /// QTM's column-major matrix of a 90 degree turn about z gives the quaternion (0, 0, sin 45, cos 45).
    #[test]
    fn qtm_matrix_is_column_major() {
        // Rz(90): columns (0, 1, 0), (-1, 0, 0), (0, 0, 1).
        let body = Body6d {
            position_mm: [1000.0, 0.0, -500.0],
            rotation: [0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0],
            residual_mm: None,
        };
        let frame = Frame6d { timestamp_us: 2_000_000, frame_number: 7, ..Default::default() };
        let (s, bad) = qtm_sample(&body, &frame);
        assert!(bad.is_none());
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let q = s.orientation_xyzw;
        assert!((q[2] - h).abs() < 1e-6 && (q[3] - h).abs() < 1e-6 && q[0].abs() < 1e-9, "{q:?}");
        assert_eq!(s.position_m, [1.0, 0.0, -0.5]);
        assert_eq!((s.frame, s.t_ns), (7, 2_000_000_000));
        let nan = Body6d { position_mm: [f32::NAN; 3], ..body };
        let (s, bad) = qtm_sample(&nan, &frame);
        assert!(s.occluded && bad.is_none() && s.position_m == [0.0; 3]);
    }
}
