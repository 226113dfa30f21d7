//! `impactd map`: a heatmap over the clubface (SVG) of a launch or flight number, for a delivery given by flags.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::Args;
use impactd::offline::plot::MapMetric;

use super::args::{load_club, model_name, one_model, write_output, DeliveryArgs};

#[derive(Debug, Args)]
pub struct MapArgs {
    /// Club preset (driver, iron7) or a path to a club .toml file.
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// Impact model (`impact::registry`).
    #[arg(long, default_value = impactd::impact::registry::DEFAULT_MODEL, value_parser = model_name)]
    pub model: String,
    /// The number shown in colour.
    #[arg(long, value_enum, default_value = "ball-speed")]
    pub metric: MapMetric,
    #[command(flatten)]
    pub delivery: DeliveryArgs,
    /// Grid cells along each face axis.
    #[arg(long, default_value_t = 21)]
    pub cells: usize,
    /// With --model ground: the turf, soft, medium or firm (Table 4.3), a soil .toml file, or none (the ball
    /// on a tee, no ground).
    #[arg(long)]
    pub soil: Option<String>,
    /// The SVG file to write.
    #[arg(short = 'o', long = "output", default_value = "map.svg")]
    pub output: PathBuf,
}

pub fn run(args: &MapArgs) -> Result<ExitCode> {
    if !(3..=101).contains(&args.cells) {
        bail!("--cells must be within 3 and 101");
    }
    let mut loaded = load_club(&args.club)?;
    super::args::set_soil(&mut loaded, args.soil.as_deref(), &args.model)?;
    let club = loaded.club.clone();
    // An impossible delivery (a speed outside 1-100 m/s, a non-finite angle) is an error, not a blank map.
    let equipment = impactd::impact::Equipment::new(club.clone());
    impactd::predict::state_of(&args.delivery.input(), &club, &equipment).context("the delivery")?;
    let model = one_model(&args.model, &loaded, impactd::impact::impulse::DEFAULT_COR)?;
    let mut heat =
        impactd::offline::plot::face_map(&club, model.as_ref(), &args.delivery.input(), args.metric, args.cells)
            .context("no impact location on the face has a prediction")?;
    if let Some(note) = &heat.note {
        eprintln!("warning: {note}");
    }
    if let Some(soil) = &args.soil {
        heat.title += &format!(", soil {soil}");
    }
    write_output(&args.output, &heat.svg(820.0, heat.fitted_height(820.0, 360.0, 760.0)))?;
    Ok(ExitCode::SUCCESS)
}
