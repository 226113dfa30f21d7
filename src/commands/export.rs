//! `impactd export FILE.mcap... --format trackman-csv [-o OUT]`: a recording's predicted shots in TrackMan
//! Performance Studio's CSV layout (`sep=,`, header, units row; right positive for path, face and direction), one
//! row per shot (the first model's prediction, or `--model`'s), for a coach's spreadsheet or TrackMan's tools. After
//! TrackMan's columns come impactd's (`session::trackman_csv::IMPACTD_COLUMNS`): the head's angular velocity and,
//! for a shot a launch monitor measured live (a comparison in the recording), the measurement.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use impactd::session::trackman_csv;

#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ExportFormat {
    /// TrackMan Performance Studio's CSV export.
    TrackmanCsv,
}

#[derive(Debug, Args)]
pub struct ExportArgs {
    /// MCAP recordings.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// The layout written.
    #[arg(long, value_enum)]
    pub format: ExportFormat,
    /// The model whose predictions are exported (default: the first one each shot was published with).
    #[arg(long)]
    pub model: Option<String>,
    /// Output file (default stdout).
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
}

pub fn run(args: &ExportArgs) -> Result<ExitCode> {
    let ExportFormat::TrackmanCsv = args.format;
    let mut rows = Vec::new();
    for path in &args.files {
        let r = impactd::daemon::recording::launches::read(path, args.model.as_deref())
            .with_context(|| path.display().to_string())?;
        for d in &r.damage {
            eprintln!("{}: {d}", path.display());
        }
        let comparisons =
            impactd::daemon::recording::shots::read(path).with_context(|| path.display().to_string())?.comparisons;
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        for p in &r.launches {
            let t = std::time::UNIX_EPOCH + std::time::Duration::from_nanos(p.t_impact_ns);
            let date = humantime::format_rfc3339_seconds(t).to_string();
            let measured = trackman_csv::measured_for(p, &comparisons);
            rows.push(trackman_csv::row(p, &name, &date, measured));
        }
    }
    match &args.output {
        Some(path) => {
            let file = std::fs::File::create(path).with_context(|| format!("creating {}", path.display()))?;
            trackman_csv::write(std::io::BufWriter::new(file), &rows)?;
        }
        None => trackman_csv::write(std::io::stdout().lock(), &rows)?,
    }
    Ok(ExitCode::SUCCESS)
}
