//! `impactd plot ground`: the iron-plus-ground model's strikes over time (seed section 4.3). The upper chart is
//! the ground's vertical and horizontal force on the head for a fat and a good strike (Figure 4.10), the lower
//! one the face angle and dynamic loft through the same strikes (Figure 4.15); time runs from the ball's first
//! contact on the undisturbed swing.

use super::{LineChart, Series, PALETTE};
use crate::impact::continuous::iron_ground::{GroundResult, GroundTracePoint};

/// Why the strikes cannot be drawn.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GroundPlotError {
    #[error("the {0} strike has no trace (run it with a trace)")]
    NoTrace(&'static str),
    #[error("the {0} strike never touched the ground: nothing to draw")]
    NoGround(&'static str),
}

fn series(name: String, color: usize, r: &GroundResult, y: fn(&GroundTracePoint) -> f64) -> Series {
    Series { name, points: r.trace.iter().map(|p| (p.t_ms, y(p))).collect(), color: PALETTE[color], right_axis: false }
}

/// Figures 4.10 and 4.15 for `strikes` (a label and a run with its trace each), as one SVG titled `title`.
pub fn ground_svg(title: &str, strikes: &[(&'static str, &GroundResult)]) -> Result<String, GroundPlotError> {
    for (label, r) in strikes {
        if r.trace.is_empty() {
            return Err(GroundPlotError::NoTrace(label));
        }
        if r.peak_ground_force_n <= 0.0 {
            return Err(GroundPlotError::NoGround(label));
        }
    }
    let mut forces = Vec::new();
    let mut angles = Vec::new();
    for (k, (label, r)) in strikes.iter().enumerate() {
        let what = format!("{label} strike, peak {:.0} N", r.peak_ground_force_n);
        forces.push(series(format!("{what}: vertical"), 2 * k, r, |p| p.ground_vertical_n));
        forces.push(series(format!("{what}: horizontal"), 2 * k + 1, r, |p| p.ground_horizontal_n));
        angles.push(Series {
            name: format!("{label}: face angle (open +)"),
            points: r.trace.iter().map(|p| (p.t_ms, p.face_angle_deg)).collect(),
            color: PALETTE[2 * k],
            right_axis: false,
        });
        angles.push(Series {
            name: format!("{label}: dynamic loft (right axis)"),
            points: r.trace.iter().map(|p| (p.t_ms, p.dynamic_loft_deg)).collect(),
            color: PALETTE[2 * k + 1],
            right_axis: true,
        });
    }
    let top = LineChart {
        title: format!("{title}: ground force on the head (Figure 4.10)"),
        x_label: "time from the ball's first contact (ms)".into(),
        y_label: "force (N)".into(),
        y2_label: None,
        series: forces,
        equal_axes: false,
    };
    let bottom = LineChart {
        title: "face angle and dynamic loft, the swing's own turning included (Figure 4.15)".into(),
        x_label: "time from the ball's first contact (ms)".into(),
        y_label: "face angle (deg)".into(),
        y2_label: Some("dynamic loft (deg)".into()),
        series: angles,
        equal_axes: false,
    };
    let (w, h) = (900.0, 420.0);
    Ok(format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{}"><rect width="100%" height="100%" fill="white"/><g>{}</g><g transform="translate(0,{h})">{}</g></svg>"#,
        2.0 * h,
        top.svg(w, h),
        bottom.svg(w, h)
    ))
}
