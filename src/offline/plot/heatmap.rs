//! Heatmaps: a value over a uniform grid, drawn to the same scale on both axes, with round ticks that include 0,
//! an optional outline that clips the cells (only what is inside it is drawn), labelled markers, and a colour
//! bar with round ticks along its length. Signed values get a diverging palette centred on zero (blue below,
//! red above), unsigned ones a sequential palette (viridis).

use std::fmt::Write;

use super::{escape, fmt_tick, nice_step, range};

/// A heatmap over a grid with a colour bar.
pub struct Heatmap {
    /// One line per `\n`; the first is the largest.
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    /// The colour bar's label: the value's name and unit.
    pub value_label: String,
    /// Cell centres along x and y (uniform, at least 2 each).
    pub xs: Vec<f64>,
    pub ys: Vec<f64>,
    /// `values[j][i]` at `(xs[i], ys[j])`; NaN cells are left blank.
    pub values: Vec<Vec<f64>>,
    /// Whether the value has a sign that means something (a direction): a diverging palette centred on zero.
    pub signed: bool,
    /// A closed outline (data units), e.g. the clubface's: drawn, and the cells are clipped to it.
    pub outline: Vec<[f64; 2]>,
    /// Labelled points drawn over the cells (data units), e.g. the face centre and the CG.
    pub markers: Vec<(String, [f64; 2])>,
    /// A line of small text under the title (e.g. why some cells are blank).
    pub note: Option<String>,
}

const VIRIDIS: [(f64, [f64; 3]); 5] = [
    (0.0, [68.0, 1.0, 84.0]),
    (0.25, [59.0, 82.0, 139.0]),
    (0.5, [33.0, 145.0, 140.0]),
    (0.75, [94.0, 201.0, 98.0]),
    (1.0, [253.0, 231.0, 37.0]),
];
/// ColorBrewer's RdBu, blue for negative, near-white at zero, red for positive.
const DIVERGING: [(f64, [f64; 3]); 5] = [
    (0.0, [33.0, 102.0, 172.0]),
    (0.25, [146.0, 197.0, 222.0]),
    (0.5, [247.0, 247.0, 247.0]),
    (0.75, [244.0, 165.0, 130.0]),
    (1.0, [178.0, 24.0, 43.0]),
];

fn colour(stops: &[(f64, [f64; 3])], t: f64) -> String {
    let t = t.clamp(0.0, 1.0);
    let i = stops.windows(2).position(|w| t <= w[1].0).unwrap_or(stops.len() - 2);
    let ((t0, a), (t1, b)) = (stops[i], stops[i + 1]);
    let f = (t - t0) / (t1 - t0);
    let c = |k: usize| (a[k] + (b[k] - a[k]) * f).round() as u8;
    format!("#{:02x}{:02x}{:02x}", c(0), c(1), c(2))
}

/// The colour scale: `lo..hi` with round ticks every `step`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColourScale {
    pub lo: f64,
    pub hi: f64,
    pub step: f64,
}

impl ColourScale {
    /// Round bounds around `values`: symmetric about zero when `signed`, else the nearest ticks outside the range.
    pub fn of(values: impl Iterator<Item = f64>, signed: bool) -> Self {
        let (v0, v1) = range(values);
        if signed {
            let m = v0.abs().max(v1.abs()).max(1e-9);
            let step = nice_step(m, 2.5);
            let hi = (m / step - 1e-9).ceil() * step;
            ColourScale { lo: -hi, hi, step }
        } else {
            let step = nice_step(v1 - v0, 6.0);
            ColourScale { lo: (v0 / step + 1e-9).floor() * step, hi: (v1 / step - 1e-9).ceil() * step, step }
        }
    }

    /// The round values from `lo` to `hi`.
    pub fn ticks(&self) -> Vec<f64> {
        let n = ((self.hi - self.lo) / self.step).round() as i64;
        (0..=n).map(|k| self.lo + k as f64 * self.step).collect()
    }

    fn fraction(&self, v: f64) -> f64 {
        (v - self.lo) / (self.hi - self.lo)
    }
}

/// Round ticks (multiples of `step`, so 0 when the span holds it) within `lo..=hi`.
fn ticks_within(lo: f64, hi: f64, step: f64) -> impl Iterator<Item = f64> {
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first..=last).map(move |k| k as f64 * step)
}

impl Heatmap {
    fn stops(&self) -> &'static [(f64, [f64; 3])] {
        if self.signed {
            &DIVERGING
        } else {
            &VIRIDIS
        }
    }

    /// The colour scale of the finite values.
    pub fn scale(&self) -> ColourScale {
        ColourScale::of(self.values.iter().flatten().copied(), self.signed)
    }

    /// The height (px) at which `svg(width, _)` fills its width: the grid's aspect plus the title and margins,
    /// within `min..=max`.
    pub fn fitted_height(&self, width: f64, min: f64, max: f64) -> f64 {
        let span = |v: &[f64]| {
            let n = v.len().max(2) as f64;
            (v.last().unwrap_or(&1.0) - v.first().unwrap_or(&0.0)) * n / (n - 1.0)
        };
        let lines = self.title.lines().count().max(1) as f64;
        let top = 20.0 + 18.0 * lines + if self.note.is_some() { 16.0 } else { 0.0 };
        let plot_w = width - 70.0 - 150.0;
        (top + 50.0 + plot_w * span(&self.ys) / span(&self.xs).max(1e-9)).clamp(min, max)
    }

    /// The heatmap as an SVG document of the given size (px).
    pub fn svg(&self, width: f64, height: f64) -> String {
        let title_lines: Vec<&str> = self.title.lines().collect();
        let note_px = if self.note.is_some() { 16.0 } else { 0.0 };
        let (ml, mr, mt, mb) = (70.0, 150.0, 20.0 + 18.0 * title_lines.len().max(1) as f64 + note_px, 50.0);
        let (aw, ah) = (width - ml - mr, height - mt - mb);
        let (nx, ny) = (self.xs.len().max(2), self.ys.len().max(2));
        let dx = (self.xs.last().unwrap_or(&1.0) - self.xs.first().unwrap_or(&0.0)) / (nx - 1) as f64;
        let dy = (self.ys.last().unwrap_or(&1.0) - self.ys.first().unwrap_or(&0.0)) / (ny - 1) as f64;
        let (x0, x1) = (self.xs.first().unwrap_or(&0.0) - dx / 2.0, self.xs.last().unwrap_or(&1.0) + dx / 2.0);
        let (y0, y1) = (self.ys.first().unwrap_or(&0.0) - dy / 2.0, self.ys.last().unwrap_or(&1.0) + dy / 2.0);
        // The same scale both ways (a face drawn to its shape), centred in the available area.
        let k = (aw / (x1 - x0)).min(ah / (y1 - y0));
        let (pw, ph) = ((x1 - x0) * k, (y1 - y0) * k);
        let (left, top) = (ml + (aw - pw) / 2.0, mt + (ah - ph) / 2.0);
        let sx = |x: f64| left + (x - x0) * k;
        let sy = |y: f64| top + ph - (y - y0) * k;
        let scale = self.scale();
        let stops = self.stops();
        let mut out = super::svg_open(width, height, &title_lines, self.note.as_deref());
        let outline: Vec<String> = self.outline.iter().map(|p| format!("{:.1},{:.1}", sx(p[0]), sy(p[1]))).collect();
        if !outline.is_empty() {
            let _ = write!(
                out,
                r#"<defs><clipPath id="outline"><polygon points="{}"/></clipPath></defs>"#,
                outline.join(" ")
            );
            out.push_str(r#"<g clip-path="url(#outline)" shape-rendering="crispEdges">"#);
        } else {
            out.push_str(r#"<g shape-rendering="crispEdges">"#);
        }
        for (j, row) in self.values.iter().enumerate() {
            for (i, v) in row.iter().enumerate().filter(|(_, v)| v.is_finite()) {
                let (cx, cy) = (self.xs[i], self.ys[j]);
                let _ = write!(
                    out,
                    r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="{}"><title>{:.3}</title></rect>"#,
                    sx(cx - dx / 2.0),
                    sy(cy + dy / 2.0),
                    dx * k + 0.4,
                    dy * k + 0.4,
                    colour(stops, scale.fraction(*v)),
                    v
                );
            }
        }
        out.push_str("</g>");
        let _ = write!(
            out,
            r##"<rect x="{left:.1}" y="{top:.1}" width="{pw:.1}" height="{ph:.1}" fill="none" stroke="#333"/>"##
        );
        if !outline.is_empty() {
            let _ = write!(
                out,
                r##"<polygon points="{}" fill="none" stroke="#111" stroke-width="2"/>"##,
                outline.join(" ")
            );
        }
        // Axes: one round step for both (same scale), ticks at its multiples, so 0 is one of them.
        let step = nice_step((x1 - x0).max(y1 - y0), 8.0);
        for x in ticks_within(x0, x1, step) {
            let px = sx(x);
            let _ = write!(
                out,
                r##"<line x1="{px:.1}" y1="{:.1}" x2="{px:.1}" y2="{:.1}" stroke="#333"/><text x="{px:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
                top + ph,
                top + ph + 5.0,
                top + ph + 18.0,
                fmt_tick(x, step)
            );
        }
        for y in ticks_within(y0, y1, step) {
            let py = sy(y);
            let _ = write!(
                out,
                r##"<line x1="{:.1}" y1="{py:.1}" x2="{left:.1}" y2="{py:.1}" stroke="#333"/><text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"##,
                left - 5.0,
                left - 8.0,
                py + 4.0,
                fmt_tick(y, step)
            );
        }
        for (n, (name, p)) in self.markers.iter().enumerate() {
            let (x, y) = (sx(p[0]), sy(p[1]));
            // The first marker is a ring labelled above right, the others dots labelled below left.
            let (fill, dx_px, dy_px, anchor) =
                if n == 0 { ("white", 7.0, -7.0, "start") } else { ("#111", -7.0, 15.0, "end") };
            let _ = write!(
                out,
                r##"<circle cx="{x:.1}" cy="{y:.1}" r="4" fill="{fill}" stroke="#111" stroke-width="1.5"/><text x="{:.1}" y="{:.1}" font-size="11" text-anchor="{anchor}" stroke="white" stroke-width="3" paint-order="stroke">{}</text>"##,
                x + dx_px,
                y + dy_px,
                escape(name)
            );
        }
        let (bottom, pt) = (top + ph, top + ph);
        let _ = write!(
            out,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text><text transform="translate(18,{:.1}) rotate(-90)" text-anchor="middle">{}</text>"#,
            left + pw / 2.0,
            bottom + 38.0,
            escape(&self.x_label),
            top + ph / 2.0,
            escape(&self.y_label)
        );
        // The colour bar, as tall as the plot, with a tick and a label at each round value.
        let bx = ml + aw + 24.0;
        let gradient: String =
            stops.iter().map(|(t, _)| format!(r#"<stop offset="{t}" stop-color="{}"/>"#, colour(stops, *t))).collect();
        let _ = write!(
            out,
            r##"<defs><linearGradient id="bar" x1="0" y1="1" x2="0" y2="0">{gradient}</linearGradient></defs><rect x="{bx:.1}" y="{top:.1}" width="16" height="{ph:.1}" fill="url(#bar)" stroke="#333"/>"##
        );
        for v in scale.ticks() {
            let y = pt - scale.fraction(v) * ph;
            let _ = write!(
                out,
                r##"<line x1="{:.1}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#333"/><text x="{:.1}" y="{:.1}">{}</text>"##,
                bx + 16.0,
                bx + 21.0,
                bx + 24.0,
                y + 4.0,
                fmt_tick(v, scale.step)
            );
        }
        let _ = write!(
            out,
            r#"<text transform="translate({:.1},{:.1}) rotate(90)" text-anchor="middle">{}</text>"#,
            bx + 90.0,
            top + ph / 2.0,
            escape(&self.value_label)
        );
        out.push_str("</svg>\n");
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A signed scale is symmetric about zero with 0 among its ticks; an unsigned one spans the values between
    /// round ticks.
    #[test]
    fn colour_scales_are_round() {
        let s = ColourScale::of([-945.0, 409.0].into_iter(), true);
        assert_eq!((s.lo, s.hi, s.step), (-1000.0, 1000.0, 500.0));
        assert!(s.ticks().contains(&0.0));
        let s = ColourScale::of([82.3, 110.6].into_iter(), false);
        assert_eq!((s.lo, s.hi, s.step), (80.0, 115.0, 5.0));
        assert_eq!(s.ticks().len(), 8);
        // The zero of a diverging palette is its middle (near-white).
        assert_eq!(colour(&DIVERGING, ColourScale::of([-3.0, 1.0].into_iter(), true).fraction(0.0)), "#f7f7f7");
    }

    #[test]
    fn axis_ticks_include_zero() {
        let t: Vec<f64> = ticks_within(-34.7, 39.7, 10.0).collect();
        assert_eq!(t, vec![-30.0, -20.0, -10.0, 0.0, 10.0, 20.0, 30.0]);
    }
}
