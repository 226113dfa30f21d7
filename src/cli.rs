//! The `impactd` command line (clap). `main` only parses and calls [`run`].

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::equipment::ClubSpec;
use crate::impact::{
    DeliveryMetrics, Equipment, ImpactError, ImpactModel, ImpulseModel, ImpulseVariant,
};
use crate::wire::{DeliveryInput, PredictOutput};

/// Predicts golf ball launch conditions from motion-capture samples of the clubhead.
#[derive(Debug, Parser)]
#[command(name = "impactd", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

impl Cli {
    /// Whether this is `impactd demo` (which prints its own lines instead of logging).
    pub fn is_demo(&self) -> bool {
        #[cfg(feature = "daemon")]
        if matches!(self.command, Command::Demo(_)) {
            return true;
        }
        false
    }
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// JSONL deliveries in (stdin or --input), JSONL launch conditions out.
    Predict(PredictArgs),
    /// Times each model in-process on a fixed spread of deliveries.
    Bench(BenchArgs),
    /// Evaluations against synthetic truth.
    #[command(subcommand)]
    Eval(EvalCommand),
    /// Write the JSON Schemas of every message type.
    Schemas {
        /// Directory to write `<Type>.json` into.
        #[arg(short = 'o', long = "output", default_value = "schemas")]
        output: PathBuf,
    },
    /// The daemon: clubhead samples in on zenoh, predictions out, everything recorded.
    #[cfg(feature = "daemon")]
    Run(crate::cli_daemon::RunArgs),
    /// The daemon and a simulated rig in one process: zero setup.
    #[cfg(feature = "daemon")]
    Demo(crate::cli_daemon::DemoArgs),
    /// A synthetic rig publishing clubhead samples at real rate, with the truth of each shot.
    #[cfg(feature = "daemon")]
    Sim(crate::cli_daemon::SimArgs),
    /// The pipeline over a recording (MCAP) or a JSONL file of samples.
    #[cfg(feature = "daemon")]
    Replay(crate::cli_daemon::ReplayArgs),
    /// Channels, counts, duration and shots of a recording.
    #[cfg(feature = "daemon")]
    Info { file: PathBuf },
    /// Salvage a recording cut off by a crash (exit 0: nothing lost, 3: data lost).
    #[cfg(feature = "daemon")]
    Recover(crate::cli_daemon::RecoverArgs),
}

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
    #[arg(long, default_value_t = 720.0)]
    pub rate: f64,
    /// Number of swings.
    #[arg(long, default_value_t = 1000)]
    pub shots: usize,
    /// Gaussian position noise per axis (mm).
    #[arg(long, default_value_t = 0.2)]
    pub noise_mm: f64,
    /// Gaussian orientation noise per axis (deg).
    #[arg(long, default_value_t = 0.1)]
    pub noise_deg: f64,
    /// Gaussian timestamp jitter (us).
    #[arg(long, default_value_t = 0.0)]
    pub jitter_us: f64,
    /// Probability that a frame is dropped.
    #[arg(long, default_value_t = 0.0)]
    pub drop: f64,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Estimators to compare (comma-separated).
    #[arg(long, value_delimiter = ',', default_value = "linear2,poly")]
    pub estimators: Vec<String>,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Impact models selectable on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ModelName {
    Standard,
    Adjusted,
    Slip,
}

impl ModelName {
    fn variant(self) -> ImpulseVariant {
        match self {
            ModelName::Standard => ImpulseVariant::Standard,
            ModelName::Adjusted => ImpulseVariant::Adjusted,
            ModelName::Slip => ImpulseVariant::Slip,
        }
    }
}

#[derive(Debug, Args)]
pub struct PredictArgs {
    /// Club preset (driver, iron7) or a path to a club .toml file.
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// Impact model.
    #[arg(long, value_enum, default_value = "adjusted")]
    pub model: ModelName,
    /// Coefficient of restitution along the face normal (seed eq. 3.6).
    #[arg(long, default_value_t = crate::impact::impulse::DEFAULT_COR)]
    pub cor: f64,
    /// Read deliveries from this file instead of stdin.
    #[arg(long, short)]
    pub input: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Print JSON (`{"stages": [{"name", "ns_per_op"}]}`) instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Only stages whose name contains this.
    #[arg(long)]
    pub filter: Option<String>,
}

/// Loads a club preset by name or a club file by path.
pub fn load_club(spec: &str) -> Result<ClubSpec> {
    let path = Path::new(spec);
    if spec.ends_with(".toml") || path.exists() {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading club file {spec}"))?;
        ClubSpec::from_toml_str(&text).with_context(|| format!("club file {spec}"))
    } else {
        Ok(ClubSpec::preset(spec)?)
    }
}

fn open_input(path: Option<&Path>) -> Result<Box<dyn BufRead>> {
    Ok(match path {
        Some(p) => Box::new(BufReader::new(
            std::fs::File::open(p).with_context(|| format!("opening input {}", p.display()))?,
        )),
        None => Box::new(BufReader::new(std::io::stdin())),
    })
}

/// The field a prediction error is about, so the message can name it.
fn describe(err: &ImpactError, input: &DeliveryInput) -> String {
    match err {
        ImpactError::SpeedOutOfRange { speed_mps } => format!(
            "field `club_speed_mph`: {:.1} mph ({speed_mps:.1} m/s) is outside 1-100 m/s",
            input.club_speed_mph
        ),
        ImpactError::OffFace { .. } | ImpactError::Face(_) => {
            format!("fields `impact_h_mm`/`impact_v_mm`: {err}")
        }
        ImpactError::NotFinite { field } => format!("field `{field}`: must be a finite number"),
        ImpactError::NotApproaching => {
            format!("fields `club_path_deg`/`face_angle_deg`/`dynamic_loft_deg`: {err}")
        }
        other => other.to_string(),
    }
}

fn predict(args: &PredictArgs) -> Result<ExitCode> {
    if !(0.0..=1.0).contains(&args.cor) {
        bail!("--cor must be within 0 and 1, got {}", args.cor);
    }
    let club = load_club(&args.club)?;
    let equipment = Equipment::new(club.clone());
    let model = ImpulseModel::new(args.model.variant()).with_cor(args.cor);
    let input = open_input(args.input.as_deref())?;
    let stdout = std::io::stdout().lock();
    let stderr = std::io::stderr().lock();
    let tally = crate::jsonl::process(
        "impactd predict",
        input,
        stdout,
        stderr,
        |d: DeliveryInput| {
            d.check_finite().map_err(|e| describe(&e, &d))?;
            let delivery = d.to_delivery(club.loft_deg());
            let state = delivery
                .to_state(&equipment)
                .map_err(|e| describe(&e, &d))?;
            let launch = model
                .predict(&state, &equipment)
                .map_err(|e| describe(&e, &d))?;
            Ok(PredictOutput::new(
                &launch,
                &DeliveryMetrics::from_state(&state, &club),
                d.handedness.unwrap_or_default(),
            ))
        },
    )?;
    Ok(if tally.rejected > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

fn bench(args: &BenchArgs) -> Result<ExitCode> {
    let mut stages = crate::stages::all_stages();
    if let Some(f) = &args.filter {
        stages.retain(|s| s.name.contains(f.as_str()));
    }
    let mut results = Vec::new();
    let mut err = std::io::stderr().lock();
    for stage in &mut stages {
        if !args.json {
            let _ = write!(err, "timing {} ...\r", stage.name);
        }
        let ns = crate::stages::time_stage(stage, 15, 40);
        results.push(serde_json::json!({ "name": stage.name, "ns_per_op": ns }));
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::json!({ "stages": results }))?;
    } else {
        writeln!(out, "{:<36} {:>14}", "stage", "median/op")?;
        for r in &results {
            let ns = r["ns_per_op"].as_f64().unwrap_or(f64::NAN);
            let shown = if ns < 1e3 {
                format!("{ns:.0} ns")
            } else if ns < 1e6 {
                format!("{:.2} us", ns / 1e3)
            } else {
                format!("{:.2} ms", ns / 1e6)
            };
            writeln!(
                out,
                "{:<36} {:>14}",
                r["name"].as_str().unwrap_or(""),
                shown
            )?;
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn eval_extrapolation(args: &ExtrapolationArgs) -> Result<ExitCode> {
    if !(args.rate >= 60.0 && args.rate <= 10_000.0) {
        bail!("--rate must be within 60 and 10000 Hz, got {}", args.rate);
    }
    if args.noise_mm < 0.0
        || args.noise_deg < 0.0
        || args.jitter_us < 0.0
        || !(0.0..1.0).contains(&args.drop)
    {
        bail!("noise, jitter and drop probability must not be negative (drop below 1)");
    }
    let estimators = args
        .estimators
        .iter()
        .map(|n| {
            crate::kinematics::EstimatorSpec::by_name(n).with_context(|| {
                format!(
                    "unknown estimator '{n}' (known: {})",
                    crate::kinematics::EstimatorSpec::NAMES.join(", ")
                )
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let config = crate::eval::EvalConfig {
        club: load_club(&args.club)?,
        rate_hz: args.rate,
        shots: args.shots,
        noise_mm: args.noise_mm,
        noise_deg: args.noise_deg,
        jitter_us: args.jitter_us,
        drop_probability: args.drop,
        seed: args.seed,
        estimators,
    };
    let mut err = std::io::stderr().lock();
    let step = (args.shots / 20).max(1);
    let report = crate::eval::run(&config, |done| {
        if done % step == 0 || done == args.shots {
            let _ = write!(err, "\r{done}/{} swings", args.shots);
            if done == args.shots {
                let _ = writeln!(err);
            }
        }
    });
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string(&report)?)?;
        return Ok(ExitCode::SUCCESS);
    }
    writeln!(
        out,
        "{} at {} Hz, {} swings, noise {} mm / {} deg, seed {}",
        report.club, report.rate_hz, report.shots, report.noise_mm, report.noise_deg, report.seed
    )?;
    write!(out, "{:<22}", "error (est - truth)")?;
    for e in &report.estimators {
        write!(out, " {:>21}", format!("{} rms / max", e.name))?;
    }
    writeln!(out)?;
    for (k, key) in report.estimators[0]
        .errors
        .entries()
        .iter()
        .map(|(k, _)| *k)
        .enumerate()
    {
        write!(out, "{key:<22}")?;
        for e in &report.estimators {
            let s = e.errors.entries()[k].1;
            write!(
                out,
                " {:>10} / {:>8}",
                format!("{:.4}", s.rms),
                format!("{:.3}", s.max)
            )?;
        }
        writeln!(out)?;
    }
    for e in &report.estimators {
        if !e.refused.is_empty() {
            writeln!(
                out,
                "{}: {} estimated, refused {:?}",
                e.name, e.shots, e.refused
            )?;
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Predict(args) => predict(&args),
        Command::Bench(args) => bench(&args),
        Command::Eval(EvalCommand::Extrapolation(args)) => eval_extrapolation(&args),
        Command::Schemas { output } => {
            std::fs::create_dir_all(&output)
                .with_context(|| format!("creating {}", output.display()))?;
            for (name, schema) in crate::wire::schemas() {
                let path = output.join(format!("{name}.json"));
                std::fs::write(&path, schema)
                    .with_context(|| format!("writing {}", path.display()))?;
            }
            Ok(ExitCode::SUCCESS)
        }
        #[cfg(feature = "daemon")]
        Command::Run(args) => crate::cli_daemon::run(&args),
        #[cfg(feature = "daemon")]
        Command::Demo(args) => crate::cli_daemon::demo_cmd(&args),
        #[cfg(feature = "daemon")]
        Command::Sim(args) => crate::cli_daemon::sim(&args),
        #[cfg(feature = "daemon")]
        Command::Replay(args) => crate::cli_daemon::replay_cmd(&args),
        #[cfg(feature = "daemon")]
        Command::Info { file } => crate::cli_daemon::info(&file),
        #[cfg(feature = "daemon")]
        Command::Recover(args) => crate::cli_daemon::recover(&args),
    }
}
