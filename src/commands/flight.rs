//! `impactd flight`: JSONL launches in (the fields `impactd predict` writes), JSONL trajectories out.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;

use super::args::{exit_code, open_input, ConditionArgs};

#[derive(Debug, Args)]
pub struct FlightArgs {
    #[command(flatten)]
    pub conditions: ConditionArgs,
    /// Also output the path, sampled every this many seconds.
    #[arg(long)]
    pub points_s: Option<f64>,
    #[arg(long, short)]
    pub input: Option<PathBuf>,
}

pub fn run(args: &FlightArgs) -> Result<ExitCode> {
    let flight = impactd::flight::Flight { conditions: args.conditions.conditions()?, ..Default::default() };
    let every = args.points_s.unwrap_or(0.0);
    // The finest path sampling: a ball in flight for 10 s gives at most 10,000 points.
    const MIN_POINTS_S: f64 = 1e-3;
    if !every.is_finite() || (every != 0.0 && !(MIN_POINTS_S..=60.0).contains(&every)) {
        bail!("--points-s must be within {MIN_POINTS_S} and 60 s");
    }
    let input = open_input(args.input.as_deref())?;
    let tally = impactd::jsonl::process(
        "impactd flight",
        input,
        std::io::stdout().lock(),
        std::io::stderr().lock(),
        |l: impactd::wire::FlightInput| l.to_launch().map(|launch| flight.fly(&launch, every)),
    )?;
    Ok(exit_code(tally))
}
