//! A bounded, record-level MCAP reader for recordings that may be cut off or damaged.
//!
//! Every length read from the file is checked against the bytes that hold it before anything is allocated: a
//! record may not claim more than the file has left, a string or map more than its record, a chunk's compressed
//! data more than its record, and a chunk's uncompressed size is checked against the zstd frame's own size and
//! a ratio no zstd frame can exceed before the buffer exists. Each chunk's CRC is checked. Every loop advances
//! or stops, so a scan ends on any input.
//!
//! A damaged record whose length is intact (a chunk with a bad CRC, a record that does not parse) is stepped
//! over and named in [`Scan::damage`]. Damage to the framing itself (a length that points nowhere) stops the
//! scan, unless it is asked to resynchronise: then it searches forward for the next record that checks out (a
//! chunk only when its sizes agree and its CRC matches) and goes on from there.

use std::collections::{BTreeMap, HashMap};

use super::damage::{DamageReason, ScanStop};
use super::source::{Source, MAX_RECORD_BYTES};

pub use crate::daemon::recording::records::MAX_CHUNK_BYTES;
use crate::daemon::recording::records::{op, parse, unpack, Rec};
pub use crate::daemon::recording::records::{ChannelDef, RawMessage, SchemaDef};

/// The MCAP magic that starts and ends a file.
pub const MAGIC: &[u8; 8] = b"\x89MCAP0\r\n";

/// Something the scan could not read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Damage {
    /// Byte offset where the unreadable part starts.
    pub offset: u64,
    /// Its length in bytes.
    pub bytes: u64,
    /// The log-time range a damaged chunk's header claims, if it could be read.
    pub time_range_ns: Option<(u64, u64)>,
    /// How many messages had been read before it (the neighbours bound its time range).
    pub after_message: usize,
    pub reason: DamageReason,
}

/// One chunk that was read whole: where it is in the file and how many messages it held.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ChunkSpan {
    pub offset: u64,
    pub bytes: u64,
    pub messages: u64,
}

/// Everything a scan could read, and what it could not.
#[derive(Debug, Clone, Default)]
pub struct Scan {
    pub schemas: HashMap<u16, SchemaDef>,
    pub channels: HashMap<u16, ChannelDef>,
    /// Messages in file order ([`scan`] keeps them; [`scan_source`] hands them to its visitor instead).
    pub messages: Vec<RawMessage>,
    /// Messages read.
    pub message_count: u64,
    /// The size of the file read.
    pub file_bytes: u64,
    /// The earliest and the latest log time of the messages read.
    pub first_log_time_ns: Option<u64>,
    pub last_log_time_ns: Option<u64>,
    /// The log time of the last message read, in file order.
    pub last_message_ns: Option<u64>,
    /// Per entry of `damage`: the log times of the messages read just before and just after it.
    pub damage_neighbours_ns: Vec<(Option<u64>, Option<u64>)>,
    pub metadata: Vec<(String, BTreeMap<String, String>)>,
    /// Messages per channel the summary's statistics record counts (when the summary was read).
    pub statistics: Option<BTreeMap<u16, u64>>,
    pub chunks: Vec<ChunkSpan>,
    /// Chunks read whole per compression (`zstd`, `lz4`, "" for none).
    pub compression: BTreeMap<String, u64>,
    pub damage: Vec<Damage>,
    /// The footer and the closing magic were read: the file was finished.
    pub finished: bool,
    /// The scan stopped at damage it could not step over.
    pub stopped: Option<ScanStop>,
}

impl Scan {
    /// Nothing was damaged and the file was finished.
    pub fn intact(&self) -> bool {
        self.finished && self.damage.is_empty() && self.stopped.is_none()
    }

    /// One line per problem, for people.
    pub fn problems(&self) -> Vec<String> {
        let mut out: Vec<String> =
            self.damage.iter().map(|d| format!("{} bytes at offset {}: {}", d.bytes, d.offset, d.reason)).collect();
        if let Some(s) = &self.stopped {
            out.push(format!("stopped: {s}"));
        } else if !self.finished {
            out.push("cut off: no footer (the file was not closed)".into());
        }
        out
    }
}

/// How a scan treats damage to the framing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OnDamage {
    /// Stop at the first damage that cannot be stepped over.
    Stop,
    /// Search forward for the next valid record.
    Resync,
}

/// The (opcode, body, next offset) of the record at `pos`, if its length fits the file.
fn frame<S: Source>(src: &mut S, pos: u64) -> Result<(u8, &[u8], u64), DamageReason> {
    let left = src.size_bytes() - pos;
    if left < 9 {
        return Err(DamageReason::CutInHeader { left_bytes: left });
    }
    let header = src.get(pos, 9).map_err(|e| DamageReason::Unreadable(e.into()))?;
    let opcode = header[0];
    let mut len = [0u8; 8];
    len.copy_from_slice(&header[1..9]);
    let len = u64::from_le_bytes(len);
    if len > left - 9 {
        return Err(DamageReason::PastEnd { opcode, claimed_bytes: len, left_bytes: left - 9 });
    }
    if len > MAX_RECORD_BYTES {
        return Err(DamageReason::TooLong { opcode, claimed_bytes: len });
    }
    let body = src.get(pos + 9, len as usize).map_err(|e| DamageReason::Unreadable(e.into()))?;
    Ok((opcode, body, pos + 9 + len))
}

/// [`frame`] inside a chunk's records, in memory.
fn frame_in(bytes: &[u8], pos: usize) -> Result<(u8, &[u8], usize), DamageReason> {
    let left = bytes.len() - pos;
    if left < 9 {
        return Err(DamageReason::CutInHeader { left_bytes: left as u64 });
    }
    let opcode = bytes[pos];
    let mut len = [0u8; 8];
    len.copy_from_slice(&bytes[pos + 1..pos + 9]);
    let len = u64::from_le_bytes(len);
    if len > (left - 9) as u64 {
        return Err(DamageReason::PastEnd { opcode, claimed_bytes: len, left_bytes: (left - 9) as u64 });
    }
    let end = pos + 9 + len as usize;
    Ok((opcode, &bytes[pos + 9..end], end))
}

/// Whether a valid record starts at `pos` (a chunk only when it unpacks and its CRC matches).
fn valid_at<S: Source>(src: &mut S, pos: u64) -> bool {
    const STARTS: [u8; 9] = [
        op::CHUNK,
        op::METADATA,
        op::SCHEMA,
        op::CHANNEL,
        op::DATA_END,
        op::CHUNK_INDEX,
        op::STATISTICS,
        op::METADATA_INDEX,
        op::SUMMARY_OFFSET,
    ];
    if !src.get(pos, 1).is_ok_and(|b| STARTS.contains(&b[0])) {
        return false;
    }
    let Ok((opcode, body, _)) = frame(src, pos) else { return false };
    match parse(opcode, body) {
        Ok(Rec::Chunk(c)) => unpack(&c).is_ok(),
        Ok(_) => true,
        Err(_) => false,
    }
}

/// Reads everything readable from `bytes` (a whole MCAP file in memory), keeping every message in file order.
pub fn scan(bytes: &[u8], on_damage: OnDamage) -> Scan {
    let mut messages = Vec::new();
    let mut s = scan_source(&mut { bytes }, on_damage, &mut |_, m| messages.push(m));
    s.messages = messages;
    s
}

/// The CRCs a scan keeps as it goes: the data section's up to the current record, and the bytes after the data
/// end (the summary section, which the footer's CRC covers) while they stay small.
#[derive(Default)]
struct Crcs {
    data: crc32fast::Hasher,
    /// Where the data end record starts, once it was read; the bytes from there are kept in `summary`.
    data_end_at: Option<u64>,
    summary: Vec<u8>,
    summary_too_big: bool,
}

/// Summary sections up to this size have their CRC checked.
const MAX_CHECKED_SUMMARY_BYTES: usize = 64 << 20;

impl Crcs {
    /// Feeds the bytes `[from, to)` of `src`, a bounded piece at a time.
    fn feed<S: Source>(&mut self, src: &mut S, from: u64, to: u64) {
        let mut at = from;
        while at < to {
            let n = (to - at).min(1 << 20) as usize;
            let Ok(piece) = src.get(at, n) else { return };
            if self.data_end_at.is_none() {
                self.data.update(piece);
            } else if !self.summary_too_big {
                if self.summary.len() + piece.len() > MAX_CHECKED_SUMMARY_BYTES {
                    self.summary_too_big = true;
                    self.summary = Vec::new();
                } else {
                    self.summary.extend_from_slice(piece);
                }
            }
            at += n as u64;
        }
    }
}

/// Reads everything readable from `src`, handing each message to `visit` in file order with the scan so far
/// (its channels and schemas as read up to that message); the returned scan keeps no messages.
pub fn scan_source<S: Source>(src: &mut S, on_damage: OnDamage, visit: &mut dyn FnMut(&Scan, RawMessage)) -> Scan {
    let len = src.size_bytes();
    let mut s = Scan { file_bytes: len, ..Scan::default() };
    let magic_ok = src.get(0, MAGIC.len()).is_ok_and(|b| b == MAGIC);
    if !magic_ok {
        // A damaged magic costs nothing more when the records behind it are found.
        if on_damage == OnDamage::Stop || len <= MAGIC.len() as u64 {
            s.stopped = Some(ScanStop::NoMagic);
            return s;
        }
        let reason = DamageReason::OpeningMagic;
        s.damage.push(Damage { offset: 0, bytes: MAGIC.len() as u64, time_range_ns: None, after_message: 0, reason });
    }
    let mut crcs = Crcs::default();
    crcs.feed(src, 0, MAGIC.len() as u64);
    let mut pos = MAGIC.len() as u64;
    while pos < len {
        let damaged = match frame(src, pos) {
            Ok((opcode, body, next)) => match parse(opcode, body) {
                Ok(rec) => {
                    if let Rec::DataEnd { .. } = rec {
                        crcs.data_end_at = Some(pos);
                    }
                    let footer = s.take(rec, pos, next, &crcs, visit);
                    crcs.feed(src, pos, next);
                    if footer {
                        let magic =
                            len - next == MAGIC.len() as u64 && src.get(next, MAGIC.len()).is_ok_and(|b| b == MAGIC);
                        s.finished = magic;
                        if !magic {
                            s.damage.push(Damage {
                                offset: next,
                                bytes: len - next,
                                time_range_ns: None,
                                after_message: s.message_count as usize,
                                reason: DamageReason::ClosingMagic,
                            });
                        }
                        break;
                    }
                    pos = next;
                    continue;
                }
                Err(e) if on_damage == OnDamage::Stop => {
                    // The length is intact as far as anyone can tell: step over the record.
                    let reason = DamageReason::Record { opcode, source: e };
                    s.damage.push(Damage {
                        offset: pos,
                        bytes: next - pos,
                        time_range_ns: None,
                        after_message: s.message_count as usize,
                        reason,
                    });
                    crcs.feed(src, pos, next);
                    pos = next;
                    continue;
                }
                Err(e) => DamageReason::Record { opcode, source: e },
            },
            Err(e) => e,
        };
        if on_damage == OnDamage::Stop {
            s.stopped = Some(ScanStop::At { offset: pos, reason: damaged });
            return s;
        }
        let next = (pos + 1..len).find(|&p| valid_at(src, p)).unwrap_or(len);
        let after_message = s.message_count as usize;
        s.damage.push(Damage { offset: pos, bytes: next - pos, time_range_ns: None, after_message, reason: damaged });
        crcs.feed(src, pos, next);
        pos = next;
    }
    if !magic_ok && s.chunks.is_empty() && s.message_count == 0 {
        s.stopped = Some(ScanStop::NothingReadable);
    }
    while s.damage_neighbours_ns.len() < s.damage.len() {
        s.damage_neighbours_ns.push((s.last_message_ns, None));
    }
    s
}

impl Scan {
    /// Takes one record at `pos..next` (0..0 inside a chunk); true when it is the footer.
    fn take(&mut self, rec: Rec, pos: u64, next: u64, crcs: &Crcs, visit: &mut dyn FnMut(&Scan, RawMessage)) -> bool {
        match rec {
            Rec::Schema(id, d) => {
                self.schemas.entry(id).or_insert(d);
            }
            Rec::Channel(id, d) => {
                self.channels.entry(id).or_insert(d);
            }
            Rec::Message(m) => {
                self.message_count += 1;
                self.first_log_time_ns = Some(self.first_log_time_ns.map_or(m.log_time, |t| t.min(m.log_time)));
                self.last_log_time_ns = Some(self.last_log_time_ns.map_or(m.log_time, |t| t.max(m.log_time)));
                while self.damage_neighbours_ns.len() < self.damage.len() {
                    self.damage_neighbours_ns.push((self.last_message_ns, Some(m.log_time)));
                }
                self.last_message_ns = Some(m.log_time);
                visit(self, m);
            }
            Rec::Metadata(name, m) => self.metadata.push((name, m)),
            Rec::Statistics(counts) => self.statistics = Some(counts),
            Rec::DataEnd { crc } => {
                // 0: the writer computed none. Covers everything before the record, the opening magic included.
                let actual = crcs.data.clone().finalize();
                if crc != 0 && actual != crc {
                    self.damage.push(Damage {
                        offset: 0,
                        bytes: pos,
                        time_range_ns: None,
                        after_message: self.message_count as usize,
                        reason: DamageReason::DataCrc { actual, recorded: crc },
                    });
                }
            }
            Rec::Footer { summary_start, summary_offset_start, summary_crc } => {
                // The summary CRC covers the summary section (or nothing) through the footer's two offsets.
                let start = if summary_start == 0 { pos } else { summary_start };
                if summary_crc != 0 {
                    let mut footer = vec![op::FOOTER];
                    footer.extend_from_slice(&(8u64 + 8 + 4).to_le_bytes());
                    footer.extend_from_slice(&summary_start.to_le_bytes());
                    footer.extend_from_slice(&summary_offset_start.to_le_bytes());
                    let summary = crcs.data_end_at.and_then(|at| {
                        let from = usize::try_from(start.checked_sub(at)?).ok()?;
                        (!crcs.summary_too_big && start <= pos).then(|| crcs.summary.get(from..)).flatten()
                    });
                    let actual = summary.map(|bytes| {
                        let mut h = crc32fast::Hasher::new();
                        h.update(bytes);
                        h.update(&footer);
                        h.finalize()
                    });
                    let unchecked = crcs.summary_too_big && start >= crcs.data_end_at.unwrap_or(u64::MAX);
                    if actual != Some(summary_crc) && !unchecked {
                        self.damage.push(Damage {
                            offset: start,
                            bytes: (pos + 1 + 8 + 16).saturating_sub(start),
                            time_range_ns: None,
                            after_message: self.message_count as usize,
                            reason: DamageReason::SummaryCrc { recorded: summary_crc },
                        });
                    }
                }
                return true;
            }
            Rec::Other => {}
            Rec::Chunk(c) => match unpack(&c)
                .map_err(DamageReason::from)
                .and_then(|records| self.chunk_records(&records, crcs, visit))
            {
                Ok(messages) => {
                    self.chunks.push(ChunkSpan { offset: pos, bytes: next - pos, messages });
                    *self.compression.entry(c.compression.clone()).or_default() += 1;
                }
                Err(reason) => self.damage.push(Damage {
                    offset: pos,
                    bytes: next - pos,
                    time_range_ns: Some((c.start_ns, c.end_ns)),
                    after_message: self.message_count as usize,
                    reason,
                }),
            },
        }
        false
    }

    /// The records of an unpacked chunk: all of them or none.
    fn chunk_records(
        &mut self,
        records: &[u8],
        crcs: &Crcs,
        visit: &mut dyn FnMut(&Scan, RawMessage),
    ) -> Result<u64, DamageReason> {
        let mut pos = 0;
        let mut recs = Vec::new();
        while pos < records.len() {
            let (opcode, body, next) = frame_in(records, pos).map_err(|e| DamageReason::ChunkFraming(Box::new(e)))?;
            recs.push(parse(opcode, body).map_err(|source| DamageReason::ChunkRecord { opcode, source })?);
            pos = next;
        }
        if recs.iter().any(|r| matches!(r, Rec::Chunk(_) | Rec::Footer { .. } | Rec::DataEnd { .. })) {
            return Err(DamageReason::ChunkNesting);
        }
        let messages = recs.iter().filter(|r| matches!(r, Rec::Message(_))).count() as u64;
        for rec in recs {
            self.take(rec, 0, 0, crcs, visit);
        }
        Ok(messages)
    }
}
