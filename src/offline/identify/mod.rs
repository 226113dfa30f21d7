//! Parameter identification and accuracy tables against measured launches (seed section 3.1.3).
//!
//! The seed records clubhead motion and a launch monitor's measurements of the same shots, compares each model's
//! predictions with them (Tables 3.2-3.7: measured mean, mean absolute error and standard deviation per launch
//! field, absolute and as a percentage of the measured mean) and identifies each model's parameters by
//! minimising eq. 3.13:
//!
//! `C = Σ_j Σ_i (1/n) |x_sim,i,j − x_exp,i,j| / mean(x_exp,i,1..n)`   (eq. 3.13)
//!
//! over the five launch fields `i` (ball speed, launch angle, launch direction, backspin, sidespin) and the `n`
//! shots `j`. Launch direction and sidespin are signed and scatter about zero, so the denominator here is the
//! mean of the *absolute* measured values (the seed's azimuth "mean" of 2.19 deg and sidespin "mean" of 490 rpm
//! can only be means of magnitudes); for ball speed, launch angle and backspin it is the ordinary mean.
//!
//! - [`dataset`]: shots as JSONL (`{"delivery": {...}, "measured": {...}}`) resolved to impact states.
//! - [`cost`]: eq. 3.13 and the seed's table statistics, evaluated in parallel over shots in a fixed order.
//! - [`params`]: each model's identifiable parameters with bounds ([`params::ParamSet`]).
//! - [`optimize`]: differential evolution (the global search) and Nelder-Mead (the local refinement).
//! - [`least_squares`]: Levenberg-Marquardt on reweighted residuals (the local refinement of a model resolved in
//!   time); [`local`]: the local stage, by either.
//! - [`objective`]: what a fit minimises: eq. 3.13 (the default) or the launch monitor's noise likelihood.
//! - [`fit`]: the seed's procedure (global, then local) and k-fold cross-validation.
//! - [`fisher`]: the Fisher information of the shots and each parameter's Cramér-Rao bound.
//! - [`synth`]: synthetic datasets with known parameters and launch-monitor noise.
//! - [`club_toml`]: the fitted parameters written as a club file.
//! - [`trackman_reading`]: TrackMan's loft and face angle (the contact point's) turned into the face centre's.
//!
//! Everything is deterministic for a seed: parallel sums are collected per shot and added in shot order.

pub mod by_club;
pub mod club_toml;
pub mod cost;
pub mod dataset;
pub mod fisher;
pub mod fit;
pub mod least_squares;
pub mod local;
pub mod objective;
pub mod optimize;
pub mod params;
pub mod synth;
pub mod trackman_reading;

pub use cost::{CostScales, FieldStats, ModelTable, FIELDS};
pub use dataset::{DatasetLine, Shot};
pub use fit::{FitOptions, FitReport};
pub use objective::Objective;
pub use params::{FitModel, ParamDef, ParamSpace};

/// Errors of the identification layer.
#[derive(Debug, thiserror::Error)]
pub enum IdentifyError {
    #[error("line {line}: {reason}")]
    Line { line: usize, reason: String },
    #[error(transparent)]
    FitModel(#[from] crate::impact::FitModelError),
    #[error("model `{model}` has no parameter `{name}` (it has: {known})")]
    UnknownParam { model: String, name: String, known: String },
    #[error("no shots to {0}")]
    NoShots(&'static str),
    #[error("{0} folds need at least as many shots")]
    TooFewShots(usize),
    #[error(transparent)]
    Impact(#[from] crate::impact::ImpactError),
    #[error(transparent)]
    Equipment(#[from] crate::equipment::EquipmentError),
    #[error("noise: {0}")]
    Noise(String),
    #[error("writing the club file: {0}")]
    Write(#[source] toml::ser::Error),
}
