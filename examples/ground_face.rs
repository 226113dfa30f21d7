//! The iron-plus-ground model over the face (seed section 4.3, Figures 4.10-4.17), one swing, as JSON lines:
//! for each reading of the ball (the one-cycle reading of Table 3.5, the default, and the table as printed), each impact
//! location with and without ground on firm soil, fat and good strikes on every soil, and the sole tilted toe
//! down; then the leading edge's height. Usage, from the crate's root: `cargo run --release --example
//! ground_face`; `scripts/ground-table.py` turns the output into docs/ground.md and research/ground-findings.md
//! (scripts/make-docs.sh runs both).

#![allow(clippy::unwrap_used)]

use impactd::equipment::soil::SoilSpec;
use impactd::equipment::ClubSpec;
use impactd::flight::{Flight, LaunchState};
use impactd::impact::continuous::iron_ground::{reference_swing, GroundModel, GroundResult, PreparedGround};
use impactd::impact::continuous::{TwoLayerParams, TwoLayerReading};
use impactd::impact::{Equipment, LaunchMetrics};
use impactd::math::Real;
use serde_json::json;

fn shot(p: &PreparedGround, eq: &Equipment, flight: &Flight, h_mm: Real, v_mm: Real) -> serde_json::Value {
    let state = match reference_swing(h_mm, v_mm).to_state(eq) {
        Ok(s) => s,
        Err(e) => return json!({ "error": e.to_string() }),
    };
    let r: GroundResult = match p.simulate(&state, 0) {
        Ok(r) => r,
        Err(e) => return json!({ "error": e.to_string() }),
    };
    let l = LaunchMetrics::from_ball(&r.launch.ball_velocity_mps, &r.launch.ball_spin_radps);
    let t = flight
        .fly(&LaunchState { velocity_mps: r.launch.ball_velocity_mps, spin_radps: r.launch.ball_spin_radps }, 0.0);
    json!({
        "ball_speed_mph": l.ball_speed_mph, "launch_angle_deg": l.launch_angle_deg, "launch_direction_deg": l.launch_direction_deg,
        "backspin_rpm": l.backspin_rpm, "sidespin_rpm": l.sidespin_rpm, "carry_yd": t.carry_yd, "offline_yd": t.offline_yd,
        "strike": r.strike, "ground_contact_before_ball_ms": r.ground_contact_before_ball_ms,
        "club_speed_loss_mph": r.club_speed_loss_mph, "face_angle_change_deg": r.face_angle_change_deg,
        "dynamic_loft_change_deg": r.dynamic_loft_change_deg, "divot_depth_mm": r.divot_depth_mm,
        "divot_length_mm": r.divot_length_mm, "peak_ground_force_n": r.peak_ground_force_n,
        "ground_contact_ms": r.ground_contact_ms, "ball_contact_us": r.ball_contact_us,
        "impulse_before_ball_n_s": { "back": -r.ground_impulse_before_ball_n_s.x, "up": r.ground_impulse_before_ball_n_s.y },
    })
}

/// The variants the findings are measured on: the continuous model's ball read two ways, the one-cycle reading
/// of Table 3.5 (the default of every continuous model) and Table 3.5 as printed; and the default ball with the
/// leading edge 20 mm down the face from its centre (a measured 7-iron's; the preset takes 12 mm).
fn variants(club: &ClubSpec) -> Vec<(&'static str, Option<TwoLayerParams>, Real)> {
    vec![
        ("one_cycle", None, 0.012),
        ("table_3_5", Some(TwoLayerParams::preset(club, TwoLayerReading::Table)), 0.012),
        ("one_cycle_edge_20mm", None, 0.020),
    ]
}

fn main() {
    let eq = Equipment::new(ClubSpec::iron7());
    let flight = Flight::default();
    for (ball, params, edge_m) in variants(&eq.club) {
        let prepare = |soil: SoilSpec, with_ground: bool, params: Option<TwoLayerParams>, toe_down_deg: Real| {
            let mut m = GroundModel::new(soil);
            m.with_ground = with_ground;
            m.params = params;
            m.sole.toe_down_deg = toe_down_deg;
            m.sole.leading_edge_below_face_centre_m = edge_m;
            m.prepare(&eq).map_err(|e| e.to_string())
        };
        let (firm, none) =
            match (prepare(SoilSpec::firm(), true, params, 0.0), prepare(SoilSpec::firm(), false, params, 0.0)) {
                (Ok(a), Ok(b)) => (a, b),
                (Err(e), _) | (_, Err(e)) => {
                    eprintln!("{e}");
                    std::process::exit(1);
                }
            };
        for v in [-20.0, -15.0, -10.0, -5.0, 0.0, 5.0, 10.0, 15.0, 20.0] {
            for h in [-20.0, -10.0, 0.0, 10.0, 20.0] {
                let line = json!({
                    "kind": "face", "ball": ball, "soil": "firm", "h_mm": h, "v_mm": v,
                    "ground": shot(&firm, &eq, &flight, h, v), "no_ground": shot(&none, &eq, &flight, h, v),
                });
                println!("{line}");
            }
        }
        for soil in SoilSpec::PRESETS {
            let Ok(spec) = SoilSpec::preset(soil) else { continue };
            let Ok(p) = prepare(spec, true, params, 0.0) else { continue };
            for (name, v) in [("fat_top", 20.0), ("fat", 15.0), ("good", 0.0)] {
                println!(
                    "{}",
                    json!({ "kind": "soil", "ball": ball, "soil": soil, "strike_at": name, "v_mm": v,
                            "ground": shot(&p, &eq, &flight, 0.0, v) })
                );
            }
        }
        // The sole's heel-toe tilt (`[sole] toe_down_deg`): the toe digging first moves the ground's force toward
        // the toe, the direction that opens the face.
        for toe_down_deg in [0.0, 5.0, 10.0].into_iter().filter(|_| edge_m == 0.012) {
            let Ok(p) = prepare(SoilSpec::firm(), true, params, toe_down_deg) else { continue };
            for v in [10.0, 20.0] {
                println!(
                    "{}",
                    json!({ "kind": "toe_down", "ball": ball, "toe_down_deg": toe_down_deg, "h_mm": 0.0, "v_mm": v,
                            "ground": shot(&p, &eq, &flight, 0.0, v), "no_ground": shot(&none, &eq, &flight, 0.0, v) })
                );
            }
        }
    }
    // The leading edge's height is the one club dimension that decides which strikes are fat: a measured
    // 7-iron's face centre sits ~20 mm up the face from the leading edge (the preset takes 12 mm).
    for le_mm in [12.0, 20.0] {
        let make = |with_ground: bool| {
            let mut m = GroundModel::new(SoilSpec::firm());
            m.sole.leading_edge_below_face_centre_m = le_mm * 1e-3;
            m.with_ground = with_ground;
            m.prepare(&eq)
        };
        let (Ok(g), Ok(n)) = (make(true), make(false)) else { continue };
        for v in [-15.0, -10.0, -5.0, 0.0, 5.0, 10.0] {
            let line = json!({
                "kind": "leading_edge", "ball": "one_cycle", "leading_edge_below_face_centre_mm": le_mm,
                "h_mm": 0.0, "v_mm": v,
                "ground": shot(&g, &eq, &flight, 0.0, v), "no_ground": shot(&n, &eq, &flight, 0.0, v),
            });
            println!("{line}");
        }
    }
}
