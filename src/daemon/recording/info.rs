//! `impactd info`: what `mcap info` says of a recording (start and end dates in UTC, duration, compression,
//! messages and rate per topic) and what only impactd knows (shots per rig, the session's metadata, whether the
//! file was recovered), read by the bounded reader ([`mcap_read`](crate::daemon::recording::reader)) up to the first damage it
//! cannot step over, which it names. Topics and rigs are listed in natural order (rig1, rig2, rig10).

use std::cmp::Ordering;
use std::collections::BTreeMap;
use std::path::Path;
use std::time::{Duration, UNIX_EPOCH};

use crate::daemon::recording::reader::OnDamage;
use crate::daemon::recording::recover::RECOVERED_METADATA;
use crate::daemon::DaemonError;

/// A description of a recording for `impactd info`, and whether it could be read whole.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Info {
    pub text: String,
    /// Finished and undamaged.
    pub intact: bool,
}

/// Describes a recording: dates, channels, counts and rates, shots, metadata, and anything it could not read.
pub fn info(path: &Path) -> Result<Info, DaemonError> {
    let mut counts: BTreeMap<String, (String, u64)> = BTreeMap::new();
    let mut shots: BTreeMap<String, u64> = BTreeMap::new();
    let scan = crate::daemon::recording::stream::read_messages(path, OnDamage::Stop, |scan, channel, m| {
        let (topic, schema) = match channel {
            Some(c) => (c.topic.clone(), scan.schemas.get(&c.schema_id).map(|s| s.name.clone()).unwrap_or_default()),
            None => (format!("(unknown channel {})", m.channel_id), String::new()),
        };
        if let Some(rig) = topic.trim_start_matches('/').strip_prefix("golf/").and_then(|t| t.strip_suffix("/launch")) {
            *shots.entry(rig.to_string()).or_default() += 1;
        }
        counts.entry(topic).or_insert((schema, 0)).1 += 1;
    })?;
    let (first, last) = (scan.first_log_time_ns.unwrap_or(u64::MAX), scan.last_log_time_ns.unwrap_or(0));
    let mut metadata = Vec::new();
    let mut recovered = None;
    for (name, m) in &scan.metadata {
        if name == RECOVERED_METADATA {
            recovered = Some(m);
        }
        let keys: Vec<String> =
            m.iter().filter(|(k, _)| k.as_str() != "config_toml").map(|(k, v)| format!("{k}={v}")).collect();
        metadata.push(format!("  {name}: {}", keys.join(", ")));
    }
    let total: u64 = counts.values().map(|c| c.1).sum();
    let duration_ns = last.saturating_sub(first);
    let mut out = format!("file:        {} ({})\n", path.display(), human_bytes(scan.file_bytes));
    out += &format!(
        "complete:    {}\n",
        if scan.intact() {
            "yes (summary and footer present)"
        } else {
            "no: cut off or damaged; run `impactd recover`"
        }
    );
    for p in scan.problems() {
        out += &format!("damaged:     {p}\n");
    }
    out += &match recovered {
        Some(r) => format!(
            "recovered:   yes, by `impactd recover` from {} at {}{}\n",
            r.get("from").map_or("?", String::as_str),
            r.get("recovered_at").map_or("?", String::as_str),
            match r.get("input_complete").map(String::as_str) {
                Some("false") => " (the input was cut off or damaged: data may be missing)",
                _ => "",
            }
        ),
        None => "recovered:   no\n".to_string(),
    };
    if total > 0 {
        out += &format!("start:       {} (UTC)\n", utc(first));
        out += &format!("end:         {} (UTC)\n", utc(last));
        out += &format!("duration:    {}\n", human_duration(duration_ns));
    }
    let compression: Vec<String> = scan
        .compression
        .iter()
        .map(|(c, n)| {
            format!("{} ({n} chunk{})", if c.is_empty() { "none" } else { c }, if *n == 1 { "" } else { "s" })
        })
        .collect();
    out += &format!(
        "compression: {}\n",
        if compression.is_empty() { "no chunks".to_string() } else { compression.join(", ") }
    );
    out += &format!("messages:    {total}{}\n", if scan.intact() { "" } else { " (readable)" });
    let mut topics: Vec<(&String, &(String, u64))> = counts.iter().collect();
    topics.sort_by(|a, b| natural_cmp(a.0, b.0));
    out += "channels:\n";
    for (topic, (schema, n)) in topics {
        let rate =
            if duration_ns > 0 { format!("{:.1} Hz", *n as f64 / (duration_ns as f64 * 1e-9)) } else { "-".into() };
        out += &format!("  {topic:<40} {schema:<32} {n:>9} msgs {rate:>10}\n");
    }
    let mut rigs: Vec<(&String, &u64)> = shots.iter().collect();
    rigs.sort_by(|a, b| natural_cmp(a.0, b.0));
    out += "shots:\n";
    for (rig, n) in rigs {
        out += &format!("  {rig}: {n} predicted\n");
    }
    if !metadata.is_empty() {
        out += "metadata:\n";
        out += &metadata.join("\n");
        out.push('\n');
    }
    Ok(Info { text: out, intact: scan.intact() })
}

/// Natural order: runs of digits compare as numbers, so rig2 comes before rig10.
pub fn natural_cmp(a: &str, b: &str) -> Ordering {
    let (mut a, mut b) = (a, b);
    loop {
        let (Some(ca), Some(cb)) = (a.chars().next(), b.chars().next()) else {
            return a.len().cmp(&b.len());
        };
        let ord = if ca.is_ascii_digit() && cb.is_ascii_digit() {
            let na = a.find(|c: char| !c.is_ascii_digit()).unwrap_or(a.len());
            let nb = b.find(|c: char| !c.is_ascii_digit()).unwrap_or(b.len());
            let (da, db) = (a[..na].trim_start_matches('0'), b[..nb].trim_start_matches('0'));
            let ord = da.len().cmp(&db.len()).then_with(|| da.cmp(db)).then_with(|| na.cmp(&nb));
            (a, b) = (&a[na..], &b[nb..]);
            ord
        } else {
            (a, b) = (&a[ca.len_utf8()..], &b[cb.len_utf8()..]);
            ca.cmp(&cb)
        };
        if ord != Ordering::Equal {
            return ord;
        }
    }
}

/// A Unix time in nanoseconds as an ISO 8601 UTC date with milliseconds.
fn utc(t_ns: u64) -> String {
    humantime::format_rfc3339_millis(UNIX_EPOCH + Duration::from_nanos(t_ns)).to_string()
}

/// A duration for people: `850 ms`, `12.345 s`, `3 min 04.5 s`, `2 h 05 min 09 s`.
pub fn human_duration(ns: u64) -> String {
    let s = ns as f64 * 1e-9;
    if s < 1.0 {
        format!("{:.0} ms", s * 1e3)
    } else if s < 60.0 {
        format!("{s:.3} s")
    } else if s < 3600.0 {
        format!("{} min {:04.1} s", (s / 60.0).floor(), s % 60.0)
    } else {
        let whole = s as u64;
        format!("{} h {:02} min {:02} s", whole / 3600, whole % 3600 / 60, whole % 60)
    }
}

fn human_bytes(n: u64) -> String {
    match n {
        0..1_000 => format!("{n} bytes"),
        1_000..1_000_000 => format!("{:.1} kB", n as f64 / 1e3),
        _ => format!("{:.1} MB", n as f64 / 1e6),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rigs_sort_naturally() {
        let mut rigs = vec!["rig10", "rig2", "rig1", "bay1", "rig02"];
        rigs.sort_by(|a, b| natural_cmp(a, b));
        assert_eq!(rigs, ["bay1", "rig1", "rig2", "rig02", "rig10"]);
        let mut topics = vec!["/golf/rig10/launch", "/golf/rig2/launch", "/golf/rig1/status"];
        topics.sort_by(|a, b| natural_cmp(a, b));
        assert_eq!(topics, ["/golf/rig1/status", "/golf/rig2/launch", "/golf/rig10/launch"]);
    }

    #[test]
    fn durations_and_dates_read_as_people_write_them() {
        assert_eq!(human_duration(850_000_000), "850 ms");
        assert_eq!(human_duration(12_345_000_000), "12.345 s");
        assert_eq!(human_duration(184_500_000_000), "3 min 04.5 s");
        assert_eq!(human_duration(7_509_000_000_000), "2 h 05 min 09 s");
        // 2026-11-23T15:17:12Z is 1795447032 s after the epoch.
        assert_eq!(utc(1_795_447_032_123_000_000), "2026-11-23T15:17:12.123Z");
    }
}
