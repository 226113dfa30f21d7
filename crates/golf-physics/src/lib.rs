//! `golf_physics` predicts how a golf ball leaves the clubface and where it flies, from the clubhead's state at
//! impact. The seed's driver with the adjusted impulse-momentum model (its Table 3.1 and 3.3), 113 mph, 13 deg of
//! dynamic loft and 1.3 deg down, launches the ball at 163.96 mph with 2447 rpm of backspin:
//!
//! ```
//! use golf_physics::equipment::ClubSpec;
//! use golf_physics::impact::{Delivery, Equipment, ImpactModel, ImpulseModel, ImpulseVariant, LaunchMetrics};
//! use golf_physics::math::Vector3;
//!
//! # fn main() -> Result<(), golf_physics::impact::ImpactError> {
//! let equipment = Equipment::new(ClubSpec::driver());
//! let delivery = Delivery {
//!     club_speed_mps: golf_physics::units::mph_to_mps(113.0),
//!     attack_angle_rad: (-1.3f64).to_radians(),
//!     club_path_rad: 0.0,
//!     face_angle_rad: 0.0,
//!     dynamic_loft_rad: 13f64.to_radians(),
//!     impact_h_m: 0.0,
//!     impact_v_m: 0.0,
//!     club_angular_velocity_radps: Vector3::zeros(),
//! };
//! let state = delivery.to_state(&equipment)?;
//! let launch = ImpulseModel::new(ImpulseVariant::Adjusted).predict(&state, &equipment)?;
//! let m = LaunchMetrics::from_ball(&launch.ball_velocity_mps, &launch.ball_spin_radps);
//! assert!((m.ball_speed_mph - 163.957).abs() < 1e-3);
//! assert!((m.backspin_rpm - 2447.3).abs() < 0.1);
//! # Ok(())
//! # }
//! ```
//!
//! ```text
//! clubhead samples (lab frame)
//!         v
//! kinematics: calibrate -> track -> detect impact -> extrapolate to t_impact -> ImpactState (world frame)
//!         v
//! impact models: ImpactModel::predict(&ImpactState, &Equipment) -> Launch (+ the club after impact)
//!         v                                   (impulse-momentum family; continuous two-layer ball)
//! flight: Launch -> Trajectory (carry, apex, land angle, offline)
//! ```
//!
//! [`pipeline`] runs the whole chain on one rig's samples, emitting the impact and launch messages of [`wire`]:
//! samples in, events out, no clocks and no IO. The crate reads no files and opens no sockets; the `impactd`
//! daemon (zenoh, MCAP recording, the CLI) is built on top of it. The examples (`cargo run -p golf-physics
//! --example ...`) predict one delivery (`predict_delivery`), fly a launch (`fly_launch`) and sweep the impact
//! location across the face (`face_sweep`).
//!
//! Frames (TrackMan's): the world has its origin at the ball, x toward the target, y up, z to the right of the
//! target line; the club frame sits at the head's CG and equals the world at a square address (z toward the toe).
//! Units are SI inside (m, s, kg, rad); `_mph`, `_rpm`, `_deg` and `_mm` appear only in names that say so.
//! The physics follows A. W. Caldwell, "Development and Comparison of 3D Dynamic Models of Golf Clubhead-Ball
//! Impacts", MASc thesis, University of Waterloo, 2023 (UWSpace,
//! <https://uwspace.uwaterloo.ca/items/90da9fb0-a7f3-4a5f-9002-e292ff1810c9>; "the seed"), chapters 3 and 4; each
//! model cites its equations beside its code.

#![warn(missing_docs)]
#![forbid(unsafe_code)]
#![cfg_attr(test, allow(clippy::unwrap_used))]

pub mod equipment;
pub mod face;
pub mod flight;
pub mod impact;
pub mod integrate;
pub mod kinematics;
pub mod math;
pub mod pipeline;
pub mod rng;
pub mod swing;
pub mod units;
pub mod wire;
