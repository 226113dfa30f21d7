//! A NatNet rigid body as a clubhead sample (`mocap::track`'s rules: units, NaN and occlusion).

use super::{Frame, RigidBody};
use crate::mocap::track::{placeholder, s_to_ns, BadPose, BodySample, UNIT_TOL};

/// A NatNet rigid body of `frame` as a sample. `clock_hz` converts the mid-exposure stamp.
pub fn natnet_sample(body: &RigidBody, frame: &Frame, clock_hz: Option<u64>) -> (BodySample, Option<BadPose>) {
    let p = body.position_m.map(f64::from);
    let q = body.orientation_xyzw.map(f64::from);
    let exposure_t_ns = match clock_hz {
        Some(hz) if hz > 0 && frame.mid_exposure_ticks > 0 => {
            Some((frame.mid_exposure_ticks as u128 * 1_000_000_000 / hz as u128).min(u64::MAX as u128) as u64)
        }
        _ => None,
    };
    let mut s = BodySample {
        frame: u64::from(frame.frame_number as u32),
        t_ns: s_to_ns(frame.timestamp_s),
        position_m: p,
        orientation_xyzw: q,
        occluded: !body.tracking_valid,
        exposure_t_ns,
        fit_residual_m: None,
        system_latency_us: None,
    };
    let finite = p.iter().chain(q.iter()).all(|v| v.is_finite());
    let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    let bad = if !finite {
        Some(BadPose::NotFinite)
    } else if (norm - 1.0).abs() > UNIT_TOL {
        Some(BadPose::NotRotation)
    } else {
        None
    };
    if bad.is_some() {
        placeholder(&mut s);
        s.occluded = true;
    }
    (s, bad.filter(|_| body.tracking_valid))
}
