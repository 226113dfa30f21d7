//! `impactd`: parses the command line and runs the command (see `commands`).

use std::process::ExitCode;

use clap::Parser;

mod commands;

fn main() -> ExitCode {
    let cli = commands::Cli::parse();
    commands::init_logging(&cli);
    match commands::run(cli) {
        Ok(code) => code,
        // The reader went away (`impactd flight | head`): nothing is lost that anyone wanted.
        Err(err) if commands::is_broken_pipe(&err) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("impactd: {err:#}");
            ExitCode::from(2)
        }
    }
}
