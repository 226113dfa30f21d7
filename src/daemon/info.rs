//! `impactd info`: channels, counts, duration, shots and metadata of a recording, read by the bounded reader
//! ([`mcap_read`](super::mcap_read)) up to the first damage it cannot step over, which it names.

use std::collections::BTreeMap;
use std::path::Path;

use super::replay::{is_mcap, read_file};
use super::DaemonError;

/// A description of a recording for `impactd info`, and whether it could be read whole.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Info {
    pub text: String,
    /// Finished and undamaged.
    pub intact: bool,
}

/// Describes a recording: channels, counts, duration, shots, metadata, and anything it could not read.
pub fn info(path: &Path) -> Result<Info, DaemonError> {
    let bytes = read_file(path)?;
    if !is_mcap(&bytes) {
        return Err(DaemonError::NotMcap { path: path.display().to_string() });
    }
    let scan = super::mcap_read::scan(&bytes, super::mcap_read::OnDamage::Stop);
    let mut counts: BTreeMap<String, (String, u64)> = BTreeMap::new();
    let (mut first, mut last) = (u64::MAX, 0u64);
    let mut shots: BTreeMap<String, u64> = BTreeMap::new();
    for m in &scan.messages {
        first = first.min(m.log_time);
        last = last.max(m.log_time);
        let (topic, schema) = match scan.channels.get(&m.channel_id) {
            Some(c) => (c.topic.clone(), scan.schemas.get(&c.schema_id).map(|s| s.name.clone()).unwrap_or_default()),
            None => (format!("(unknown channel {})", m.channel_id), String::new()),
        };
        if let Some(rig) = topic.trim_start_matches('/').strip_prefix("golf/").and_then(|t| t.strip_suffix("/launch")) {
            *shots.entry(rig.to_string()).or_default() += 1;
        }
        counts.entry(topic).or_insert((schema, 0)).1 += 1;
    }
    let metadata: Vec<String> = scan
        .metadata
        .iter()
        .map(|(name, m)| {
            let keys: Vec<String> =
                m.iter().filter(|(k, _)| k.as_str() != "config_toml").map(|(k, v)| format!("{k}={v}")).collect();
            format!("  {name}: {}", keys.join(", "))
        })
        .collect();
    let total: u64 = counts.values().map(|c| c.1).sum();
    let mut out = format!("file:      {} ({} bytes)\n", path.display(), bytes.len());
    out += &format!(
        "complete:  {}\n",
        if scan.intact() {
            "yes (summary and footer present)"
        } else {
            "no: cut off or damaged; run `impactd recover`"
        }
    );
    for p in scan.problems() {
        out += &format!("damaged:   {p}\n");
    }
    if total > 0 {
        out += &format!("duration:  {:.3} s\n", (last - first) as f64 * 1e-9);
    }
    out += &format!("messages:  {total}{}\n", if scan.intact() { "" } else { " (readable)" });
    out += "channels:\n";
    for (topic, (schema, n)) in &counts {
        out += &format!("  {topic:<40} {schema:<32} {n:>9}\n");
    }
    out += "shots:\n";
    for (rig, n) in &shots {
        out += &format!("  {rig}: {n} predicted\n");
    }
    if !metadata.is_empty() {
        out += "metadata:\n";
        out += &metadata.join("\n");
        out.push('\n');
    }
    Ok(Info { text: out, intact: scan.intact() })
}
