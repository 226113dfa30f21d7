//! What the vertical and the horizontal parts of the ground's force each do to a fat strike (seed section 4.3),
//! as JSON lines: the swing of examples/ground_face struck 5-20 mm up the face on Table 4.3's firm soil with its
//! moduli scaled by 1, 4 and 10 (4 is the firm soil with the sinkage read in mm), run with the whole ground
//! force, its vertical part alone and its horizontal part alone (each point's force of the model's force laws
//! with only those world components kept: `PartOfGround`, research/tests/ground_part.rs), and without ground.
//! Usage, from the crate's root: `cargo run --release --example ground_parts`; `research/scripts/ground-parts.py` turns
//! the output into research/ground-parts.md (scripts/make-docs.sh runs both).

#![allow(clippy::unwrap_used)]

use impactd::equipment::soil::SoilSpec;
use impactd::equipment::ClubSpec;
use impactd::flight::{Flight, LaunchState};
use impactd::impact::continuous::iron_ground::{reference_swing, GroundModel, PreparedGround};
use impactd::impact::{Equipment, LaunchMetrics};
use impactd::math::{Real, Vector3};
use serde_json::json;

#[path = "../research/tests/ground_part.rs"]
mod ground_part;
use ground_part::PartOfGround;

/// One shot `v_mm` up the face with the world components `keep` of the ground's force (`None`: the model alone).
fn shot(p: &PreparedGround, keep: Option<Vector3>, eq: &Equipment, flight: &Flight, v_mm: Real) -> serde_json::Value {
    let state = reference_swing(0.0, v_mm).to_state(eq).unwrap();
    let r = match keep {
        Some(keep) => p.simulate_with(&state, 1, |ground| PartOfGround { ground, keep }),
        None => p.simulate(&state, 1),
    }
    .unwrap();
    let l = LaunchMetrics::from_ball(&r.launch.ball_velocity_mps, &r.launch.ball_spin_radps);
    let t = flight
        .fly(&LaunchState { velocity_mps: r.launch.ball_velocity_mps, spin_radps: r.launch.ball_spin_radps }, 0.0);
    // The steepest the ground's force leans from the vertical before the ball (while above 5 % of its peak).
    let before: Vec<_> = r.trace.iter().take_while(|q| q.ball_normal_n == 0.0).collect();
    let peak = before.iter().map(|q| q.ground_vertical_n.hypot(q.ground_horizontal_n)).fold(0.0, Real::max);
    let max_ratio = before
        .iter()
        .filter(|q| q.ground_vertical_n.hypot(q.ground_horizontal_n) > 0.05 * peak && q.ground_vertical_n > 0.0)
        .map(|q| q.ground_horizontal_n / q.ground_vertical_n)
        .fold(0.0, Real::max);
    let j = r.ground_impulse_before_ball_n_s;
    json!({
        "ball_speed_mph": l.ball_speed_mph, "backspin_rpm": l.backspin_rpm, "sidespin_rpm": l.sidespin_rpm,
        "launch_direction_deg": l.launch_direction_deg, "carry_yd": t.carry_yd, "offline_yd": t.offline_yd,
        "club_speed_loss_mph": r.club_speed_loss_mph, "face_angle_change_deg": r.face_angle_change_deg,
        "dynamic_loft_change_deg": r.dynamic_loft_change_deg,
        "impulse_before_ball_n_s": { "back": -j.x, "up": j.y, "toward_toe": j.z },
        "max_horizontal_over_vertical": max_ratio,
        "ground_contact_before_ball_ms": r.ground_contact_before_ball_ms,
    })
}

fn main() {
    let eq = Equipment::new(ClubSpec::iron7());
    let flight = Flight::default();
    let prepare = |scale: Real, with_ground: bool| {
        let mut m = GroundModel::new(SoilSpec::firm().with_moduli_scaled(scale));
        m.with_ground = with_ground;
        m.prepare(&eq).unwrap()
    };
    let none = prepare(1.0, false);
    let parts = [
        ("whole", Vector3::new(1.0, 1.0, 1.0)),
        ("vertical", Vector3::new(0.0, 1.0, 0.0)),
        ("horizontal", Vector3::new(1.0, 0.0, 1.0)),
    ];
    for v in [5.0, 10.0, 15.0, 20.0] {
        println!("{}", json!({ "kind": "no_ground", "v_mm": v, "shot": shot(&none, None, &eq, &flight, v) }));
    }
    for scale in [1.0, 4.0, 10.0] {
        let p = prepare(scale, true);
        for (part, keep) in parts {
            for v in [5.0, 10.0, 15.0, 20.0] {
                println!(
                    "{}",
                    json!({ "kind": "part", "scale": scale, "part": part, "v_mm": v,
                            "shot": shot(&p, Some(keep), &eq, &flight, v) })
                );
            }
        }
    }
}
