use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| "info".into()),
        )
        .with_writer(std::io::stderr)
        .init();
    let cli = impactd::cli::Cli::parse();
    match impactd::cli::run(cli) {
        Ok(code) => code,
        Err(err) => {
            eprintln!("impactd: {err:#}");
            ExitCode::from(2)
        }
    }
}
