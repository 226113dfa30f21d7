//! `impactd plot dispersion FILE.mcap... [--units imperial|metric] [-o dispersion.svg]`: carry against side per
//! club (label, else club file) of recordings, with each club's 1 and 2 SD ellipses and the target line. Shots the
//! user excluded with `impactd session --exclude` are left out.

use std::collections::BTreeSet;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::Args;
use impactd::offline::plot::{dispersion_svg, DispersionGroup};
use impactd::session::{club_of, Quantity, ShotId, Units};

use super::args::write_output;

#[derive(Debug, Args)]
pub struct DispersionArgs {
    /// MCAP recordings.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Units of the axes.
    #[arg(long, value_enum, default_value_t = Units::Imperial)]
    pub units: Units,
    /// The model whose predictions are drawn (default: the first one each shot was published with).
    #[arg(long)]
    pub model: Option<String>,
    /// Output SVG file.
    #[arg(short = 'o', long = "output", default_value = "dispersion.svg")]
    pub output: PathBuf,
}

pub fn run(args: &DispersionArgs) -> Result<ExitCode> {
    let (unit, factor) = Quantity::Distance.unit(args.units);
    let mut groups: Vec<DispersionGroup> = Vec::new();
    let mut left_out = 0;
    for path in &args.files {
        let r = impactd::daemon::recording::launches::read(path, args.model.as_deref())
            .with_context(|| path.display().to_string())?;
        let excluded = super::session::kept_exclusions(path)?;
        for p in &r.launches {
            if excluded.contains(&ShotId { rig: p.rig.clone(), shot: p.shot }) {
                left_out += 1;
                continue;
            }
            let Some(f) = &p.flight else { continue };
            let name = club_of(p);
            let point = (f.offline_m * factor, f.carry_m * factor);
            match groups.iter_mut().find(|g| g.name == name) {
                Some(g) => g.points.push(point),
                None => groups.push(DispersionGroup { name: name.to_string(), points: vec![point] }),
            }
        }
    }
    if groups.is_empty() {
        bail!("no shots with a flight in the recordings (a rig with `flight = false` has no carry)");
    }
    let shots: usize = groups.iter().map(|g| g.points.len()).sum();
    let files: BTreeSet<String> =
        args.files.iter().filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned())).collect();
    let note = format!(
        "{shots} shots of {} ({} excluded); ellipses: 1 and 2 SD of side and carry; calm air at sea level",
        files.into_iter().collect::<Vec<_>>().join(", "),
        left_out
    );
    write_output(&args.output, &dispersion_svg(&groups, unit, "Dispersion: carry and side per club", Some(&note)))?;
    Ok(ExitCode::SUCCESS)
}
