//! The line the daemon logs per shot and per comparison, in the configuration's `units` (imperial: mph; metric:
//! m/s; angles in degrees and spin in rpm in both). The messages on the wire keep both units.

use crate::session::Units;
use crate::units::MPS_PER_MPH;
use crate::wire::{ComparisonMessage, LaunchPrediction};

fn speed(mph: f64, units: Units) -> (f64, &'static str) {
    match units {
        Units::Imperial => (mph, "mph"),
        Units::Metric => (mph * MPS_PER_MPH, "m/s"),
    }
}

/// `rig bay1 shot 3 (adjusted): 158.8 mph, launch 12.5 deg, ... (254 us)`.
pub fn launch(rig: &str, l: &LaunchPrediction, units: Units) -> String {
    let m = &l.launch.launch;
    let (v, unit) = speed(m.ball_speed_mph, units);
    let carry = match (&l.flight, units) {
        (Some(f), Units::Imperial) => format!(", carry {:.0} yd", f.carry_yd),
        (Some(f), Units::Metric) => format!(", carry {:.0} m", f.carry_m),
        (None, _) => String::new(),
    };
    format!(
        "rig {rig} shot {} ({}): {v:.1} {unit}, launch {:.1} deg, direction {:.1} deg, backspin {:.0} rpm, sidespin {:.0} rpm{carry} ({:.0} us)",
        l.shot, l.model, m.launch_angle_deg, m.launch_direction_deg, m.backspin_rpm, m.sidespin_rpm, l.latency_us
    )
}

/// `rig bay1 shot 3 (adjusted) vs DEVICE: ball speed +1.2 mph, ...` (residuals, predicted - measured).
pub fn comparison(rig: &str, c: &ComparisonMessage, units: Units) -> String {
    let r = &c.residual;
    let (v, unit) = speed(r.ball_speed_mph, units);
    format!(
        "rig {rig} shot {} ({}) vs {}: ball speed {v:+.1} {unit}, launch {:+.1} deg, direction {:+.1} deg, backspin {:+.0} rpm, sidespin {:+.0} rpm ({:.0} us)",
        c.shot, c.model, c.device, r.launch_angle_deg, r.launch_direction_deg, r.backspin_rpm, r.sidespin_rpm, c.latency_us
    )
}
