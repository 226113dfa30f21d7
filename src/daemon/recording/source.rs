//! Where the recording reader gets its bytes: a slice already in memory, or a regular file read through a
//! window, so a recording of any size is read in memory bounded by its largest record rather than its size.
//!
//! Written here rather than memory-mapping the file (the `memmap2` crate): a map needs `unsafe` and turns a
//! recording truncated while it is read into a SIGBUS, where a read returns an error the reader reports.

use std::io::{Read, Seek, SeekFrom};

/// The largest record a windowed read takes (a chunk is at most [`MAX_CHUNK_BYTES`](super::records::MAX_CHUNK_BYTES)
/// uncompressed, so compressed too; a summary or metadata record of more is refused as damage).
pub const MAX_RECORD_BYTES: u64 = super::records::MAX_CHUNK_BYTES + (1 << 20);

/// How much a windowed read fetches at a time at least.
const WINDOW_BYTES: usize = 4 << 20;

/// Random access to a recording's bytes, in ranges that were checked against its length.
pub trait Source {
    /// The recording's length in bytes.
    fn size_bytes(&self) -> u64;
    /// `n` bytes at `offset` (`offset + n <= size_bytes()`); an error when the file cannot be read there.
    fn get(&mut self, offset: u64, n: usize) -> std::io::Result<&[u8]>;
}

impl Source for &[u8] {
    fn size_bytes(&self) -> u64 {
        <[u8]>::len(self) as u64
    }
    fn get(&mut self, offset: u64, n: usize) -> std::io::Result<&[u8]> {
        let start = usize::try_from(offset).map_err(|_| std::io::ErrorKind::InvalidInput)?;
        <[u8]>::get(self, start..start.saturating_add(n)).ok_or_else(|| std::io::ErrorKind::UnexpectedEof.into())
    }
}

/// A regular file read through a window that moves forward with the reader (and back, when it resynchronises
/// or checks a summary).
pub struct FileSource {
    file: std::fs::File,
    len: u64,
    window: Vec<u8>,
    window_start: u64,
}

impl FileSource {
    pub fn new(file: std::fs::File) -> std::io::Result<Self> {
        let len = file.metadata()?.len();
        Ok(FileSource { file, len, window: Vec::new(), window_start: 0 })
    }
}

impl Source for FileSource {
    fn size_bytes(&self) -> u64 {
        self.len
    }

    fn get(&mut self, offset: u64, n: usize) -> std::io::Result<&[u8]> {
        let end = offset.checked_add(n as u64).filter(|&e| e <= self.len).ok_or(std::io::ErrorKind::UnexpectedEof)?;
        let window_end = self.window_start + self.window.len() as u64;
        if offset < self.window_start || end > window_end {
            let want = (n.max(WINDOW_BYTES) as u64).min(self.len - offset) as usize;
            self.window.clear();
            self.window.resize(want, 0);
            self.file.seek(SeekFrom::Start(offset))?;
            self.file.read_exact(&mut self.window)?;
            self.window_start = offset;
            // A window's worth of a file no bigger than a record is all the reader ever holds.
            if self.window.capacity() > 2 * want.max(WINDOW_BYTES) {
                self.window.shrink_to(want.max(WINDOW_BYTES));
            }
        }
        let start = (offset - self.window_start) as usize;
        Ok(&self.window[start..start + n])
    }
}

/// Whether the bytes start with the MCAP magic.
pub fn is_mcap(bytes: &[u8]) -> bool {
    bytes.starts_with(mcap::MAGIC)
}

/// The most read of a recording that is not a regular file (a pipe, a device).
pub const MAX_STREAMED_RECORDING_BYTES: u64 = 1 << 30;

/// A recording opened for reading: a regular file through a window; anything else (a pipe, `/dev/zero`) read
/// into memory, only when it starts with the MCAP magic and only up to [`MAX_STREAMED_RECORDING_BYTES`].
pub enum Opened {
    File(FileSource),
    Bytes(Vec<u8>),
}

impl Opened {
    pub fn open(path: &std::path::Path) -> Result<Opened, crate::daemon::ReadError> {
        use crate::daemon::ReadError;
        let io = |e| ReadError::Io { what: format!("reading {}", path.display()), source: e };
        let file = std::fs::File::open(path).map_err(io)?;
        if file.metadata().map_err(io)?.is_file() {
            return FileSource::new(file).map(Opened::File).map_err(io);
        }
        let mut bytes = Vec::new();
        let mut capped = file.take(MAX_STREAMED_RECORDING_BYTES + 1);
        (&mut capped).take(mcap::MAGIC.len() as u64).read_to_end(&mut bytes).map_err(io)?;
        if !is_mcap(&bytes) {
            return Err(ReadError::NotMcap { path: path.display().to_string() });
        }
        capped.read_to_end(&mut bytes).map_err(io)?;
        if bytes.len() as u64 > MAX_STREAMED_RECORDING_BYTES {
            return Err(ReadError::StreamTooLarge {
                path: path.display().to_string(),
                limit_bytes: MAX_STREAMED_RECORDING_BYTES,
            });
        }
        Ok(Opened::Bytes(bytes))
    }

    /// Whether it starts with the MCAP magic.
    pub fn is_mcap(&mut self) -> bool {
        match self {
            Opened::File(f) => f.get(0, mcap::MAGIC.len()).is_ok_and(is_mcap),
            Opened::Bytes(b) => is_mcap(b),
        }
    }
}
