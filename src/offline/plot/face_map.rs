//! `impactd map`'s picture: a launch or flight number over the clubface for one delivery, drawn only on the face
//! (the club's outline), with the face centre and the CG marked and the delivery in the title.

use super::{delivery_conditions, Heatmap};
use crate::equipment::ClubSpec;
use crate::flight::{Flight, LaunchState};
use crate::impact::{Equipment, ImpactError, ImpactModel, LaunchMetrics};
use crate::wire::DeliveryInput;

/// What `impactd map` colours the face by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MapMetric {
    BallSpeed,
    Smash,
    Launch,
    LaunchDirection,
    Backspin,
    Sidespin,
    SpinAxis,
    Carry,
    Offline,
}

impl MapMetric {
    /// The colour bar's label: the metric's name and unit, and its sign convention when it has one.
    pub fn label(self) -> &'static str {
        match self {
            MapMetric::BallSpeed => "ball speed (mph)",
            MapMetric::Smash => "smash factor (ball speed / club speed)",
            MapMetric::Launch => "launch angle (deg)",
            MapMetric::LaunchDirection => "launch direction (deg, right +)",
            MapMetric::Backspin => "backspin (rpm)",
            MapMetric::Sidespin => "sidespin (rpm, + fade/slice)",
            MapMetric::SpinAxis => "spin axis (deg, + fade/slice)",
            MapMetric::Carry => "carry (yd)",
            MapMetric::Offline => "offline (yd, right +)",
        }
    }

    /// Whether the metric's sign is a direction (left/right): drawn with a palette diverging from zero.
    pub fn signed(self) -> bool {
        matches!(self, MapMetric::LaunchDirection | MapMetric::Sidespin | MapMetric::SpinAxis | MapMetric::Offline)
    }
}

fn value(
    metric: MapMetric,
    model: &dyn ImpactModel,
    equipment: &Equipment,
    delivery: &DeliveryInput,
    (h_mm, v_mm): (f64, f64),
) -> Result<f64, ImpactError> {
    let mut input = delivery.clone();
    input.impact_h_mm = h_mm;
    input.impact_v_mm = v_mm;
    let state = input.to_delivery(equipment.club.loft_deg()).to_state(equipment)?;
    let launch = model.predict(&state, equipment)?;
    let m = LaunchMetrics::from_ball(&launch.ball_velocity_mps, &launch.ball_spin_radps);
    let fly = || {
        let launch = LaunchState { velocity_mps: launch.ball_velocity_mps, spin_radps: launch.ball_spin_radps };
        Flight::default().fly(&launch, 0.0)
    };
    Ok(match metric {
        MapMetric::BallSpeed => m.ball_speed_mph,
        MapMetric::Smash => m.ball_speed_mph / delivery.club_speed_mph,
        MapMetric::Launch => m.launch_angle_deg,
        MapMetric::LaunchDirection => m.launch_direction_deg,
        MapMetric::Backspin => m.backspin_rpm,
        MapMetric::Sidespin => m.sidespin_rpm,
        MapMetric::SpinAxis => m.spin_axis_deg,
        MapMetric::Carry => fly().carry_yd,
        MapMetric::Offline => fly().offline_yd,
    })
}

/// Where a grid cell centred at `(h, v)` (mm, sides `dh` x `dv`) is evaluated: its centre when that is on the
/// face; else, when the outline crosses the cell, the point on the face nearest the centre along the line to the
/// face centre (the cell is drawn clipped to the outline, so it shows the face's edge); else nowhere.
fn sample_point(club: &ClubSpec, (h, v): (f64, f64), (dh, dv): (f64, f64)) -> Option<(f64, f64)> {
    let on = |h: f64, v: f64| club.on_face(h * 1e-3, v * 1e-3);
    if on(h, v) {
        return Some((h, v));
    }
    let sub = [-0.5, -0.25, 0.0, 0.25, 0.5];
    let crossed = sub.iter().any(|a| sub.iter().any(|b| on(h + a * dh, v + b * dv)))
        || club.face_outline.vertices_mm.iter().any(|p| (p[0] - h).abs() <= dh / 2.0 && (p[1] - v).abs() <= dv / 2.0);
    if !crossed {
        return None;
    }
    // Bisection on the fraction of the way from the face centre (on the face) to the cell's centre (off it).
    let (mut inside, mut outside) = (0.0, 1.0);
    for _ in 0..40 {
        let mid = 0.5 * (inside + outside);
        if on(mid * h, mid * v) {
            inside = mid;
        } else {
            outside = mid;
        }
    }
    Some((inside * h, inside * v))
}

/// `metric` of `model`'s prediction over a `cells` x `cells` grid tiling the bounding box of `club`'s face
/// outline, for `delivery` (its impact location ignored). Cells off the face are NaN (blank); a cell the outline
/// crosses shows the value at the face's edge (see `sample_point`) and is drawn clipped to the outline. Cells
/// the model cannot predict are NaN and counted in the picture's note; when none can be predicted, the error at
/// the face centre (or the first) is returned instead of a blank picture.
pub fn face_map(
    club: &ClubSpec,
    model: &dyn ImpactModel,
    delivery: &DeliveryInput,
    metric: MapMetric,
    cells: usize,
) -> Result<Heatmap, ImpactError> {
    let equipment = Equipment::new(club.clone());
    let n = cells.max(2);
    let (h0, h1, v0, v1) = club.face_outline.bounds_mm();
    let (dh, dv) = ((h1 - h0) / n as f64, (v1 - v0) / n as f64);
    let xs: Vec<f64> = (0..n).map(|i| h0 + (i as f64 + 0.5) * dh).collect();
    let ys: Vec<f64> = (0..n).map(|j| v0 + (j as f64 + 0.5) * dv).collect();
    let mut values = vec![vec![f64::NAN; n]; n];
    let (mut first_error, mut failed) = (None, 0);
    for (j, v) in ys.iter().enumerate() {
        for (i, h) in xs.iter().enumerate() {
            let Some(at) = sample_point(club, (*h, *v), (dh, dv)) else { continue };
            match value(metric, model, &equipment, delivery, at) {
                Ok(x) => values[j][i] = x,
                Err(e) => {
                    failed += 1;
                    first_error.get_or_insert(e);
                }
            }
        }
    }
    if !values.iter().flatten().any(|x| x.is_finite()) {
        return Err(match value(metric, model, &equipment, delivery, (0.0, 0.0)) {
            Err(e) => e,
            Ok(_) => first_error.unwrap_or(ImpactError::NotFinite { field: "map" }),
        });
    }
    let label = metric.label();
    let cg_mm = [-club.face.center_m.dot(&club.face.t0()) * 1e3, -club.face.center_m.dot(&club.face.u0()) * 1e3];
    Ok(Heatmap {
        // The toe (+h) is drawn right: the face of a right-handed club as seen from behind the head, looking
        // toward the target (from the ball, a right-handed club's toe is on the left).
        title: format!(
            "{}, {}: {}\n{}\n{}",
            club.name,
            model.name(),
            label,
            delivery_conditions(delivery, club.loft_deg()),
            FACE_SIDE
        ),
        x_label: "impact location toward the toe (mm)".into(),
        y_label: "impact location up the face (mm)".into(),
        value_label: label.into(),
        xs,
        ys,
        values,
        signed: metric.signed(),
        outline: club.face_outline.vertices_mm.clone(),
        markers: vec![("face centre".into(), [0.0, 0.0]), ("CG (behind the face)".into(), cg_mm)],
        note: first_error.map(|e| format!("{failed} cells on the face left blank: no prediction ({e})")),
    })
}

/// Which side of the face a map shows, in its title.
pub const FACE_SIDE: &str =
    "face of a right-handed club seen from behind the head, looking toward the target: toe right, heel left, crown up";

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::{ImpulseModel, ImpulseVariant};

    /// The 7-iron's map: cells off its outline are blank (its bounding box's corner beside the hosel, (-33, 27)
    /// mm, is off the face), the centre cell has a value, and signed metrics are the diverging ones.
    #[test]
    fn the_map_covers_the_face_only() {
        let club = ClubSpec::iron7();
        let model = ImpulseModel::new(ImpulseVariant::Adjusted);
        let d = DeliveryInput { club_speed_mph: 85.0, ..DeliveryInput::default() };
        let heat = face_map(&club, &model, &d, MapMetric::BallSpeed, 21).unwrap();
        assert!(heat.values[20][0].is_nan(), "the heel's top corner is off the face");
        assert!(heat.values[10][10].is_finite());
        assert!(heat.title.contains("club 85 mph") && heat.title.contains("dynamic loft"));
        assert!(MapMetric::Offline.signed() && !MapMetric::Carry.signed());
    }

    /// A model that cannot predict the toe half of the face.
    #[derive(Debug)]
    struct HeelOnly(ImpulseModel);

    impl ImpactModel for HeelOnly {
        fn name(&self) -> &'static str {
            "heel-only"
        }
        fn run(
            &self,
            state: &crate::impact::ImpactState,
            equipment: &Equipment,
            options: &crate::impact::RunOptions,
        ) -> Result<crate::impact::ModelRun, ImpactError> {
            if state.impact_h_m > 0.0 {
                return Err(ImpactError::Singular);
            }
            self.0.run(state, equipment, options)
        }
    }

    /// Cells the model cannot predict are blank and counted in the picture's note, never silently.
    #[test]
    fn blank_cells_are_said() {
        let club = ClubSpec::iron7();
        let d = DeliveryInput { club_speed_mph: 85.0, ..DeliveryInput::default() };
        let heat =
            face_map(&club, &HeelOnly(ImpulseModel::new(ImpulseVariant::Adjusted)), &d, MapMetric::Carry, 9).unwrap();
        let note = heat.note.clone().unwrap();
        assert!(note.contains("cells on the face left blank") && note.contains("singular"), "{note}");
        assert!(heat.values[4][0].is_finite() && heat.values[4][8].is_nan());
        assert!(heat.svg(800.0, 560.0).contains(&note));
    }
}
