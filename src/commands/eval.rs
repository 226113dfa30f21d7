//! `impactd eval`: evaluations against synthetic truth.

use std::io::Write;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::{Args, Subcommand, ValueEnum};

use super::args::load_club;

#[derive(Debug, Subcommand)]
pub enum EvalCommand {
    /// Synthetic swings through every impact-state estimator: errors of the delivery and of the launch.
    Extrapolation(ExtrapolationArgs),
}

#[derive(Debug, Args)]
pub struct ExtrapolationArgs {
    /// Club preset or club file.
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// Capture rate (Hz).
    #[arg(long, default_value_t = 720.0, value_parser = super::checked::capture_rate_hz)]
    pub rate: f64,
    /// Number of swings.
    #[arg(long, default_value_t = 1000, value_parser = super::checked::count_usize)]
    pub shots: usize,
    /// Gaussian position noise per axis (mm).
    #[arg(long, default_value_t = 0.2, value_parser = super::checked::magnitude)]
    pub noise_mm: f64,
    /// Gaussian orientation noise per axis (deg).
    #[arg(long, default_value_t = 0.1, value_parser = super::checked::magnitude)]
    pub noise_deg: f64,
    /// Gaussian timestamp jitter (us).
    #[arg(long, default_value_t = 0.0, value_parser = super::checked::magnitude)]
    pub jitter_us: f64,
    /// Probability that a frame is dropped.
    #[arg(long, default_value_t = 0.0, value_parser = super::checked::probability)]
    pub drop: f64,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Estimators to compare (comma-separated).
    #[arg(long, value_delimiter = ',', default_value = "linear2,poly,arc")]
    pub estimators: Vec<String>,
    /// Shape of the swings' path before impact: an arc (the `arc` estimator's own model) or a double pendulum
    /// (arm and club, the wrist uncocking).
    #[arg(long, value_enum, default_value_t = PathArg::Arc)]
    pub path: PathArg,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
}

/// `--path` of `impactd eval extrapolation`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PathArg {
    Arc,
    DoublePendulum,
}

pub fn run(command: &EvalCommand) -> Result<ExitCode> {
    match command {
        EvalCommand::Extrapolation(args) => extrapolation(args),
    }
}

fn extrapolation(args: &ExtrapolationArgs) -> Result<ExitCode> {
    if !(args.rate >= 60.0 && args.rate <= 10_000.0) {
        bail!("--rate must be within 60 and 10000 Hz, got {}", args.rate);
    }
    if args.shots == 0 {
        bail!("--shots must be at least 1");
    }
    if args.noise_mm < 0.0 || args.noise_deg < 0.0 || args.jitter_us < 0.0 || !(0.0..1.0).contains(&args.drop) {
        bail!("noise, jitter and drop probability must not be negative (drop below 1)");
    }
    let estimators = args
        .estimators
        .iter()
        .map(|n| {
            impactd::kinematics::EstimatorSpec::by_name(n).with_context(|| {
                format!("unknown estimator '{n}' (known: {})", impactd::kinematics::EstimatorSpec::NAMES.join(", "))
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let loaded = load_club(&args.club)?;
    let config = impactd::offline::eval::EvalConfig {
        launch_model: super::args::one_model("adjusted", &loaded, impactd::impact::impulse::DEFAULT_COR)?,
        club: loaded.club.clone(),
        rate_hz: args.rate,
        shots: args.shots,
        noise_mm: args.noise_mm,
        noise_deg: args.noise_deg,
        jitter_us: args.jitter_us,
        drop_probability: args.drop,
        seed: args.seed,
        estimators,
        path: match args.path {
            PathArg::Arc => impactd::offline::swing::SwingPath::Arc,
            PathArg::DoublePendulum => impactd::offline::swing::SwingPath::DoublePendulum,
        },
    };
    let mut progress = super::progress::Progress::new(args.shots as u64, "swings");
    let report = impactd::offline::eval::run(&config, |done| progress.set(done as u64, None));
    progress.finish();
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string(&report)?)?;
        return Ok(ExitCode::SUCCESS);
    }
    writeln!(
        out,
        "{} at {} Hz, {} swings on {} paths, noise {} mm / {} deg, seed {}",
        report.club,
        report.rate_hz,
        report.shots,
        report.path.name(),
        report.noise_mm,
        report.noise_deg,
        report.seed
    )?;
    write!(out, "{:<22}", "error (est - truth)")?;
    for e in &report.estimators {
        write!(out, " {:>21}", format!("{} rms / max", e.name))?;
    }
    writeln!(out)?;
    let rows = |e: &impactd::offline::eval::EstimatorReport| {
        let mut rows = e.errors.entries().to_vec();
        rows.extend(e.club_data.entries());
        rows
    };
    for (k, key) in rows(&report.estimators[0]).iter().map(|(k, _)| *k).enumerate() {
        write!(out, "{key:<22}")?;
        for e in &report.estimators {
            let s = rows(e)[k].1;
            write!(out, " {:>10} / {:>8}", format!("{:.4}", s.rms), format!("{:.3}", s.max))?;
        }
        writeln!(out)?;
    }
    for e in report.estimators.iter().filter(|e| !e.coverage.is_empty()) {
        writeln!(
            out,
            "{}: the reported uncertainty against the truth, {} shots ({} without an uncertainty)",
            e.name, e.coverage[0].shots, e.without_uncertainty
        )?;
        writeln!(
            out,
            "  {:<22} {:>9} {:>9} {:>11} {:>11} {:>7}",
            "field", "<=1 sigma", "<=2 sigma", "rms sigma", "rms error", "rms z"
        )?;
        for c in &e.coverage {
            writeln!(
                out,
                "  {:<22} {:>8.1}% {:>8.1}% {:>11.4} {:>11.4} {:>7.2}",
                c.field,
                100.0 * c.within_1_sigma,
                100.0 * c.within_2_sigma,
                c.rms_sigma,
                c.rms_error,
                c.rms_z
            )?;
        }
    }
    for e in &report.estimators {
        if !e.refused.is_empty() {
            writeln!(out, "{}: {} estimated, refused {:?}", e.name, e.shots, e.refused)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}
