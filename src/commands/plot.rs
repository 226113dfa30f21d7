//! `impactd plot`: pictures (SVG) of the continuous model's forces and of flights.

use std::io::BufRead;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::{Args, Subcommand};
use impactd::impact::Equipment;

use super::args::{load_club, open_input, write_output, ConditionArgs, DeliveryArgs};

#[derive(Debug, Subcommand)]
pub enum PlotCommand {
    /// The continuous model's normal and tangential force and the ball's spin through one impact.
    Forces(ForcesArgs),
    /// Side and top views of one or more shots: JSONL launches in (stdin or --input).
    Trajectory(TrajectoryArgs),
}

#[derive(Debug, Args)]
pub struct ForcesArgs {
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// A model resolved in time (continuous, ...).
    #[arg(long, default_value = "continuous", value_parser = super::args::model_name)]
    pub model: String,
    #[command(flatten)]
    pub delivery: DeliveryArgs,
    /// Output SVG file.
    #[arg(short = 'o', long = "output", default_value = "forces.svg")]
    pub output: PathBuf,
}

#[derive(Debug, Args)]
pub struct TrajectoryArgs {
    #[command(flatten)]
    pub conditions: ConditionArgs,
    /// Firmness of the fairway the ball bounces and rolls on: 0 soft, 0.5 Penner's fairway, 1 firm.
    #[arg(long, default_value_t = 0.5)]
    pub firmness: f64,
    #[arg(long, short)]
    pub input: Option<PathBuf>,
    #[arg(short = 'o', long = "output", default_value = "trajectory.svg")]
    pub output: PathBuf,
}

pub fn run(command: &PlotCommand) -> Result<ExitCode> {
    match command {
        PlotCommand::Forces(args) => forces(args),
        PlotCommand::Trajectory(args) => trajectory(args),
    }
}

fn forces(args: &ForcesArgs) -> Result<ExitCode> {
    let loaded = load_club(&args.club)?;
    let club = loaded.club.clone();
    let model = super::args::one_model(&args.model, &loaded, impactd::impact::impulse::DEFAULT_COR)?;
    let equipment = Equipment::new(club.clone());
    let input = args.delivery.input();
    let state = impactd::predict::state_of(&input, &club, &equipment)?;
    let Some(r) = model.trace(&state, &equipment, 2) else {
        anyhow::bail!("--model {} is not resolved in time: it has no forces to plot", args.model);
    };
    let r = r?;
    let chart = impactd::plot::forces_chart(&club.name, input.club_speed_mph, &r);
    write_output(&args.output, &chart.svg(900.0, 520.0))?;
    Ok(ExitCode::SUCCESS)
}

fn trajectory(args: &TrajectoryArgs) -> Result<ExitCode> {
    let flight = args.conditions.flight(args.firmness)?;
    let mut flights = Vec::new();
    for (i, line) in open_input(args.input.as_deref())?.lines().enumerate() {
        let line = line.context("reading input")?;
        if line.trim().is_empty() {
            continue;
        }
        let l: impactd::wire::FlightInput =
            impactd::jsonl::parse_line(&line).with_context(|| format!("line {}", i + 1))?;
        let launch = l.to_launch().map_err(|e| anyhow::anyhow!("line {}: {e}", i + 1))?;
        flights.push(flight.fly(&launch, 0.05));
    }
    if flights.is_empty() {
        bail!("no launches read");
    }
    write_output(&args.output, &impactd::plot::trajectories_svg(&flights))?;
    Ok(ExitCode::SUCCESS)
}
