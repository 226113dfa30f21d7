//! What the bounded MCAP reader could not read, as typed reasons: a record that does not parse
//! ([`RecordError`]), a chunk that does not unpack ([`ChunkError`]), damage to the framing or a checksum
//! ([`DamageReason`]) and why a scan stopped ([`ScanStop`]). Their texts are what `impactd info` and `recover`
//! print.

/// A record whose length is intact but whose fields do not parse.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum RecordError {
    #[error("a length runs past the end of its record")]
    LengthPastRecord,
    #[error("a string is not UTF-8")]
    NotUtf8,
    #[error("a map repeats a key")]
    RepeatedKey,
    #[error("the record is longer than its fields")]
    LongerThanFields,
    #[error("unknown record type")]
    UnknownType,
}

/// A chunk record that parses but whose records cannot be unpacked.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ChunkError {
    #[error("uncompressed chunk of {data_bytes} bytes says {claimed_bytes}")]
    UncompressedSize { data_bytes: u64, claimed_bytes: u64 },
    #[error("chunk claims {claimed_bytes} bytes uncompressed from {data_bytes} (at most {bound_bytes})")]
    ClaimsTooMuch { claimed_bytes: u64, data_bytes: u64, bound_bytes: u64 },
    #[error("chunk claims {claimed_bytes} bytes uncompressed, its zstd frame {framed_bytes}")]
    FrameDisagrees { claimed_bytes: u64, framed_bytes: u64 },
    #[error("the zstd frame header is damaged")]
    FrameHeader,
    #[error("zstd: {0}")]
    Zstd(#[source] IoCause),
    #[error("chunk decompressed to {got_bytes} bytes, not {claimed_bytes}")]
    DecompressedSize { got_bytes: u64, claimed_bytes: u64 },
    #[error("unsupported chunk compression `{}`", .0.escape_debug())]
    UnsupportedCompression(String),
    #[error("chunk CRC {got:08x} is not the recorded {recorded:08x}")]
    Crc { got: u32, recorded: u32 },
}

/// Why a stretch of a recording could not be read.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DamageReason {
    #[error("cut off inside a record header ({left_bytes} bytes left)")]
    CutInHeader { left_bytes: u64 },
    #[error("record 0x{opcode:02x} claims {claimed_bytes} bytes; {left_bytes} are left")]
    PastEnd { opcode: u8, claimed_bytes: u64, left_bytes: u64 },
    #[error("record 0x{opcode:02x} claims {claimed_bytes} bytes, more than any record impactd reads")]
    TooLong { opcode: u8, claimed_bytes: u64 },
    /// The file could not be read there.
    #[error("unreadable: {0}")]
    Unreadable(#[source] IoCause),
    #[error("record 0x{opcode:02x}: {source}")]
    Record {
        opcode: u8,
        #[source]
        source: RecordError,
    },
    #[error(transparent)]
    Chunk(#[from] ChunkError),
    #[error("inside a chunk: {0}")]
    ChunkFraming(#[source] Box<DamageReason>),
    #[error("inside a chunk, record 0x{opcode:02x}: {source}")]
    ChunkRecord {
        opcode: u8,
        #[source]
        source: RecordError,
    },
    #[error("a chunk holds a chunk, a footer or a data end")]
    ChunkNesting,
    #[error("the opening magic is damaged")]
    OpeningMagic,
    #[error("the footer is not followed by the closing magic")]
    ClosingMagic,
    #[error(
        "the data section's CRC is {actual:08x}, its DataEnd record says {recorded:08x}: a record in it (a \
         message, the metadata, the recorded configuration) changed after it was written"
    )]
    DataCrc { actual: u32, recorded: u32 },
    #[error(
        "the summary's CRC does not match its footer ({recorded:08x}): the summary, its statistics or indexes \
         changed after they were written"
    )]
    SummaryCrc { recorded: u32 },
    /// Not damage the reader found but what a file that was never closed lacks (`recover`'s report).
    #[error("cut off: whatever was written after the last complete chunk")]
    CutOff,
}

/// Why a scan stopped before the end of the file.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ScanStop {
    #[error("not an MCAP file (no magic)")]
    NoMagic,
    #[error("not an MCAP file (no magic, no readable record)")]
    NothingReadable,
    #[error("at byte {offset}: {reason}")]
    At {
        offset: u64,
        #[source]
        reason: DamageReason,
    },
}

/// An IO error kept as the cause of a reason: shared so that reasons stay `Clone`, equal when their kind and text
/// are (IO errors themselves are neither).
#[derive(Debug, Clone, thiserror::Error)]
#[error(transparent)]
pub struct IoCause(#[from] std::sync::Arc<std::io::Error>);

impl From<std::io::Error> for IoCause {
    fn from(e: std::io::Error) -> Self {
        IoCause(std::sync::Arc::new(e))
    }
}

impl PartialEq for IoCause {
    fn eq(&self, other: &Self) -> bool {
        self.0.kind() == other.0.kind() && self.0.to_string() == other.0.to_string()
    }
}

impl Eq for IoCause {}
