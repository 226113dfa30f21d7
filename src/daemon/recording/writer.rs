//! MCAP recording on a writer thread behind a bounded queue (ARCHITECTURE.md section 4).
//!
//! Every zenoh message in and out is a record with `log_time` = receive (or publish) wall time and
//! `publish_time` = the capture or publish time, topic `/` + key, message encoding `json`, schema encoding
//! `jsonschema`. Foxglove's well-known `foxglove.PoseInFrame` (the club in the world) and `foxglove.SceneUpdate`
//! (ball and club at impact, the predicted flight) channels sit beside them (built in [`crate::daemon::recording::channels`], shared
//! with the live view), and a `session` metadata record holds versions and the configuration. Chunks are
//! zstd-compressed and closed (flushed to the file) after every shot and at least once a second, so a killed
//! daemon loses at most the last second. Sending never blocks: a full queue drops the record and counts it.

use std::collections::{BTreeMap, HashMap};
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{sync_channel, Receiver, RecvTimeoutError, SyncSender, TrySendError};
use std::sync::{Arc, OnceLock};
use std::time::{Duration, Instant};

use crate::daemon::clock::Clock;
use crate::daemon::recording::channels::Schema;
pub use crate::daemon::recording::record::Record;
use crate::daemon::DaemonError;

/// The `session` metadata of a recording: versions, the configuration (the daemon's `DaemonConfig`) and its
/// start on `clock`.
pub fn session_metadata(config: &impl serde::Serialize, clock: &Clock) -> BTreeMap<String, String> {
    let mut m = BTreeMap::new();
    m.insert("impactd_version".into(), env!("CARGO_PKG_VERSION").into());
    m.insert("wire_version".into(), crate::wire::WIRE_VERSION.to_string());
    // The types at another version, `Type/version` comma-separated.
    let versions: Vec<String> = crate::wire::MessageType::ALL
        .iter()
        .filter(|t| t.version() != crate::wire::WIRE_VERSION)
        .map(|t| format!("{}/{}", t.name(), t.version()))
        .collect();
    m.insert("wire_versions".into(), versions.join(","));
    m.insert("config_toml".into(), toml::to_string(config).unwrap_or_default());
    m.insert("start_ns".into(), clock.wall_ns().to_string());
    m
}

/// Queue length between the prediction path and the writer.
pub const QUEUE_CAPACITY: usize = 1 << 16;

/// What was written.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct RecorderSummary {
    pub messages: u64,
    pub dropped: u64,
    pub flushes: u64,
    /// The write error (a full disk...) that stopped the recording.
    pub error: Option<String>,
}

/// The sending side of a recording.
pub struct Recorder {
    tx: Option<SyncSender<Record>>,
    dropped: Arc<AtomicU64>,
    error: Arc<OnceLock<String>>,
    join: Option<std::thread::JoinHandle<Result<RecorderSummary, DaemonError>>>,
    pub path: PathBuf,
    /// A sender waits for room in a full queue rather than drop (a replay, which has time; the daemon never
    /// waits).
    wait: bool,
}

impl Recorder {
    /// Creates the file and starts the writer; `session` becomes the `session` metadata record, and the
    /// `session_end` record is stamped on `clock`. An existing file is replaced only with `overwrite`.
    pub fn create(
        path: &Path,
        session: BTreeMap<String, String>,
        overwrite: bool,
        clock: Clock,
    ) -> Result<Recorder, DaemonError> {
        Self::create_with(path, session, overwrite, false, clock)
    }

    /// As [`create`](Self::create), with senders that wait for the writer when its queue is full, so nothing
    /// is dropped (a replay writing as fast as it reads: its memory stays the queue's).
    pub fn create_waiting(
        path: &Path,
        session: BTreeMap<String, String>,
        overwrite: bool,
        clock: Clock,
    ) -> Result<Recorder, DaemonError> {
        Self::create_with(path, session, overwrite, true, clock)
    }

    fn create_with(
        path: &Path,
        session: BTreeMap<String, String>,
        overwrite: bool,
        wait: bool,
        clock: Clock,
    ) -> Result<Recorder, DaemonError> {
        let file = crate::output_file::create_output(path, overwrite)?;
        let (tx, rx) = sync_channel::<Record>(QUEUE_CAPACITY);
        let dropped = Arc::new(AtomicU64::new(0));
        let error: Arc<OnceLock<String>> = Arc::new(OnceLock::new());
        let (dropped_w, error_w) = (dropped.clone(), error.clone());
        let path_s = path.display().to_string();
        let join = std::thread::Builder::new()
            .name("impactd-recorder".into())
            .spawn(move || {
                let mut summary = RecorderSummary::default();
                if let Err(e) = write_all(file, session, &rx, &mut summary, &dropped_w, &clock) {
                    // Said once, at once, with the OS's reason; the daemon goes on predicting.
                    let mut reason = e.to_string();
                    let mut source = std::error::Error::source(&e);
                    while let Some(s) = source {
                        reason = format!("{reason}: {s}");
                        source = s.source();
                    }
                    tracing::error!("recording {path_s}: {reason}; nothing more is recorded");
                    let _ = error_w.set(reason.clone());
                    summary.error = Some(reason);
                    while rx.recv().is_ok() {
                        dropped_w.fetch_add(1, Ordering::Relaxed);
                    }
                }
                summary.dropped = dropped_w.load(Ordering::Relaxed);
                Ok(summary)
            })
            .map_err(|e| DaemonError::Io { what: "starting the recorder".into(), source: e })?;
        Ok(Recorder { tx: Some(tx), dropped, error, join: Some(join), path: path.to_path_buf(), wait })
    }

    /// Queues a record without blocking (waiting, for a [`create_waiting`](Self::create_waiting) recorder); a
    /// full queue drops it and counts the drop.
    pub fn send(&self, record: Record) {
        if let Some(tx) = &self.tx {
            if self.wait {
                if tx.send(record).is_err() {
                    self.dropped.fetch_add(1, Ordering::Relaxed);
                }
            } else if let Err(TrySendError::Full(_) | TrySendError::Disconnected(_)) = tx.try_send(record) {
                self.dropped.fetch_add(1, Ordering::Relaxed);
            }
        }
    }

    /// Records dropped so far.
    pub fn dropped(&self) -> u64 {
        self.dropped.load(Ordering::Relaxed)
    }

    /// A handle that can send from other threads.
    pub fn handle(&self) -> RecorderHandle {
        RecorderHandle {
            tx: self.tx.clone(),
            dropped: self.dropped.clone(),
            error: self.error.clone(),
            live: None,
            wait: self.wait,
        }
    }

    /// Writes the summary and closes the file.
    pub fn finish(mut self) -> Result<RecorderSummary, DaemonError> {
        self.tx.take();
        match self.join.take().map(|j| j.join()) {
            Some(Ok(r)) => r,
            Some(Err(_)) => Err(DaemonError::WriterPanicked { path: self.path.display().to_string() }),
            None => Ok(RecorderSummary::default()),
        }
    }
}

/// A cloneable sender to a [`Recorder`], and to the live view when one is serving.
#[derive(Clone)]
pub struct RecorderHandle {
    tx: Option<SyncSender<Record>>,
    dropped: Arc<AtomicU64>,
    error: Arc<OnceLock<String>>,
    live: Option<Arc<dyn RecordTap>>,
    wait: bool,
}

/// Another taker of what is recorded (the Foxglove live view): it takes a record without waiting.
pub trait RecordTap: Send + Sync {
    fn send(&self, record: Record);
}

impl RecorderHandle {
    /// A handle that records nothing.
    pub fn none() -> Self {
        RecorderHandle {
            tx: None,
            dropped: Arc::new(AtomicU64::new(0)),
            error: Arc::new(OnceLock::new()),
            live: None,
            wait: false,
        }
    }

    /// This handle, also feeding the live view.
    pub fn with_live(mut self, live: Option<Arc<dyn RecordTap>>) -> Self {
        self.live = live;
        self
    }

    /// Queues a record without blocking (a full queue drops it and counts the drop).
    pub fn send(&self, record: Record) {
        if let Some(live) = &self.live {
            if !matches!(record, Record::Flush) {
                live.send(record.clone());
            }
        }
        if let Some(tx) = &self.tx {
            let sent = if self.wait { tx.send(record).is_ok() } else { tx.try_send(record).is_ok() };
            if !sent {
                self.dropped.fetch_add(1, Ordering::Relaxed);
            }
        }
    }

    /// Whether anything (the recording or the live view) takes records.
    pub fn enabled(&self) -> bool {
        self.tx.is_some() || self.live.is_some()
    }

    pub fn dropped(&self) -> u64 {
        self.dropped.load(Ordering::Relaxed)
    }

    /// The write error that stopped the recording, if one did.
    pub fn error(&self) -> Option<String> {
        self.error.get().cloned()
    }
}

/// Writes records until the senders are gone; the first write error ends it.
fn write_all(
    file: std::fs::File,
    session: BTreeMap<String, String>,
    rx: &Receiver<Record>,
    summary: &mut RecorderSummary,
    dropped: &AtomicU64,
    clock: &Clock,
) -> Result<(), mcap::McapError> {
    let mut w = mcap::WriteOptions::new()
        .compression(Some(mcap::Compression::Zstd))
        .chunk_size(Some(512 * 1024))
        // Chunks close after every shot; per-chunk message indexes would grow the writer's summary in memory by
        // ~2 KiB a chunk. Chunk indexes (time ranges) are kept, and readers scan chunks.
        .emit_message_indexes(false)
        .profile("")
        .library(format!("impactd {}", env!("CARGO_PKG_VERSION")))
        .create(BufWriter::new(file))?;
    w.write_metadata(&mcap::records::Metadata { name: "session".into(), metadata: session })?;
    w.flush()?;
    let mut channels = Channels::default();
    let mut last_flush = Instant::now();
    loop {
        match rx.recv_timeout(Duration::from_millis(200)) {
            Ok(Record::Flush) => {
                w.flush()?;
                summary.flushes += 1;
                last_flush = Instant::now();
            }
            Ok(record) => {
                channels.write(&mut w, record)?;
                summary.messages += 1;
            }
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => break,
        }
        if last_flush.elapsed() >= Duration::from_millis(900) {
            w.flush()?;
            summary.flushes += 1;
            last_flush = Instant::now();
        }
    }
    let mut end = BTreeMap::new();
    end.insert("messages".to_string(), summary.messages.to_string());
    end.insert("dropped".to_string(), dropped.load(Ordering::Relaxed).to_string());
    end.insert("end_ns".to_string(), clock.wall_ns().to_string());
    w.write_metadata(&mcap::records::Metadata { name: "session_end".into(), metadata: end })?;
    w.finish()?;
    Ok(())
}

#[derive(Default)]
struct Channels {
    schemas: HashMap<Schema, u16>,
    channels: HashMap<String, u16>,
    sequence: u32,
}

impl Channels {
    fn schema<W: std::io::Write + std::io::Seek>(
        &mut self,
        w: &mut mcap::Writer<W>,
        schema: Schema,
    ) -> Result<u16, mcap::McapError> {
        if let Some(id) = self.schemas.get(&schema) {
            return Ok(*id);
        }
        let id = w.add_schema(&schema.name(), "jsonschema", schema.text().as_bytes())?;
        self.schemas.insert(schema, id);
        Ok(id)
    }

    fn channel<W: std::io::Write + std::io::Seek>(
        &mut self,
        w: &mut mcap::Writer<W>,
        topic: &str,
        schema: Schema,
    ) -> Result<u16, mcap::McapError> {
        if let Some(id) = self.channels.get(topic) {
            return Ok(*id);
        }
        let schema_id = self.schema(w, schema)?;
        let id = w.add_channel(schema_id, topic, "json", &BTreeMap::new())?;
        self.channels.insert(topic.to_string(), id);
        Ok(id)
    }

    fn write<W: std::io::Write + std::io::Seek>(
        &mut self,
        w: &mut mcap::Writer<W>,
        record: Record,
    ) -> Result<(), mcap::McapError> {
        let Some(e) = crate::daemon::recording::channels::encode(record) else { return Ok(()) };
        let channel_id = self.channel(w, &e.topic, e.schema)?;
        self.sequence = self.sequence.wrapping_add(1);
        let header = mcap::records::MessageHeader {
            channel_id,
            sequence: self.sequence,
            log_time: e.log_time_ns,
            publish_time: e.publish_time_ns,
        };
        w.write_to_known_channel(&header, &e.data)
    }
}
