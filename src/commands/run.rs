//! `impactd run`: the daemon; clubhead samples in on zenoh, predictions out, everything recorded.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::Args;
use impactd::daemon::{DaemonConfig, DaemonError, RunOptions};

/// The exit code of a daemon that refused to serve a rig another daemon serves.
pub const RIG_SERVED_EXIT: u8 = 4;

use super::args::ZenohFlags;

#[derive(Debug, Args)]
pub struct RunArgs {
    /// impactd's configuration (rigs, clubs, models, calibration); default: one rig `rig1` with a driver.
    #[arg(short = 'c', long = "config")]
    pub config: Option<PathBuf>,
    /// Record every message to this MCAP file.
    #[arg(long)]
    pub record: Option<PathBuf>,
    /// Replace an existing recording.
    #[arg(long, alias = "force")]
    pub overwrite: bool,
    /// Take over rigs another daemon already serves (it stops, closing its recording) instead of refusing to
    /// start (exit 4).
    #[arg(long)]
    pub take_over: bool,
    #[command(flatten)]
    pub bridges: BridgeArgs,
    #[command(flatten)]
    pub zenoh: ZenohFlags,
}

/// The optional edges of `run` and `demo`: a golf simulator to send shots to, and the Foxglove live view.
#[derive(Debug, Args)]
pub struct BridgeArgs {
    /// Send every rig's shots to this Open Connect v1 golf simulator (GSPro, OpenGolfSim: HOST:921), for rigs
    /// whose configuration names none.
    #[arg(long = "open-connect", value_name = "HOST:PORT")]
    pub open_connect: Option<String>,
    /// Serve the Foxglove live view (Foxglove WebSocket protocol) on this address (default 127.0.0.1:8765).
    #[arg(long, value_name = "HOST:PORT", num_args = 0..=1, default_missing_value = "127.0.0.1:8765")]
    pub foxglove: Option<String>,
    /// Units of the lines printed and logged per shot (default: the configuration's `units`, imperial).
    #[arg(long, value_enum)]
    pub units: Option<impactd::session::Units>,
    /// Serve the bay screen (a web page per rig) on this address (default 127.0.0.1:8080; overrides `[web]`).
    #[arg(long, value_name = "HOST:PORT", num_args = 0..=1, default_missing_value = impactd::daemon::bridges::web::DEFAULT_ADDRESS)]
    pub web: Option<String>,
    /// A host name the bay screen answers as, besides its listen address and localhost (repeatable; adds to
    /// `[web] hosts`): the name its screens open it by. Any other `Host` is answered 421.
    #[arg(long = "web-host", value_name = "NAME")]
    pub web_host: Vec<String>,
}

impl BridgeArgs {
    /// Applies `--open-connect` to the rigs without a simulator.
    pub(super) fn apply(&self, config: &mut DaemonConfig) -> Result<()> {
        if let Some(a) = self.open_connect.as_deref() {
            if !impactd::daemon::bridges::open_connect::valid_host_port(a) {
                bail!("--open-connect `{a}` is not HOST:PORT");
            }
            config.set_default_open_connect(a);
        }
        if let Some(u) = self.units {
            config.units = u;
        }
        if !self.web_host.is_empty() {
            match (&self.web, config.web.as_mut()) {
                (_, Some(w)) => w.hosts.extend(self.web_host.iter().cloned()),
                (Some(listen), None) => {
                    config.web = Some(impactd::daemon::config::WebConfig {
                        listen: listen.clone(),
                        hosts: self.web_host.clone(),
                        token: None,
                    })
                }
                (None, None) => bail!("--web-host needs --web (or a [web] section in the configuration)"),
            }
        }
        Ok(())
    }

    /// The bay screen's address: `--web`, else the configuration's `[web] listen`.
    pub(super) fn web(&self, config: &DaemonConfig) -> Option<String> {
        self.web.clone().or_else(|| config.web.as_ref().map(|w| w.listen.clone()))
    }
}

/// Completes on SIGINT or SIGTERM.
pub(super) async fn shutdown_signal() {
    let ctrl_c = async {
        let _ = tokio::signal::ctrl_c().await;
    };
    #[cfg(unix)]
    let term = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut s) => {
                s.recv().await;
            }
            Err(_) => std::future::pending::<()>().await,
        }
    };
    #[cfg(not(unix))]
    let term = std::future::pending::<()>();
    tokio::select! {
        _ = ctrl_c => {}
        _ = term => {}
    }
}

pub(super) fn runtime() -> Result<tokio::runtime::Runtime> {
    tokio::runtime::Builder::new_multi_thread().enable_all().build().context("starting the async runtime")
}

pub(super) fn load_config(path: Option<&std::path::Path>) -> Result<(DaemonConfig, Vec<impactd::pipeline::RigSetup>)> {
    Ok(match path {
        Some(p) => DaemonConfig::load(p)?,
        None => {
            let c = DaemonConfig::default();
            let s = c.setups()?;
            (c, s)
        }
    })
}

pub fn run(args: &RunArgs) -> Result<ExitCode> {
    let (mut config, _) = load_config(args.config.as_deref())?;
    args.bridges.apply(&mut config)?;
    let setups = config.setups()?;
    let web = args.bridges.web(&config);
    let rt = runtime()?;
    rt.block_on(async {
        let session = args.zenoh.args()?.open().await?;
        let rigs: Vec<String> = config.rigs.iter().map(|r| r.name.clone()).collect();
        tracing::info!(
            "impactd {} serving rigs {} (zenoh id {})",
            env!("CARGO_PKG_VERSION"),
            rigs.join(", "),
            session.zid()
        );
        if let Some(r) = &args.record {
            tracing::info!("recording to {}", r.display());
        }
        let summary = impactd::daemon::run(
            config,
            setups,
            &session,
            RunOptions {
                record: args.record.clone(),
                overwrite: args.overwrite,
                foxglove: args.bridges.foxglove.clone(),
                web,
                take_over: args.take_over,
                ..Default::default()
            },
            shutdown_signal(),
        )
        .await;
        let summary = match summary {
            Ok(s) => s,
            Err(e @ (DaemonError::RigServed { .. } | DaemonError::TakeOver { .. })) => {
                // One daemon per rig: a refusal has its own exit code, so a supervisor can tell it apart.
                tracing::error!("{e}");
                let _ = session.close().await;
                return Ok(ExitCode::from(RIG_SERVED_EXIT));
            }
            Err(e) => return Err(super::error::CliError::from(e).into()),
        };
        let _ = session.close().await;
        if let Some(why) = &summary.taken_over {
            tracing::warn!("stopped: {why}");
        }
        for (rig, c) in &summary.rigs {
            tracing::info!("rig {rig}: {} samples, {} shots, {} predictions", c.samples, c.shots, c.predictions);
        }
        if summary.unknown_rig_samples > 0 {
            tracing::warn!("{} samples arrived for rigs this daemon does not serve", summary.unknown_rig_samples);
        }
        if let Some(r) = &summary.recorder {
            match &r.error {
                Some(e) => {
                    tracing::error!(
                        "recording failed: {e}; {} messages written before it, {} not recorded",
                        r.messages,
                        r.dropped
                    );
                    // A recording that failed is a failed run, whatever else went well.
                    return Ok(ExitCode::from(1));
                }
                None => tracing::info!("recording closed: {} messages, {} dropped", r.messages, r.dropped),
            }
        }
        Ok(ExitCode::SUCCESS)
    })
}
