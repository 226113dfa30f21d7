//! `impactd bench`: times each stage in-process on a fixed spread of deliveries.

use std::io::Write;
use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;

#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Print JSON (`{"date", "machine", "load", "stages": [{"name", "ns_per_op"}]}`, `load` the one-minute load
    /// average before and after; with `--baseline` each stage also has
    /// `baseline_ns_per_op`, `ratio` and `slower`, and the document `baseline` and `slower`) instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Only stages whose name contains this.
    #[arg(long)]
    pub filter: Option<String>,
    /// A saved `impactd bench --json` run: each stage's time against it, and every stage slower by more than
    /// 20 % named (on stderr, and as `slower` in the JSON).
    #[arg(long, value_name = "FILE")]
    pub baseline: Option<std::path::PathBuf>,
}

pub fn run(args: &BenchArgs) -> Result<ExitCode> {
    let mut stages = impactd::stages::all_stages();
    if let Some(f) = &args.filter {
        stages.retain(|s| s.name.contains(f.as_str()));
        if stages.is_empty() {
            let names: Vec<String> = impactd::stages::all_stages().into_iter().map(|s| s.name).collect();
            bail!("--filter {f}: no stage's name contains it (stages: {})", names.join(", "));
        }
    }
    let baseline = args.baseline.as_deref().map(super::bench_baseline::load).transpose()?;
    let load_before = super::bench_baseline::load_average();
    let mut results = Vec::new();
    let mut slower = Vec::new();
    let mut progress = super::progress::Progress::new(stages.len() as u64, "stages");
    for (i, stage) in stages.iter_mut().enumerate() {
        if !args.json {
            progress.set(i as u64, Some(&stage.name));
        }
        let ns = impactd::stages::time_stage(stage, 15, 40);
        let compared = baseline.as_deref().and_then(|b| super::bench_baseline::compare(b, &stage.name, ns));
        if compared.as_ref().is_some_and(|c| c.slower) {
            slower.push(stage.name.clone());
        }
        results.push(super::bench_baseline::stage_json(&stage.name, ns, compared.as_ref()));
    }
    progress.finish();
    let mut out = std::io::stdout().lock();
    let (date, machine) = super::bench_baseline::date_and_machine();
    if args.json {
        let load = [load_before, super::bench_baseline::load_average()];
        let mut doc = serde_json::json!({ "date": date, "machine": machine, "load": load, "stages": results });
        if let Some(path) = &args.baseline {
            doc["baseline"] = serde_json::json!(path.display().to_string());
            doc["slower"] = serde_json::json!(slower);
        }
        writeln!(out, "{doc}")?;
    } else {
        let with_base = baseline.is_some();
        write!(out, "{:<36} {:>14}", "stage", "median/op")?;
        if with_base {
            write!(out, " {:>14} {:>7}", "baseline", "ratio")?;
        }
        writeln!(out)?;
        for r in &results {
            write!(out, "{:<36} {:>14}", r["name"].as_str().unwrap_or(""), shown(r["ns_per_op"].as_f64()))?;
            if with_base {
                match r["ratio"].as_f64() {
                    Some(ratio) => write!(out, " {:>14} {ratio:>7.2}", shown(r["baseline_ns_per_op"].as_f64()))?,
                    None => write!(out, " {:>14} {:>7}", "-", "-")?,
                }
            }
            writeln!(out)?;
        }
        writeln!(out, "{date}, {machine}")?;
    }
    if let Some(path) = &args.baseline {
        let pct = 100.0 * super::bench_baseline::SLOWER_FRACTION;
        if slower.is_empty() {
            eprintln!("no stage slower than {} by more than {pct:.0} %", path.display());
        } else {
            eprintln!("slower than {} by more than {pct:.0} %: {}", path.display(), slower.join(", "));
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Nanoseconds in the unit that suits them.
fn shown(ns: Option<f64>) -> String {
    let ns = ns.unwrap_or(f64::NAN);
    if ns < 1e3 {
        format!("{ns:.0} ns")
    } else if ns < 1e6 {
        format!("{:.2} us", ns / 1e3)
    } else {
        format!("{:.2} ms", ns / 1e6)
    }
}
