//! TrackMan's club data of the path from the frames (docs/club-data.md): swing direction, swing plane and the
//! low point, computed once per detected impact from the face centre's positions over the last
//! [`WINDOW_MS`] before it.
//!
//! - The path is fitted with an arc ([`ArcFit`]: a plane through the points by total least squares, in it a
//!   circle with a cubic angle and a quadratic radius in time), the same model as the `arc` estimator's path.
//! - Swing plane: the angle between the fitted plane and the ground, `acos |m · y|` for its normal `m`.
//! - Swing direction: the azimuth of the plane's base line `b = m × y` (its intersection with the ground),
//!   oriented toward the target, `atan2(b_z, b_x)` (right +).
//! - Low point: the point of the fitted path where its height turns from falling to rising, the path continued
//!   past contact as the approach would go on without the ball; its distance from the face centre at contact
//!   along `b` (after +) and its height above the ball's bottom.
//!
//! Dynamic lie, closure rate and face to path come from the impact state alone ([`DeliveryMetrics`]).
//!
//! [`DeliveryMetrics`]: crate::impact::DeliveryMetrics

use super::arc::ArcFit;
use super::sample::ClubPose;
use crate::impact::SwingArc;
use crate::math::{Real, Vector3};

/// The span of frames before impact the path is fitted over (ms): the last 50-90 deg of the downswing's arc.
/// Chosen on the synthetic swings at 720 Hz with 0.2 mm / 0.1 deg of noise (crates/golf-physics/tests/club_data.rs): the low
/// point's RMS error is 1.2-1.6 mm on arcs at 50 and 60 ms but 4-6 mm on double-pendulum paths at 60 ms
/// (the uncocking wrist bends the path away from a circle over the longer span) against 2.3-2.6 mm at 50 ms;
/// at 40 ms and below the noise takes over (3-12 mm).
pub const WINDOW_MS: Real = 50.0;

/// How far from contact the low point is looked for (s): an iron's low point is 2-6 ms after it, a driver's
/// 0-5 ms before it.
pub const LOW_POINT_REACH_S: Real = 0.03;

/// The time of the path's lowest point nearest `t_contact_s`, from the rate of its height `rate(t)`: forward from
/// the contact while the path still falls, back from it while it rises, in steps of a quarter millisecond to
/// the sign change and then by bisection to 1e-15 s; `None` beyond [`LOW_POINT_REACH_S`].
pub fn lowest_time(rate: impl Fn(Real) -> Real, t_contact_s: Real) -> Option<Real> {
    const STEP_S: Real = 2.5e-4;
    let falling = rate(t_contact_s) < 0.0;
    let step = if falling { STEP_S } else { -STEP_S };
    let mut a = t_contact_s;
    for _ in 0..(LOW_POINT_REACH_S / STEP_S) as usize {
        let b = a + step;
        if (rate(b) < 0.0) != falling {
            // The falling end and the rising end of the bracket.
            let (mut lo, mut hi) = if falling { (a, b) } else { (b, a) };
            while (hi - lo).abs() > 1e-15 {
                let mid = 0.5 * (lo + hi);
                if mid == lo || mid == hi {
                    break;
                }
                if rate(mid) < 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(0.5 * (lo + hi));
        }
        a = b;
    }
    None
}

/// The swing plane's base line and angle for a plane normal `m` (any sign): `(direction, plane)` in radians and
/// the base line's unit vector toward the target; `None` for a level plane (no base line).
pub fn plane_angles(m: &Vector3) -> Option<(Real, Real, Vector3)> {
    let m = m.try_normalize(1e-12)?;
    let base = m.cross(&Vector3::y());
    let norm = base.norm();
    if norm < 1e-9 {
        return None;
    }
    let mut base = base / norm;
    if base.x < 0.0 {
        base = -base;
    }
    Some((base.z.atan2(base.x), m.y.abs().clamp(0.0, 1.0).acos(), base))
}

/// The path's metrics from its plane normal, the face centre at contact and the lowest point (m, world).
pub fn swing_arc_of(
    normal: &Vector3,
    at_contact_m: &Vector3,
    lowest_m: &Vector3,
    ball_position_m: &Vector3,
    ball_radius_m: Real,
) -> Option<SwingArc> {
    let (direction, plane, base) = plane_angles(normal)?;
    let d = lowest_m - at_contact_m;
    Some(SwingArc {
        swing_direction_deg: direction.to_degrees(),
        swing_plane_deg: plane.to_degrees(),
        low_point_distance_mm: (d.x * base.x + d.z * base.z) * 1e3,
        low_point_height_mm: (lowest_m.y - (ball_position_m.y - ball_radius_m)) * 1e3,
    })
}

/// The swing arc of the frames before impact (`pre_impact` oldest first, all before `reveal_t_ns`), with the
/// contact at `t_contact_s` from the revealing frame (the estimate's `t_from_reveal_s`); `None` when the frames
/// do not fit an arc or the path has no low point within reach. `estimated` is the estimate's own arc of the
/// face centre (times from the revealing frame), used when there is one: the `arc` estimator keeps its 60 ms arc
/// only while it fits the frames as well as a polynomial does, so a path it rejects (a wrist uncocking late)
/// is fitted again over the shorter [`WINDOW_MS`], and the fit is paid once per shot where the arc fits.
pub fn swing_arc(
    pre_impact: &[ClubPose],
    reveal_t_ns: u64,
    t_contact_s: Real,
    estimated: Option<&ArcFit>,
    face_centre_club_m: &Vector3,
    ball_position_m: &Vector3,
    ball_radius_m: Real,
) -> Option<SwingArc> {
    let arc = match estimated {
        Some(a) => *a,
        None => fit_window(pre_impact, reveal_t_ns, face_centre_club_m)?,
    };
    let t_low = lowest_time(|t| arc.velocity(t).y, t_contact_s)?;
    swing_arc_of(&arc.normal(), &arc.position(t_contact_s), &arc.position(t_low), ball_position_m, ball_radius_m)
}

/// The arc of the face centre over the last [`WINDOW_MS`] of `pre_impact`, times from the revealing frame.
fn fit_window(pre_impact: &[ClubPose], reveal_t_ns: u64, face_centre_club_m: &Vector3) -> Option<ArcFit> {
    let newest = pre_impact.last()?.t_ns;
    let span_ns = (WINDOW_MS * 1e6) as u64;
    let rel = |t_ns: u64| -((reveal_t_ns.saturating_sub(t_ns)) as Real) * 1e-9;
    let first = pre_impact.iter().rposition(|p| newest - p.t_ns > span_ns).map_or(0, |i| i + 1);
    let points: Vec<(Real, Vector3)> = pre_impact[first..]
        .iter()
        .map(|p| (rel(p.t_ns), (p.world_from_club * crate::math::Point3::from(*face_centre_club_m)).coords))
        .collect();
    ArcFit::fit(&points)
}
