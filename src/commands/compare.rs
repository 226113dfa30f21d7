//! `impactd compare FILE... [--models LIST] [--club C] [--json]`: each model's accuracy against measured
//! launches, in the layout of the seed's Tables 3.2-3.7 (measured mean; MAE and STD, absolute and as % of the
//! mean, per field per model; eq. 3.13 cost; time per shot).
//!
//! A FILE is a TrackMan Performance Studio CSV export or TrackMan report JSON (club data as the delivery, ball
//! data as the measurement), a JSONL dataset (`{"delivery": {...}, "measured": {...}}` per line) or an MCAP
//! recording. Of a recording, without `--models`, the predictions it holds paired live with measurements (its
//! comparisons) are tabled as recorded; with `--models`, each model is run again on the recorded deliveries. A
//! delivery the club refuses (an impact location off its face, a lie it cannot have) is left out and counted per
//! reason (`refused` in the JSON), not fatal.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::Args;
use impactd::equipment::BallSpec;
use impactd::impact::registry::{self, BuildOptions};
use impactd::impact::Equipment;
use impactd::offline::identify::cost::model_table;
#[cfg(feature = "daemon")]
use impactd::offline::identify::cost::recorded_table;
#[cfg(feature = "daemon")]
use impactd::offline::identify::dataset::fields_of_launch;
use impactd::offline::identify::dataset::read_jsonl;
use impactd::offline::identify::{DatasetLine, ModelTable, FIELDS};

#[derive(Debug, Args)]
pub struct CompareArgs {
    /// JSONL datasets, TrackMan CSV exports, TrackMan report JSON or MCAP recordings.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// The models to run, comma-separated (default: a recording's live comparisons, as recorded; else
    /// standard,adjusted,slip,continuous).
    #[arg(long)]
    pub models: Option<String>,
    /// Club preset or club file (default: the recording's club, else driver).
    #[arg(long)]
    pub club: Option<String>,
    /// One JSON object instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Units of the table (the JSON keeps mph, as the field names say).
    #[arg(long, value_enum, default_value_t = impactd::session::Units::Imperial)]
    pub units: impactd::session::Units,
    /// TrackMan exports (CSV or report JSON): each club (the `Club` column) on its preset; ball speed, launch,
    /// spin (shots with measured spin) and spin axis as MAE and bias per model and club.
    #[arg(long, conflicts_with_all = ["club", "residuals"])]
    pub by_club: bool,
    /// With --by-club: only shots with an impact location.
    #[arg(long, requires = "by_club")]
    pub located: bool,
    /// With --by-club and the ground model: the turf (soft, medium, firm, a soil file) or none (on a tee).
    #[arg(long, requires = "by_club")]
    pub soil: Option<String>,
    /// With --by-club: TrackMan's loft and face read through its spin relation, as the face the seed's ball needs
    /// to leave in TrackMan's direction with TrackMan's spin (the measured launch enters the delivery: launch and
    /// spin are then no independent test; research/real-shots.md).
    #[arg(long, requires = "by_club")]
    pub spin_relation: bool,
    /// Also each shot's residuals (predicted - measured, per field, in the files' order): a line per shot and
    /// model after the table, or `residuals` in the JSON.
    #[arg(long)]
    pub residuals: bool,
}

/// One shot's residuals under one model (`None`: the model failed on it).
#[derive(Debug, serde::Serialize)]
struct ShotResiduals {
    model: String,
    /// 1-based, in the files' order.
    shot: usize,
    residual: Option<impactd::wire::LaunchFields>,
}

/// The shots of the files: dataset lines, the recordings' comparisons, and the club a recording names.
pub struct Loaded {
    pub lines: Vec<DatasetLine>,
    #[cfg(feature = "daemon")]
    pub comparisons: Vec<impactd::wire::ComparisonMessage>,
    pub recording_club: Option<String>,
    /// Whether any file was a recording.
    #[cfg_attr(not(feature = "daemon"), allow(dead_code))]
    pub any_recording: bool,
}

fn is_mcap(path: &Path) -> Result<bool> {
    use std::io::Read;
    let mut magic = [0u8; 8];
    let mut f = std::fs::File::open(path).with_context(|| format!("opening {}", path.display()))?;
    let n = f.read(&mut magic).with_context(|| format!("reading {}", path.display()))?;
    Ok(n == 8 && magic.starts_with(b"\x89MCAP"))
}

/// Reads every file.
pub fn load_files(files: &[PathBuf]) -> Result<Loaded> {
    let mut loaded = Loaded {
        lines: Vec::new(),
        #[cfg(feature = "daemon")]
        comparisons: Vec::new(),
        recording_club: None,
        any_recording: false,
    };
    for path in files {
        if is_mcap(path)? {
            #[cfg(feature = "daemon")]
            {
                let r = impactd::daemon::recording::shots::read(path)?;
                for d in &r.damage {
                    eprintln!("{}: {d}", path.display());
                }
                loaded.lines.extend(r.lines);
                loaded.comparisons.extend(r.comparisons);
                if loaded.recording_club.is_none() {
                    loaded.recording_club = r.club;
                }
                loaded.any_recording = true;
            }
            #[cfg(not(feature = "daemon"))]
            bail!("{}: reading recordings needs the daemon feature", path.display());
        } else {
            let file = std::fs::File::open(path).with_context(|| format!("reading {}", path.display()))?;
            let mut input = std::io::BufReader::new(file);
            // A launch monitor's export says so at its start (`session::measured`); anything else is streamed as
            // JSONL, a bounded line at a time.
            let head = std::io::BufRead::fill_buf(&mut input).with_context(|| format!("reading {}", path.display()))?;
            let head = String::from_utf8_lossy(head).into_owned();
            if let Some(format) = impactd::session::measured::format_of(&head) {
                let mut text = String::new();
                std::io::Read::read_to_string(&mut input, &mut text)
                    .with_context(|| format!("reading {}", path.display()))?;
                let (rows, skipped) = impactd::session::measured::read_labelled(format, &text)
                    .with_context(|| format!("{} ({})", path.display(), format.describe()))?;
                if skipped.total() > 0 {
                    eprintln!("{}: {}", path.display(), skipped.describe());
                }
                loaded.lines.extend(rows.into_iter().map(|(line, _)| line));
            } else {
                let lines = read_jsonl(input).with_context(|| path.display().to_string())?;
                loaded.lines.extend(lines);
            }
        }
    }
    Ok(loaded)
}

/// The club of `--club`, else the recording's (when it loads), else the driver.
pub fn club_spec(arg: Option<&str>, loaded: &Loaded) -> String {
    match (arg, &loaded.recording_club) {
        (Some(c), _) => c.to_string(),
        (None, Some(c)) if impactd::equipment::load_club(c).is_ok() => c.clone(),
        _ => "driver".into(),
    }
}

pub fn run(args: &CompareArgs) -> Result<ExitCode> {
    if args.by_club {
        let models = args.models.clone().unwrap_or_else(|| "standard,adjusted,slip,continuous".into());
        let report = super::compare_clubs::by_club(
            &args.files,
            &models,
            args.located,
            args.soil.as_deref(),
            args.spin_relation,
        )?;
        if args.json {
            println!("{}", serde_json::to_string_pretty(&report)?);
        } else {
            print!("{}", super::compare_clubs::render(&report));
        }
        return Ok(ExitCode::SUCCESS);
    }
    let loaded = load_files(&args.files)?;
    let club_name = club_spec(args.club.as_deref(), &loaded);
    let club = super::args::load_club(&club_name)?;
    let mut tables: Vec<ModelTable> = Vec::new();
    let mut per_shot: Vec<ShotResiduals> = Vec::new();
    let mut refused: std::collections::BTreeMap<String, usize> = std::collections::BTreeMap::new();
    #[cfg(feature = "daemon")]
    if args.models.is_none() && loaded.any_recording {
        let mut models: Vec<String> = loaded.comparisons.iter().map(|c| c.model.clone()).collect();
        models.dedup();
        models.sort();
        models.dedup();
        for m in models {
            let (pred, meas): (Vec<_>, Vec<_>) = loaded
                .comparisons
                .iter()
                .filter(|c| c.model == m)
                .map(|c| (Some(fields_of_launch(&c.predicted)), fields_of_launch(&c.measured)))
                .unzip();
            tables.push(recorded_table(&format!("{m} (recorded)"), &pred, &meas));
        }
    }
    if tables.is_empty() {
        if loaded.lines.is_empty() {
            bail!("no measured shots in the files");
        }
        let ball = BallSpec::SEED;
        let equipment = Equipment { club: club.club.clone(), ball };
        // A delivery the club refuses (off its face, a lie it cannot have) is left out and counted, not fatal.
        let (mut shots, mut numbers) = (Vec::new(), Vec::new());
        for (i, line) in loaded.lines.iter().enumerate() {
            match line.to_shot(&equipment) {
                Ok(s) => {
                    shots.push(s);
                    numbers.push(i + 1);
                }
                Err(e) => *refused.entry(super::compare_clubs::refusal(&e)).or_insert(0) += 1,
            }
        }
        for (reason, n) in &refused {
            eprintln!("{n} shots refused ({reason}), left out");
        }
        if shots.is_empty() {
            bail!("no shot the club accepts in the files");
        }
        let models = args.models.clone().unwrap_or_else(|| "standard,adjusted,slip,continuous".into());
        for name in models.split(',').map(str::trim) {
            let model = registry::build_one(name, &club, &BuildOptions { ball, ..Default::default() })?;
            tables.push(model_table(name, model.as_ref(), &equipment, &shots));
            if args.residuals {
                let predicted = impactd::offline::identify::cost::predict_all(model.as_ref(), &equipment, &shots);
                for ((p, s), shot) in predicted.iter().zip(&shots).zip(&numbers) {
                    let residual = p.map(|p| {
                        let r: [f64; 5] = std::array::from_fn(|k| p[k] - s.measured[k]);
                        impactd::offline::identify::dataset::launch_fields(&r)
                    });
                    per_shot.push(ShotResiduals { model: name.to_string(), shot: *shot, residual });
                }
            }
        }
    } else if args.residuals {
        bail!("--residuals needs --models (a recording's comparisons are tabled as recorded)");
    }
    if args.json {
        let mut out =
            serde_json::json!({ "club": club_name, "files": args.files, "tables": tables, "refused": refused });
        if args.residuals {
            out["residuals"] = serde_json::to_value(&per_shot)?;
        }
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        print!("{}", render(&club_name, &tables, args.units));
        for s in &per_shot {
            match &s.residual {
                Some(r) => {
                    let (speed, unit) = match args.units {
                        impactd::session::Units::Imperial => (r.ball_speed_mph, "mph"),
                        impactd::session::Units::Metric => (r.ball_speed_mph * impactd::units::MPS_PER_MPH, "m/s"),
                    };
                    println!(
                        "shot {:>4} {}: ball speed {speed:+.3} {unit}, launch {:+.3} deg, direction {:+.3} deg, backspin {:+.1} rpm, sidespin {:+.1} rpm",
                        s.shot, s.model, r.launch_angle_deg, r.launch_direction_deg, r.backspin_rpm, r.sidespin_rpm
                    )
                }
                None => println!("shot {:>4} {}: the model failed", s.shot, s.model),
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// The seed's table layout: one row per field, a column group (MAE, STD, each with % of the mean) per model.
pub fn render(club: &str, tables: &[ModelTable], units: impactd::session::Units) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let shots = tables.first().map_or(0, |t| t.shots);
    let _ = writeln!(s, "club {club}, {shots} shots (MAE and STD of |predicted - measured|; % of the measured mean)");
    let _ = write!(s, "{:<16} {:>9}", "field", "measured");
    for t in tables {
        let _ = write!(s, " | {:^31}", t.model);
    }
    let _ = writeln!(s);
    let _ = write!(s, "{:<16} {:>9}", "", "mean");
    for _ in tables {
        let _ = write!(s, " | {:>8} {:>6} {:>8} {:>6}", "MAE", "%", "STD", "%");
    }
    let _ = writeln!(s);
    let metric = units == impactd::session::Units::Metric;
    for (i, (_, label)) in FIELDS.iter().enumerate() {
        // Ball speed in m/s for metric tables; the percentages do not change.
        let (label, scale) = match (i, metric) {
            (0, true) => ("Speed (m/s)", impactd::units::MPS_PER_MPH),
            _ => (*label, 1.0),
        };
        let mean = tables.first().map_or(0.0, |t| t.fields[i].measured_mean) * scale;
        let _ = write!(s, "{label:<16} {mean:>9.2}");
        for t in tables {
            let f = &t.fields[i];
            let _ = write!(s, " | {:>8.2} {:>6.1} {:>8.2} {:>6.1}", f.mae * scale, f.mae_pct, f.std * scale, f.std_pct);
        }
        let _ = writeln!(s);
    }
    let _ = write!(s, "{:<26}", "eq. 3.13 cost");
    for t in tables {
        let _ = write!(s, " | {:>31.4}", t.cost);
    }
    let _ = writeln!(s);
    let _ = write!(s, "{:<26}", "time per shot (us)");
    for t in tables {
        let _ = write!(s, " | {:>31.1}", t.time_per_shot_us);
    }
    let _ = writeln!(s);
    let _ = write!(s, "{:<26}", "failed shots");
    for t in tables {
        let _ = write!(s, " | {:>31}", t.failed);
    }
    let _ = writeln!(s);
    s
}
