//! `impactd replay`: the daemon's pipelines over a recording (MCAP) or a JSONL file of samples, like rosbag2's
//! `play`: a pace (`--rate`), a part (`--rig`, `--start-offset`, `--duration`), `--loop`, and what goes out on
//! zenoh (`--publish` the predictions, `--publish-samples` the raw samples so a recording drives another daemon),
//! and `--pause`/`--start-paused` (space on a terminal, lines on stdin otherwise: `replay_pause`).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::Args;
use impactd::daemon::replay::{self, PauseControl, Publish, ReplayCapture, ReplayFile, ReplayIndex, ReplayOptions};
use impactd::daemon::replay::{ReplayReport, ReplaySource, Selection};
use impactd::pipeline::Event;

use super::args::{model_name, ZenohFlags};
use super::run::runtime;

#[derive(Debug, Args)]
#[command(after_help = super::capture_check::QUALITY_HELP)]
pub struct ReplayArgs {
    /// An MCAP recording, a JSONL file of ClubheadSample messages, or a capture: C3D or TRC (with --markers),
    /// a pose table (CSV/TSV with --columns or its sidecar TABLE.columns).
    pub file: PathBuf,
    /// A marker capture's marker set (TOML `[markers]`): the tracked body fitted to each frame.
    #[arg(long)]
    pub markers: Option<PathBuf>,
    #[command(flatten)]
    pub fit: super::import::FitArgs,
    #[command(flatten)]
    pub capture: super::import::CaptureArgs,
    #[command(flatten)]
    pub impact: super::capture_check::ImpactArgs,
    /// Configuration; default: the one stored in the recording, else one rig per rig name found.
    #[arg(short = 'c', long = "config")]
    pub config: Option<PathBuf>,
    /// Every rig's club (preset or .toml file) instead of the configured one; a JSONL file has none stored.
    #[arg(long)]
    pub club: Option<String>,
    /// Every rig's impact model instead of the configured one. A model other than the recorded one is a
    /// comparison: it is reported, not failed.
    #[arg(long, value_parser = model_name)]
    pub model: Option<String>,
    /// Replay at this multiple of real time (default: as fast as possible).
    #[arg(long, value_parser = super::checked::pace)]
    pub rate: Option<f64>,
    /// Replay only these rigs (comma-separated).
    #[arg(long, value_delimiter = ',')]
    pub rig: Vec<String>,
    /// Skip this much capture time at the start (s).
    #[arg(long, default_value_t = 0.0, value_parser = super::checked::seconds_or_zero)]
    pub start_offset: f64,
    /// Replay only this much capture time from the start (after --start-offset) (s).
    #[arg(long, value_parser = super::checked::seconds)]
    pub duration: Option<f64>,
    /// Control the replay from stdin: on a terminal, space or Enter pauses and resumes; otherwise lines `pause`,
    /// `resume` or `toggle` (a paused replay resumes when stdin ends).
    #[arg(long)]
    pub pause: bool,
    /// Start paused (implies --pause).
    #[arg(long)]
    pub start_paused: bool,
    /// Replay again and again until interrupted (Ctrl-C).
    #[arg(long = "loop", conflicts_with = "output")]
    pub repeat: bool,
    /// Publish the predictions on zenoh as the daemon would.
    #[arg(long)]
    pub publish: bool,
    /// Publish the recorded clubhead samples on `mocap/<rig>/clubhead`, paced by --rate, so another daemon
    /// predicts from them live.
    #[arg(long)]
    pub publish_samples: bool,
    /// Record the replay to a new MCAP file: samples, impacts, launches and status, as `impactd run` records.
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
    /// Replace the -o file if it exists.
    #[arg(long, requires = "output")]
    pub overwrite: bool,
    #[command(flatten)]
    pub zenoh: ZenohFlags,
}

pub fn run(args: &ReplayArgs) -> Result<ExitCode> {
    if let Some(out) = &args.output {
        if same_file(&args.file, out) {
            bail!("-o {}: that is the input; a replay never writes over its recording", out.display());
        }
    }
    if !(args.start_offset.is_finite() && args.start_offset >= 0.0) {
        bail!("--start-offset must be a non-negative number of seconds, got {}", args.start_offset);
    }
    if args.duration.is_some_and(|d| !(d.is_finite() && d > 0.0)) {
        bail!("--duration must be a positive number of seconds");
    }
    let started = Instant::now();
    let input = open(args)?;
    let index = input.index().into_owned();
    for d in &index.damage {
        eprintln!("{}: damaged: {d}", args.file.display());
    }
    for (former, current) in &index.renamed_models {
        eprintln!("{}: recorded model name {former} is now {current}; compared as {current}", args.file.display());
    }
    let before = index.before_uncertainty();
    if before > 0 {
        eprintln!(
            "{}: {before} recorded predictions were made before predictions carried their uncertainty \
             (LaunchPrediction version 1): the replay's have it, and are compared without it",
            args.file.display()
        );
    }
    if !index.skipped_lines.is_empty() {
        for l in index.skipped_lines.iter().take(5) {
            eprintln!("skipped {l}");
        }
        eprintln!("{} lines skipped: not clubhead samples", index.skipped);
    }
    if index.samples() == 0 {
        bail!(
            "{}: no clubhead samples to replay (an empty, truncated or damaged recording, or not a recording or \
             JSONL file of ClubheadSample messages)",
            args.file.display()
        );
    }
    let select = selection(&index, args)?;
    let (mut config, mut setups) = replay::resolve_config(&input, args.config.as_deref())?;
    let recorded: Vec<(String, String)> = config.rigs.iter().map(|r| (r.club.clone(), r.model.clone())).collect();
    if args.club.is_some() || args.model.is_some() {
        for rig in &mut config.rigs {
            rig.club = args.club.clone().unwrap_or_else(|| rig.club.clone());
            rig.model = args.model.clone().unwrap_or_else(|| rig.model.clone());
        }
        setups = config.setups()?;
    } else if index.config_toml.is_none() && args.config.is_none() {
        let (club, model) = recorded.first().cloned().unwrap_or_default();
        eprintln!(
            "{}: no configuration stored: replaying with club {club} and model {model} (set --club, --model or -c)",
            args.file.display()
        );
    }
    args.impact.apply(&mut setups)?;
    if let Some(what) = args.impact.describe() {
        eprintln!("{}: the impact instant is given ({what}): the estimate is made there", args.file.display());
    }
    let layout = capture_layout(args, &input, &setups)?;
    let losses = |frame: u64| layout.as_ref().map_or_else(Vec::new, |l| l.losses_before(frame, 100));
    let changed = config.rigs.iter().zip(&recorded).any(|(r, (club, model))| &r.club != club || &r.model != model);
    let publish = match (args.publish, args.publish_samples) {
        (true, true) => Some(Publish::Both),
        (true, false) => Some(Publish::Predictions),
        (false, true) => Some(Publish::Samples),
        (false, false) => None,
    };
    let pause = (args.pause || args.start_paused).then(|| Arc::new(PauseControl::new(args.start_paused)));
    let options = ReplayOptions {
        rate: args.rate,
        output: args.output.clone(),
        overwrite: args.overwrite,
        publish: publish.unwrap_or_default(),
        pause: pause.clone(),
        select,
        clock: Default::default(),
    };
    let load_s = started.elapsed().as_secs_f64();
    let rt = runtime()?;
    // Restores the terminal when the replay ends.
    let _keys = pause.map(super::replay_pause::start);
    rt.block_on(async {
        let session = match publish {
            Some(_) => Some(args.zenoh.args()?.open_as(impactd::daemon::bus::Role::Join).await?),
            None => None,
        };
        super::error::positive_rate(args.rate)?;
        let mut out = std::io::stdout().lock();
        let mut report;
        loop {
            report = replay::run(&input, &config, setups.clone(), session.as_ref(), &options, |e, bytes| {
                if let Event::Launch(_) = e {
                    let _ = writeln!(out, "{}", String::from_utf8_lossy(bytes));
                }
                for line in super::capture_check::describe(e, &losses) {
                    eprintln!("{line}");
                }
            })
            .await?;
            if !args.repeat {
                break;
            }
        }
        if let Some(s) = session {
            let _ = s.close().await;
        }
        if let Input::Capture(c, rig) = &input {
            if let Some(counts) = c.counts() {
                eprintln!("{}: rig {rig}: {}", args.file.display(), super::import::describe(&counts, c.format()));
            }
        }
        for d in &report.damage {
            eprintln!("{}: damaged: {d}", args.file.display());
        }
        if report.stats.samples == 0 {
            // Nothing was replayed: a recording of nothing is not left behind.
            if let Some(out) = &args.output {
                let _ = std::fs::remove_file(out);
            }
            if report.stats.left_out == 0 {
                bail!("{}: no clubhead sample could be read (damaged)", args.file.display());
            }
            bail!("--rig/--start-offset/--duration leave no samples");
        }
        print_throughput(&report, load_s);
        let mut code = verdict(&report, changed.then(|| describe(&config, &recorded)), report.stats.left_out > 0);
        if report.recorded == 0 && !report.damaged {
            let s = &report.stats;
            code = super::capture_check::nothing_predicted(s.predictions, s.failed, s.missed).unwrap_or(code);
        }
        if index.skipped > 0 {
            // A line that is not a sample is bad input, as for every command that reads lines (exit 2).
            eprintln!("{} lines of {} are not clubhead samples (exit 2)", index.skipped, args.file.display());
            return Ok(ExitCode::from(super::args::BAD_INPUT_EXIT));
        }
        Ok(code)
    })
}

/// A replay's input: a recording or a JSONL file, or a capture (and the rig its samples go to).
enum Input {
    File(Box<ReplayFile>),
    Capture(Box<ReplayCapture>, String),
}

impl ReplaySource for Input {
    fn index(&self) -> std::borrow::Cow<'_, ReplayIndex> {
        match self {
            Input::File(f) => f.index(),
            Input::Capture(c, _) => c.index(),
        }
    }

    fn items(&self) -> Result<replay::Items<'_>, impactd::daemon::DaemonError> {
        match self {
            Input::File(f) => f.items(),
            Input::Capture(c, _) => c.items(),
        }
    }
}

/// The replay's input: a capture (C3D or TRC fitted with --markers, a pose table read by its columns), else a
/// recording or JSONL samples.
fn open(args: &ReplayArgs) -> Result<Input> {
    let Some(format) = args.capture.format(&args.file)? else {
        if args.markers.is_some() || args.capture.columns.is_some() || args.capture.units.is_some() {
            bail!(
                "--markers, --columns and --units are for captures ({}); {} is not one",
                impactd::captures::format_names(),
                args.file.display()
            );
        }
        // The rigs' capture times are needed only to count --start-offset and --duration from.
        let times = args.start_offset > 0.0 || args.duration.is_some();
        return Ok(Input::File(Box::new(ReplayFile::open(&args.file, times)?)));
    };
    if format.markers.is_some() && args.markers.is_none() {
        bail!("{} is a {}: --markers SET.toml says which markers are the club", args.file.display(), format.what);
    }
    // The capture's samples go to the rig named by --rig, else the configuration's first rig.
    let rig = match (args.rig.first(), &args.config) {
        (Some(r), _) => r.clone(),
        (None, Some(path)) => {
            impactd::daemon::DaemonConfig::load(path)?.0.rigs.first().map(|r| r.name.clone()).unwrap_or_default()
        }
        (None, None) => format.name.replace('-', "_"),
    };
    let face_centre = if format.markers.is_none() { Some(face_centre(args, &rig)?) } else { None };
    let options = args.capture.options(&rig, args.markers.as_deref(), &args.fit, face_centre)?;
    let capture =
        ReplayCapture::open(&args.file, format, options).with_context(|| format!("{}", args.file.display()))?;
    for w in &capture.warnings {
        eprintln!("{}: warning: {w}", args.file.display());
    }
    Ok(Input::Capture(Box::new(capture), rig))
}

/// The face centre (club frame, m) of the club `rig` replays with: --club, else the configuration's, else the
/// default rig's (what places a pose table with `origin=face-centre`).
fn face_centre(args: &ReplayArgs, rig: &str) -> Result<impactd::math::Vector3> {
    let club = match (&args.club, &args.config) {
        (Some(c), _) => c.clone(),
        (None, Some(path)) => {
            let config = impactd::daemon::DaemonConfig::load(path)?.0;
            let found = config.rigs.iter().find(|r| r.name == rig).or(config.rigs.first());
            found.map(|r| r.club.clone()).unwrap_or_default()
        }
        (None, None) => {
            impactd::daemon::DaemonConfig::default().rigs.first().map(|r| r.club.clone()).unwrap_or_default()
        }
    };
    Ok(super::args::load_club(&club)?.club.face.center_m)
}

/// A capture's layout, checked against the rig it replays into: the face centre near the head's markers, a grip
/// marker at a club's length (a refusal, exit 2, before any swing); its marker losses name the markers a shot
/// lacked.
fn capture_layout(
    args: &ReplayArgs,
    input: &Input,
    setups: &[impactd::pipeline::RigSetup],
) -> Result<Option<replay::CaptureLayout>> {
    let (Input::Capture(_, rig), Some(markers)) = (input, &args.markers) else { return Ok(None) };
    let fitter = args.fit.fitter(markers)?;
    let grip = super::import::stated_shaft(markers)?.grip;
    let layout = replay::CaptureLayout::scan(&args.file, &fitter, &grip, args.capture.units.as_deref())
        .with_context(|| format!("{}", args.file.display()))?;
    if let Some(setup) = setups.iter().find(|s| &s.name == rig).or(setups.first()) {
        let face = setup.calibration.club_from_body.inverse() * impactd::math::Point3::from(setup.club.face.center_m);
        if let Some(why) = replay::face_from_markers_refusal(&fitter.set, &face.coords) {
            bail!("{}: rig {}: {why}", args.file.display(), setup.name);
        }
    }
    if let Some(why) = layout.club_length_refusal() {
        bail!("{}: {why}", args.file.display());
    }
    Ok(Some(layout))
}

/// The samples of the chosen rigs and capture times (from the earliest sample of those rigs).
fn selection(index: &ReplayIndex, args: &ReplayArgs) -> Result<Selection> {
    if !args.rig.is_empty() {
        let mut rigs: Vec<&String> = index.rigs.keys().collect();
        rigs.sort_by(|a, b| impactd::daemon::recording::info::natural_cmp(a, b));
        if let Some(missing) = args.rig.iter().find(|r| !index.rigs.contains_key(*r)) {
            let names: Vec<&str> = rigs.iter().map(|r| r.as_str()).collect();
            bail!("--rig {missing}: no samples of that rig (rigs: {})", names.join(", "));
        }
    }
    if args.start_offset == 0.0 && args.duration.is_none() {
        return Ok(Selection { rigs: args.rig.clone(), from_ns: 0, to_ns: None });
    }
    let chosen = index.rigs.iter().filter(|(name, _)| args.rig.is_empty() || args.rig.contains(name));
    let t0 = chosen.map(|(_, span)| span.first_t_ns).min().unwrap_or(0);
    let from_ns = t0.saturating_add((args.start_offset * 1e9) as u64);
    // No --duration keeps every sample from `from` on, the one at t_ns = u64::MAX too.
    let to_ns = args.duration.map(|d| from_ns.saturating_add((d * 1e9) as u64));
    Ok(Selection { rigs: args.rig.clone(), from_ns, to_ns })
}

/// The configured rigs' club and model against the recorded ones, for people.
fn describe(config: &impactd::daemon::DaemonConfig, recorded: &[(String, String)]) -> String {
    let parts: Vec<String> = config
        .rigs
        .iter()
        .zip(recorded)
        .map(|(r, (club, model))| format!("{}: {} {} (recorded: {club} {model})", r.name, r.club, r.model))
        .collect();
    parts.join(", ")
}

fn print_throughput(report: &ReplayReport, load_s: f64) {
    let stats = &report.stats;
    let total_s = (load_s + report.elapsed_s).max(1e-9);
    eprintln!(
        "replayed {} samples in {:.3} s ({:.3} s loading and parsing, {:.3} s through the pipelines): {:.2} million \
         samples/s including loading; {} predictions, {} failed{}",
        stats.samples,
        total_s,
        load_s,
        report.elapsed_s,
        stats.samples as f64 / total_s / 1e6,
        stats.predictions,
        stats.failed,
        if stats.unknown_rig > 0 {
            format!(", {} samples for unconfigured rigs", stats.unknown_rig)
        } else {
            String::new()
        }
    );
}

/// Exit 0 for a reproduction, a comparison or a partial replay; 1 when a whole replay of the recorded
/// configuration differs; 3 for a damaged recording.
fn verdict(report: &ReplayReport, comparison: Option<String>, partial: bool) -> ExitCode {
    if report.damaged {
        eprintln!(
            "the recording is damaged: {} predictions over its readable part, {} equal to the {} recorded \
             predictions that could be read; not a reproduction",
            report.produced, report.reproduced, report.recorded
        );
        return ExitCode::from(3);
    }
    if report.recorded == 0 {
        return ExitCode::SUCCESS;
    }
    let same = format!(
        "{} of {} recorded predictions reproduced byte for byte{}",
        report.reproduced,
        report.recorded,
        if report.produced != report.recorded { format!(" ({} produced)", report.produced) } else { String::new() }
    );
    if let Some(what) = comparison {
        eprintln!("comparison, not a reproduction: {what}; {same}");
        return ExitCode::SUCCESS;
    }
    if partial {
        eprintln!("part of the recording replayed (--rig, --start-offset or --duration): {same}");
        return ExitCode::SUCCESS;
    }
    eprintln!("{same}");
    if report.reproduces_recording() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}

/// Whether `a` and `b` name the same file (same canonical path, or the same inode through a hard link).
pub(super) fn same_file(a: &Path, b: &Path) -> bool {
    if let (Ok(ca), Ok(cb)) = (a.canonicalize(), b.canonicalize()) {
        if ca == cb {
            return true;
        }
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) {
            return ma.dev() == mb.dev() && ma.ino() == mb.ino();
        }
    }
    false
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn a_hard_link_and_a_dotted_path_are_the_same_file() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.mcap");
        std::fs::write(&a, b"x").unwrap();
        let link = dir.path().join("b.mcap");
        std::fs::hard_link(&a, &link).unwrap();
        assert!(same_file(&a, &dir.path().join(".").join("a.mcap")));
        assert!(same_file(&a, &link));
        assert!(!same_file(&a, &dir.path().join("new.mcap")));
    }
}
