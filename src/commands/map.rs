//! `impactd map`: a heatmap over the clubface (SVG) of a launch or flight number, for a delivery given by flags.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;
use impactd::plot::MapMetric;

use super::args::{load_club, model_name, one_model, write_output, DeliveryArgs};

#[derive(Debug, Args)]
pub struct MapArgs {
    #[arg(long, default_value = "driver")]
    pub club: String,
    #[arg(long, default_value = "adjusted", value_parser = model_name)]
    pub model: String,
    #[arg(long, value_enum, default_value = "ball-speed")]
    pub metric: MapMetric,
    #[command(flatten)]
    pub delivery: DeliveryArgs,
    /// Grid cells along each face axis.
    #[arg(long, default_value_t = 21)]
    pub cells: usize,
    #[arg(short = 'o', long = "output", default_value = "map.svg")]
    pub output: PathBuf,
}

pub fn run(args: &MapArgs) -> Result<ExitCode> {
    if !(3..=101).contains(&args.cells) {
        bail!("--cells must be within 3 and 101");
    }
    let loaded = load_club(&args.club)?;
    let club = loaded.club.clone();
    let model = one_model(&args.model, &loaded, impactd::impact::impulse::DEFAULT_COR)?;
    let heat = impactd::plot::face_map(&club, model.as_ref(), &args.delivery.input(), args.metric, args.cells);
    write_output(&args.output, &heat.svg(760.0, 520.0))?;
    Ok(ExitCode::SUCCESS)
}
