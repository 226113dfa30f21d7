//! `impactd predict`: JSONL deliveries in, JSONL launch conditions out (or, with `--table`, a table in
//! `--units`).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;
use impactd::predict::Predictor;
use impactd::session::Units;

use super::args::{exit_code, load_club, model_name, open_input, resolved_in_time, ConditionArgs};
use super::launch_table::TableLines;

#[derive(Debug, Args)]
pub struct PredictArgs {
    /// Club preset (driver, iron7) or a path to a club .toml file.
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// Impact model (standard, adjusted, slip, continuous, ...: `impact::registry`); a group (`both`) or a
    /// comma-separated list answers each line once per model, each answer naming its `model`.
    #[arg(long, default_value = impactd::impact::registry::DEFAULT_MODEL, value_parser = model_name)]
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
    /// With --model ground: the turf, soft, medium or firm (Table 4.3), a soil .toml file, or none (the ball
    /// on a tee, no ground).
    #[arg(long)]
    pub soil: Option<String>,
    /// Also fly each ball: add carry, total, apex, offline, hang time and land angle to each line.
    #[arg(long)]
    pub flight: bool,
    /// With --flight: firmness of the fairway (0 soft, 0.5 Penner's fairway, 1 firm).
    #[arg(long, default_value_t = 0.5, requires = "flight")]
    pub firmness: f64,
    #[command(flatten)]
    pub conditions: ConditionArgs,
    /// Print a table to read instead of JSON lines (the JSON carries both unit systems).
    #[arg(long)]
    pub table: bool,
    /// Units of the table.
    #[arg(long, value_enum, default_value_t = Units::Imperial, requires = "table")]
    pub units: Units,
}

pub fn run(args: &PredictArgs) -> Result<ExitCode> {
    if !(0.0..=1.0).contains(&args.cor) {
        bail!("--cor must be within 0 and 1, got {}", args.cor);
    }
    let mut loaded = load_club(&args.club)?;
    super::args::set_soil(&mut loaded, args.soil.as_deref(), &args.model)?;
    if args.trace && !resolved_in_time(&args.model) {
        bail!("--trace needs a model resolved in time (continuous, ground), not {}", args.model);
    }
    // One model, or a group or list of them (`both`): each line is answered by each, naming it.
    let options = impactd::impact::registry::BuildOptions { cor: args.cor, ..Default::default() };
    let models = impactd::impact::registry::build(&args.model, &loaded, &options)?;
    let predictors: Vec<Predictor<'_>> = models
        .iter()
        .map(|m| if args.trace { Predictor::Traced(m.as_ref()) } else { Predictor::Plain(m.as_ref()) })
        .collect();
    let input = open_input(args.input.as_deref())?;
    let (out, err) = (std::io::stdout().lock(), std::io::stderr().lock());
    let out: Box<dyn std::io::Write> =
        if args.table { Box::new(TableLines::new(out, args.units)) } else { Box::new(out) };
    let tally = if args.flight {
        let lines = super::flight_lines::FlightLines::new(out, args.conditions.flight(args.firmness)?);
        impactd::predict::run_models(&loaded.club, &predictors, input, lines, err)?
    } else {
        impactd::predict::run_models(&loaded.club, &predictors, input, out, err)?
    };
    Ok(exit_code(tally))
}
