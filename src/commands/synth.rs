//! `impactd synth --model M --club C [--set NAME=VALUE ...] [--shots N] [--seed K] -o shots.jsonl`: a synthetic
//! dataset of measured shots for `compare` and `fit`: deliveries drawn from the club's typical ranges, launched
//! by the model with the given parameters, plus launch-monitor noise per field (default 0.5 mph ball speed,
//! 0.2 deg launch angle, 0.3 deg launch direction, 150 rpm backspin and 150 rpm sidespin, independent normals).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{anyhow, Result};
use clap::Args;
use impactd::offline::identify::dataset::to_jsonl;
use impactd::offline::identify::synth::{generate, DeliveryRanges, LmNoise, SynthSpec};
use impactd::offline::identify::{FitModel, ParamSpace};

#[derive(Debug, Args)]
pub struct SynthArgs {
    /// The model that launches the balls.
    #[arg(long, default_value = "adjusted")]
    pub model: String,
    /// Club preset or club file.
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// A parameter's true value in SI (`delta_mass=0.0073`), repeatable (`fit`'s parameter names).
    #[arg(long = "set", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub set: Vec<String>,
    /// Number of shots.
    #[arg(long, default_value_t = 500, value_parser = super::checked::count_usize)]
    pub shots: usize,
    /// Seed of the deliveries and the noise.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Launch-monitor noise, comma-separated: ball speed (mph), launch (deg), direction (deg), backspin (rpm),
    /// sidespin (rpm) [default: 0.5,0.2,0.3,150,150].
    #[arg(
        long,
        value_name = "MPH,DEG,DEG,RPM,RPM",
        value_delimiter = ',',
        default_values_t = LmNoise::default().as_array(),
        hide_default_value = true
    )]
    pub noise: Vec<f64>,
    /// The JSONL file to write (standard output without it).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

pub fn run(args: &SynthArgs) -> Result<ExitCode> {
    let mut club = super::args::load_club(&args.club)?;
    if !args.set.is_empty() {
        let model = FitModel::parse(&args.model)?;
        let mut names = Vec::new();
        let mut values = Vec::new();
        for s in &args.set {
            let (n, v) = s.split_once('=').ok_or_else(|| anyhow!("--set {s}: expected NAME=VALUE"))?;
            names.push(n.trim().to_string());
            values.push(v.trim().parse::<f64>().map_err(|e| anyhow!("--set {s}: {e}"))?);
        }
        club = ParamSpace::new(model, &names)?.club_with(&club, &values);
    }
    let n = &args.noise;
    if n.len() != 5 || n.iter().any(|s| !(s.is_finite() && *s >= 0.0)) {
        return Err(anyhow!(
            "--noise: expected 5 standard deviations (mph, deg, deg, rpm, rpm), none negative, got {n:?}"
        ));
    }
    let spec = SynthSpec {
        ranges: DeliveryRanges::for_club(&club.club),
        club,
        model: args.model.clone(),
        shots: args.shots,
        noise: LmNoise {
            ball_speed_mph: n[0],
            launch_angle_deg: n[1],
            launch_direction_deg: n[2],
            backspin_rpm: n[3],
            sidespin_rpm: n[4],
        },
        seed: args.seed,
    };
    let text = to_jsonl(&generate(&spec)?);
    match &args.output {
        Some(path) => super::args::write_output(path, &text)?,
        None => print!("{text}"),
    }
    Ok(ExitCode::SUCCESS)
}
