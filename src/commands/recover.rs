//! `impactd recover`: salvages a recording cut off by a crash (exit 0: nothing lost, 3: data lost).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;

#[derive(Debug, Args)]
pub struct RecoverArgs {
    /// The damaged or cut-off MCAP recording (read only).
    pub file: PathBuf,
    /// The new, finished MCAP file (it records that it was recovered, and from what).
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

pub fn run(args: &RecoverArgs) -> Result<ExitCode> {
    if args.file == args.output || super::replay::same_file(&args.file, &args.output) {
        bail!("-o {}: that is the input; the output must be a new file", args.output.display());
    }
    let r = impactd::daemon::recording::recover::recover(&args.file, &args.output)?;
    if r.complete {
        eprintln!("{}: complete; {} messages copied to {}", args.file.display(), r.messages, args.output.display());
        return Ok(ExitCode::SUCCESS);
    }
    eprintln!(
        "{}: cut off or damaged; salvaged {} messages in {} intact chunks into {}",
        args.file.display(),
        r.messages,
        r.chunks,
        args.output.display()
    );
    for line in r.report() {
        eprintln!("  {line}");
    }
    Ok(ExitCode::from(3))
}
