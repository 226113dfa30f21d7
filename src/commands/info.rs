//! `impactd info`: for an MCAP recording, dates, duration, compression, channels with counts and rates, shots,
//! and whether it was recovered; for a C3D capture, rate, frames, markers, units and analog channels.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::Args;
use impactd::daemon::recording::c3d;

#[derive(Debug, Args)]
pub struct InfoArgs {
    /// An MCAP recording (`impactd run --record`, `replay -o`, `recover -o`) or a C3D capture.
    pub file: PathBuf,
    /// JSON instead of text (C3D captures).
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &InfoArgs) -> Result<ExitCode> {
    if is_c3d(&args.file)? {
        let reader = c3d::open(&args.file).with_context(|| format!("{}", args.file.display()))?;
        let summary = c3d::C3dSummary::new(&reader.info);
        if args.json {
            println!("{}", serde_json::to_string_pretty(&summary)?);
        } else {
            print!("{}", summary.text());
        }
        return Ok(ExitCode::SUCCESS);
    }
    if args.json {
        bail!("--json is for C3D captures; {} is read as an MCAP recording", args.file.display());
    }
    let info = impactd::daemon::recording::info::info(&args.file)?;
    print!("{}", info.text);
    Ok(if info.intact { ExitCode::SUCCESS } else { ExitCode::from(3) })
}

/// A C3D capture by its first bytes (and not MCAP's magic); a `.c3d` name that is not one is an error here.
pub fn is_c3d(path: &Path) -> Result<bool> {
    let mut first = [0u8; 8];
    let mut file = std::fs::File::open(path).with_context(|| format!("opening {}", path.display()))?;
    let n = file.read(&mut first).with_context(|| format!("reading {}", path.display()))?;
    let named = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("c3d"));
    let looks = c3d::looks_like_c3d(&first[..n]) && !first.starts_with(b"\x89MCAP");
    if named && !looks {
        bail!("{} is named .c3d but is not a C3D file (a C3D header's second byte is 0x50)", path.display());
    }
    Ok(looks)
}
