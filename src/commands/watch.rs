//! `impactd watch [RIG]`: a live table of each shot as it lands, for the fitter at the bay with no Foxglove
//! open: one line per swing (its first prediction) with TrackMan's metrics (`session::shot_table`), in
//! `--units imperial|metric`, the header repeated every 20 lines. Every rig without RIG.

use std::collections::HashSet;
use std::io::Write;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Args;
use impactd::daemon::bus::Role;
use impactd::session::shot_table;
use impactd::session::Units;
use impactd::wire::{keys, LaunchPrediction};

use super::args::ZenohFlags;
use super::run::{runtime, shutdown_signal};

/// Lines between repeated headers.
const HEADER_EVERY: usize = 20;

#[derive(Debug, Args)]
pub struct WatchArgs {
    /// The rig to watch (default: every rig).
    pub rig: Option<String>,
    /// Units of the table.
    #[arg(long, value_enum, default_value_t = Units::Imperial)]
    pub units: Units,
    /// Stop after this many shots (default: until stopped).
    #[arg(long)]
    pub count: Option<u64>,
    #[command(flatten)]
    pub zenoh: ZenohFlags,
}

pub fn run(args: &WatchArgs) -> Result<ExitCode> {
    let key = keys::launch(args.rig.as_deref().unwrap_or("*"));
    let rt = runtime()?;
    rt.block_on(async {
        let session = args.zenoh.args()?.open_as(Role::Join).await?;
        let subscriber =
            session.declare_subscriber(key.clone()).await.map_err(|e| anyhow::anyhow!("subscribing to {key}: {e}"))?;
        eprintln!("watching {key} (Ctrl-C to stop)");
        let stdout = std::io::stdout();
        let mut seen = HashSet::new();
        let mut shown = 0u64;
        let shutdown = shutdown_signal();
        tokio::pin!(shutdown);
        loop {
            let sample = tokio::select! {
                s = subscriber.recv_async() => match s {
                    Ok(s) => s,
                    Err(_) => break,
                },
                _ = &mut shutdown => break,
            };
            let p = match serde_json::from_slice::<LaunchPrediction>(&sample.payload().to_bytes()) {
                Ok(p) => p,
                Err(e) => {
                    eprintln!("{}: not a launch prediction: {e}", sample.key_expr());
                    continue;
                }
            };
            // A swing's first prediction only (a daemon with two models publishes two per swing).
            if !seen.insert((p.rig.clone(), p.shot)) {
                continue;
            }
            let mut out = stdout.lock();
            if (shown as usize).is_multiple_of(HEADER_EVERY) {
                for line in shot_table::header(args.units) {
                    writeln!(out, "{line}").context("writing the table")?;
                }
            }
            writeln!(out, "{}", shot_table::row(&p, args.units)).context("writing the table")?;
            out.flush().context("writing the table")?;
            shown += 1;
            if args.count.is_some_and(|n| shown >= n) {
                break;
            }
        }
        drop(subscriber);
        let _ = session.close().await;
        Ok(ExitCode::SUCCESS)
    })
}
