//! The figures the command line draws: the continuous model's forces through one impact (`impactd plot forces`),
//! side and top views of flights (`impactd plot trajectory`), and a ball on a rigid plate under Maw's model
//! (`impactd plot maw-plate`, seed Figure 3.4). The face map (`impactd map`) is in `face_map`.

use super::{Extras, LineChart, Mark, Series, PALETTE};
use crate::flight::Trajectory;
use crate::impact::continuous::law::maw::MawParams;
use crate::impact::continuous::plate;
use crate::impact::{LaunchMetrics, ModelRun};
use crate::session::Units;
use crate::units::radps_to_rpm;
use crate::wire::DeliveryInput;

/// A model's normal and tangential force and the ball's and cover's spin through one impact `r` of `club_name`
/// swung at `club_speed_mph`, read from its course by name (`None` without a course: a model not resolved in
/// time).
pub fn forces_chart(club_name: &str, club_speed_mph: f64, r: &ModelRun) -> Option<LineChart> {
    let course = r.course.as_ref()?;
    let m = LaunchMetrics::from_ball(&r.launch.ball_velocity_mps, &r.launch.ball_spin_radps);
    let series = |name: &str, color: usize, right_axis: bool, y: &str| Series {
        name: name.into(),
        points: course.trace.series("t_us", y),
        color: PALETTE[color],
        right_axis,
    };
    let number = |name: &str| course.summary.number(name).unwrap_or(f64::NAN);
    Some(LineChart {
        title: format!(
            "{} at {:.0} mph: contact {:.0} µs, peak {:.1} kN; ball {:.1} mph, {:.0} rpm",
            club_name,
            club_speed_mph,
            number("contact_time_us"),
            number("peak_normal_force_n") / 1e3,
            m.ball_speed_mph,
            m.total_spin_rpm
        ),
        x_label: "time from first contact (µs)".into(),
        y_label: "force on the ball (N)".into(),
        y2_label: Some("ball spin (rpm)".into()),
        series: vec![
            series("normal force", 0, false, "normal_force_n"),
            series("tangential force (+ along the face's slip)", 1, false, "tangential_force_n"),
            series("ball spin (right axis)", 2, true, "ball_spin_rpm"),
            series("cover spin (right axis)", 3, true, "cover_spin_rpm"),
        ],
        equal_axes: false,
    })
}

/// Seed Figure 3.4: the normal and tangential force and the spin of a ball (the seed's) striking a rigid plate at
/// `speed_mps` and `incidence_deg` from the plate's normal under Maw's model with `params`, elastic (no damping)
/// against damped (`params` as given).
pub fn maw_plate_chart(params: &MawParams, speed_mps: f64, incidence_deg: f64) -> LineChart {
    let ball = crate::equipment::BallSpec::SEED;
    let mut series = Vec::new();
    let mut title = format!("Plate, {speed_mps} m/s at {incidence_deg} deg:");
    let cases = [("elastic", MawParams { d_s_per_m: 0.0, ..*params }), ("damped", *params)];
    for (i, (label, p)) in cases.into_iter().enumerate() {
        let small_strain = p.contact_arm == crate::impact::continuous::law::hertz::ContactArm::Radius;
        let r = plate::impact(small_strain, &p, &ball, speed_mps, incidence_deg, 0.25e-6, 8);
        title += &format!(" {label} {:.1} m/s, {:.0} rpm;", r.rebound_normal_mps, radps_to_rpm(r.spin_radps));
        let pick = |f: fn(&plate::PlateSample) -> f64| r.samples.iter().map(|s| (s.t_us, f(s))).collect::<Vec<_>>();
        let lines = [
            ("normal force", pick(|s| s.normal_force_n), false),
            ("tangential force", pick(|s| s.tangential_force_n), false),
            ("spin, right axis (rpm)", pick(|s| radps_to_rpm(s.spin_radps)), true),
        ];
        for (j, (name, points, right_axis)) in lines.into_iter().enumerate() {
            series.push(Series {
                name: format!("{label}: {name}"),
                points,
                color: PALETTE[(2 * j + i) % PALETTE.len()],
                right_axis,
            });
        }
    }
    LineChart {
        title,
        x_label: "time from first contact (µs)".into(),
        y_label: "force on the ball (N)".into(),
        y2_label: Some("ball spin (rpm)".into()),
        series,
        equal_axes: false,
    }
}

/// Side and top views of flights (sampled with their `points`), as one SVG, in yards.
pub fn trajectories_svg(flights: &[Trajectory]) -> String {
    trajectories_figure(flights, &[], Units::Imperial, None)
}

/// The delivery of a picture's title, in TrackMan's names.
pub fn delivery_title(d: &DeliveryInput, static_loft_deg: f64) -> String {
    format!(
        "{}, impact {:+.0} mm toe / {:+.0} mm up",
        delivery_conditions(d, static_loft_deg),
        d.impact_h_mm,
        d.impact_v_mm
    )
}

/// The delivery without its impact location (a face map's, which spans the face), in TrackMan's names.
pub fn delivery_conditions(d: &DeliveryInput, static_loft_deg: f64) -> String {
    format!(
        "club {:.0} mph, attack {:+.1}°, path {:+.1}°, face {:+.1}°, dynamic loft {:.1}°",
        d.club_speed_mph,
        d.attack_angle_deg,
        d.club_path_deg,
        d.face_angle_deg,
        d.dynamic_loft_or_delivered(static_loft_deg)
    )
}

/// The most landing labels a view carries; beyond them the legend's means speak.
const MAX_LABELS: usize = 10;

/// The side view (downrange to the right, height up) above a top view (downrange up the page, right of the
/// target to the right), each scaled to the shots. `clubs` names each flight's club (empty: none): the shots of a
/// club share its colour and one legend entry with its mean carry, total and offline; an unnamed shot has its own.
/// Landings are marked, and labelled with their carry where a label clears the others (at most
/// [`MAX_LABELS`] per view). Distances in yards or metres (`units`); `conditions` is printed under the titles.
pub fn trajectories_figure(flights: &[Trajectory], clubs: &[String], units: Units, conditions: Option<&str>) -> String {
    let (unit, scale) = match units {
        Units::Imperial => ("yd", 1.0 / crate::units::M_PER_YD),
        Units::Metric => ("m", 1.0),
    };
    // Groups in order of first appearance: a club's shots, or an unnamed shot alone.
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    for k in 0..flights.len() {
        match clubs.get(k).filter(|c| !c.is_empty()) {
            Some(c) => match groups.iter_mut().find(|g| &g.0 == c) {
                Some(g) => g.1.push(k),
                None => groups.push((c.clone(), vec![k])),
            },
            None => groups.push((String::new(), vec![k])),
        }
    }
    let mut side = Vec::new();
    let mut top = Vec::new();
    let (mut side_marks, mut top_marks) = (Vec::new(), Vec::new());
    for (g, (club, shots)) in groups.iter().enumerate() {
        let color = PALETTE[g % PALETTE.len()];
        let n = shots.len() as f64;
        let mean = |f: fn(&Trajectory) -> f64| shots.iter().map(|&k| f(&flights[k])).sum::<f64>() / n * scale;
        let numbers = format!(
            "carry {:.0} {unit}, total {:.0} {unit}, apex {:.0} {unit}, offline {:+.0} {unit} (right +)",
            mean(|t| t.carry_m),
            mean(|t| t.total_m),
            mean(|t| t.apex_m),
            mean(|t| t.offline_m)
        );
        let legend = if club.is_empty() {
            format!("shot {}: {numbers}", shots[0] + 1)
        } else {
            format!("{club} ({} shots, mean): {numbers}", shots.len())
        };
        for (i, &k) in shots.iter().enumerate() {
            let t = &flights[k];
            let name = if i == 0 { legend.clone() } else { String::new() };
            side.push(Series {
                name: name.clone(),
                points: t.points.iter().map(|p| (p[1] * scale, p[2] * scale)).collect(),
                color,
                right_axis: false,
            });
            // World frame: x downrange, z right of the target line. On the page: right is +z, up is +x.
            top.push(Series {
                name,
                points: t.points.iter().map(|p| (p[3] * scale, p[1] * scale)).collect(),
                color,
                right_axis: false,
            });
            // Landing: the first sampled point back on the ground after the apex.
            let apex =
                t.points.iter().enumerate().fold((0, f64::MIN), |a, (i, p)| if p[2] > a.1 { (i, p[2]) } else { a });
            if let Some(land) = t.points.iter().skip(apex.0).find(|p| p[2] <= 1e-3) {
                let label = Some(format!("{:.0} {unit}", t.carry_m * scale));
                side_marks.push(Mark { x: land[1] * scale, y: land[2] * scale, color, label: label.clone() });
                top_marks.push(Mark { x: land[3] * scale, y: land[1] * scale, color, label });
            }
        }
    }
    clear_labels(&mut side_marks, &side);
    clear_labels(&mut top_marks, &top);
    let side = LineChart {
        title: "side view".into(),
        x_label: format!("downrange ({unit})"),
        y_label: format!("height ({unit})"),
        y2_label: None,
        series: side,
        equal_axes: false,
    };
    let top = LineChart {
        title: "top view (downrange up, right of the target to the right)".into(),
        x_label: format!("offline ({unit}, right +)"),
        y_label: format!("downrange ({unit})"),
        y2_label: None,
        series: top,
        equal_axes: false,
    };
    let w = 900.0;
    let (h1, h2) = (side.total_height(380.0), top.total_height(560.0));
    let side = side.svg_with(w, 380.0, &Extras { marks: &side_marks, note: conditions });
    let top = top.svg_with(w, 560.0, &Extras { marks: &top_marks, note: conditions });
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{}"><g>{side}</g><g transform="translate(0,{h1})">{top}</g></svg>"#,
        h1 + h2
    )
}

/// Drops the labels that would overlap one already kept or another mark (a label, written to the right of its
/// mark, is about 6 % of the x range wide and 4 % of the y range high on these charts), keeping at most
/// [`MAX_LABELS`]; the marks stay.
fn clear_labels(marks: &mut [Mark], series: &[Series]) {
    let range = |f: fn(&(f64, f64)) -> f64| {
        let v = series.iter().flat_map(|s| s.points.iter().map(f)).filter(|v| v.is_finite());
        let (lo, hi) = v.fold((f64::MAX, f64::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)));
        (hi - lo).max(1e-9)
    };
    let (dx, dy) = (0.06 * range(|p| p.0), 0.04 * range(|p| p.1));
    let at: Vec<(f64, f64)> = marks.iter().map(|m| (m.x, m.y)).collect();
    let mut kept: Vec<(f64, f64)> = Vec::new();
    for (i, m) in marks.iter_mut().enumerate() {
        let clear = kept.iter().all(|&(x, y)| (m.x - x).abs() > dx || (m.y - y).abs() > dy);
        // No other mark's circle on the label's span.
        let uncovered = at
            .iter()
            .enumerate()
            .all(|(j, &(x, y))| j == i || !(x - m.x > -0.01 * dx && x - m.x < dx && (y - m.y).abs() < dy));
        if clear && uncovered && kept.len() < MAX_LABELS {
            kept.push((m.x, m.y));
        } else {
            m.label = None;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mark(x: f64, y: f64) -> Mark {
        Mark { x, y, color: PALETTE[0], label: Some(format!("{x:.0}")) }
    }

    /// Labels never overlap another label or a mark's circle, and no view carries more than ten.
    #[test]
    fn landing_labels_clear_each_other_and_the_marks() {
        let series =
            vec![Series { name: String::new(), points: vec![(0.0, 0.0), (300.0, 40.0)], color: "", right_axis: false }];
        // On the ground (y = 0): 6 % of 300 yd is 18 yd; 150 is covered by the mark at 160, 200 and 205 by 210.
        let mut marks: Vec<Mark> = [150.0, 160.0, 200.0, 205.0, 210.0].iter().map(|&x| mark(x, 0.0)).collect();
        clear_labels(&mut marks, &series);
        let labelled: Vec<f64> = marks.iter().filter(|m| m.label.is_some()).map(|m| m.x).collect();
        assert_eq!(labelled, [160.0, 210.0]);
        let mut many: Vec<Mark> = (0..30).map(|i| mark(i as f64 * 10.0, 0.0)).collect();
        clear_labels(&mut many, &series);
        assert!(many.iter().filter(|m| m.label.is_some()).count() <= MAX_LABELS);
    }

    /// A club's shots share a colour and one legend entry; metric axes are in metres.
    #[test]
    fn shots_of_a_club_share_a_colour_and_an_entry() {
        let flight = crate::flight::Flight::default();
        let launch = |speed_mps: f64, launch_deg: f64| {
            let (s, c) = launch_deg.to_radians().sin_cos();
            crate::flight::LaunchState {
                velocity_mps: crate::math::Vector3::new(speed_mps * c, speed_mps * s, 0.0),
                spin_radps: crate::math::Vector3::new(0.0, 0.0, -250.0),
            }
        };
        let flights: Vec<Trajectory> =
            [(70.0, 11.0), (68.0, 12.0), (50.0, 18.0)].iter().map(|&(v, a)| flight.fly(&launch(v, a), 0.05)).collect();
        let clubs = ["Driver".to_string(), "Driver".to_string(), "7 Iron".to_string()];
        let svg = trajectories_figure(&flights, &clubs, Units::Metric, None);
        assert_eq!(svg.matches("Driver (2 shots, mean)").count(), 2, "one entry per view");
        assert_eq!(svg.matches("7 Iron (1 shots, mean)").count(), 2);
        assert!(svg.contains("downrange (m)") && svg.contains("offline (m, right +)") && !svg.contains("(yd"));
    }
}
