//! `impactd bench`: times each stage in-process on a fixed spread of deliveries.

use std::io::Write;
use std::process::ExitCode;

use anyhow::Result;
use clap::Args;

#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Print JSON (`{"stages": [{"name", "ns_per_op"}]}`) instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Only stages whose name contains this.
    #[arg(long)]
    pub filter: Option<String>,
}

pub fn run(args: &BenchArgs) -> Result<ExitCode> {
    let mut stages = impactd::stages::all_stages();
    if let Some(f) = &args.filter {
        stages.retain(|s| s.name.contains(f.as_str()));
    }
    let mut results = Vec::new();
    let mut err = std::io::stderr().lock();
    for stage in &mut stages {
        if !args.json {
            let _ = write!(err, "timing {} ...\r", stage.name);
        }
        let ns = impactd::stages::time_stage(stage, 15, 40);
        results.push(serde_json::json!({ "name": stage.name, "ns_per_op": ns }));
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::json!({ "stages": results }))?;
    } else {
        writeln!(out, "{:<36} {:>14}", "stage", "median/op")?;
        for r in &results {
            let ns = r["ns_per_op"].as_f64().unwrap_or(f64::NAN);
            let shown = if ns < 1e3 {
                format!("{ns:.0} ns")
            } else if ns < 1e6 {
                format!("{:.2} us", ns / 1e3)
            } else {
                format!("{:.2} ms", ns / 1e6)
            };
            writeln!(out, "{:<36} {:>14}", r["name"].as_str().unwrap_or(""), shown)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}
