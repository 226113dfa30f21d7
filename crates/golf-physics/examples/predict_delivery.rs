//! Predicts the launch of one delivery with any model of the registry, and flies it.
//!
//! `cargo run -p golf-physics --example predict_delivery -- [CLUB] [MODEL] [CLUB_SPEED_MPH]`
//! (defaults: `driver slip 113`; clubs are the presets, `driver`, `iron7`, `sw`, ...).

use golf_physics::equipment::presets;
use golf_physics::flight::{Flight, LaunchState};
use golf_physics::impact::registry::{self, BuildOptions};
use golf_physics::impact::{Delivery, Equipment, LaunchMetrics};
use golf_physics::math::Vector3;
use golf_physics::units::mph_to_mps;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arg = |i: usize, default: &str| std::env::args().nth(i).unwrap_or_else(|| default.to_string());
    let (club_name, model_name) = (arg(1, "driver"), arg(2, registry::DEFAULT_MODEL));
    let speed_mph: f64 = arg(3, "113").parse()?;

    // A preset's club file (a club file's text works the same: `ClubFile::parse(&text)`).
    let club =
        presets::find(&club_name).ok_or_else(|| format!("no preset `{club_name}`: {}", presets::names()))?.load()?;
    // The model with the club file's own parameters for it (its `[slip]`, `[continuous]`, ... section).
    let model = registry::build_one(&model_name, &club, &BuildOptions::default())?;
    let equipment = Equipment::new(club.club.clone());

    // The clubhead at impact, as TrackMan reports it: speed, attack angle, path, face angle and dynamic loft,
    // struck 5 mm toward the toe.
    let delivery = Delivery {
        club_speed_mps: mph_to_mps(speed_mph),
        attack_angle_rad: (-1.3f64).to_radians(),
        club_path_rad: 0.0,
        face_angle_rad: 1f64.to_radians(),
        dynamic_loft_rad: (club.club.face.loft_rad + 2f64.to_radians()),
        impact_h_m: 0.005,
        impact_v_m: 0.0,
        club_angular_velocity_radps: Vector3::zeros(),
    };
    let state = delivery.to_state(&equipment)?;
    let launch = model.predict(&state, &equipment)?;
    let m = LaunchMetrics::from_ball(&launch.ball_velocity_mps, &launch.ball_spin_radps);
    println!("{} with {}, {speed_mph} mph:", club.club.name, model.name());
    println!(
        "  ball {:.1} mph, launch {:.1} deg, direction {:.1} deg, backspin {:.0} rpm, sidespin {:.0} rpm",
        m.ball_speed_mph, m.launch_angle_deg, m.launch_direction_deg, m.backspin_rpm, m.sidespin_rpm
    );

    let flight = Flight::default();
    let t =
        flight.fly(&LaunchState { velocity_mps: launch.ball_velocity_mps, spin_radps: launch.ball_spin_radps }, 0.0);
    println!(
        "  carry {:.1} yd, offline {:.1} yd, apex {:.1} yd, total {:.1} yd",
        t.carry_yd, t.offline_yd, t.apex_yd, t.total_yd
    );
    Ok(())
}
