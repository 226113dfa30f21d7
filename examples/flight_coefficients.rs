//! Draws the fitted drag and lift against the published measurements and Nathan's model's coefficients: `docs/flight-drag.svg` and
//! `docs/flight-lift.svg` (`cargo run --release --no-default-features --example flight_coefficients`).

#![allow(clippy::unwrap_used)]

use impactd::flight::reference::{bearman_harvey, lyu, nathan, BH_CD, BH_CL};
use impactd::flight::{aero, Aero, Flight};
use impactd::offline::plot::{LineChart, Series, PALETTE};
use impactd::units::radps_to_rpm;

fn main() -> std::io::Result<()> {
    let f = Flight::default();
    let (rho, mu, r) = (f.conditions.density_kg_m3(), f.conditions.viscosity_pa_s(), f.ball.radius_m);
    let speeds: Vec<f64> = (0..=70).map(|i| 20.0 + i as f64).collect();
    for (drag, file, label) in [(true, "docs/flight-drag.svg", "C_D"), (false, "docs/flight-lift.svg", "C_L")] {
        let mut series = Vec::new();
        for (k, s) in [0.1, 0.25].into_iter().enumerate() {
            let pick = |(d, l): (f64, f64)| if drag { d } else { l };
            let model = speeds
                .iter()
                .map(|&v| (v, pick(Aero::FITTED.coefficients(aero::reynolds(v, 2.0 * r, rho, mu), s))))
                .collect();
            // Each source only where it measured: Bearman and Harvey 2000-6000 rpm, Lyu et al. 1500-4500 rpm.
            let rpm = |v: f64| radps_to_rpm(s * v / r);
            let bh = speeds
                .iter()
                .filter(|&&v| (2000.0..=6000.0).contains(&rpm(v)) && v <= 88.1)
                .map(|&v| (v, bearman_harvey(if drag { &BH_CD } else { &BH_CL }, v, rpm(v))))
                .collect();
            let lyu_points = speeds
                .iter()
                .filter(|&&v| (1500.0..=4500.0).contains(&radps_to_rpm(s * v / 0.0215)) && v <= 91.0)
                .map(|&v| (v, pick(lyu(v, s))))
                .collect();
            series.push(Series {
                name: format!("model, S = {s}"),
                points: model,
                color: PALETTE[k],
                right_axis: false,
            });
            series.push(Series {
                name: format!("Bearman & Harvey 1976, S = {s}"),
                points: bh,
                color: PALETTE[2 + k],
                right_axis: false,
            });
            series.push(Series {
                name: format!("Lyu et al. 2018, S = {s}"),
                points: lyu_points,
                color: PALETTE[4 + k],
                right_axis: false,
            });
            // Nathan's model is a fit over the whole range, drawn everywhere.
            series.push(Series {
                name: format!("Nathan (libgolf), S = {s}"),
                points: speeds.iter().map(|&v| (v, pick(nathan(aero::reynolds(v, 2.0 * r, rho, mu), s)))).collect(),
                color: PALETTE[6 + k],
                right_axis: false,
            });
        }
        let chart = LineChart {
            title: format!("{label} of the fitted model against the measurements, at spin ratios 0.1 and 0.25"),
            x_label: "airspeed (m/s)".into(),
            y_label: label.into(),
            y2_label: None,
            series,
            equal_axes: false,
        };
        std::fs::write(file, chart.svg(900.0, 520.0))?;
        eprintln!("wrote {file}");
    }
    Ok(())
}
