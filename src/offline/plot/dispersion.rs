//! The dispersion chart a fitter prints: carry against side per club, each club's shots with its 1 and 2 SD
//! ellipses (the covariance of side and carry), the target line, a legend inside the canvas and units on the
//! axes. Side is drawn across (right of the target +), carry up the page.

use std::fmt::Write;

use super::{axis_labels, escape, fmt_tick, nice_step, range, svg_open, PALETTE};

/// One club's shots: `(side, carry)` in the chart's unit.
#[derive(Debug, Clone, PartialEq)]
pub struct DispersionGroup {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

/// A point `(side, carry)`.
pub type Point = (f64, f64);
/// A 2x2 covariance `[[sxx, sxy], [sxy, syy]]`.
pub type Covariance = [[f64; 2]; 2];
/// A club's 1 and 2 SD ellipses, as points.
type Ellipses = [Vec<Point>; 2];

/// Mean and covariance of points (sample covariance; `None` below 3 points).
pub fn mean_covariance(points: &[Point]) -> Option<(Point, Covariance)> {
    let n = points.len();
    if n < 3 {
        return None;
    }
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n as f64;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n as f64;
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for (x, y) in points {
        sxx += (x - mx) * (x - mx);
        sxy += (x - mx) * (y - my);
        syy += (y - my) * (y - my);
    }
    let d = (n - 1) as f64;
    Some(((mx, my), [[sxx / d, sxy / d], [sxy / d, syy / d]]))
}

/// The `k`-SD ellipse of a covariance about `mean`, as `samples` points: `mean + k (√λ₁ cos t e₁ + √λ₂ sin t e₂)`.
pub fn ellipse(mean: (f64, f64), cov: [[f64; 2]; 2], k: f64, samples: usize) -> Vec<(f64, f64)> {
    let (a, b, c) = (cov[0][0], cov[0][1], cov[1][1]);
    let half_trace = 0.5 * (a + c);
    let root = (0.25 * (a - c) * (a - c) + b * b).sqrt();
    let (l1, l2) = ((half_trace + root).max(0.0), (half_trace - root).max(0.0));
    let angle = 0.5 * (2.0 * b).atan2(a - c);
    let (e1, e2) = ((angle.cos(), angle.sin()), (-angle.sin(), angle.cos()));
    (0..samples)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / samples as f64;
            let (u, v) = (k * l1.sqrt() * t.cos(), k * l2.sqrt() * t.sin());
            (mean.0 + u * e1.0 + v * e2.0, mean.1 + u * e1.1 + v * e2.1)
        })
        .collect()
}

/// The chart (SVG). `unit` names the distance unit (`yd`, `m`); `note` goes under the title.
pub fn dispersion_svg(groups: &[DispersionGroup], unit: &str, title: &str, note: Option<&str>) -> String {
    let (width, height) = (900.0, 760.0);
    let shapes: Vec<(Option<Ellipses>, &DispersionGroup)> = groups
        .iter()
        .map(|g| (mean_covariance(&g.points).map(|(m, c)| [ellipse(m, c, 1.0, 72), ellipse(m, c, 2.0, 72)]), g))
        .collect();
    let all =
        || shapes.iter().flat_map(|(e, g)| g.points.iter().copied().chain(e.iter().flat_map(|e| e[1].iter().copied())));
    let (x_lo, x_hi) = range(all().map(|p| p.0).chain([0.0]));
    let (y_lo, y_hi) = range(all().map(|p| p.1).chain([0.0]));
    let x_half = x_lo.abs().max(x_hi.abs()) * 1.08;
    let x_step = nice_step(2.0 * x_half, 8.0);
    let x_half = (x_half / x_step).ceil() * x_step;
    let y_step = nice_step(y_hi - y_lo.min(0.0), 8.0);
    let (y0, y1) = ((y_lo.min(0.0) / y_step).floor() * y_step, (y_hi * 1.04 / y_step).ceil() * y_step);
    let (ml, mt, mr, mb) = (70.0, 70.0, 30.0, 50.0);
    let (pw, ph) = (width - ml - mr, height - mt - mb);
    let sx = |x: f64| ml + (x + x_half) / (2.0 * x_half) * pw;
    let sy = |y: f64| mt + (y1 - y) / (y1 - y0) * ph;
    let mut out = svg_open(width, height, &[title], note);
    let _ = write!(out, r##"<rect x="{ml}" y="{mt}" width="{pw}" height="{ph}" fill="none" stroke="#333"/>"##);
    let mut x = -x_half;
    while x <= x_half + 1e-9 {
        let _ = write!(
            out,
            r##"<line x1="{0:.1}" y1="{mt}" x2="{0:.1}" y2="{1:.1}" stroke="#eee"/><text x="{0:.1}" y="{2:.1}" text-anchor="middle">{3}</text>"##,
            sx(x),
            mt + ph,
            mt + ph + 16.0,
            fmt_tick(x, x_step)
        );
        x += x_step;
    }
    let mut y = y0;
    while y <= y1 + 1e-9 {
        let _ = write!(
            out,
            r##"<line x1="{ml}" y1="{0:.1}" x2="{1:.1}" y2="{0:.1}" stroke="#eee"/><text x="{2:.1}" y="{3:.1}" text-anchor="end">{4}</text>"##,
            sy(y),
            ml + pw,
            ml - 6.0,
            sy(y) + 4.0,
            fmt_tick(y, y_step)
        );
        y += y_step;
    }
    let _ = write!(
        out,
        r##"<line x1="{0:.1}" y1="{mt}" x2="{0:.1}" y2="{1:.1}" stroke="#222" stroke-dasharray="6 4"/><text x="{2:.1}" y="{3:.1}" fill="#222">target line</text>"##,
        sx(0.0),
        mt + ph,
        sx(0.0) + 4.0,
        mt + 14.0
    );
    for (i, (ellipses, g)) in shapes.iter().enumerate() {
        let colour = PALETTE[i % PALETTE.len()];
        if let Some(e) = ellipses {
            for (k, dash) in [(0, ""), (1, r#" stroke-dasharray="5 3""#)] {
                let path: Vec<String> = e[k].iter().map(|p| format!("{:.1},{:.1}", sx(p.0), sy(p.1))).collect();
                let _ = write!(
                    out,
                    r#"<polygon points="{}" fill="{colour}" fill-opacity="{}" stroke="{colour}"{dash}/>"#,
                    path.join(" "),
                    if k == 0 { 0.12 } else { 0.04 }
                );
            }
        }
        for p in &g.points {
            let _ = write!(
                out,
                r#"<circle cx="{:.1}" cy="{:.1}" r="3" fill="{colour}" fill-opacity="0.85"/>"#,
                sx(p.0),
                sy(p.1)
            );
        }
    }
    // The legend, inside the plot area's top right corner.
    let rows = shapes.len() + 2;
    let (lw, lh) = (190.0, 18.0 * rows as f64 + 10.0);
    let (lx, ly) = (ml + pw - lw - 8.0, mt + 8.0);
    let _ = write!(
        out,
        r##"<rect x="{lx:.1}" y="{ly:.1}" width="{lw}" height="{lh:.1}" fill="white" fill-opacity="0.9" stroke="#999"/>"##
    );
    for (i, (_, g)) in shapes.iter().enumerate() {
        let (cy, colour) = (ly + 14.0 + 18.0 * i as f64, PALETTE[i % PALETTE.len()]);
        let _ = write!(
            out,
            r#"<circle cx="{:.1}" cy="{:.1}" r="4" fill="{colour}"/><text x="{:.1}" y="{:.1}">{} ({} shots)</text>"#,
            lx + 12.0,
            cy - 4.0,
            lx + 22.0,
            cy,
            escape(&g.name),
            g.points.len()
        );
    }
    let cy = ly + 14.0 + 18.0 * shapes.len() as f64;
    let _ = write!(
        out,
        r##"<line x1="{0:.1}" y1="{1:.1}" x2="{2:.1}" y2="{1:.1}" stroke="#555"/><text x="{3:.1}" y="{4:.1}">1 SD ellipse</text><line x1="{0:.1}" y1="{5:.1}" x2="{2:.1}" y2="{5:.1}" stroke="#555" stroke-dasharray="5 3"/><text x="{3:.1}" y="{6:.1}">2 SD ellipse</text>"##,
        lx + 6.0,
        cy - 4.0,
        lx + 18.0,
        lx + 22.0,
        cy,
        cy + 14.0,
        cy + 18.0
    );
    axis_labels(
        &mut out,
        (ml, mt, pw, ph),
        height,
        &format!("side ({unit}; right of the target +)"),
        &format!("carry ({unit})"),
    );
    out += "</svg>\n";
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 1-SD ellipse of uncorrelated points has the SDs as half-axes along x and y.
    #[test]
    fn ellipse_half_axes_are_the_sds() {
        let cov = [[4.0, 0.0], [0.0, 100.0]];
        let e = ellipse((1.0, 200.0), cov, 1.0, 4);
        let close = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9;
        assert!(e.iter().any(|p| close(*p, (1.0, 210.0))), "{e:?}");
        assert!(e.iter().any(|p| close(*p, (1.0, 190.0))), "{e:?}");
        assert!(e.iter().any(|p| close(*p, (3.0, 200.0)) || close(*p, (-1.0, 200.0))), "{e:?}");
        let (m, c) = mean_covariance(&[(0.0, 0.0), (2.0, 2.0), (4.0, 4.0)]).unwrap();
        assert_eq!(m, (2.0, 2.0));
        assert_eq!(c, [[4.0, 4.0], [4.0, 4.0]]);
    }
}
