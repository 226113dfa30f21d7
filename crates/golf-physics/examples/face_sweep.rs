//! Sweeps the impact location across the face: how ball speed, launch, spin and carry change toward the toe,
//! the heel, high and low (gear effect on a curved driver face, the lost speed off-centre).
//!
//! `cargo run -p golf-physics --example face_sweep -- [CLUB] [MODEL]` (defaults: `driver slip`).

use golf_physics::equipment::presets;
use golf_physics::flight::{Flight, LaunchState};
use golf_physics::impact::registry::{self, BuildOptions};
use golf_physics::impact::{Delivery, Equipment, LaunchMetrics};
use golf_physics::math::Vector3;
use golf_physics::units::mph_to_mps;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arg = |i: usize, default: &str| std::env::args().nth(i).unwrap_or_else(|| default.to_string());
    let (club_name, model_name) = (arg(1, "driver"), arg(2, registry::DEFAULT_MODEL));
    let club =
        presets::find(&club_name).ok_or_else(|| format!("no preset `{club_name}`: {}", presets::names()))?.load()?;
    let model = registry::build_one(&model_name, &club, &BuildOptions::default())?;
    let equipment = Equipment::new(club.club.clone());
    let flight = Flight::default();

    // 100 mph, 1.3 deg down, square to the target, 3 deg more dynamic loft than the club's static loft.
    println!("{} with {}: impact location (mm, toe +, up +) -> launch", club.club.name, model.name());
    println!("  h_mm  v_mm   ball_mph  launch_deg  backspin_rpm  sidespin_rpm  carry_yd  offline_yd");
    for v_mm in [10.0, 0.0, -10.0] {
        for h_mm in [-20.0, -10.0, 0.0, 10.0, 20.0] {
            let delivery = Delivery {
                club_speed_mps: mph_to_mps(100.0),
                attack_angle_rad: (-1.3f64).to_radians(),
                club_path_rad: 0.0,
                face_angle_rad: 0.0,
                dynamic_loft_rad: club.club.face.loft_rad + 3f64.to_radians(),
                impact_h_m: h_mm * 1e-3,
                impact_v_m: v_mm * 1e-3,
                club_angular_velocity_radps: Vector3::zeros(),
            };
            // A location off the face (outside its outline or curvature) is refused with a reason.
            let launch = match delivery.to_state(&equipment).and_then(|s| model.predict(&s, &equipment)) {
                Ok(launch) => launch,
                Err(e) => {
                    println!("{h_mm:6.0}{v_mm:6.0}   refused: {e}");
                    continue;
                }
            };
            let m = LaunchMetrics::from_ball(&launch.ball_velocity_mps, &launch.ball_spin_radps);
            let t = flight
                .fly(&LaunchState { velocity_mps: launch.ball_velocity_mps, spin_radps: launch.ball_spin_radps }, 0.0);
            println!(
                "{h_mm:6.0}{v_mm:6.0}   {:8.1}  {:10.1}  {:12.0}  {:12.0}  {:8.1}  {:10.1}",
                m.ball_speed_mph, m.launch_angle_deg, m.backspin_rpm, m.sidespin_rpm, t.carry_yd, t.offline_yd
            );
        }
    }
    Ok(())
}
