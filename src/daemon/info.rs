//! `impactd info`: channels, counts, duration, shots and metadata of a recording.

use std::collections::BTreeMap;
use std::path::Path;

use super::replay::{is_mcap, mcap_err, read_file};
use super::DaemonError;

/// A description of a recording for `impactd info`.
pub fn info(path: &Path) -> Result<String, DaemonError> {
    let bytes = read_file(path)?;
    if !is_mcap(&bytes) {
        return Err(DaemonError::NotMcap { path: path.display().to_string() });
    }
    let mut counts: BTreeMap<String, (String, u64)> = BTreeMap::new();
    let (mut first, mut last) = (u64::MAX, 0u64);
    let mut damaged = None;
    let mut shots: BTreeMap<String, u64> = BTreeMap::new();
    for message in mcap::MessageStream::new_with_options(&bytes, mcap::read::Options::IgnoreEndMagic.into())
        .map_err(|e| mcap_err(path, e))?
    {
        let m = match message {
            Ok(m) => m,
            Err(e) => {
                damaged = Some(e.to_string());
                break;
            }
        };
        first = first.min(m.log_time);
        last = last.max(m.log_time);
        let schema = m.channel.schema.as_ref().map(|s| s.name.clone()).unwrap_or_default();
        let entry = counts.entry(m.channel.topic.clone()).or_insert((schema, 0));
        entry.1 += 1;
        let topic = m.channel.topic.trim_start_matches('/');
        if let Some(rig) = crate::wire::keys::rig_of_launch(topic) {
            *shots.entry(rig.to_string()).or_default() += 1;
        }
    }
    let mut metadata = Vec::new();
    for record in mcap::read::LinearReader::new_with_options(&bytes, mcap::read::Options::IgnoreEndMagic.into())
        .map_err(|e| mcap_err(path, e))?
        .flatten()
    {
        if let mcap::records::Record::Metadata(m) = record {
            let keys: Vec<String> = m
                .metadata
                .iter()
                .filter(|(k, _)| k.as_str() != "config_toml")
                .map(|(k, v)| format!("{k}={v}"))
                .collect();
            metadata.push(format!("  {}: {}", m.name, keys.join(", ")));
        }
    }
    let complete = mcap::read::footer(&bytes).is_ok() && damaged.is_none();
    let total: u64 = counts.values().map(|c| c.1).sum();
    let mut out = format!("file:      {} ({} bytes)\n", path.display(), bytes.len());
    out += &format!(
        "complete:  {}\n",
        if complete { "yes (summary and footer present)" } else { "no: cut off; run `impactd recover`" }
    );
    if let Some(d) = damaged {
        out += &format!("damaged:   {d}\n");
    }
    if total > 0 {
        out += &format!("duration:  {:.3} s\n", (last - first) as f64 * 1e-9);
    }
    out += &format!("messages:  {total}\n");
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
    Ok(out)
}
