//! `impactd plot`: pictures (SVG) of a model's forces through one impact, of flights, of strikes off the turf,
//! and of a ball on a rigid plate under Maw's model (seed Figure 3.4).

use std::io::BufRead;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::{Args, Subcommand};
use impactd::impact::Equipment;

use super::args::{load_club, open_input, write_output, ConditionArgs, DeliveryArgs};

#[derive(Debug, Subcommand)]
pub enum PlotCommand {
    /// A model resolved in time (continuous, maw, arakawa): normal and tangential force and ball spin through one
    /// impact.
    Forces(ForcesArgs),
    /// Side and top views of one or more shots: JSONL launches in (stdin or --input).
    Trajectory(TrajectoryArgs),
    /// Seed Figure 3.4: a ball on a rigid plate at 44 m/s and 30 degrees, elastic Maw against damped Maw.
    MawPlate(MawPlateArgs),
    /// The ground model's force on the head for a fat and a good strike, and the face angle and loft over time.
    Ground(super::plot_ground::GroundPlotArgs),
    /// Carry against side per club of recordings, with 1 and 2 SD ellipses and the target line.
    #[cfg(feature = "daemon")]
    Dispersion(super::plot_dispersion::DispersionArgs),
}

#[derive(Debug, Args)]
pub struct ForcesArgs {
    /// Club preset (driver, iron7) or a path to a club .toml file.
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
    /// Read launches from this file instead of stdin.
    #[arg(long, short)]
    pub input: Option<PathBuf>,
    /// Units of the axes and labels.
    #[arg(long, value_enum, default_value_t = impactd::session::Units::Imperial)]
    pub units: impactd::session::Units,
    /// Output SVG file.
    #[arg(short = 'o', long = "output", default_value = "trajectory.svg")]
    pub output: PathBuf,
}

#[derive(Debug, Args)]
pub struct MawPlateArgs {
    /// Output SVG file.
    #[arg(short = 'o', long = "output", default_value = "docs/maw-plate.svg")]
    pub output: PathBuf,
    /// Impact speed (m/s).
    #[arg(long, default_value_t = 44.0)]
    pub speed_mps: f64,
    /// Incidence from the plate's normal (deg).
    #[arg(long, default_value_t = 30.0)]
    pub incidence_deg: f64,
    /// Rings of Maw's model.
    #[arg(long, default_value_t = 20)]
    pub rings: usize,
}

pub fn run(command: &PlotCommand) -> Result<ExitCode> {
    match command {
        PlotCommand::Forces(args) => forces(args),
        PlotCommand::Trajectory(args) => trajectory(args),
        PlotCommand::MawPlate(args) => maw_plate(args),
        PlotCommand::Ground(args) => super::plot_ground::run(args),
        #[cfg(feature = "daemon")]
        PlotCommand::Dispersion(args) => super::plot_dispersion::run(args),
    }
}

/// Table 3.6's driver parameters with `--rings` rings.
fn maw_plate(args: &MawPlateArgs) -> Result<ExitCode> {
    use impactd::impact::continuous::law::maw::MawParams;
    let params = MawParams { rings: args.rings, ..MawParams::DRIVER };
    params.validate()?;
    let chart = impactd::offline::plot::maw_plate_chart(&params, args.speed_mps, args.incidence_deg);
    write_output(&args.output, &chart.svg(1000.0, 560.0))?;
    Ok(ExitCode::SUCCESS)
}

fn forces(args: &ForcesArgs) -> Result<ExitCode> {
    let loaded = load_club(&args.club)?;
    let club = loaded.club.clone();
    let model = super::args::one_model(&args.model, &loaded, impactd::impact::impulse::DEFAULT_COR)?;
    let equipment = Equipment::new(club.clone());
    let input = args.delivery.input();
    let state = impactd::predict::state_of(&input, &club, &equipment)?;
    let r = model.run(&state, &equipment, &impactd::impact::RunOptions::traced(2))?;
    let Some(mut chart) = impactd::offline::plot::forces_chart(&club.name, input.club_speed_mph, &r) else {
        anyhow::bail!("--model {} is not resolved in time: it has no forces to plot", args.model);
    };
    chart.title = format!(
        "{} ({})\n{}",
        chart.title,
        args.model,
        impactd::offline::plot::delivery_title(&input, club.loft_deg())
    );
    write_output(&args.output, &chart.svg(900.0, 520.0))?;
    Ok(ExitCode::SUCCESS)
}

fn trajectory(args: &TrajectoryArgs) -> Result<ExitCode> {
    let flight = args.conditions.flight(args.firmness)?;
    let mut flights = Vec::new();
    let mut clubs = Vec::new();
    for (i, line) in open_input(args.input.as_deref())?.lines().enumerate() {
        let line = line.context("reading input")?;
        if line.trim().is_empty() {
            continue;
        }
        let l: impactd::wire::FlightInput =
            impactd::jsonl::parse_line(&line).with_context(|| format!("line {}", i + 1))?;
        let launch = l.to_launch().map_err(|e| anyhow::anyhow!("line {}: {e}", i + 1))?;
        flights.push(flight.fly(&launch, 0.05));
        // The club a line names (its `club` field, or the labels' of a recorded launch): its shots share a colour.
        let v: serde_json::Value = serde_json::from_str(&line).unwrap_or_default();
        let club = v["labels"]["club"].as_str().or_else(|| v["club"].as_str()).unwrap_or_default();
        clubs.push(club.to_string());
    }
    if flights.is_empty() {
        bail!("no launches read");
    }
    let c = &args.conditions;
    let conditions = format!(
        "wind {:.1} m/s toward {:.0}° (0 tailwind, 90 to the right), {:.1} °C, humidity {:.0} %, altitude {:.0} m, {}firmness {:.2}",
        c.wind_mps,
        c.wind_dir_deg,
        c.temp_c,
        c.humidity,
        c.altitude_m,
        c.pressure_hpa.map_or(String::new(), |p| format!("{p:.0} hPa, ")),
        args.firmness
    );
    write_output(
        &args.output,
        &impactd::offline::plot::trajectories_figure(&flights, &clubs, args.units, Some(&conditions)),
    )?;
    Ok(ExitCode::SUCCESS)
}
