//! The `impactd` command line (clap derive), one file per command. Each command parses its flags, calls the
//! library and prints; the work itself is library code that tests drive in-process.

use std::process::ExitCode;

use anyhow::Result;
use clap::{Parser, Subcommand};

mod args;
mod bench;
mod eval;
mod flight;
mod flight_fit;
mod map;
mod plot;
mod predict;
mod schemas;

#[cfg(feature = "daemon")]
mod demo;
#[cfg(feature = "daemon")]
mod info;
#[cfg(feature = "daemon")]
mod recover;
#[cfg(feature = "daemon")]
mod replay;
#[cfg(feature = "daemon")]
mod run;
#[cfg(feature = "daemon")]
mod sim;

/// Predicts golf ball launch conditions from motion-capture samples of the clubhead.
#[derive(Debug, Parser)]
#[command(name = "impactd", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// JSONL deliveries in (stdin or --input), JSONL launch conditions out.
    Predict(predict::PredictArgs),
    /// Times each model in-process on a fixed spread of deliveries.
    Bench(bench::BenchArgs),
    /// Evaluations against synthetic truth.
    #[command(subcommand)]
    Eval(eval::EvalCommand),
    /// JSONL launches in (the fields `impactd predict` writes), JSONL trajectories out.
    Flight(flight::FlightArgs),
    /// Refit the flight model's coefficients to the TrackMan tour averages and show the fit.
    FlightFit(flight_fit::FlightFitArgs),
    /// A heatmap over the clubface (SVG) of a launch or flight number, for a delivery given by flags.
    Map(map::MapArgs),
    /// Pictures (SVG).
    #[command(subcommand)]
    Plot(plot::PlotCommand),
    /// Write the JSON Schemas of every message type.
    Schemas(schemas::SchemasArgs),
    /// The daemon: clubhead samples in on zenoh, predictions out, everything recorded.
    #[cfg(feature = "daemon")]
    Run(run::RunArgs),
    /// The daemon and a simulated rig in one process: zero setup.
    #[cfg(feature = "daemon")]
    Demo(demo::DemoArgs),
    /// A synthetic rig publishing clubhead samples at real rate, with the truth of each shot.
    #[cfg(feature = "daemon")]
    Sim(sim::SimArgs),
    /// The pipeline over a recording (MCAP) or a JSONL file of samples.
    #[cfg(feature = "daemon")]
    Replay(replay::ReplayArgs),
    /// Channels, counts, duration and shots of a recording.
    #[cfg(feature = "daemon")]
    Info(info::InfoArgs),
    /// Salvage a recording cut off by a crash (exit 0: nothing lost, 3: data lost).
    #[cfg(feature = "daemon")]
    Recover(recover::RecoverArgs),
}

/// Logs to stderr: at info (zenoh at warn), except for the demo, which prints its own lines; `RUST_LOG` overrides.
pub fn init_logging(cli: &Cli) {
    #[cfg(feature = "daemon")]
    let quiet = matches!(cli.command, Command::Demo(_));
    #[cfg(not(feature = "daemon"))]
    let quiet = {
        let _ = cli;
        false
    };
    let default_filter = if quiet { "warn" } else { "info,zenoh=warn" };
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| default_filter.into()),
        )
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .with_writer(std::io::stderr)
        .init();
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Predict(args) => predict::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Eval(command) => eval::run(&command),
        Command::Flight(args) => flight::run(&args),
        Command::FlightFit(args) => flight_fit::run(&args),
        Command::Map(args) => map::run(&args),
        Command::Plot(command) => plot::run(&command),
        Command::Schemas(args) => schemas::run(&args),
        #[cfg(feature = "daemon")]
        Command::Run(args) => run::run(&args),
        #[cfg(feature = "daemon")]
        Command::Demo(args) => demo::run(&args),
        #[cfg(feature = "daemon")]
        Command::Sim(args) => sim::run(&args),
        #[cfg(feature = "daemon")]
        Command::Replay(args) => replay::run(&args),
        #[cfg(feature = "daemon")]
        Command::Info(args) => info::run(&args),
        #[cfg(feature = "daemon")]
        Command::Recover(args) => recover::run(&args),
    }
}

/// Whether `err` comes from writing to a reader that went away (`impactd flight | head`).
pub fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|e| e.downcast_ref::<std::io::Error>().is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe))
}
