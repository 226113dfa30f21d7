//! What the vertical and horizontal parts of the ground's force each do to a fat strike (research/ground-parts.md):
//! the lean of the force is bounded by eq. 4.4-4.9 in closed form, and each part turns the ball its own way. A
//! part acts alone through `PartOfGround` (research/tests/ground_part.rs), the model's force laws point by point.

#![allow(clippy::unwrap_used)]

use impactd::equipment::soil::SoilSpec;
use impactd::equipment::ClubSpec;
use impactd::impact::continuous::iron_ground::{reference_swing, GroundModel, GroundResult, PreparedGround};
use impactd::impact::{Equipment, LaunchMetrics};
use impactd::math::{Real, Vector3};

use crate::ground_part::PartOfGround;

/// Firm soil (Table 4.3) with both moduli scaled; `keep` the world components of the ground's force kept, `None`
/// for no ground.
fn prepared(eq: &Equipment, scale: Real, keep: Option<Vector3>) -> (PreparedGround, Option<Vector3>) {
    let mut m = GroundModel::new(SoilSpec::firm().with_moduli_scaled(scale));
    m.with_ground = keep.is_some();
    (m.prepare(eq).unwrap(), keep)
}

/// The strike `v_mm` up the face, with only the kept part of the ground's force acting (the model itself without
/// `keep`).
fn run(
    (p, keep): &(PreparedGround, Option<Vector3>),
    eq: &Equipment,
    v_mm: Real,
    trace_every: usize,
) -> (GroundResult, LaunchMetrics) {
    let state = reference_swing(0.0, v_mm).to_state(eq).unwrap();
    let r = match keep {
        Some(keep) => p.simulate_with(&state, trace_every, |ground| PartOfGround { ground, keep: *keep }),
        None => p.simulate(&state, trace_every),
    }
    .unwrap();
    let l = LaunchMetrics::from_ball(&r.launch.ball_velocity_mps, &r.launch.ball_spin_radps);
    (r, l)
}

/// Keeping every component is the seed's model, bit for bit; the vertical part alone has no horizontal impulse
/// and the horizontal part alone no vertical one.
#[test]
fn parts_keep_what_they_name() {
    let eq = Equipment::new(ClubSpec::iron7());
    let (plain, _) = run(&(GroundModel::new(SoilSpec::firm()).prepare(&eq).unwrap(), None), &eq, 15.0, 0);
    let (ones, _) = run(&prepared(&eq, 1.0, Some(Vector3::repeat(1.0))), &eq, 15.0, 0);
    assert_eq!(plain.launch.ball_velocity_mps, ones.launch.ball_velocity_mps);
    assert_eq!(plain.ground_impulse_n_s, ones.ground_impulse_n_s);
    assert_eq!(plain.launch.ball_spin_radps, ones.launch.ball_spin_radps);
    assert_eq!(plain.divot_length_mm, ones.divot_length_mm);
    let (v, _) = run(&prepared(&eq, 1.0, Some(Vector3::new(0.0, 1.0, 0.0))), &eq, 15.0, 0);
    let (h, _) = run(&prepared(&eq, 1.0, Some(Vector3::new(1.0, 0.0, 1.0))), &eq, 15.0, 0);
    let jv = v.ground_impulse_before_ball_n_s;
    let jh = h.ground_impulse_before_ball_n_s;
    assert!(jv.y > 0.05 && jv.x == 0.0 && jv.z == 0.0, "{jv:?}");
    assert!(jh.x < -0.02 && jh.y == 0.0, "{jh:?}");
    // The whole force's impulse before the ball lies between and near the parts' (the parts move the head
    // differently, so the sinkage differs a little).
    let jw = plain.ground_impulse_before_ball_n_s;
    assert!((jw.y / jv.y - 1.0).abs() < 0.1 && (jw.x / jh.x - 1.0).abs() < 0.1, "{jw:?} {jv:?} {jh:?}");
}

/// Eq. 4.4-4.9: each sole point's force leans Φ + θ back from the vertical (pressure along the inward normal,
/// shear tan Φ of it against the slip), so the resultant leans at most Φ + θ_LE; eq. 4.13's face force adds
/// under 1.5 N. With the 4° bounce and the face de-lofted 5.5° by the delivery (30.5° static, 25° delivered),
/// tan(30° − 1.5°) = 0.543; whatever the soil's strength, the ground's force before the ball leans no more.
#[test]
fn the_ground_force_leans_no_more_than_phi_plus_the_leading_edge() {
    let eq = Equipment::new(ClubSpec::iron7());
    let bound = (30.0f64 - 1.5).to_radians().tan();
    for scale in [1.0, 10.0] {
        let (r, _) = run(&prepared(&eq, scale, Some(Vector3::repeat(1.0))), &eq, 20.0, 1);
        let before: Vec<_> = r.trace.iter().take_while(|q| q.ball_normal_n == 0.0).collect();
        let peak = before.iter().map(|q| q.ground_vertical_n.hypot(q.ground_horizontal_n)).fold(0.0, Real::max);
        let lean = before
            .iter()
            .filter(|q| q.ground_vertical_n.hypot(q.ground_horizontal_n) > 0.05 * peak)
            .map(|q| (q.ground_horizontal_n - 1.5) / q.ground_vertical_n)
            .fold(0.0, Real::max);
        let j = r.ground_impulse_before_ball_n_s;
        println!("x{scale}: steepest lean {lean:.3} (bound {bound:.3}), impulse ratio {:.3}", -j.x / j.y);
        assert!(lean > 0.3 && lean <= bound, "x{scale}: {lean}");
        assert!(-j.x / j.y < bound, "x{scale}: {j:?}");
    }
}

/// What each part does at the top of the face (v = +20 mm) on firm soil x4 (the sinkage read in mm): the
/// vertical part pushes the head up, so the ball meets the face lower (faster) and the head turns toe-up and out
/// along the stiff shaft (draw, left); the horizontal part slows the head (slower ball) and holds the toe back
/// (fade). Together, as the vertical part is the larger, the fat strike draws and flies left.
#[test]
fn the_vertical_part_draws_and_the_horizontal_part_fades() {
    let eq = Equipment::new(ClubSpec::iron7());
    let (_, teed) = run(&prepared(&eq, 4.0, None), &eq, 20.0, 0);
    let (_, vert) = run(&prepared(&eq, 4.0, Some(Vector3::new(0.0, 1.0, 0.0))), &eq, 20.0, 0);
    let (_, horiz) = run(&prepared(&eq, 4.0, Some(Vector3::new(1.0, 0.0, 1.0))), &eq, 20.0, 0);
    let (whole_r, whole) = run(&prepared(&eq, 4.0, Some(Vector3::repeat(1.0))), &eq, 20.0, 0);
    let d = |l: &LaunchMetrics| {
        (l.ball_speed_mph - teed.ball_speed_mph, l.sidespin_rpm - teed.sidespin_rpm, l.backspin_rpm - teed.backspin_rpm)
    };
    let (dv, dh, dw) = (d(&vert), d(&horiz), d(&whole));
    println!("vertical {dv:?}, horizontal {dh:?}, whole {dw:?}");
    assert!(dv.0 > 2.0 && dv.1 < -200.0, "vertical part: faster ball, draw: {dv:?}");
    assert!(dh.0 < -1.0 && dh.1 > 50.0, "horizontal part: slower ball, fade: {dh:?}");
    assert!(dw.1 < dv.1 + dh.1 + 100.0 && dw.1 < 0.0, "whole: draw {dw:?}");
    assert!(dw.2 < -500.0, "backspin falls: {dw:?}");
    assert!(whole_r.face_angle_change_deg < 0.0, "face closes: {}", whole_r.face_angle_change_deg);
}
