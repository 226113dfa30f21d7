//! `impactd flight`: JSONL launches in (the fields `impactd predict` writes), each answered with its own fields
//! and its trajectory's, with the bounce and roll (with `--table`, a table in `--units`); or, with `--coefficients`,
//! the drag and lift coefficients the flight uses.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;
use impactd::flight::{aero, Flight};

use super::args::{exit_code, open_input, ConditionArgs};
use super::launch_table::TableLines;
use impactd::session::Units;

#[derive(Debug, Args)]
pub struct FlightArgs {
    #[command(flatten)]
    pub conditions: ConditionArgs,
    /// Firmness of the fairway the ball bounces and rolls on: 0 soft, 0.5 Penner's fairway, 1 firm.
    #[arg(long, default_value_t = 0.5)]
    pub firmness: f64,
    /// Print the drag and lift coefficients over a grid of airspeeds and spin ratios instead of flying.
    #[arg(long)]
    pub coefficients: bool,
    /// With --coefficients: JSON instead of a table.
    #[arg(long, requires = "coefficients")]
    pub json: bool,
    /// Also output the path, sampled every this many seconds.
    #[arg(long, value_parser = super::checked::seconds)]
    pub points_s: Option<f64>,
    /// Read launches from this file instead of stdin.
    #[arg(long, short)]
    pub input: Option<PathBuf>,
    /// Print a table to read instead of JSON lines (the JSON carries both unit systems).
    #[arg(long, conflicts_with_all = ["coefficients", "points_s"])]
    pub table: bool,
    /// Units of the table.
    #[arg(long, value_enum, default_value_t = Units::Imperial, requires = "table")]
    pub units: Units,
}

pub fn run(args: &FlightArgs) -> Result<ExitCode> {
    let flight = args.conditions.flight(args.firmness)?;
    if args.coefficients {
        return coefficients(&flight, args.json);
    }
    let every = args.points_s.unwrap_or(0.0);
    // The finest path sampling: a ball in flight for 10 s gives at most 10,000 points.
    const MIN_POINTS_S: f64 = 1e-3;
    if !every.is_finite() || (every != 0.0 && !(MIN_POINTS_S..=60.0).contains(&every)) {
        bail!("--points-s must be within {MIN_POINTS_S} and 60 s");
    }
    let input = open_input(args.input.as_deref())?;
    let out = std::io::stdout().lock();
    let out: Box<dyn std::io::Write> =
        if args.table { Box::new(TableLines::new(out, args.units)) } else { Box::new(out) };
    let tally = impactd::jsonl::process(
        "impactd flight",
        input,
        out,
        std::io::stderr().lock(),
        |line: serde_json::Map<String, serde_json::Value>| super::flight_lines::with_flight(line, &flight, every),
    )?;
    Ok(exit_code(tally))
}

/// The flight's `C_D` and `C_L` over [`aero::GRID_SPEEDS_MPS`] × [`aero::GRID_SPIN_RATIOS`] in its air.
fn coefficients(flight: &Flight, json: bool) -> Result<ExitCode> {
    let c = &flight.conditions;
    let grid = aero::grid(&flight.aero, flight.ball.radius_m, c.density_kg_m3(), c.viscosity_pa_s());
    if json {
        println!("{}", serde_json::to_string_pretty(&grid)?);
        return Ok(ExitCode::SUCCESS);
    }
    println!("C_D / C_L of `Aero::FITTED` (air {:.3} kg/m3); rows airspeed, columns spin ratio", c.density_kg_m3());
    print!("{:>7} {:>8}", "m/s", "Re");
    for s in aero::GRID_SPIN_RATIOS {
        print!(" {:>11}", format!("S {s:.2}"));
    }
    println!();
    for row in grid.chunks(aero::GRID_SPIN_RATIOS.len()) {
        print!("{:>7.0} {:>8.0}", row[0].speed_mps, row[0].reynolds);
        for p in row {
            print!(" {:>11}", format!("{:.3}/{:.3}", p.c_d, p.c_l));
        }
        println!();
    }
    Ok(ExitCode::SUCCESS)
}
