//! A metric's one-sigma uncertainty on a shot, where the launch carries one (`delivery.uncertainty`,
//! `launch.uncertainty`: on every launch a rig predicts from frames), in the metric's base unit so it scales like
//! the value (`metrics::Quantity::unit`).

use crate::math::Real;
use crate::units::MPS_PER_MPH;
use crate::wire::LaunchPrediction;

type Of = fn(&LaunchPrediction) -> Option<Real>;

/// The metrics that carry an uncertainty and where it is, in the base unit.
const SIGMAS: [(&str, Of); 11] = [
    ("club_speed", |p| Some(p.delivery.uncertainty.as_ref()?.club_speed_mph * MPS_PER_MPH)),
    ("attack_angle", |p| Some(p.delivery.uncertainty.as_ref()?.attack_angle_deg)),
    ("club_path", |p| Some(p.delivery.uncertainty.as_ref()?.club_path_deg)),
    ("face_angle", |p| Some(p.delivery.uncertainty.as_ref()?.face_angle_deg)),
    ("face_to_path", |p| Some(p.delivery.uncertainty.as_ref()?.face_to_path_deg)),
    ("dynamic_loft", |p| Some(p.delivery.uncertainty.as_ref()?.dynamic_loft_deg)),
    ("ball_speed", |p| Some(p.launch.uncertainty.as_ref()?.ball_speed_mph * MPS_PER_MPH)),
    ("launch_angle", |p| Some(p.launch.uncertainty.as_ref()?.launch_angle_deg)),
    ("launch_direction", |p| Some(p.launch.uncertainty.as_ref()?.launch_direction_deg)),
    ("spin_rate", |p| Some(p.launch.uncertainty.as_ref()?.total_spin_rpm)),
    ("spin_axis", |p| Some(p.launch.uncertainty.as_ref()?.spin_axis_deg)),
];

/// The one-sigma uncertainty of the metric `base` (`club_speed`, `spin_axis`, ...) on `p`, in its base unit
/// (m/s, deg, rpm); `None` where the metric has none or the shot carries none (a delivery typed in, a recording
/// made before uncertainties were published).
pub fn sigma(p: &LaunchPrediction, base: &str) -> Option<Real> {
    let (_, of) = SIGMAS.iter().find(|(b, _)| *b == base)?;
    of(p).filter(|s| s.is_finite())
}

/// Whether the metric `base` can carry an uncertainty.
pub fn has_sigma(base: &str) -> bool {
    SIGMAS.iter().any(|(b, _)| *b == base)
}
