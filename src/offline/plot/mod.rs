//! Small SVG charts (no dependencies): line charts with axes, ticks and a legend, and heatmaps. They return the
//! SVG text; writing it is the caller's business.

use std::fmt::Write;

mod dispersion;
mod face_map;
mod figures;
mod ground;
mod heatmap;
mod line;
pub use dispersion::{dispersion_svg, ellipse, mean_covariance, DispersionGroup};
pub use face_map::{face_map, MapMetric};
pub use figures::{
    delivery_conditions, delivery_title, forces_chart, maw_plate_chart, trajectories_figure, trajectories_svg,
};
pub use ground::{ground_svg, GroundPlotError};
pub use heatmap::{ColourScale, Heatmap};
pub use line::{Extras, LineChart, Mark, Series};

/// Colours for successive series.
pub const PALETTE: [&str; 8] = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"];

fn nice_step(span: f64, ticks: f64) -> f64 {
    let raw = (span / ticks).max(1e-12);
    let mag = 10f64.powf(raw.log10().floor());
    let r = raw / mag;
    mag * if r < 1.5 {
        1.0
    } else if r < 3.5 {
        2.0
    } else if r < 7.5 {
        5.0
    } else {
        10.0
    }
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if hi - lo < 1e-12 {
        return (lo - 1.0, hi + 1.0);
    }
    (lo, hi)
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

/// An SVG document's opening: a white background, the title's lines centred at the top (the first larger) and an
/// optional note under them in grey.
fn svg_open(width: f64, height: f64, title_lines: &[&str], note: Option<&str>) -> String {
    let mut out = String::new();
    let _ = write!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="12"><rect width="100%" height="100%" fill="white"/>"#
    );
    for (i, line) in title_lines.iter().enumerate() {
        let _ = write!(
            out,
            r#"<text x="{}" y="{}" font-size="{}" text-anchor="middle">{}</text>"#,
            width / 2.0,
            22.0 + 18.0 * i as f64,
            if i == 0 { 15 } else { 13 },
            escape(line)
        );
    }
    if let Some(note) = note {
        let _ = write!(
            out,
            r##"<text x="{}" y="{}" font-size="11" fill="#555" text-anchor="middle">{}</text>"##,
            width / 2.0,
            22.0 + 18.0 * title_lines.len() as f64,
            escape(note)
        );
    }
    out
}

/// The x label under the plot area and the y label beside it; `area` is (left, top, width, height).
fn axis_labels(out: &mut String, (ml, mt, pw, ph): (f64, f64, f64, f64), height: f64, x: &str, y: &str) {
    let _ = write!(
        out,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
        ml + pw / 2.0,
        height - 12.0,
        escape(x)
    );
    let _ = write!(
        out,
        r#"<text transform="translate(16,{:.1}) rotate(-90)" text-anchor="middle">{}</text>"#,
        mt + ph / 2.0,
        escape(y)
    );
}

fn fmt_tick(v: f64, step: f64) -> String {
    let v = if v.abs() < 1e-9 * step.abs().max(1e-300) { 0.0 } else { v };
    let decimals = if step >= 1.0 { 0 } else { (-step.log10().floor()) as usize };
    format!("{v:.decimals$}")
}
