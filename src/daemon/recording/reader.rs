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
    pub reason: String,
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
    /// Messages in file order.
    pub messages: Vec<RawMessage>,
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
    pub stopped: Option<String>,
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
fn frame(bytes: &[u8], pos: usize) -> Result<(u8, &[u8], usize), String> {
    let left = bytes.len() - pos;
    if left < 9 {
        return Err(format!("cut off inside a record header ({left} bytes left)"));
    }
    let opcode = bytes[pos];
    let mut len = [0u8; 8];
    len.copy_from_slice(&bytes[pos + 1..pos + 9]);
    let len = u64::from_le_bytes(len);
    if len > (left - 9) as u64 {
        return Err(format!("record 0x{opcode:02x} claims {len} bytes; {} are left", left - 9));
    }
    let end = pos + 9 + len as usize;
    Ok((opcode, &bytes[pos + 9..end], end))
}

/// Whether a valid record starts at `pos` (a chunk only when it unpacks and its CRC matches).
fn valid_at(bytes: &[u8], pos: usize) -> bool {
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
    if !STARTS.contains(&bytes[pos]) {
        return false;
    }
    let Ok((opcode, body, _)) = frame(bytes, pos) else { return false };
    match parse(opcode, body) {
        Ok(Rec::Chunk(c)) => unpack(&c).is_ok(),
        Ok(_) => true,
        Err(_) => false,
    }
}

/// Reads everything readable from `bytes` (a whole MCAP file).
pub fn scan(bytes: &[u8], on_damage: OnDamage) -> Scan {
    let mut s = Scan::default();
    if !bytes.starts_with(MAGIC) {
        // A damaged magic costs nothing more when the records behind it are found.
        if on_damage == OnDamage::Stop || bytes.len() <= MAGIC.len() {
            s.stopped = Some("not an MCAP file (no magic)".into());
            return s;
        }
        let reason = "the opening magic is damaged".to_string();
        s.damage.push(Damage { offset: 0, bytes: MAGIC.len() as u64, time_range_ns: None, after_message: 0, reason });
    }
    let mut pos = MAGIC.len();
    while pos < bytes.len() {
        let damaged = match frame(bytes, pos) {
            Ok((opcode, body, next)) => match parse(opcode, body) {
                Ok(rec) => {
                    if s.take(rec, pos, next, bytes) {
                        break;
                    }
                    pos = next;
                    continue;
                }
                Err(e) if on_damage == OnDamage::Stop => {
                    // The length is intact as far as anyone can tell: step over the record.
                    let reason = format!("record 0x{opcode:02x}: {e}");
                    s.damage.push(Damage {
                        offset: pos as u64,
                        bytes: (next - pos) as u64,
                        time_range_ns: None,
                        after_message: s.messages.len(),
                        reason,
                    });
                    pos = next;
                    continue;
                }
                Err(e) => format!("record 0x{opcode:02x}: {e}"),
            },
            Err(e) => e,
        };
        if on_damage == OnDamage::Stop {
            s.stopped = Some(format!("at byte {pos}: {damaged}"));
            return s;
        }
        let next = (pos + 1..bytes.len()).find(|&p| valid_at(bytes, p)).unwrap_or(bytes.len());
        let after_message = s.messages.len();
        s.damage.push(Damage {
            offset: pos as u64,
            bytes: (next - pos) as u64,
            time_range_ns: None,
            after_message,
            reason: damaged,
        });
        pos = next;
    }
    if !bytes.starts_with(MAGIC) && s.chunks.is_empty() && s.messages.is_empty() {
        s.stopped = Some("not an MCAP file (no magic, no readable record)".into());
    }
    s
}

impl Scan {
    /// Takes one record; true when the file ends here (footer and magic).
    fn take(&mut self, rec: Rec, pos: usize, next: usize, bytes: &[u8]) -> bool {
        match rec {
            Rec::Schema(id, d) => {
                self.schemas.entry(id).or_insert(d);
            }
            Rec::Channel(id, d) => {
                self.channels.entry(id).or_insert(d);
            }
            Rec::Message(m) => self.messages.push(m),
            Rec::Metadata(name, m) => self.metadata.push((name, m)),
            Rec::Statistics(counts) => self.statistics = Some(counts),
            Rec::Footer => {
                self.finished = &bytes[next..] == MAGIC;
                if !self.finished {
                    self.damage.push(Damage {
                        offset: next as u64,
                        bytes: (bytes.len() - next) as u64,
                        time_range_ns: None,
                        after_message: self.messages.len(),
                        reason: "the footer is not followed by the closing magic".into(),
                    });
                }
                return true;
            }
            Rec::Other => {}
            Rec::Chunk(c) => {
                let span = (pos as u64, (next - pos) as u64);
                match unpack(&c).and_then(|records| self.chunk_records(&records)) {
                    Ok(messages) => {
                        self.chunks.push(ChunkSpan { offset: span.0, bytes: span.1, messages });
                        *self.compression.entry(c.compression.clone()).or_default() += 1;
                    }
                    Err(reason) => self.damage.push(Damage {
                        offset: span.0,
                        bytes: span.1,
                        time_range_ns: Some((c.start_ns, c.end_ns)),
                        after_message: self.messages.len(),
                        reason,
                    }),
                }
            }
        }
        false
    }

    /// The records of an unpacked chunk: all of them or none.
    fn chunk_records(&mut self, records: &[u8]) -> Result<u64, String> {
        let mut pos = 0;
        let mut recs = Vec::new();
        while pos < records.len() {
            let (opcode, body, next) = frame(records, pos).map_err(|e| format!("inside a chunk: {e}"))?;
            recs.push(parse(opcode, body).map_err(|e| format!("inside a chunk, record 0x{opcode:02x}: {e}"))?);
            pos = next;
        }
        if recs.iter().any(|r| matches!(r, Rec::Chunk(_) | Rec::Footer)) {
            return Err("a chunk holds a chunk or a footer".into());
        }
        let messages = recs.iter().filter(|r| matches!(r, Rec::Message(_))).count() as u64;
        for rec in recs {
            self.take(rec, 0, 0, &[]);
        }
        Ok(messages)
    }
}
