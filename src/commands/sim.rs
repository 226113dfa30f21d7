//! `impactd sim`: a synthetic rig publishing clubhead samples at real rate, with the truth of each shot.

use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;
use impactd::daemon::sim::{run_sim, SimOptions};

use super::args::{load_club, ZenohFlags};
use super::checked;
use super::error::CliError;
use super::run::{runtime, shutdown_signal};

#[derive(Debug, Args)]
pub struct SimArgs {
    /// Rig names (repeatable); default rig1, or rig1..rigN with --rigs.
    #[arg(long = "rig")]
    pub rig: Vec<String>,
    /// Number of rigs named rig1..rigN.
    #[arg(long, value_parser = checked::count_usize)]
    pub rigs: Option<usize>,
    /// Shots per rig (0: until stopped).
    #[arg(long, default_value_t = 5, value_parser = checked::count_or_zero)]
    pub shots: u64,
    /// Club preset (driver, iron7) or a path to a club .toml file.
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// Name this tracked body in every sample (a rig with `[rig.clubs]` switches to the body's club).
    #[arg(long)]
    pub body: Option<String>,
    /// Capture rate (Hz).
    #[arg(long, default_value_t = 720.0, value_parser = checked::capture_rate_hz)]
    pub rate: f64,
    /// Seconds between shots (at least 0.2).
    #[arg(long, default_value_t = 1.5, value_parser = checked::seconds)]
    pub interval: f64,
    /// Random seed of the swings and the noise.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Gaussian position noise per axis (mm).
    #[arg(long, default_value_t = 0.2, value_parser = checked::magnitude)]
    pub noise_mm: f64,
    /// Gaussian orientation noise per axis (deg).
    #[arg(long, default_value_t = 0.1, value_parser = checked::magnitude)]
    pub noise_deg: f64,
    #[command(flatten)]
    pub zenoh: ZenohFlags,
}

pub fn run(args: &SimArgs) -> Result<ExitCode> {
    let mut rigs = args.rig.clone();
    if let Some(n) = args.rigs {
        rigs.extend((1..=n).map(|i| format!("rig{i}")));
    }
    if rigs.is_empty() {
        rigs.push("rig1".into());
    }
    if args.interval < 0.2 {
        bail!("--interval must be at least 0.2 s, got {}", args.interval);
    }
    let loaded = load_club(&args.club)?;
    let tuning = Some(impactd::impact::impulse::ImpulseTuning::from_sections(&loaded.club, &loaded.sections)?);
    let options = SimOptions {
        rigs,
        club: loaded.club,
        tuning,
        shots: args.shots,
        rate_hz: args.rate,
        interval_s: args.interval,
        seed: args.seed,
        noise_mm: args.noise_mm,
        noise_deg: args.noise_deg,
        wait_for_subscriber_s: 10.0,
        body: args.body.clone(),
        ..SimOptions::default()
    };
    let zenoh = args.zenoh.args()?;
    let rt = runtime()?;
    rt.block_on(async {
        let session = zenoh.open_as(impactd::daemon::bus::Role::Join).await?;
        options.check().map_err(CliError::from)?;
        let s = run_sim(&session, options, shutdown_signal()).await?;
        let _ = session.close().await;
        eprintln!("sent {} samples, {} shots", s.samples, s.shots);
        Ok(ExitCode::SUCCESS)
    })
}
