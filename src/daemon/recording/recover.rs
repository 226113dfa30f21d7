//! `impactd recover`: copies everything readable from a cut-off or damaged recording into a new, finished MCAP
//! file, and says exactly what it could not copy.
//!
//! The input is read by [`mcap_read`](crate::daemon::recording::reader) with resynchronisation: every chunk whose bytes are
//! intact is kept, wherever the damage is. Schemas and channels come from wherever they can be read (a chunk or
//! the summary), so an intact chunk's messages are kept even when the chunk that first declared their channel
//! is lost. What is lost is reported per channel (when the summary's statistics say how many there were) and as
//! log-time ranges.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use super::damage::DamageReason;
use super::stream::read_opened;
use crate::daemon::recording::reader::{ChannelDef, OnDamage, RawMessage, Scan};
use crate::daemon::{DaemonError, ReadError};

/// Messages of one channel: kept, and lost when the file says how many there were.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ChannelTally {
    pub kept: u64,
    /// `None`: the summary that counts them is missing (a cut-off file), so the loss per channel is unknown.
    pub lost: Option<u64>,
}

/// A part of the input that was not copied.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Loss {
    pub offset: u64,
    pub bytes: u64,
    /// Log times (ns) the lost part lies within: a damaged chunk's own range, or between its readable
    /// neighbours' messages (`None` at an open end).
    pub from_ns: Option<u64>,
    pub to_ns: Option<u64>,
    pub reason: DamageReason,
}

/// What `recover` did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Recovered {
    pub messages: u64,
    /// The input was finished and undamaged: nothing was lost.
    pub complete: bool,
    /// Chunks copied whole.
    pub chunks: u64,
    pub channels: BTreeMap<String, ChannelTally>,
    pub losses: Vec<Loss>,
}

impl Recovered {
    /// The report for people, one line each.
    pub fn report(&self) -> Vec<String> {
        let t = |ns: Option<u64>| ns.map(|v| format!("{:.3} s", v as f64 * 1e-9)).unwrap_or_else(|| "?".into());
        let mut out = Vec::new();
        for l in &self.losses {
            out.push(format!(
                "lost {} bytes at offset {} (log time {} to {}): {}",
                l.bytes,
                l.offset,
                t(l.from_ns),
                t(l.to_ns),
                l.reason
            ));
        }
        for (topic, c) in &self.channels {
            let lost = match c.lost {
                Some(n) => format!("{n} lost"),
                None => "lost unknown (no summary in the file)".into(),
            };
            out.push(format!("{topic}: {} kept, {lost}", c.kept));
        }
        out
    }
}

fn mcap_err(path: &Path, e: mcap::McapError) -> DaemonError {
    DaemonError::Mcap { path: path.display().to_string(), source: e }
}

/// The losses a scan found, with time ranges.
fn losses(s: &Scan) -> Vec<Loss> {
    let file_bytes = s.file_bytes;
    let mut out: Vec<Loss> = s
        .damage
        .iter()
        .zip(&s.damage_neighbours_ns)
        .map(|(d, &(before_ns, after_ns))| {
            let (from_ns, to_ns) = match d.time_range_ns {
                Some((a, b)) if a <= b => (Some(a), Some(b)),
                _ => (before_ns, after_ns),
            };
            Loss { offset: d.offset, bytes: d.bytes, from_ns, to_ns, reason: d.reason.clone() }
        })
        .collect();
    let damaged_to_the_end = s.damage.last().is_some_and(|d| d.offset + d.bytes >= file_bytes);
    if !s.finished && s.stopped.is_none() && !damaged_to_the_end {
        let end_ns = s.last_message_ns;
        out.push(Loss { offset: 0, bytes: 0, from_ns: end_ns, to_ns: None, reason: DamageReason::CutOff });
    }
    out
}

/// The metadata record a recovered file carries: `from`, `recovered_at` (UTC), `input_complete`, `messages`.
pub const RECOVERED_METADATA: &str = "recovered";

/// Copies every readable message and metadata record of `input` into a new, finished MCAP file at `output`.
/// An existing `output` is replaced only with `overwrite`.
pub fn recover(input: &Path, output: &Path, overwrite: bool) -> Result<Recovered, DaemonError> {
    // Nothing readable at all (not an MCAP file): refused before the output is created. Only a damaged magic
    // makes this take a pass of its own.
    // (A pipe is read into memory once, and only when it starts with the magic.)
    let mut opened = super::source::Opened::open(input)?;
    if !opened.is_mcap() {
        let s = read_opened(opened, input, OnDamage::Resync, |_, _, _| {})?;
        if let Some(reason) = &s.stopped {
            return Err(ReadError::Unreadable { path: input.display().to_string(), source: reason.clone() }.into());
        }
        opened = super::source::Opened::open(input)?;
    }
    let file = crate::output_file::create_output(output, overwrite)?;
    let mut w = mcap::WriteOptions::new()
        .compression(Some(mcap::Compression::Zstd))
        .profile("")
        .create(std::io::BufWriter::new(file))
        .map_err(|e| mcap_err(output, e))?;
    let mut schema_ids: HashMap<u16, u16> = HashMap::new();
    let mut channel_ids: HashMap<u16, u16> = HashMap::new();
    let mut kept: BTreeMap<u16, u64> = BTreeMap::new();
    let mut failed: Option<mcap::McapError> = None;
    let s = read_opened(opened, input, OnDamage::Resync, |s, channel, m| {
        if failed.is_some() {
            return;
        }
        let written = copy_message(&mut w, s, channel, &m, &mut schema_ids, &mut channel_ids);
        match written {
            Ok(()) => *kept.entry(m.channel_id).or_default() += 1,
            Err(e) => failed = Some(e),
        }
    })?;
    if let Some(e) = failed {
        return Err(mcap_err(output, e));
    }
    if let Some(reason) = &s.stopped {
        return Err(ReadError::Unreadable { path: input.display().to_string(), source: reason.clone() }.into());
    }
    for (name, metadata) in &s.metadata {
        w.write_metadata(&mcap::records::Metadata { name: name.clone(), metadata: metadata.clone() })
            .map_err(|e| mcap_err(output, e))?;
    }
    // Say so in the file: `impactd info` reports a recovered recording and what it was recovered from.
    let mut note = BTreeMap::new();
    note.insert("from".to_string(), input.display().to_string());
    note.insert(
        "recovered_at".to_string(),
        humantime::format_rfc3339_seconds(
            std::time::UNIX_EPOCH + std::time::Duration::from_nanos(crate::daemon::clock::Clock::system().wall_ns()),
        )
        .to_string(),
    );
    note.insert("input_complete".to_string(), s.intact().to_string());
    note.insert("messages".to_string(), s.message_count.to_string());
    w.write_metadata(&mcap::records::Metadata { name: RECOVERED_METADATA.into(), metadata: note })
        .map_err(|e| mcap_err(output, e))?;
    w.finish().map_err(|e| mcap_err(output, e))?;
    let topic = |id: u16| s.channels.get(&id).map(|c| c.topic.clone()).unwrap_or_else(|| format!("channel {id}"));
    let mut channels: BTreeMap<String, ChannelTally> = BTreeMap::new();
    let ids: std::collections::BTreeSet<u16> =
        kept.keys().chain(s.statistics.iter().flat_map(|st| st.keys())).copied().collect();
    for id in ids {
        let k = kept.get(&id).copied().unwrap_or(0);
        let lost = s.statistics.as_ref().map(|st| st.get(&id).copied().unwrap_or(0).saturating_sub(k));
        channels.insert(topic(id), ChannelTally { kept: k, lost });
    }
    Ok(Recovered {
        messages: s.message_count,
        complete: s.intact(),
        chunks: s.chunks.len() as u64,
        channels,
        losses: losses(&s),
    })
}

/// Writes one message, declaring its schema and channel in the output the first time they are used.
fn copy_message<W: std::io::Write + std::io::Seek>(
    w: &mut mcap::Writer<W>,
    s: &Scan,
    channel: Option<&ChannelDef>,
    m: &RawMessage,
    schema_ids: &mut HashMap<u16, u16>,
    channel_ids: &mut HashMap<u16, u16>,
) -> Result<(), mcap::McapError> {
    let id = match channel_ids.get(&m.channel_id) {
        Some(id) => *id,
        None => {
            let id = match channel {
                Some(c) => {
                    let schema_id = match (c.schema_id, s.schemas.get(&c.schema_id)) {
                        (0, _) | (_, None) => 0,
                        (sid, Some(schema)) => match schema_ids.get(&sid) {
                            Some(id) => *id,
                            None => {
                                let id = w.add_schema(&schema.name, &schema.encoding, &schema.data)?;
                                schema_ids.insert(sid, id);
                                id
                            }
                        },
                    };
                    w.add_channel(schema_id, &c.topic, &c.message_encoding, &c.metadata)?
                }
                // Its channel record is lost everywhere: keep the bytes under a name that says so.
                None => w.add_channel(0, &format!("/unknown_channel_{}", m.channel_id), "", &BTreeMap::new())?,
            };
            channel_ids.insert(m.channel_id, id);
            id
        }
    };
    let header = mcap::records::MessageHeader {
        channel_id: id,
        sequence: m.sequence,
        log_time: m.log_time,
        publish_time: m.publish_time,
    };
    w.write_to_known_channel(&header, &m.data)
}
