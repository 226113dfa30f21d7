//! `impactd replay`: the daemon's pipelines over a recording (MCAP) or a JSONL file of samples.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::Args;
use impactd::daemon::replay::{self, ReplayOptions};
use impactd::pipeline::Event;

use super::args::ZenohArgs;
use super::run::runtime;

#[derive(Debug, Args)]
pub struct ReplayArgs {
    /// An MCAP recording or a JSONL file of ClubheadSample messages.
    pub file: PathBuf,
    /// Configuration; default: the one stored in the recording, else one rig per rig name found.
    #[arg(short = 'c', long = "config")]
    pub config: Option<PathBuf>,
    /// Replay at this multiple of real time (default: as fast as possible).
    #[arg(long)]
    pub rate: Option<f64>,
    /// Publish the predictions on zenoh as the daemon would.
    #[arg(long)]
    pub publish: bool,
    /// Record the replay to a new MCAP file.
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub zenoh: ZenohArgs,
}

pub fn run(args: &ReplayArgs) -> Result<ExitCode> {
    let input = replay::load(&args.file)?;
    for d in &input.damage {
        eprintln!("{}: damaged: {d}", args.file.display());
    }
    if !input.skipped_lines.is_empty() {
        for l in input.skipped_lines.iter().take(5) {
            eprintln!("skipped {l}");
        }
        eprintln!("{} lines skipped: not clubhead samples", input.skipped_lines.len());
    }
    let (config, setups) = replay::resolve_config(&input, args.config.as_deref())?;
    let options = ReplayOptions { rate: args.rate, output: args.output.clone() };
    let rt = runtime()?;
    rt.block_on(async {
        let session =
            if args.publish { Some(args.zenoh.open_as(impactd::daemon::bus::Role::Join).await?) } else { None };
        let mut out = std::io::stdout().lock();
        let report = replay::run(&input, &config, setups, session.as_ref(), &options, |e, bytes| match e {
            Event::Launch(_) => {
                let _ = writeln!(out, "{}", String::from_utf8_lossy(bytes));
            }
            Event::Failed { shot, frame, reason, .. } => {
                eprintln!("shot {shot} (frame {frame}): no prediction: {reason}")
            }
            _ => {}
        })
        .await?;
        if let Some(s) = session {
            let _ = s.close().await;
        }
        let stats = &report.stats;
        eprintln!(
            "replayed {} samples in {:.3} s ({:.2} million samples/s): {} predictions, {} failed{}",
            stats.samples,
            report.elapsed_s,
            stats.samples as f64 / report.elapsed_s.max(1e-9) / 1e6,
            stats.predictions,
            stats.failed,
            if stats.unknown_rig > 0 {
                format!(", {} samples for unconfigured rigs", stats.unknown_rig)
            } else {
                String::new()
            }
        );
        if report.damaged {
            eprintln!(
                "the recording is damaged: {} predictions over its readable part, {} equal to the {} recorded \
                 predictions that could be read; not a reproduction",
                report.produced, report.reproduced, report.recorded
            );
            return Ok(ExitCode::from(3));
        }
        if report.recorded > 0 {
            eprintln!(
                "{} of {} recorded predictions reproduced byte for byte{}",
                report.reproduced,
                report.recorded,
                if report.produced != report.recorded {
                    format!(" ({} produced)", report.produced)
                } else {
                    String::new()
                }
            );
        }
        Ok(if report.reproduces_recording() { ExitCode::SUCCESS } else { ExitCode::from(1) })
    })
}
