//! The daemon's commands: `run`, `demo`, `sim`, `replay`, `info`, `recover`.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::Args;

use crate::daemon::bus::ZenohArgs;
use crate::daemon::demo::{demo, DemoOptions};
use crate::daemon::replay;
use crate::daemon::sim::{run_sim, SimOptions};
use crate::daemon::{DaemonConfig, RunOptions};
use crate::pipeline::Event;

#[derive(Debug, Args)]
pub struct RunArgs {
    /// impactd's configuration (rigs, clubs, models, calibration); default: one rig `rig1` with a driver.
    #[arg(short = 'c', long = "config")]
    pub config: Option<PathBuf>,
    /// Record every message to this MCAP file.
    #[arg(long)]
    pub record: Option<PathBuf>,
    #[command(flatten)]
    pub zenoh: ZenohArgs,
}

#[derive(Debug, Args)]
pub struct DemoArgs {
    /// Shots to swing.
    #[arg(long, default_value_t = 5)]
    pub shots: u64,
    /// Club preset or club file.
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// Print predictions as JSON.
    #[arg(long)]
    pub json: bool,
    /// The recording's path.
    #[arg(long, default_value = "impactd-demo.mcap")]
    pub record: PathBuf,
    /// Random seed of the swings.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Capture rate (Hz).
    #[arg(long, default_value_t = 720.0)]
    pub rate: f64,
}

#[derive(Debug, Args)]
pub struct SimArgs {
    /// Rig names (repeatable); default rig1, or rig1..rigN with --rigs.
    #[arg(long = "rig")]
    pub rig: Vec<String>,
    /// Number of rigs named rig1..rigN.
    #[arg(long)]
    pub rigs: Option<usize>,
    /// Shots per rig (0: until stopped).
    #[arg(long, default_value_t = 5)]
    pub shots: u64,
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// Capture rate (Hz).
    #[arg(long, default_value_t = 720.0)]
    pub rate: f64,
    /// Seconds between shots.
    #[arg(long, default_value_t = 1.5)]
    pub interval: f64,
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    #[arg(long, default_value_t = 0.2)]
    pub noise_mm: f64,
    #[arg(long, default_value_t = 0.1)]
    pub noise_deg: f64,
    #[command(flatten)]
    pub zenoh: ZenohArgs,
}

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

#[derive(Debug, Args)]
pub struct RecoverArgs {
    pub file: PathBuf,
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

/// Completes on SIGINT or SIGTERM.
pub async fn shutdown_signal() {
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

fn runtime() -> Result<tokio::runtime::Runtime> {
    tokio::runtime::Builder::new_multi_thread().enable_all().build().context("starting the async runtime")
}

fn load_config(path: Option<&std::path::Path>) -> Result<(DaemonConfig, Vec<crate::pipeline::RigSetup>)> {
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
    let (config, setups) = load_config(args.config.as_deref())?;
    let rt = runtime()?;
    rt.block_on(async {
        let session = args.zenoh.open().await?;
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
        let summary =
            crate::daemon::run(config, setups, &session, RunOptions { record: args.record.clone() }, shutdown_signal())
                .await?;
        let _ = session.close().await;
        for (rig, c) in &summary.rigs {
            tracing::info!("rig {rig}: {} samples, {} shots, {} predictions", c.samples, c.shots, c.predictions);
        }
        if let Some(r) = &summary.recorder {
            tracing::info!("recording closed: {} messages, {} dropped", r.messages, r.dropped);
        }
        Ok(ExitCode::SUCCESS)
    })
}

pub fn demo_cmd(args: &DemoArgs) -> Result<ExitCode> {
    if args.shots == 0 {
        bail!("--shots must be at least 1");
    }
    let club = crate::cli::load_club(&args.club)?;
    let mut config = DaemonConfig::default();
    config.rigs[0].club = args.club.clone();
    let sim = SimOptions { club, shots: args.shots, seed: args.seed, rate_hz: args.rate, ..SimOptions::default() };
    eprintln!(
        "impactd demo: daemon and a synthetic {} rig on loopback zenoh, {} shots at {} Hz; recording to {}",
        args.club,
        args.shots,
        args.rate,
        args.record.display()
    );
    let rt = runtime()?;
    let summary = rt.block_on(demo(
        DemoOptions { config, sim, record: Some(args.record.clone()), json: args.json },
        shutdown_signal(),
    ))?;
    let (shots, predictions): (u64, u64) =
        summary.rigs.values().fold((0, 0), |(s, p), c| (s + c.shots, p + c.predictions));
    eprintln!(
        "{predictions} of {} shots predicted ({shots} impacts detected). Recording: {} (try `impactd info {}` or open it in Foxglove)",
        args.shots,
        args.record.display(),
        args.record.display()
    );
    let mut flagged = std::collections::BTreeMap::<&str, u64>::new();
    for (name, n) in summary.rigs.values().flat_map(|c| c.flagged.iter()) {
        *flagged.entry(name.as_str()).or_default() += n;
    }
    if !flagged.is_empty() {
        let list: Vec<String> = flagged.iter().map(|(k, n)| format!("{k} x{n}")).collect();
        eprintln!("sanity flags raised: {}", list.join(", "));
    }
    Ok(if predictions >= args.shots { ExitCode::SUCCESS } else { ExitCode::from(1) })
}

pub fn sim(args: &SimArgs) -> Result<ExitCode> {
    let mut rigs = args.rig.clone();
    if let Some(n) = args.rigs {
        rigs.extend((1..=n).map(|i| format!("rig{i}")));
    }
    if rigs.is_empty() {
        rigs.push("rig1".into());
    }
    if !(60.0..=10_000.0).contains(&args.rate) || args.interval < 0.2 {
        bail!("--rate must be within 60 and 10000 Hz and --interval at least 0.2 s");
    }
    let options = SimOptions {
        rigs,
        club: crate::cli::load_club(&args.club)?,
        shots: args.shots,
        rate_hz: args.rate,
        interval_s: args.interval,
        seed: args.seed,
        noise_mm: args.noise_mm,
        noise_deg: args.noise_deg,
        wait_for_subscriber_s: 10.0,
    };
    let rt = runtime()?;
    rt.block_on(async {
        let session = args.zenoh.open().await?;
        let s = run_sim(&session, options, shutdown_signal()).await?;
        let _ = session.close().await;
        eprintln!("sent {} samples, {} shots", s.samples, s.shots);
        Ok(ExitCode::SUCCESS)
    })
}

pub fn replay_cmd(args: &ReplayArgs) -> Result<ExitCode> {
    let input = replay::load(&args.file)?;
    let (config, setups) = match (&args.config, &input.config_toml) {
        (Some(p), _) => DaemonConfig::load(p)?,
        (None, Some(text)) => DaemonConfig::parse(text).context("the configuration stored in the recording")?,
        (None, None) => {
            let mut config = DaemonConfig::default();
            let mut names: Vec<String> = input.samples.iter().map(|s| s.rig.clone()).collect();
            names.sort();
            names.dedup();
            if !names.is_empty() {
                let template = config.rigs[0].clone();
                config.rigs = names
                    .into_iter()
                    .map(|name| crate::daemon::config::RigConfig { name, ..template.clone() })
                    .collect();
            }
            let s = config.setups()?;
            (config, s)
        }
    };
    if let Some(r) = args.rate {
        if !(r > 0.0) {
            bail!("--rate must be positive");
        }
    }
    let rt = runtime()?;
    rt.block_on(async {
        let session = if args.publish { Some(args.zenoh.open().await?) } else { None };
        let mut publishers = std::collections::HashMap::new();
        if let Some(s) = &session {
            for r in &config.rigs {
                let p = s
                    .declare_publisher(crate::wire::keys::launch(&r.name))
                    .encoding(crate::wire::encoding("LaunchPrediction"))
                    .await
                    .map_err(|e| anyhow::anyhow!("zenoh: {e}"))?;
                publishers.insert(r.name.clone(), p);
            }
        }
        let recorder = args
            .output
            .as_deref()
            .map(|p| crate::daemon::recorder::Recorder::create(p, crate::daemon::live::session_metadata(&config)))
            .transpose()?;
        let mut out = std::io::stdout().lock();
        let mut produced = Vec::new();
        let start = std::time::Instant::now();
        let mut first_t: Option<u64> = None;
        let rate = args.rate;
        let stats = replay::replay(
            &input,
            setups,
            |t_ns| {
                if let Some(r) = rate {
                    let t0 = *first_t.get_or_insert(t_ns);
                    let due = std::time::Duration::from_secs_f64((t_ns.saturating_sub(t0)) as f64 * 1e-9 / r);
                    if let Some(wait) = due.checked_sub(start.elapsed()) {
                        std::thread::sleep(wait);
                    }
                }
            },
            |e| match e {
                Event::Launch(l) => {
                    let bytes = serde_json::to_vec(l).unwrap_or_default();
                    let _ = writeln!(out, "{}", String::from_utf8_lossy(&bytes));
                    if let Some(p) = publishers.get(&l.rig) {
                        use zenoh::Wait;
                        let _ = p.put(bytes.clone()).wait();
                    }
                    if let Some(r) = &recorder {
                        let now = crate::daemon::wall_ns();
                        r.send(crate::daemon::recorder::Record::Message {
                            key: crate::wire::keys::launch(&l.rig),
                            type_name: "LaunchPrediction",
                            log_time_ns: now,
                            publish_time_ns: now,
                            data: bytes.clone(),
                        });
                    }
                    produced.push(bytes);
                }
                Event::Failed { shot, frame, reason, .. } => {
                    eprintln!("shot {shot} (frame {frame}): no prediction: {reason}")
                }
                _ => {}
            },
        );
        if let Some(r) = recorder {
            r.finish()?;
        }
        let elapsed = start.elapsed().as_secs_f64();
        eprintln!(
            "replayed {} samples in {:.3} s ({:.2} million samples/s): {} predictions, {} failed{}",
            stats.samples,
            elapsed,
            stats.samples as f64 / elapsed.max(1e-9) / 1e6,
            stats.predictions,
            stats.failed,
            if stats.unknown_rig > 0 {
                format!(", {} samples for unconfigured rigs", stats.unknown_rig)
            } else {
                String::new()
            }
        );
        if !input.recorded_launches.is_empty() {
            let same = produced.iter().zip(&input.recorded_launches).filter(|(a, b)| a == b).count();
            eprintln!(
                "{same} of {} recorded predictions reproduced byte for byte{}",
                input.recorded_launches.len(),
                if produced.len() != input.recorded_launches.len() {
                    format!(" ({} produced)", produced.len())
                } else {
                    String::new()
                }
            );
            if same != input.recorded_launches.len() || produced.len() != input.recorded_launches.len() {
                return Ok(ExitCode::from(1));
            }
        }
        if let Some(s) = session {
            let _ = s.close().await;
        }
        Ok(ExitCode::SUCCESS)
    })
}

pub fn info(file: &std::path::Path) -> Result<ExitCode> {
    print!("{}", replay::info(file)?);
    Ok(ExitCode::SUCCESS)
}

pub fn recover(args: &RecoverArgs) -> Result<ExitCode> {
    if args.file == args.output {
        bail!("the output must be a new file");
    }
    let r = replay::recover(&args.file, &args.output)?;
    if r.complete {
        eprintln!("{}: complete; {} messages copied to {}", args.file.display(), r.messages, args.output.display());
        Ok(ExitCode::SUCCESS)
    } else {
        eprintln!(
            "{}: cut off; salvaged {} messages into {} (the unfinished last chunk, at most about a second, is lost)",
            args.file.display(),
            r.messages,
            args.output.display()
        );
        Ok(ExitCode::from(3))
    }
}
