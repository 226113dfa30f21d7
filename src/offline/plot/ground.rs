//! `impactd plot ground`: the iron-plus-ground model's strikes over time (seed section 4.3). The upper chart is
//! the ground's vertical and horizontal force on the head for a fat and a good strike (Figure 4.10), the lower
//! one the face angle and dynamic loft through the same strikes (Figure 4.15); time runs from the ball's first
//! contact on the undisturbed swing.

use super::{LineChart, Series, PALETTE};
use crate::impact::continuous::iron_ground::GROUND_REPORT;
use crate::impact::report::Trace;
use crate::impact::ModelRun;

/// Why the strikes cannot be drawn.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GroundPlotError {
    #[error("the {0} strike has no trace (run it with a trace)")]
    NoTrace(&'static str),
    #[error("the {0} strike never touched the ground: nothing to draw")]
    NoGround(&'static str),
}

fn series(name: String, color: usize, trace: &Trace, y: &str, right_axis: bool) -> Series {
    Series { name, points: trace.series("t_ms", y), color: PALETTE[color], right_axis }
}

/// Figures 4.10 and 4.15 for `strikes` (a label and a run with its trace each), as one SVG titled `title`: the
/// runs' `ground` reports and traces are read by name.
pub fn ground_svg(title: &str, strikes: &[(&'static str, &ModelRun)]) -> Result<String, GroundPlotError> {
    let mut runs = Vec::new();
    for (label, r) in strikes {
        let trace = match &r.course {
            Some(c) if !c.trace.is_empty() => &c.trace,
            _ => return Err(GroundPlotError::NoTrace(label)),
        };
        let peak_n = match r.report.as_ref().filter(|r| r.key == GROUND_REPORT) {
            Some(g) => g.fields.number("peak_ground_force_n").unwrap_or(0.0),
            None => 0.0,
        };
        if peak_n <= 0.0 {
            return Err(GroundPlotError::NoGround(label));
        }
        runs.push((label, trace, peak_n));
    }
    let mut forces = Vec::new();
    let mut angles = Vec::new();
    for (k, (label, trace, peak_n)) in runs.into_iter().enumerate() {
        let what = format!("{label} strike, peak {peak_n:.0} N");
        forces.push(series(format!("{what}: vertical"), 2 * k, trace, "ground_vertical_n", false));
        forces.push(series(format!("{what}: horizontal"), 2 * k + 1, trace, "ground_horizontal_n", false));
        angles.push(series(format!("{label}: face angle (open +)"), 2 * k, trace, "face_angle_deg", false));
        angles.push(series(format!("{label}: dynamic loft (right axis)"), 2 * k + 1, trace, "dynamic_loft_deg", true));
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
    // Each chart's legend goes below its plot, inside the canvas: the charts are stacked by their full heights.
    let (w, h) = (900.0, 420.0);
    let (h1, h2) = (top.total_height(h), bottom.total_height(h));
    Ok(format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{}"><rect width="100%" height="100%" fill="white"/><g>{}</g><g transform="translate(0,{h1})">{}</g></svg>"#,
        h1 + h2,
        top.svg(w, h),
        bottom.svg(w, h)
    ))
}
