//! `impactd schemas`: writes the JSON Schema of every message type.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Args;

#[derive(Debug, Args)]
pub struct SchemasArgs {
    /// Directory to write `<Type>.json` into.
    #[arg(short = 'o', long = "output", default_value = "schemas")]
    pub output: PathBuf,
}

pub fn run(args: &SchemasArgs) -> Result<ExitCode> {
    let output = &args.output;
    std::fs::create_dir_all(output).with_context(|| format!("creating {}", output.display()))?;
    for (name, schema) in impactd::wire::schemas() {
        let path = output.join(format!("{name}.json"));
        std::fs::write(&path, schema).with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(ExitCode::SUCCESS)
}
