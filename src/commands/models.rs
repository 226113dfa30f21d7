//! `impactd models`: the model registry, as the README and docs/club-files.md show it (generated from here by
//! scripts/registry-docs.sh, and checked against it by tests/registry_docs.rs).

use std::process::ExitCode;

use anyhow::Result;
use clap::Args;
use impactd::impact::registry;

#[derive(Debug, Args)]
pub struct ModelsArgs {
    /// The club-file sections each model reads, with their fields, instead of the models.
    #[arg(long)]
    pub sections: bool,
}

pub fn run(args: &ModelsArgs) -> Result<ExitCode> {
    print!("{}", if args.sections { registry::sections_markdown() } else { registry::models_markdown() });
    Ok(ExitCode::SUCCESS)
}
