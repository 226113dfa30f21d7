//! `impactd info`: channels, counts, duration and shots of a recording.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::Args;

#[derive(Debug, Args)]
pub struct InfoArgs {
    pub file: PathBuf,
}

pub fn run(args: &InfoArgs) -> Result<ExitCode> {
    let info = impactd::daemon::info::info(&args.file)?;
    print!("{}", info.text);
    Ok(if info.intact { ExitCode::SUCCESS } else { ExitCode::from(3) })
}
