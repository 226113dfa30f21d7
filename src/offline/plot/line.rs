//! Line charts: axes with round ticks, an optional right-hand axis whose zero lines up with the left one's, a
//! legend below the plot (never over a curve), a title of one or more lines, and optional marks (points with a
//! label, such as where a ball lands) and a note (the conditions of a flight).

use std::fmt::Write;

use super::{axis_labels, escape, fmt_tick, nice_step, range};

/// One line of a chart.
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub color: &'static str,
    /// Draw on the right-hand axis.
    pub right_axis: bool,
}

/// A line chart.
pub struct LineChart {
    /// One line per `\n`.
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub y2_label: Option<String>,
    pub series: Vec<Series>,
    /// Keep x and y to the same scale (trajectories).
    pub equal_axes: bool,
}

/// A point drawn as a ring on the left axis' scale, with an optional label beside it.
pub struct Mark {
    pub x: f64,
    pub y: f64,
    pub color: &'static str,
    pub label: Option<String>,
}

/// What a chart may carry beside its series.
#[derive(Default)]
pub struct Extras<'a> {
    pub marks: &'a [Mark],
    /// A line of small text under the title (conditions, units).
    pub note: Option<&'a str>,
}

const LEGEND_ROW_PX: f64 = 16.0;

/// Widens `(lo, hi)` and `(lo2, hi2)` so that 0 sits at the same height on both axes; each range includes 0.
fn align_zeros((lo, hi): (f64, f64), (lo2, hi2): (f64, f64)) -> ((f64, f64), (f64, f64)) {
    let (lo, hi, lo2, hi2) = (lo.min(0.0), hi.max(0.0), lo2.min(0.0), hi2.max(0.0));
    // The fraction of each axis below zero; both take the larger.
    let below = |lo: f64, hi: f64| if hi - lo > 0.0 { -lo / (hi - lo) } else { 0.0 };
    let f = below(lo, hi).max(below(lo2, hi2));
    let fit = |lo: f64, hi: f64| {
        if f >= 1.0 {
            // One axis is all below zero: no common zero height exists inside both frames.
            (lo, hi)
        } else if hi > 0.0 {
            let lo = lo.min(-f * hi / (1.0 - f));
            // A range already below more than f cannot be: f is the maximum.
            (lo, hi)
        } else {
            (lo, -lo * (1.0 - f) / f.max(1e-12))
        }
    };
    (fit(lo, hi), fit(lo2, hi2))
}

impl LineChart {
    /// The chart as an SVG document of the given size (px).
    pub fn svg(&self, width: f64, height: f64) -> String {
        self.svg_with(width, height, &Extras::default())
    }

    /// The height of the SVG that `svg_with(_, height, _)` draws: the legend's rows are added below the plot.
    pub fn total_height(&self, height: f64) -> f64 {
        height + self.legend_px()
    }

    /// Series with an empty name draw no legend row (several curves under one entry).
    fn legend_px(&self) -> f64 {
        LEGEND_ROW_PX * self.series.iter().filter(|s| !s.name.is_empty()).count() as f64 + 8.0
    }

    /// The chart with marks and a note; the legend below the plot adds its rows to `height`.
    pub fn svg_with(&self, width: f64, height: f64, extras: &Extras<'_>) -> String {
        let title_lines: Vec<&str> = self.title.lines().collect();
        let title_px = 18.0 * title_lines.len().max(1) as f64 + if extras.note.is_some() { 16.0 } else { 0.0 };
        let legend_px = self.legend_px();
        let height = self.total_height(height);
        let (ml, mr, mt, mb) =
            (70.0, if self.y2_label.is_some() { 70.0 } else { 20.0 }, 16.0 + title_px, 50.0 + legend_px);
        let (pw, ph) = (width - ml - mr, height - mt - mb);
        let (x0, x1) = range(
            self.series.iter().flat_map(|s| s.points.iter().map(|p| p.0)).chain(extras.marks.iter().map(|m| m.x)),
        );
        let left = |right: bool| self.series.iter().filter(move |s| s.right_axis == right);
        let (mut y0, mut y1) =
            range(left(false).flat_map(|s| s.points.iter().map(|p| p.1)).chain(extras.marks.iter().map(|m| m.y)));
        let (mut y20, mut y21) = range(left(true).flat_map(|s| s.points.iter().map(|p| p.1)));
        let pad = |lo: f64, hi: f64| (lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo));
        // Padded on every side: the longest shot and the highest point stay inside the frame.
        let (mut x0, mut x1) = pad(x0, x1);
        (y0, y1) = pad(y0, y1);
        (y20, y21) = pad(y20, y21);
        if self.y2_label.is_some() {
            ((y0, y1), (y20, y21)) = align_zeros((y0, y1), (y20, y21));
        }
        if self.equal_axes {
            let sx = (x1 - x0) / pw;
            let sy = (y1 - y0) / ph;
            if sx > sy {
                let mid = 0.5 * (y0 + y1);
                y0 = mid - 0.5 * sx * ph;
                y1 = mid + 0.5 * sx * ph;
            } else {
                let mid = 0.5 * (x0 + x1);
                x0 = mid - 0.5 * sy * pw;
                x1 = mid + 0.5 * sy * pw;
            }
        }
        let sx = |x: f64| ml + (x - x0) / (x1 - x0) * pw;
        let sy = |y: f64| mt + ph - (y - y0) / (y1 - y0) * ph;
        let sy2 = |y: f64| mt + ph - (y - y20) / (y21 - y20) * ph;
        let mut out = super::svg_open(width, height, &title_lines, extras.note);
        // Grid and ticks.
        let xs = nice_step(x1 - x0, 8.0);
        let mut x = (x0 / xs).ceil() * xs;
        while x <= x1 + 1e-9 {
            let px = sx(x);
            let _ =
                write!(out, r##"<line x1="{px:.1}" y1="{mt}" x2="{px:.1}" y2="{:.1}" stroke="#e5e5e5"/>"##, mt + ph);
            let _ = write!(
                out,
                r#"<text x="{px:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
                mt + ph + 16.0,
                fmt_tick(x, xs)
            );
            x += xs;
        }
        let ys = nice_step(y1 - y0, 6.0);
        let mut y = (y0 / ys).ceil() * ys;
        while y <= y1 + 1e-9 {
            let py = sy(y);
            let _ =
                write!(out, r##"<line x1="{ml}" y1="{py:.1}" x2="{:.1}" y2="{py:.1}" stroke="#e5e5e5"/>"##, ml + pw);
            let _ = write!(
                out,
                r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"#,
                ml - 6.0,
                py + 4.0,
                fmt_tick(y, ys)
            );
            y += ys;
        }
        if self.y2_label.is_some() {
            let ys2 = nice_step(y21 - y20, 6.0);
            let mut y = (y20 / ys2).ceil() * ys2;
            while y <= y21 + 1e-9 {
                let _ = write!(
                    out,
                    r#"<text x="{:.1}" y="{:.1}">{}</text>"#,
                    ml + pw + 6.0,
                    sy2(y) + 4.0,
                    fmt_tick(y, ys2)
                );
                y += ys2;
            }
        }
        if y0 < 0.0 && y1 > 0.0 {
            let _ = write!(
                out,
                r##"<line x1="{ml}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#999"/>"##,
                sy(0.0),
                ml + pw,
                sy(0.0)
            );
        }
        if x0 < 0.0 && x1 > 0.0 {
            let _ = write!(
                out,
                r##"<line x1="{:.1}" y1="{mt}" x2="{:.1}" y2="{:.1}" stroke="#999"/>"##,
                sx(0.0),
                sx(0.0),
                mt + ph
            );
        }
        let _ = write!(out, r##"<rect x="{ml}" y="{mt}" width="{pw}" height="{ph}" fill="none" stroke="#333"/>"##);
        axis_labels(&mut out, (ml, mt, pw, ph), height - legend_px, &self.x_label, &self.y_label);
        if let Some(l) = &self.y2_label {
            let _ = write!(
                out,
                r#"<text transform="translate({:.1},{:.1}) rotate(90)" text-anchor="middle">{}</text>"#,
                width - 14.0,
                mt + ph / 2.0,
                escape(l)
            );
        }
        let mut row = 0usize;
        for s in &self.series {
            let pts: Vec<String> = s
                .points
                .iter()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .map(|&(x, y)| format!("{:.1},{:.1}", sx(x), if s.right_axis { sy2(y) } else { sy(y) }))
                .collect();
            let dash = if s.right_axis { r#" stroke-dasharray="6,3""# } else { "" };
            let _ = write!(
                out,
                r#"<polyline fill="none" stroke="{}" stroke-width="1.8"{dash} points="{}"/>"#,
                s.color,
                pts.join(" ")
            );
            if s.name.is_empty() {
                continue;
            }
            // The legend, below the x axis' label: clear of every curve.
            let ly = height - legend_px + 4.0 + LEGEND_ROW_PX * (row as f64 + 0.75);
            row += 1;
            let _ = write!(
                out,
                r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{}" stroke-width="2"{dash}/>"#,
                ml,
                ly - 4.0,
                ml + 20.0,
                ly - 4.0,
                s.color
            );
            let _ = write!(out, r#"<text x="{:.1}" y="{ly:.1}">{}</text>"#, ml + 26.0, escape(&s.name));
        }
        for m in extras.marks {
            let (px, py) = (sx(m.x), sy(m.y));
            let _ = write!(
                out,
                r#"<circle cx="{px:.1}" cy="{py:.1}" r="4" fill="white" stroke="{}" stroke-width="2"/>"#,
                m.color
            );
            if let Some(l) = &m.label {
                let _ =
                    write!(out, r#"<text x="{:.1}" y="{:.1}" font-size="11">{}</text>"#, px + 7.0, py + 4.0, escape(l));
            }
        }
        out.push_str("</svg>\n");
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both axes' zeros at the same height: the fraction of each range below zero is equal.
    #[test]
    fn zeros_line_up() {
        let ((lo, hi), (lo2, hi2)) = align_zeros((-500.0, 9000.0), (-100.0, 3000.0));
        let below = |lo: f64, hi: f64| -lo / (hi - lo);
        assert!((below(lo, hi) - below(lo2, hi2)).abs() < 1e-12, "{lo} {hi} {lo2} {hi2}");
        assert_eq!((hi, hi2), (9000.0, 3000.0));
        // A range all above zero gains zero at the other's height.
        let ((lo, hi), (lo2, hi2)) = align_zeros((100.0, 200.0), (-50.0, 50.0));
        assert!((below(lo, hi) - 0.5).abs() < 1e-12 && (below(lo2, hi2) - 0.5).abs() < 1e-12);
    }
}
