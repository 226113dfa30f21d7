use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = impactd::cli::Cli::parse();
    // The demo prints its own lines; elsewhere impactd logs at info and zenoh at warn.
    let default_filter = if cli.is_demo() { "warn" } else { "info,zenoh=warn" };
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| default_filter.into()),
        )
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .with_writer(std::io::stderr)
        .init();
    match impactd::cli::run(cli) {
        Ok(code) => code,
        Err(err) => {
            // The reader went away (`impactd flight | head`): nothing is lost that anyone wanted.
            let broken_pipe = err.chain().any(|e| {
                e.downcast_ref::<std::io::Error>().is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
            });
            if broken_pipe {
                return ExitCode::SUCCESS;
            }
            eprintln!("impactd: {err:#}");
            ExitCode::from(2)
        }
    }
}
