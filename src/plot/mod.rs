//! Small SVG charts (no dependencies): line charts with axes, ticks and a legend, and heatmaps. They return the
//! SVG text; writing it is the caller's business.

use std::fmt::Write;

mod figures;
mod ground;
mod line;
pub use figures::{
    delivery_title, face_map, forces_chart, maw_plate_chart, trajectories_figure, trajectories_svg, MapMetric,
};
pub use ground::{ground_svg, GroundPlotError};
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

/// A heatmap over a grid with a colour bar.
pub struct Heatmap {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub value_label: String,
    pub xs: Vec<f64>,
    pub ys: Vec<f64>,
    /// `values[j][i]` at `(xs[i], ys[j])`; NaN cells are left blank.
    pub values: Vec<Vec<f64>>,
    /// A closed outline drawn over the cells (data units), e.g. the clubface's.
    pub outline: Vec<[f64; 2]>,
    /// Labelled points drawn over the cells (data units), e.g. the face centre and the CG.
    pub markers: Vec<(String, [f64; 2])>,
}

fn viridis(t: f64) -> (u8, u8, u8) {
    const STOPS: [(f64, f64, f64); 5] =
        [(68.0, 1.0, 84.0), (59.0, 82.0, 139.0), (33.0, 145.0, 140.0), (94.0, 201.0, 98.0), (253.0, 231.0, 37.0)];
    let t = t.clamp(0.0, 1.0) * 4.0;
    let i = (t.floor() as usize).min(3);
    let f = t - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    let l = |x: f64, y: f64| (x + (y - x) * f).round() as u8;
    (l(a.0, b.0), l(a.1, b.1), l(a.2, b.2))
}

impl Heatmap {
    pub fn svg(&self, width: f64, height: f64) -> String {
        let (ml, mr, mt, mb) = (70.0, 110.0, 40.0, 50.0);
        let (pw, ph) = (width - ml - mr, height - mt - mb);
        let (v0, v1) = range(self.values.iter().flatten().copied());
        let (nx, ny) = (self.xs.len().max(1), self.ys.len().max(1));
        let (cw, ch) = (pw / nx as f64, ph / ny as f64);
        let mut out = String::new();
        let _ = write!(
            out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="12"><rect width="100%" height="100%" fill="white"/>"#
        );
        let _ = write!(
            out,
            r#"<text x="{}" y="24" font-size="15" text-anchor="middle">{}</text>"#,
            width / 2.0,
            escape(&self.title)
        );
        for (j, row) in self.values.iter().enumerate() {
            for (i, v) in row.iter().enumerate() {
                if !v.is_finite() {
                    continue;
                }
                let (r, g, b) = viridis((v - v0) / (v1 - v0));
                let (x, y) = (ml + i as f64 * cw, mt + ph - (j + 1) as f64 * ch);
                let _ = write!(
                    out,
                    r#"<rect x="{x:.1}" y="{y:.1}" width="{:.1}" height="{:.1}" fill="rgb({r},{g},{b})"><title>{:.3}</title></rect>"#,
                    cw + 0.5,
                    ch + 0.5,
                    v
                );
            }
        }
        let _ = write!(out, r##"<rect x="{ml}" y="{mt}" width="{pw}" height="{ph}" fill="none" stroke="#333"/>"##);
        // Data coordinates -> pixels: cell i is centred on xs[i] (uniform grids).
        let to_px = |axis: &[f64], n: usize, size: f64, v: f64| {
            let (a, b) = (axis.first().copied().unwrap_or(0.0), axis.last().copied().unwrap_or(1.0));
            let f = if b != a { (v - a) / (b - a) * (n as f64 - 1.0) } else { 0.0 };
            (f + 0.5) * size / n as f64
        };
        let px = |p: &[f64; 2]| (ml + to_px(&self.xs, nx, pw, p[0]), mt + ph - to_px(&self.ys, ny, ph, p[1]));
        if !self.outline.is_empty() {
            let pts: Vec<String> = self.outline.iter().map(px).map(|(x, y)| format!("{x:.1},{y:.1}")).collect();
            let _ =
                write!(out, r##"<polygon points="{}" fill="none" stroke="#111" stroke-width="2"/>"##, pts.join(" "));
        }
        for (name, p) in &self.markers {
            let (x, y) = px(p);
            let _ = write!(
                out,
                r##"<circle cx="{x:.1}" cy="{y:.1}" r="4" fill="white" stroke="#111" stroke-width="1.5"/><text x="{:.1}" y="{:.1}" font-size="11">{}</text>"##,
                x + 6.0,
                y - 6.0,
                escape(name)
            );
        }
        let label_every = |n: usize| (n / 6).max(1);
        for (i, x) in self.xs.iter().enumerate().step_by(label_every(nx)) {
            let _ = write!(
                out,
                r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{x:.0}</text>"#,
                ml + (i as f64 + 0.5) * cw,
                mt + ph + 16.0
            );
        }
        for (j, y) in self.ys.iter().enumerate().step_by(label_every(ny)) {
            let _ = write!(
                out,
                r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{y:.0}</text>"#,
                ml - 6.0,
                mt + ph - (j as f64 + 0.5) * ch + 4.0
            );
        }
        axis_labels(&mut out, (ml, mt, pw, ph), height, &self.x_label, &self.y_label);
        // Colour bar.
        let bx = ml + pw + 20.0;
        for k in 0..50 {
            let t = k as f64 / 49.0;
            let (r, g, b) = viridis(t);
            let y = mt + ph - (k + 1) as f64 * ph / 50.0;
            let _ = write!(
                out,
                r#"<rect x="{bx:.1}" y="{y:.1}" width="16" height="{:.1}" fill="rgb({r},{g},{b})"/>"#,
                ph / 50.0 + 0.5
            );
        }
        let _ =
            write!(out, r#"<text x="{:.1}" y="{:.1}">{}</text>"#, bx + 20.0, mt + ph, fmt_tick(v0, (v1 - v0) / 10.0));
        let _ =
            write!(out, r#"<text x="{:.1}" y="{:.1}">{}</text>"#, bx + 20.0, mt + 10.0, fmt_tick(v1, (v1 - v0) / 10.0));
        let _ = write!(
            out,
            r#"<text transform="translate({:.1},{:.1}) rotate(90)" text-anchor="middle">{}</text>"#,
            bx + 70.0,
            mt + ph / 2.0,
            escape(&self.value_label)
        );
        out.push_str("</svg>\n");
        out
    }
}
