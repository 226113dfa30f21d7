//! The research's findings, asserted: one test binary, a module per finding (research/README.md).

// The predictions the real-shot findings share.
#[path = "../../tests/predict/mod.rs"]
mod predict;

mod driver_axis;
mod driver_centre_sidespin;
mod flight_published;
mod gear_effect;
mod ground_part;
mod ground_parts;
mod identifiability;
mod identify_likelihood;
mod maw_published;
mod offcentre_iron;
mod offcentre_monitors;
mod players_matched;
mod pointer_bound;
mod real_shots;
mod tour_iron_spin;
mod wedge_spin;
