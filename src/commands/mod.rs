//! The `impactd` command line (clap derive), one file per command. Each command parses its flags, calls the
//! library and prints; the work itself is library code that tests drive in-process.

use std::process::ExitCode;

use anyhow::Result;
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};

mod args;
mod bench;
mod bench_baseline;
#[cfg(feature = "daemon")]
mod calibrate;
mod checked;
mod compare;
mod compare_clubs;
#[cfg(feature = "daemon")]
mod error;
mod eval;
mod fit;
mod flight;
mod flight_fit;
mod flight_lines;
mod launch_table;
mod line_writer;
mod map;
mod models;
mod plot;
#[cfg(feature = "daemon")]
mod plot_dispersion;
mod plot_ground;
mod predict;
mod progress;
mod schemas;
mod synth;

#[cfg(feature = "daemon")]
mod bridge;
#[cfg(feature = "daemon")]
mod capture_check;
#[cfg(feature = "daemon")]
mod demo;
#[cfg(feature = "daemon")]
mod export;
#[cfg(feature = "daemon")]
mod import;
#[cfg(feature = "daemon")]
mod info;
#[cfg(feature = "daemon")]
mod recover;
#[cfg(feature = "daemon")]
mod replay;
#[cfg(feature = "daemon")]
mod replay_pause;
#[cfg(feature = "daemon")]
mod run;
#[cfg(feature = "daemon")]
mod session;
#[cfg(feature = "daemon")]
mod sim;
#[cfg(feature = "daemon")]
mod watch;

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
    /// Each model's accuracy against measured launches (the seed's Tables 3.2-3.7).
    Compare(compare::CompareArgs),
    /// Identify a model's parameters from measured launches (eq. 3.13) and write the fitted club file.
    Fit(fit::FitArgs),
    /// A synthetic dataset of measured launches (known parameters plus launch-monitor noise).
    Synth(synth::SynthArgs),
    /// Write the JSON Schemas of every message type.
    Schemas(schemas::SchemasArgs),
    /// The impact models of the registry (or the club-file sections they read, the club presets, the bare names).
    Models(models::ModelsArgs),
    /// The daemon: clubhead samples in on zenoh, predictions out, everything recorded.
    #[cfg(feature = "daemon")]
    Run(run::RunArgs),
    /// Motion-capture servers (OptiTrack NatNet, Qualisys QTM, Vicon DataStream) to clubhead samples on zenoh.
    #[cfg(feature = "daemon")]
    #[command(subcommand)]
    Bridge(bridge::BridgeCommand),
    /// The daemon and a simulated rig in one process: zero setup.
    #[cfg(feature = "daemon")]
    Demo(demo::DemoArgs),
    /// A synthetic rig publishing clubhead samples at real rate, with the truth of each shot.
    #[cfg(feature = "daemon")]
    Sim(sim::SimArgs),
    /// The pipeline over a recording (MCAP), a JSONL file of samples or a capture (C3D, TRC, pose table).
    #[cfg(feature = "daemon")]
    Replay(replay::ReplayArgs),
    /// Channels, counts, duration and shots of a recording.
    #[cfg(feature = "daemon")]
    Info(info::InfoArgs),
    /// A capture as clubhead samples (JSONL): C3D or TRC markers with a marker set fitted to each frame, or a pose table.
    #[cfg(feature = "daemon")]
    Import(import::ImportArgs),
    /// Calibration from static trials (C3D): a marker set, `club_from_body`, `world_from_lab`.
    #[cfg(feature = "daemon")]
    #[command(subcommand)]
    Calibrate(calibrate::CalibrateCommand),
    /// Salvage a recording cut off by a crash (exit 0: nothing lost, 3: data lost).
    #[cfg(feature = "daemon")]
    Recover(recover::RecoverArgs),
    /// A fitting session's numbers per club, player or tag: TrackMan's metrics, gapping and mishits.
    #[cfg(feature = "daemon")]
    Session(session::SessionArgs),
    /// A recording's shots in another program's layout (TrackMan Performance Studio's CSV).
    #[cfg(feature = "daemon")]
    Export(export::ExportArgs),
    /// A live table of each shot as it lands: TrackMan's metrics, one line a swing.
    #[cfg(feature = "daemon")]
    Watch(watch::WatchArgs),
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

/// Parses the process's arguments. Every command accepts negative numbers as values (`--cor -0.2`,
/// `--attack-angle-deg -5`), as the field's tools do; clap's own errors exit 2 with usage.
pub fn parse() -> Cli {
    let matches = allow_negative_numbers(Cli::command()).get_matches();
    Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit())
}

fn allow_negative_numbers(cmd: clap::Command) -> clap::Command {
    cmd.allow_negative_numbers(true).mut_subcommands(allow_negative_numbers)
}

/// An error and its causes on one line, each cause once: a cause whose text the line already holds (an error
/// that prints its source in its own message) is not repeated.
pub fn error_text(err: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in err.chain() {
        let part = cause.to_string();
        if text.contains(&part) {
            continue;
        }
        if !text.is_empty() {
            text += ": ";
        }
        text += &part;
    }
    text
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
        Command::Compare(args) => compare::run(&args),
        Command::Fit(args) => fit::run(&args),
        Command::Synth(args) => synth::run(&args),
        Command::Schemas(args) => schemas::run(&args),
        Command::Models(args) => models::run(&args),
        #[cfg(feature = "daemon")]
        Command::Run(args) => run::run(&args),
        #[cfg(feature = "daemon")]
        Command::Bridge(command) => bridge::run(&command),
        #[cfg(feature = "daemon")]
        Command::Demo(args) => demo::run(&args),
        #[cfg(feature = "daemon")]
        Command::Sim(args) => sim::run(&args),
        #[cfg(feature = "daemon")]
        Command::Replay(args) => replay::run(&args),
        #[cfg(feature = "daemon")]
        Command::Info(args) => info::run(&args),
        #[cfg(feature = "daemon")]
        Command::Import(args) => import::run(&args),
        #[cfg(feature = "daemon")]
        Command::Calibrate(command) => calibrate::run(&command),
        #[cfg(feature = "daemon")]
        Command::Recover(args) => recover::run(&args),
        #[cfg(feature = "daemon")]
        Command::Session(args) => session::run(&args),
        #[cfg(feature = "daemon")]
        Command::Export(args) => export::run(&args),
        #[cfg(feature = "daemon")]
        Command::Watch(args) => watch::run(&args),
    }
}

/// Whether `err` comes from writing to a reader that went away (`impactd flight | head`).
pub fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|e| e.downcast_ref::<std::io::Error>().is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression: "No such file or directory (os error 2): No such file or directory (os error 2)" - an error
    /// that prints its source, shown with its chain, said the cause twice.
    #[test]
    fn each_cause_is_printed_once() {
        #[derive(Debug, thiserror::Error)]
        #[error("reading x.mcap: {source}")]
        struct Reading {
            source: std::io::Error,
        }
        let io = std::io::Error::from(std::io::ErrorKind::NotFound);
        let err = anyhow::Error::new(Reading { source: io }).context("replay");
        let text = error_text(&err);
        assert_eq!(text.matches("not found").count(), 1, "{text}");
        assert!(text.starts_with("replay: reading x.mcap: "), "{text}");
    }

    /// Every argument of every command has a help text (its default is shown beside it by clap).
    #[test]
    fn every_argument_has_help() {
        fn walk(cmd: &clap::Command, path: &str, missing: &mut Vec<String>) {
            for arg in cmd.get_arguments() {
                let id = arg.get_id().as_str();
                if id != "help" && id != "version" && arg.get_help().is_none() {
                    missing.push(format!("{path} {id}"));
                }
            }
            for sub in cmd.get_subcommands() {
                walk(sub, &format!("{path} {}", sub.get_name()), missing);
            }
        }
        let cmd = Cli::command();
        cmd.clone().debug_assert();
        let mut missing = Vec::new();
        walk(&cmd, "impactd", &mut missing);
        assert!(missing.is_empty(), "arguments without help: {missing:?}");
    }

    /// Regression: `synth --help` showed the noise default as `0.5 0.2 0.3 150 150`, which `--noise` refuses (it
    /// takes the five numbers comma-separated).
    #[test]
    fn synth_noise_default_is_shown_as_the_flag_takes_it() {
        let mut cmd = Cli::command();
        let help = cmd.find_subcommand_mut("synth").map(|c| c.render_long_help().to_string()).unwrap_or_default();
        assert!(help.contains("[default: 0.5,0.2,0.3,150,150]"), "{help}");
        assert!(!help.contains("0.5 0.2"), "{help}");
        let parsed = Cli::try_parse_from(["impactd", "synth", "--noise", "0.5,0.2,0.3,150,150"]);
        let default = impactd::offline::identify::synth::LmNoise::default().as_array().to_vec();
        assert!(matches!(parsed, Ok(Cli { command: Command::Synth(ref a) }) if a.noise == default), "{parsed:?}");
        let unset = Cli::try_parse_from(["impactd", "synth"]);
        assert!(matches!(unset, Ok(Cli { command: Command::Synth(ref a) }) if a.noise == default), "{unset:?}");
    }

    #[test]
    fn negative_numbers_are_values() {
        let m = allow_negative_numbers(Cli::command())
            .try_get_matches_from(["impactd", "predict", "--cor", "-0.2"])
            .map(|m| Cli::from_arg_matches(&m));
        assert!(matches!(m, Ok(Ok(Cli { command: Command::Predict(ref a) })) if a.cor == -0.2), "{m:?}");
    }
}
