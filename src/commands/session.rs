//! `impactd session FILE.mcap... [--by club|player|tag] [--json|--csv] [--units imperial|metric]`: a fitting
//! session as coaches read it: per group the count, mean, SD and median of TrackMan's metrics, the carry gaps
//! between clubs, and the mishits flagged. `--exclude RIG:SHOT` leaves a shot out and keeps that choice beside the
//! recording (`FILE.mcap.session.json`), so every later summary leaves it out too; `--include` takes it back.
//! Shots left out on the bay (a put on `golf/<rig>/exclude`, kept in the recording) are left out as well.

use std::collections::BTreeSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Args;
use impactd::session::{summarize, GroupBy, SessionSummary, ShotId, Units, METRICS};
use serde_json::{json, Map, Value};

#[derive(Debug, Args)]
pub struct SessionArgs {
    /// MCAP recordings.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Group the shots by club (label, else club file), player or tag.
    #[arg(long, value_enum, default_value_t = GroupBy::Club)]
    pub by: GroupBy,
    /// One JSON object (every metric in both unit systems).
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// CSV: group, metric, unit, count, mean, sd, median.
    #[arg(long)]
    pub csv: bool,
    /// Units of the table and the CSV.
    #[arg(long, value_enum, default_value_t = Units::Imperial)]
    pub units: Units,
    /// The model whose predictions are summarised (default: the first one each shot was published with).
    #[arg(long)]
    pub model: Option<String>,
    /// Leave this shot out from now on (RIG:SHOT, repeatable; kept in FILE.session.json beside each recording).
    #[arg(long, value_name = "RIG:SHOT")]
    pub exclude: Vec<ShotId>,
    /// Take an excluded shot back (RIG:SHOT, repeatable).
    #[arg(long, value_name = "RIG:SHOT")]
    pub include: Vec<ShotId>,
    /// Also leave out every flagged mishit (this run only).
    #[arg(long)]
    pub exclude_outliers: bool,
}

/// The shots a user left out of a recording's summaries, kept beside it.
#[derive(Debug, Default, serde::Serialize, serde::Deserialize)]
struct Exclusions {
    excluded: BTreeSet<String>,
}

fn exclusions_path(recording: &Path) -> PathBuf {
    let mut name = recording.as_os_str().to_owned();
    name.push(".session.json");
    PathBuf::from(name)
}

/// Reads a recording's exclusions, applies `--exclude`/`--include` to those of its shots, and writes them back
/// when they changed.
fn exclusions(path: &Path, shots: &BTreeSet<ShotId>, args: &SessionArgs) -> Result<BTreeSet<ShotId>> {
    let file = exclusions_path(path);
    let mut kept: Exclusions = match std::fs::read_to_string(&file) {
        Ok(text) => serde_json::from_str(&text).with_context(|| format!("reading {}", file.display()))?,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Exclusions::default(),
        Err(e) => return Err(e).with_context(|| format!("reading {}", file.display())),
    };
    let before = kept.excluded.clone();
    for s in args.exclude.iter().filter(|s| shots.contains(s)) {
        kept.excluded.insert(s.to_string());
    }
    for s in &args.include {
        kept.excluded.remove(&s.to_string());
    }
    if kept.excluded != before {
        std::fs::write(&file, serde_json::to_string_pretty(&kept)? + "\n")
            .with_context(|| format!("writing {}", file.display()))?;
    }
    kept.excluded.iter().map(|s| s.parse::<ShotId>().map_err(|e| anyhow::anyhow!("{}: {e}", file.display()))).collect()
}

/// The shots excluded from a recording's summaries, as kept beside it.
pub fn kept_exclusions(path: &Path) -> Result<BTreeSet<ShotId>> {
    let file = exclusions_path(path);
    match std::fs::read_to_string(&file) {
        Ok(text) => {
            let kept: Exclusions =
                serde_json::from_str(&text).with_context(|| format!("reading {}", file.display()))?;
            kept.excluded
                .iter()
                .map(|s| s.parse::<ShotId>().map_err(|e| anyhow::anyhow!("{}: {e}", file.display())))
                .collect()
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(BTreeSet::new()),
        Err(e) => Err(e).with_context(|| format!("reading {}", file.display())),
    }
}

pub fn run(args: &SessionArgs) -> Result<ExitCode> {
    let mut launches = Vec::new();
    let mut excluded = BTreeSet::new();
    for path in &args.files {
        let r = impactd::daemon::recording::launches::read(path, args.model.as_deref())
            .with_context(|| path.display().to_string())?;
        for d in &r.damage {
            eprintln!("{}: {d}", path.display());
        }
        let ids: BTreeSet<ShotId> = r.launches.iter().map(|p| ShotId { rig: p.rig.clone(), shot: p.shot }).collect();
        excluded.extend(exclusions(path, &ids, args)?);
        // Shots left out on the bay (a put on golf/<rig>/exclude, recorded), unless `--include` takes them back.
        let taken_back: BTreeSet<String> = args.include.iter().map(ToString::to_string).collect();
        excluded.extend(
            r.excluded
                .iter()
                .map(|(rig, shot)| ShotId { rig: rig.clone(), shot: *shot })
                .filter(|s| !taken_back.contains(&s.to_string())),
        );
        launches.extend(r.launches);
    }
    let all: BTreeSet<String> = launches.iter().map(|p| format!("{}:{}", p.rig, p.shot)).collect();
    for s in &args.exclude {
        if !all.contains(&s.to_string()) {
            anyhow::bail!("--exclude {s}: no such shot in the recordings");
        }
    }
    if launches.is_empty() {
        anyhow::bail!("no predicted launches in the recordings");
    }
    let summary = summarize(&launches, args.by, &excluded, args.exclude_outliers);
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&to_json(&summary))?)?;
    } else if args.csv {
        write_csv(&mut out, &summary, args.units)?;
    } else {
        write_table(&mut out, &summary, args.units)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// Every group's metrics under keys with their unit, in both systems.
pub fn to_json(s: &SessionSummary) -> Value {
    let groups: Vec<Value> = s
        .groups
        .iter()
        .map(|g| {
            let mut metrics = Map::new();
            for units in [Units::Imperial, Units::Metric] {
                for (m, metric) in METRICS.iter().enumerate() {
                    let (st, _) = s.stats_in(g, m, units);
                    let value = json!({"count": st.count, "mean": st.mean, "sd": st.sd, "median": st.median});
                    metrics.insert(metric.quantity.key(metric.base, units), value);
                }
            }
            let members: Vec<String> = g.members.iter().map(ToString::to_string).collect();
            json!({"group": g.group, "shots": g.shots, "metrics": metrics, "members": members})
        })
        .collect();
    let yd = impactd::units::M_PER_YD;
    let gapping: Vec<Value> = s
        .gapping
        .iter()
        .map(|g| json!({"club": g.club, "next": g.next, "gap_m": g.gap_m, "gap_yd": g.gap_m / yd}))
        .collect();
    let outliers: Vec<Value> = s
        .outliers
        .iter()
        .map(|o| {
            json!({"shot": o.shot.to_string(), "group": o.group, "metric": o.metric, "robust_sds": o.robust_sds,
                   "excluded": o.excluded})
        })
        .collect();
    let excluded: Vec<String> = s.excluded.iter().map(ToString::to_string).collect();
    json!({"by": s.by, "groups": groups, "gapping": gapping, "outliers": outliers, "excluded": excluded})
}

fn write_csv(out: &mut impl Write, s: &SessionSummary, units: Units) -> Result<()> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record(["group", "metric", "unit", "count", "mean", "sd", "median"])?;
    for g in &s.groups {
        for (m, metric) in METRICS.iter().enumerate() {
            let (st, unit) = s.stats_in(g, m, units);
            let num = |v: f64| if v.is_finite() { format!("{v}") } else { String::new() };
            w.write_record([
                g.group.as_str(),
                metric.name,
                unit,
                &st.count.to_string(),
                &num(st.mean),
                &num(st.sd),
                &num(st.median),
            ])?;
        }
    }
    w.flush()?;
    Ok(())
}

fn write_table(out: &mut impl Write, s: &SessionSummary, units: Units) -> Result<()> {
    for g in &s.groups {
        writeln!(out, "{} ({} shots)", g.group, g.shots)?;
        writeln!(out, "  {:<18} {:>5} {:>5} {:>9} {:>8} {:>9}", "metric", "unit", "n", "mean", "SD", "median")?;
        for (m, metric) in METRICS.iter().enumerate() {
            let (st, unit) = s.stats_in(g, m, units);
            if st.count == 0 {
                continue;
            }
            let d = if matches!(unit, "rpm") {
                0
            } else if metric.base == "smash_factor" {
                2
            } else {
                1
            };
            writeln!(
                out,
                "  {:<18} {:>5} {:>5} {:>9.d$} {:>8.d$} {:>9.d$}",
                metric.name, unit, st.count, st.mean, st.sd, st.median
            )?;
        }
        writeln!(out)?;
    }
    if !s.gapping.is_empty() {
        let (unit, factor) = impactd::session::Quantity::Distance.unit(units);
        writeln!(out, "gapping (mean carry)")?;
        for g in &s.gapping {
            writeln!(out, "  {:<12} -> {:<12} {:>6.1} {unit}", g.club, g.next, g.gap_m * factor)?;
        }
        writeln!(out)?;
    }
    for o in &s.outliers {
        let what = if o.excluded { "excluded" } else { "kept: --exclude to leave it out" };
        writeln!(
            out,
            "mishit? {} ({}): {} {:.1} robust SDs from the median ({what})",
            o.shot, o.group, o.metric, o.robust_sds
        )?;
    }
    if !s.excluded.is_empty() {
        let list: Vec<String> = s.excluded.iter().map(ToString::to_string).collect();
        writeln!(out, "excluded: {}", list.join(", "))?;
    }
    Ok(())
}
