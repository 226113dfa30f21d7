//! Flies a ball from launch-monitor numbers: carry, apex, landing, bounce and roll, and the path.
//!
//! `cargo run -p golf-physics --example fly_launch -- [BALL_MPH] [LAUNCH_DEG] [BACKSPIN_RPM] [SIDESPIN_RPM]`
//! (defaults: a tour driver, `167 10.9 2686 0`).

use golf_physics::flight::{Flight, LaunchState};
use golf_physics::units::mph_to_mps;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arg = |i: usize, default: f64| -> Result<f64, std::num::ParseFloatError> {
        std::env::args().nth(i).map_or(Ok(default), |a| a.parse())
    };
    let (speed_mph, launch_deg, backspin_rpm, sidespin_rpm) =
        (arg(1, 167.0)?, arg(2, 10.9)?, arg(3, 2686.0)?, arg(4, 0.0)?);

    // The default flight: the seed's ball, sea-level air at 20 C, no wind, fairway turf.
    let flight = Flight::default();
    let launch = LaunchState::from_metrics(mph_to_mps(speed_mph), launch_deg, 0.0, backspin_rpm, sidespin_rpm);
    // Sample the path every 0.5 s (0: landing numbers only).
    let t = flight.fly(&launch, 0.5);
    println!(
        "carry {:.1} yd, offline {:.1} yd, apex {:.1} yd, hang {:.2} s, landing {:.1} deg at {:.1} m/s",
        t.carry_yd, t.offline_yd, t.apex_yd, t.hang_time_s, t.land_angle_deg, t.land_speed_mps
    );
    println!("total {:.1} yd (roll {:.1} yd)", t.total_yd, t.roll_yd);
    for [t_s, x_m, y_m, z_m] in &t.points {
        println!("  t {t_s:4.1} s: {x_m:6.1} m out, {y_m:5.1} m up, {z_m:5.1} m right");
    }
    Ok(())
}
