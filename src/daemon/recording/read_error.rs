//! The file readers' errors: a recording, a JSONL file of samples or a capture that cannot be read (on).
//! Commands that read files get them as they are; the replay, which reads as it runs, carries them in
//! `DaemonError::Read`.

/// Errors of the file readers.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    #[error("{what}: {source}")]
    Io {
        what: String,
        #[source]
        source: std::io::Error,
    },
    #[error("{path} is not an MCAP file")]
    NotMcap { path: String },
    #[error("{path}: {source}")]
    Unreadable {
        path: String,
        #[source]
        source: super::damage::ScanStop,
    },
    #[error("{path}: not a regular file, and over {limit_bytes} bytes")]
    StreamTooLarge { path: String, limit_bytes: u64 },
    #[error("{path} line {line}: {source}")]
    BadSampleLine {
        path: String,
        line: usize,
        #[source]
        source: std::io::Error,
    },
    /// A capture (C3D, TRC, a pose table) that cannot be read on.
    #[error("{path}: {source}")]
    Capture {
        path: String,
        #[source]
        source: crate::captures::CaptureError,
    },
}
