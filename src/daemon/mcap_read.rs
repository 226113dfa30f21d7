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

/// The MCAP magic that starts and ends a file.
pub const MAGIC: &[u8; 8] = b"\x89MCAP0\r\n";

/// The largest chunk (uncompressed) this reader will allocate.
pub const MAX_CHUNK_BYTES: u64 = 1 << 30;

/// No zstd frame expands more than this (a 3-byte RLE block header per 128 KiB block).
const ZSTD_MAX_RATIO: u64 = 1 << 16;

mod op {
    pub const HEADER: u8 = 0x01;
    pub const FOOTER: u8 = 0x02;
    pub const SCHEMA: u8 = 0x03;
    pub const CHANNEL: u8 = 0x04;
    pub const MESSAGE: u8 = 0x05;
    pub const CHUNK: u8 = 0x06;
    pub const MESSAGE_INDEX: u8 = 0x07;
    pub const CHUNK_INDEX: u8 = 0x08;
    pub const STATISTICS: u8 = 0x0B;
    pub const METADATA: u8 = 0x0C;
    pub const METADATA_INDEX: u8 = 0x0D;
    pub const SUMMARY_OFFSET: u8 = 0x0E;
    pub const DATA_END: u8 = 0x0F;
}

/// A schema record.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SchemaDef {
    pub name: String,
    pub encoding: String,
    pub data: Vec<u8>,
}

/// A channel record.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChannelDef {
    pub schema_id: u16,
    pub topic: String,
    pub message_encoding: String,
    pub metadata: BTreeMap<String, String>,
}

/// A message as read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RawMessage {
    pub channel_id: u16,
    pub sequence: u32,
    pub log_time: u64,
    pub publish_time: u64,
    pub data: Vec<u8>,
}

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

/// A bounded cursor over one record's body.
struct Body<'a> {
    b: &'a [u8],
    pos: usize,
}

type Parse<T> = Result<T, &'static str>;

impl<'a> Body<'a> {
    fn new(b: &'a [u8]) -> Self {
        Body { b, pos: 0 }
    }
    fn take(&mut self, n: u64) -> Parse<&'a [u8]> {
        let left = (self.b.len() - self.pos) as u64;
        if n > left {
            return Err("a length runs past the end of its record");
        }
        let s = &self.b[self.pos..self.pos + n as usize];
        self.pos += n as usize;
        Ok(s)
    }
    fn u8(&mut self) -> Parse<u8> {
        Ok(self.take(1)?[0])
    }
    fn u16(&mut self) -> Parse<u16> {
        Ok(u16::from_le_bytes(self.take(2)?.try_into().map_err(|_| "short")?))
    }
    fn u32(&mut self) -> Parse<u32> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().map_err(|_| "short")?))
    }
    fn u64(&mut self) -> Parse<u64> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().map_err(|_| "short")?))
    }
    fn string(&mut self) -> Parse<String> {
        let n = self.u32()?;
        std::str::from_utf8(self.take(n.into())?).map(str::to_string).map_err(|_| "a string is not UTF-8")
    }
    fn bytes32(&mut self) -> Parse<&'a [u8]> {
        let n = self.u32()?;
        self.take(n.into())
    }
    fn string_map(&mut self) -> Parse<BTreeMap<String, String>> {
        let mut inner = Body::new(self.bytes32()?);
        let mut m = BTreeMap::new();
        while !inner.done() {
            let k = inner.string()?;
            let v = inner.string()?;
            if m.insert(k, v).is_some() {
                return Err("a map repeats a key");
            }
        }
        Ok(m)
    }
    fn rest(&mut self) -> &'a [u8] {
        let s = &self.b[self.pos..];
        self.pos = self.b.len();
        s
    }
    fn done(&self) -> bool {
        self.pos == self.b.len()
    }
    fn end(&self) -> Parse<()> {
        if self.done() {
            Ok(())
        } else {
            Err("the record is longer than its fields")
        }
    }
}

/// A parsed record (only what a reader of impactd's recordings needs).
enum Rec<'a> {
    Schema(u16, SchemaDef),
    Channel(u16, ChannelDef),
    Message(RawMessage),
    Chunk(Box<ChunkBody<'a>>),
    Metadata(String, BTreeMap<String, String>),
    Statistics(BTreeMap<u16, u64>),
    Footer,
    Other,
}

struct ChunkBody<'a> {
    start_ns: u64,
    end_ns: u64,
    uncompressed_size: u64,
    crc: u32,
    compression: String,
    data: &'a [u8],
}

fn parse(opcode: u8, body: &[u8]) -> Parse<Rec<'_>> {
    let mut c = Body::new(body);
    let rec = match opcode {
        op::HEADER => {
            c.string()?;
            c.string()?;
            Rec::Other
        }
        op::FOOTER => {
            c.take(20)?;
            Rec::Footer
        }
        op::SCHEMA => {
            let id = c.u16()?;
            let name = c.string()?;
            let encoding = c.string()?;
            let data = c.bytes32()?.to_vec();
            Rec::Schema(id, SchemaDef { name, encoding, data })
        }
        op::CHANNEL => {
            let id = c.u16()?;
            let schema_id = c.u16()?;
            let topic = c.string()?;
            let message_encoding = c.string()?;
            let metadata = c.string_map()?;
            Rec::Channel(id, ChannelDef { schema_id, topic, message_encoding, metadata })
        }
        op::MESSAGE => Rec::Message(RawMessage {
            channel_id: c.u16()?,
            sequence: c.u32()?,
            log_time: c.u64()?,
            publish_time: c.u64()?,
            data: c.rest().to_vec(),
        }),
        op::CHUNK => {
            let start_ns = c.u64()?;
            let end_ns = c.u64()?;
            let uncompressed_size = c.u64()?;
            let crc = c.u32()?;
            let compression = c.string()?;
            let compressed_size = c.u64()?;
            let data = c.take(compressed_size)?;
            Rec::Chunk(Box::new(ChunkBody { start_ns, end_ns, uncompressed_size, crc, compression, data }))
        }
        op::METADATA => {
            let name = c.string()?;
            Rec::Metadata(name, c.string_map()?)
        }
        op::STATISTICS => {
            c.take(8 + 2 + 4 + 4 + 4 + 4 + 8 + 8)?;
            let mut inner = Body::new(c.bytes32()?);
            let mut counts = BTreeMap::new();
            while !inner.done() {
                let id = inner.u16()?;
                counts.insert(id, inner.u64()?);
            }
            Rec::Statistics(counts)
        }
        op::DATA_END => {
            c.u32()?;
            Rec::Other
        }
        op::SUMMARY_OFFSET => {
            c.u8()?;
            c.take(16)?;
            Rec::Other
        }
        op::METADATA_INDEX => {
            c.take(16)?;
            c.string()?;
            Rec::Other
        }
        op::CHUNK_INDEX => {
            c.take(32)?;
            c.bytes32()?;
            c.u64()?;
            c.string()?;
            c.take(16)?;
            Rec::Other
        }
        op::MESSAGE_INDEX => {
            c.u16()?;
            c.bytes32()?;
            Rec::Other
        }
        _ => return Err("unknown record type"),
    };
    c.end()?;
    Ok(rec)
}

/// The chunk's records, decompressed within bounds and checked against the chunk's CRC.
fn unpack(chunk: &ChunkBody) -> Result<Vec<u8>, String> {
    let n = chunk.uncompressed_size;
    let records = match chunk.compression.as_str() {
        "" => {
            if n != chunk.data.len() as u64 {
                return Err(format!("uncompressed chunk of {} bytes says {n}", chunk.data.len()));
            }
            chunk.data.to_vec()
        }
        "zstd" => {
            let bound = (chunk.data.len() as u64).saturating_mul(ZSTD_MAX_RATIO).min(MAX_CHUNK_BYTES);
            if n > bound {
                return Err(format!("chunk claims {n} bytes uncompressed from {} (at most {bound})", chunk.data.len()));
            }
            match zstd::zstd_safe::get_frame_content_size(chunk.data) {
                Ok(Some(framed)) if framed != n => {
                    return Err(format!("chunk claims {n} bytes uncompressed, its zstd frame {framed}"))
                }
                Err(_) => return Err("the zstd frame header is damaged".into()),
                _ => {}
            }
            let out = zstd::bulk::decompress(chunk.data, n as usize).map_err(|e| format!("zstd: {e}"))?;
            if out.len() as u64 != n {
                return Err(format!("chunk decompressed to {} bytes, not {n}", out.len()));
            }
            out
        }
        other => return Err(format!("unsupported chunk compression `{}`", other.escape_debug())),
    };
    if chunk.crc != 0 {
        let got = crc32fast::hash(&records);
        if got != chunk.crc {
            return Err(format!("chunk CRC {got:08x} is not the recorded {:08x}", chunk.crc));
        }
    }
    Ok(records)
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
                    Ok(messages) => self.chunks.push(ChunkSpan { offset: span.0, bytes: span.1, messages }),
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
