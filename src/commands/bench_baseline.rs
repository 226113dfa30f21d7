//! `impactd bench --baseline FILE`: each stage against a saved `impactd bench --json` run, and the machine the
//! run was timed on.

use std::path::Path;

use anyhow::{bail, Context, Result};
use serde_json::{json, Value};

/// A stage slower than its baseline by more than this fraction is named (0.2: 20 %).
pub const SLOWER_FRACTION: f64 = 0.2;

/// The stages of a saved `--json` run: name -> nanoseconds per operation.
pub fn load(path: &Path) -> Result<Vec<(String, f64)>> {
    let text = std::fs::read_to_string(path).with_context(|| format!("--baseline {}", path.display()))?;
    let doc: Value = serde_json::from_str(&text)
        .with_context(|| format!("--baseline {}: not the JSON of `impactd bench --json`", path.display()))?;
    let Some(stages) = doc["stages"].as_array() else {
        bail!("--baseline {}: no `stages` array (the output of `impactd bench --json`)", path.display());
    };
    stages
        .iter()
        .enumerate()
        .map(|(i, s)| match (s["name"].as_str(), s["ns_per_op"].as_f64()) {
            (Some(name), Some(ns)) if ns.is_finite() && ns > 0.0 => Ok((current_stage_name(name), ns)),
            _ => bail!("--baseline {}: stage {i} needs a `name` and a positive `ns_per_op`", path.display()),
        })
        .collect()
}

/// A saved stage's name as it is named today: a model stage saved under a former model name
/// (`<former>/<club>`, `impact::registry::FORMER_NAMES`) compares with the same stage under the model's name.
fn current_stage_name(name: &str) -> String {
    impactd::impact::registry::FORMER_NAMES
        .iter()
        .find_map(|(former, current)| {
            name.strip_prefix(former)?.strip_prefix('/').map(|club| format!("{current}/{club}"))
        })
        .unwrap_or_else(|| name.to_string())
}

/// One stage against its baseline: `ratio` = now / then (above 1: slower).
#[derive(Debug, Clone, PartialEq)]
pub struct Compared {
    pub baseline_ns_per_op: f64,
    pub ratio: f64,
    pub slower: bool,
}

/// The stage `name` timed at `ns` against the baseline's, `None` when the baseline has no such stage.
pub fn compare(baseline: &[(String, f64)], name: &str, ns: f64) -> Option<Compared> {
    let (_, then) = baseline.iter().find(|(n, _)| n == name)?;
    let ratio = ns / then;
    Some(Compared { baseline_ns_per_op: *then, ratio, slower: ratio > 1.0 + SLOWER_FRACTION })
}

/// The date (UTC, `YYYY-MM-DD`) and the machine (`N cores, CPU model`) a run is timed on.
pub fn date_and_machine() -> (String, String) {
    let days =
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs() / 86_400) as i64;
    let (y, m, d) = civil_from_days(days);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    (format!("{y:04}-{m:02}-{d:02}"), format!("{cores} cores, {cpu}"))
}

/// The one-minute load average (`/proc/loadavg`), where the system gives it: timings under load are slower.
pub fn load_average() -> Option<f64> {
    std::fs::read_to_string("/proc/loadavg").ok()?.split_whitespace().next()?.parse().ok()
}

/// The proleptic Gregorian date of a day count from 1970-01-01 (Howard Hinnant's `civil_from_days`).
fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    (yoe + era * 400 + i64::from(m <= 2), m, d)
}

/// The JSON of one stage: its time, and against the baseline when there is one.
pub fn stage_json(name: &str, ns: f64, compared: Option<&Compared>) -> Value {
    match compared {
        None => json!({ "name": name, "ns_per_op": ns }),
        Some(c) => json!({
            "name": name,
            "ns_per_op": ns,
            "baseline_ns_per_op": c.baseline_ns_per_op,
            "ratio": c.ratio,
            "slower": c.slower,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates() {
        assert_eq!(civil_from_days(0), (1970, 1, 1));
        // 2026-11-25 is day 20,782: 56 years of 365 days plus 14 leap days (1972-2024) to 2026-01-01, then 328.
        assert_eq!(civil_from_days(20_782), (2026, 11, 25));
        assert_eq!(civil_from_days(11_016), (2000, 2, 29));
    }

    #[test]
    fn slower_by_more_than_a_fifth() {
        let base = vec![("a".to_string(), 100.0), ("b".to_string(), 100.0)];
        assert!(compare(&base, "a", 121.0).is_some_and(|c| c.slower));
        assert!(compare(&base, "b", 119.0).is_some_and(|c| !c.slower && (c.ratio - 1.19).abs() < 1e-12));
        assert_eq!(compare(&base, "c", 1.0), None);
    }
}
