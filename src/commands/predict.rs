//! `impactd predict`: JSONL deliveries in, JSONL launch conditions out.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;
use impactd::predict::Predictor;

use super::args::{exit_code, load_club, model_name, one_model, open_input, resolved_in_time};

#[derive(Debug, Args)]
pub struct PredictArgs {
    /// Club preset (driver, iron7) or a path to a club .toml file.
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// Impact model (standard, adjusted, slip, continuous, ...: `impact::registry`).
    #[arg(long, default_value = "adjusted", value_parser = model_name)]
    pub model: String,
    /// Coefficient of restitution along the face normal (seed eq. 3.6).
    #[arg(long, default_value_t = impactd::impact::impulse::DEFAULT_COR)]
    pub cor: f64,
    /// Read deliveries from this file instead of stdin.
    #[arg(long, short)]
    pub input: Option<PathBuf>,
    /// With a model resolved in time (continuous): add the normal and tangential force and the ball's spin over time.
    #[arg(long)]
    pub trace: bool,
}

pub fn run(args: &PredictArgs) -> Result<ExitCode> {
    if !(0.0..=1.0).contains(&args.cor) {
        bail!("--cor must be within 0 and 1, got {}", args.cor);
    }
    let loaded = load_club(&args.club)?;
    if args.trace && !resolved_in_time(&args.model) {
        bail!("--trace needs a model resolved in time (continuous), not {}", args.model);
    }
    let model = one_model(&args.model, &loaded, args.cor)?;
    let predictor = if args.trace { Predictor::Traced(model.as_ref()) } else { Predictor::Plain(model.as_ref()) };
    let input = open_input(args.input.as_deref())?;
    let tally =
        impactd::predict::run(&loaded.club, predictor, input, std::io::stdout().lock(), std::io::stderr().lock())?;
    Ok(exit_code(tally))
}
