//! The records of an MCAP file, parsed within bounds: every length is checked against the bytes that hold it,
//! and a chunk is decompressed only to a size its zstd frame and the largest zstd ratio allow, then checked
//! against its CRC. Used by the reader (reader.rs).

use std::collections::BTreeMap;

use super::damage::{ChunkError, RecordError};

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

/// The largest chunk (uncompressed) this reader will allocate.
pub const MAX_CHUNK_BYTES: u64 = 1 << 30;

/// No zstd frame expands more than this (a 3-byte RLE block header per 128 KiB block).
const ZSTD_MAX_RATIO: u64 = 1 << 16;

pub(super) mod op {
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

/// A bounded cursor over one record's body.
pub(super) struct Body<'a> {
    b: &'a [u8],
    pos: usize,
}

pub(super) type Parse<T> = Result<T, RecordError>;

impl<'a> Body<'a> {
    fn new(b: &'a [u8]) -> Self {
        Body { b, pos: 0 }
    }
    fn take(&mut self, n: u64) -> Parse<&'a [u8]> {
        let left = (self.b.len() - self.pos) as u64;
        if n > left {
            return Err(RecordError::LengthPastRecord);
        }
        let s = &self.b[self.pos..self.pos + n as usize];
        self.pos += n as usize;
        Ok(s)
    }
    fn u8(&mut self) -> Parse<u8> {
        Ok(self.take(1)?[0])
    }
    fn u16(&mut self) -> Parse<u16> {
        Ok(u16::from_le_bytes(self.take(2)?.try_into().map_err(|_| RecordError::LengthPastRecord)?))
    }
    fn u32(&mut self) -> Parse<u32> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().map_err(|_| RecordError::LengthPastRecord)?))
    }
    fn u64(&mut self) -> Parse<u64> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().map_err(|_| RecordError::LengthPastRecord)?))
    }
    fn string(&mut self) -> Parse<String> {
        let n = self.u32()?;
        std::str::from_utf8(self.take(n.into())?).map(str::to_string).map_err(|_| RecordError::NotUtf8)
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
                return Err(RecordError::RepeatedKey);
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
            Err(RecordError::LongerThanFields)
        }
    }
}

/// A parsed record (only what a reader of impactd's recordings needs).
pub(super) enum Rec<'a> {
    Schema(u16, SchemaDef),
    Channel(u16, ChannelDef),
    Message(RawMessage),
    Chunk(Box<ChunkBody<'a>>),
    Metadata(String, BTreeMap<String, String>),
    Statistics(BTreeMap<u16, u64>),
    /// The start of the summary section (0: none) and the CRC of the summary through the footer's offsets.
    Footer {
        summary_start: u64,
        summary_offset_start: u64,
        summary_crc: u32,
    },
    /// The CRC of the data section (everything before this record).
    DataEnd {
        crc: u32,
    },
    Other,
}

pub(super) struct ChunkBody<'a> {
    pub(super) start_ns: u64,
    pub(super) end_ns: u64,
    pub(super) uncompressed_size: u64,
    pub(super) crc: u32,
    pub(super) compression: String,
    pub(super) data: &'a [u8],
}

pub(super) fn parse(opcode: u8, body: &[u8]) -> Parse<Rec<'_>> {
    let mut c = Body::new(body);
    let rec = match opcode {
        op::HEADER => {
            c.string()?;
            c.string()?;
            Rec::Other
        }
        op::FOOTER => {
            let summary_start = c.u64()?;
            let summary_offset_start = c.u64()?;
            Rec::Footer { summary_start, summary_offset_start, summary_crc: c.u32()? }
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
        op::DATA_END => Rec::DataEnd { crc: c.u32()? },
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
        _ => return Err(RecordError::UnknownType),
    };
    c.end()?;
    Ok(rec)
}

/// The chunk's records, decompressed within bounds and checked against the chunk's CRC.
pub(super) fn unpack(chunk: &ChunkBody) -> Result<Vec<u8>, ChunkError> {
    let n = chunk.uncompressed_size;
    let records = match chunk.compression.as_str() {
        "" => {
            if n != chunk.data.len() as u64 {
                return Err(ChunkError::UncompressedSize { data_bytes: chunk.data.len() as u64, claimed_bytes: n });
            }
            chunk.data.to_vec()
        }
        "zstd" => {
            let bound = (chunk.data.len() as u64).saturating_mul(ZSTD_MAX_RATIO).min(MAX_CHUNK_BYTES);
            if n > bound {
                return Err(ChunkError::ClaimsTooMuch {
                    claimed_bytes: n,
                    data_bytes: chunk.data.len() as u64,
                    bound_bytes: bound,
                });
            }
            match zstd::zstd_safe::get_frame_content_size(chunk.data) {
                Ok(Some(framed)) if framed != n => {
                    return Err(ChunkError::FrameDisagrees { claimed_bytes: n, framed_bytes: framed })
                }
                Err(_) => return Err(ChunkError::FrameHeader),
                _ => {}
            }
            let out = zstd::bulk::decompress(chunk.data, n as usize).map_err(|e| ChunkError::Zstd(e.into()))?;
            if out.len() as u64 != n {
                return Err(ChunkError::DecompressedSize { got_bytes: out.len() as u64, claimed_bytes: n });
            }
            out
        }
        other => return Err(ChunkError::UnsupportedCompression(other.to_string())),
    };
    if chunk.crc != 0 {
        let got = crc32fast::hash(&records);
        if got != chunk.crc {
            return Err(ChunkError::Crc { got, recorded: chunk.crc });
        }
    }
    Ok(records)
}
