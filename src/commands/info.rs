//! `impactd info`: dates, duration, compression, channels with counts and rates, shots, and whether a recording
//! was recovered.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::Args;

#[derive(Debug, Args)]
pub struct InfoArgs {
    /// An MCAP recording (`impactd run --record`, `replay -o`, `recover -o`).
    pub file: PathBuf,
}

pub fn run(args: &InfoArgs) -> Result<ExitCode> {
    let info = impactd::daemon::recording::info::info(&args.file)?;
    print!("{}", info.text);
    Ok(if info.intact { ExitCode::SUCCESS } else { ExitCode::from(3) })
}
