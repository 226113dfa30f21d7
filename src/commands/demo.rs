//! `impactd demo`: the daemon and a simulated rig in one process, zero setup.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;
use impactd::daemon::demo::{demo, DemoOptions};
use impactd::daemon::sim::SimOptions;
use impactd::daemon::DaemonConfig;

use super::args::load_club;
use super::checked;
use super::error::CliError;
use super::run::{runtime, shutdown_signal, BridgeArgs};

/// Where the demo records when not told (`--record`): replaced by each demo.
pub const DEFAULT_RECORDING: &str = "impactd-demo.mcap";

#[derive(Debug, Args)]
pub struct DemoArgs {
    /// Shots to swing.
    #[arg(long, default_value_t = 5, value_parser = checked::count)]
    pub shots: u64,
    /// Club preset or club file.
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// Print predictions as JSON.
    #[arg(long)]
    pub json: bool,
    /// The recording's path (default impactd-demo.mcap, which each demo replaces).
    #[arg(long)]
    pub record: Option<PathBuf>,
    /// Replace a recording named with --record if it exists (otherwise an existing file stops the demo, as with
    /// `run --record`); the default recording is always replaced.
    #[arg(long)]
    pub overwrite: bool,
    /// Random seed of the swings.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Capture rate (Hz).
    #[arg(long, default_value_t = 720.0, value_parser = checked::capture_rate_hz)]
    pub rate: f64,
    #[command(flatten)]
    pub bridges: BridgeArgs,
}

pub fn run(args: &DemoArgs) -> Result<ExitCode> {
    if args.shots == 0 {
        bail!("--shots must be at least 1");
    }
    let loaded = load_club(&args.club)?;
    let tuning = Some(impactd::impact::impulse::ImpulseTuning::from_sections(&loaded.club, &loaded.sections)?);
    let club = loaded.club;
    // The demo's own recording is a scratch file each demo replaces; one named with --record is kept unless asked.
    let (record, overwrite) = match &args.record {
        Some(path) => (path.clone(), args.overwrite),
        None => (PathBuf::from(DEFAULT_RECORDING), true),
    };
    let mut config = DaemonConfig::default();
    config.rigs[0].club = args.club.clone();
    args.bridges.apply(&mut config)?;
    if let Some(a) = args.bridges.web(&config) {
        eprintln!("impactd demo: the bay screen is on http://{a}/ (Ctrl-C stops the demo after the shots)");
    }
    let sim =
        SimOptions { club, tuning, shots: args.shots, seed: args.seed, rate_hz: args.rate, ..SimOptions::default() };
    eprintln!(
        "impactd demo: daemon and a synthetic {} rig on loopback zenoh, {} shots at {} Hz; recording to {}",
        args.club,
        args.shots,
        args.rate,
        record.display()
    );
    sim.check().map_err(CliError::from)?;
    let rt = runtime()?;
    let summary = rt.block_on(demo(
        DemoOptions {
            config: config.clone(),
            sim,
            record: Some(record.clone()),
            overwrite,
            json: args.json,
            foxglove: args.bridges.foxglove.clone(),
            web: args.bridges.web(&config),
        },
        shutdown_signal(),
    ))?;
    let (shots, predictions): (u64, u64) =
        summary.rigs.values().fold((0, 0), |(s, p), c| (s + c.shots, p + c.predictions));
    if let Some(e) = summary.recorder.as_ref().and_then(|r| r.error.as_ref()) {
        eprintln!("{predictions} of {} shots predicted; the recording {} failed: {e}", args.shots, record.display());
        return Ok(ExitCode::from(1));
    }
    eprintln!(
        "{predictions} of {} shots predicted ({shots} impacts detected). Recording: {} (try `impactd info {}` or open it in Foxglove)",
        args.shots,
        record.display(),
        record.display()
    );
    let mut flagged = std::collections::BTreeMap::<&str, u64>::new();
    for (name, n) in summary.rigs.values().flat_map(|c| c.flagged.iter()) {
        *flagged.entry(name.as_str()).or_default() += n;
    }
    if !flagged.is_empty() {
        let list: Vec<String> = flagged.iter().map(|(k, n)| format!("{k} x{n}")).collect();
        eprintln!("sanity flags raised: {}", list.join(", "));
    }
    Ok(if predictions >= args.shots { ExitCode::SUCCESS } else { ExitCode::from(1) })
}
