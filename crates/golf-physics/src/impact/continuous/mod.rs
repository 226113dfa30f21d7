//! Continuous impact models (seed section 3.2 and chapter 4): the collision resolved in time.
//!
//! Each model is an [`Assembly`] of parts behind small traits, integrated by the assembly's multi-rate stepping
//! ([`stepping`]: `Assembly::run_stepped`, classical Runge-Kutta's stages with a policy choosing each step,
//! events, the ground's forces held):
//!
//! - [`law`]: the contact law, normal and tangential force (eq. 3.14-3.15 in [`law::volumetric`]);
//! - [`ball`]: rigid, or two-layer (core and cover, Table 3.5);
//! - [`club`]: a free head, or the head on a flexible shaft ([`club::ShaftClub`], its modes by exponential time
//!   differencing: [`shaft`]);
//! - [`ground`]: none, or ground reaction on the head (the soil, [`ground::SoilGround`]);
//! - [`surface`]: the face's contact geometry (volume of intersection, its centroid, the normal).
//!
//! Models: [`ContinuousModel`], the two-layer model of section 3.2.1 ([`two_layer`]); [`hertzian::HertzModel`],
//! Maw's (3.2.2) and Arakawa's (3.2.3) models on a rigid ball, [`plate`], a ball on a rigid plate for them;
//! and [`iron_ground::GroundModel`], an iron on a flexible shaft striking a ball on turf (chapter 4), on the
//! multi-rate stepping.

pub mod assembly;
pub mod ball;
pub mod club;
mod course;
pub mod ground;
pub mod hertzian;
pub mod iron_ground;
pub mod law;
pub mod plate;
pub mod shaft;
mod start;
pub mod stepping;
pub mod surface;
pub mod two_layer;

pub use assembly::{Assembly, ContactForces, ContinuousResult, Integration, TracePoint};
pub use start::Start;
pub use two_layer::{ContinuousModel, TwoLayerContact, TwoLayerParams, TwoLayerReading};
