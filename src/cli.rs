//! The `impactd` command line (clap). `main` only parses and calls [`run`].

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::equipment::ClubSpec;
use crate::impact::{DeliveryMetrics, Equipment, ImpactError, ImpactModel, ImpulseModel, ImpulseVariant};
use crate::wire::{DeliveryInput, PredictOutput};

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
    Predict(PredictArgs),
    /// Times each model in-process on a fixed spread of deliveries.
    Bench(BenchArgs),
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
        let text = std::fs::read_to_string(path).with_context(|| format!("reading club file {spec}"))?;
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
        ImpactError::OffFace { .. } | ImpactError::Face(_) => format!("fields `impact_h_mm`/`impact_v_mm`: {err}"),
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
    let tally = crate::jsonl::process("impactd predict", input, stdout, stderr, |d: DeliveryInput| {
        d.check_finite().map_err(|e| describe(&e, &d))?;
        let delivery = d.to_delivery(club.loft_deg());
        let state = delivery.to_state(&equipment).map_err(|e| describe(&e, &d))?;
        let launch = model.predict(&state, &equipment).map_err(|e| describe(&e, &d))?;
        Ok(PredictOutput::new(&launch, &DeliveryMetrics::from_state(&state, &club), d.handedness.unwrap_or_default()))
    })?;
    Ok(if tally.rejected > 0 { ExitCode::from(1) } else { ExitCode::SUCCESS })
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
            writeln!(out, "{:<36} {:>14}", r["name"].as_str().unwrap_or(""), shown)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Predict(args) => predict(&args),
        Command::Bench(args) => bench(&args),
    }
}
