//! The figures the command line draws: a launch number over the clubface (`impactd map`), the continuous model's
//! forces through one impact (`impactd plot forces`) and side and top views of flights (`impactd plot trajectory`).

use super::{Heatmap, LineChart, Series, PALETTE};
use crate::equipment::ClubSpec;
use crate::flight::{Flight, LaunchState, Trajectory};
use crate::impact::continuous::{ContinuousResult, TracePoint};
use crate::impact::{Equipment, ImpactModel, LaunchMetrics};
use crate::units::m_to_yd;
use crate::wire::DeliveryInput;

/// What `impactd map` colours the face by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MapMetric {
    BallSpeed,
    Launch,
    Backspin,
    Sidespin,
    Carry,
    Offline,
}

impl MapMetric {
    /// The axis label of the metric, with its unit.
    pub fn label(self) -> &'static str {
        match self {
            MapMetric::BallSpeed => "ball speed (mph)",
            MapMetric::Launch => "launch angle (deg)",
            MapMetric::Backspin => "backspin (rpm)",
            MapMetric::Sidespin => "sidespin (rpm, + fade)",
            MapMetric::Carry => "carry (yd)",
            MapMetric::Offline => "offline (yd, right +)",
        }
    }
}

/// `metric` of `model`'s prediction over a `cells` x `cells` grid of impact locations covering the face of `club`,
/// for `delivery` (its impact location ignored); cells with no prediction are NaN (blank).
pub fn face_map(
    club: &ClubSpec,
    model: &dyn ImpactModel,
    delivery: &DeliveryInput,
    metric: MapMetric,
    cells: usize,
) -> Heatmap {
    let equipment = Equipment::new(club.clone());
    let flight = Flight::default();
    let n = cells.max(2);
    let (h0, h1, v0, v1) = club.face_outline.bounds_mm();
    let xs: Vec<f64> = (0..n).map(|i| h0 + (h1 - h0) * i as f64 / (n - 1) as f64).collect();
    let ys: Vec<f64> = (0..n).map(|j| v0 + (v1 - v0) * j as f64 / (n - 1) as f64).collect();
    let mut values = vec![vec![f64::NAN; n]; n];
    for (j, v) in ys.iter().enumerate() {
        for (i, h) in xs.iter().enumerate() {
            let mut input = delivery.clone();
            input.impact_h_mm = *h;
            input.impact_v_mm = *v;
            let Ok(state) = input.to_delivery(club.loft_deg()).to_state(&equipment) else { continue };
            let Ok(launch) = model.predict(&state, &equipment) else { continue };
            let m = LaunchMetrics::from_ball(&launch.ball_velocity_mps, &launch.ball_spin_radps);
            values[j][i] = match metric {
                MapMetric::BallSpeed => m.ball_speed_mph,
                MapMetric::Launch => m.launch_angle_deg,
                MapMetric::Backspin => m.backspin_rpm,
                MapMetric::Sidespin => m.sidespin_rpm,
                MapMetric::Carry | MapMetric::Offline => {
                    let launch =
                        LaunchState { velocity_mps: launch.ball_velocity_mps, spin_radps: launch.ball_spin_radps };
                    let t = flight.fly(&launch, 0.0);
                    if metric == MapMetric::Carry {
                        t.carry_yd
                    } else {
                        t.offline_yd
                    }
                }
            };
        }
    }
    let label = metric.label();
    Heatmap {
        title: format!("{} {}: {} at {:.0} mph", club.name, model.name(), label, delivery.club_speed_mph),
        x_label: "impact location toward the toe (mm)".into(),
        y_label: "impact location up the face (mm)".into(),
        value_label: label.into(),
        xs,
        ys,
        values,
        outline: club.face_outline.vertices_mm.clone(),
        markers: vec![
            ("face centre".into(), [0.0, 0.0]),
            ("CG".into(), [-club.face.center_m.z * 1e3, -club.face.center_m.dot(&club.face.u0()) * 1e3]),
        ],
    }
}

/// The continuous model's normal and tangential force and the ball's and cover's spin through one impact `r` of
/// `club_name` swung at `club_speed_mph`.
pub fn forces_chart(club_name: &str, club_speed_mph: f64, r: &ContinuousResult) -> LineChart {
    let m = LaunchMetrics::from_ball(&r.launch.ball_velocity_mps, &r.launch.ball_spin_radps);
    let series = |name: &str, color: usize, right_axis: bool, y: fn(&TracePoint) -> f64| Series {
        name: name.into(),
        points: r.trace.iter().map(|p| (p.t_us, y(p))).collect(),
        color: PALETTE[color],
        right_axis,
    };
    LineChart {
        title: format!(
            "{} at {:.0} mph: contact {:.0} us, peak {:.1} kN; ball {:.1} mph, {:.0} rpm",
            club_name,
            club_speed_mph,
            r.contact_time_s * 1e6,
            r.peak_normal_force_n / 1e3,
            m.ball_speed_mph,
            m.total_spin_rpm
        ),
        x_label: "time from first contact (us)".into(),
        y_label: "force on the ball (N)".into(),
        y2_label: Some("ball spin (rpm)".into()),
        series: vec![
            series("normal force", 0, false, |p| p.normal_force_n),
            series("tangential force (+ along the face's slip)", 1, false, |p| p.tangential_force_n),
            series("ball spin (right axis)", 2, true, |p| p.ball_spin_rpm),
            series("cover spin (right axis)", 3, true, |p| p.cover_spin_rpm),
        ],
        equal_axes: false,
    }
}

/// Side and top views of flights (sampled with their `points`), one above the other, as one SVG.
pub fn trajectories_svg(flights: &[Trajectory]) -> String {
    let mut side = Vec::new();
    let mut top = Vec::new();
    for (k, t) in flights.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let name = format!(
            "shot {}: carry {:.0} yd, total {:.0} yd, apex {:.0} yd, {:+.0} yd",
            k + 1,
            t.carry_yd,
            t.total_yd,
            t.apex_yd,
            t.offline_yd
        );
        side.push(Series {
            name: name.clone(),
            points: t.points.iter().map(|p| (m_to_yd(p[1]), m_to_yd(p[2]))).collect(),
            color,
            right_axis: false,
        });
        top.push(Series {
            name,
            points: t.points.iter().map(|p| (m_to_yd(p[1]), m_to_yd(p[3]))).collect(),
            color,
            right_axis: false,
        });
    }
    let side = LineChart {
        title: "side view".into(),
        x_label: "downrange (yd)".into(),
        y_label: "height (yd)".into(),
        y2_label: None,
        series: side,
        equal_axes: false,
    };
    let top = LineChart {
        title: "top view (right +)".into(),
        x_label: "downrange (yd)".into(),
        y_label: "offline (yd)".into(),
        y2_label: None,
        series: top,
        equal_axes: false,
    };
    let (w, h) = (900.0, 380.0);
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{}"><g>{}</g><g transform="translate(0,{h})">{}</g></svg>"#,
        2.0 * h,
        side.svg(w, h),
        top.svg(w, h)
    )
}
