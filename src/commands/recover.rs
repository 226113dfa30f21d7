//! `impactd recover`: salvages a recording cut off by a crash (exit 0: nothing lost, 3: data lost).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;

#[derive(Debug, Args)]
pub struct RecoverArgs {
    pub file: PathBuf,
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

pub fn run(args: &RecoverArgs) -> Result<ExitCode> {
    if args.file == args.output {
        bail!("the output must be a new file");
    }
    let r = impactd::daemon::recover::recover(&args.file, &args.output)?;
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
