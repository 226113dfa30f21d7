//! MCAP recording on a writer thread behind a bounded queue (DESIGN.md section 4).
//!
//! Every zenoh message in and out is a record with `log_time` = receive (or publish) wall time and
//! `publish_time` = the capture or publish time, topic `/` + key, message encoding `json`, schema encoding
//! `jsonschema`. Foxglove's well-known `foxglove.PoseInFrame` (the club in the world) and `foxglove.SceneUpdate`
//! (ball and club at impact) channels sit beside them, and a `session` metadata record holds versions and the
//! configuration. Chunks are zstd-compressed and closed (flushed to the file) after every shot and at least once
//! a second, so a killed daemon loses at most the last second. Sending never blocks: a full queue drops the
//! record and counts it.

use std::collections::{BTreeMap, HashMap};
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{sync_channel, RecvTimeoutError, SyncSender, TrySendError};
use std::sync::Arc;
use std::time::{Duration, Instant};

use super::{wall_ns, DaemonConfig, DaemonError};
use crate::math::Isometry3;
use crate::wire::{ImpactStateMsg, MessageType};

/// The `session` metadata of a recording: versions and the configuration.
pub fn session_metadata(config: &DaemonConfig) -> BTreeMap<String, String> {
    let mut m = BTreeMap::new();
    m.insert("impactd_version".into(), env!("CARGO_PKG_VERSION").into());
    m.insert("wire_version".into(), crate::wire::WIRE_VERSION.to_string());
    m.insert("config_toml".into(), toml::to_string(config).unwrap_or_default());
    m.insert("start_ns".into(), wall_ns().to_string());
    m
}

/// Queue length between the prediction path and the writer.
pub const QUEUE_CAPACITY: usize = 1 << 16;

/// One thing to record.
#[derive(Debug, Clone)]
pub enum Record {
    /// A zenoh message: its key (without the leading `/`), its wire type, and its JSON bytes.
    Message { key: String, message_type: MessageType, log_time_ns: u64, publish_time_ns: u64, data: Vec<u8> },
    /// The club's pose in the world at a sample (Foxglove `PoseInFrame` on `/foxglove/<rig>/club_pose`).
    ClubPose { rig: String, t_ns: u64, log_time_ns: u64, world_from_club: Isometry3 },
    /// Ball and club at an impact (Foxglove `SceneUpdate` on `/foxglove/<rig>/impact_scene`).
    ImpactScene {
        rig: String,
        t_ns: u64,
        log_time_ns: u64,
        ball_position_m: [f64; 3],
        ball_radius_m: f64,
        club: ImpactStateMsg,
    },
    /// Close the current chunk and push it to the file.
    Flush,
}

/// What was written.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct RecorderSummary {
    pub messages: u64,
    pub dropped: u64,
    pub flushes: u64,
}

/// The sending side of a recording.
pub struct Recorder {
    tx: Option<SyncSender<Record>>,
    dropped: Arc<AtomicU64>,
    join: Option<std::thread::JoinHandle<Result<RecorderSummary, DaemonError>>>,
    pub path: PathBuf,
}

impl Recorder {
    /// Creates the file and starts the writer; `session` becomes the `session` metadata record.
    pub fn create(path: &Path, session: BTreeMap<String, String>) -> Result<Recorder, DaemonError> {
        let file = std::fs::File::create(path)
            .map_err(|e| DaemonError::Io { what: format!("creating {}", path.display()), source: e })?;
        let (tx, rx) = sync_channel::<Record>(QUEUE_CAPACITY);
        let dropped = Arc::new(AtomicU64::new(0));
        let dropped_w = dropped.clone();
        let path_s = path.display().to_string();
        let join = std::thread::Builder::new()
            .name("impactd-recorder".into())
            .spawn(move || {
                let err = |e: mcap::McapError| DaemonError::Mcap { path: path_s.clone(), reason: e.to_string() };
                let mut w = mcap::WriteOptions::new()
                    .compression(Some(mcap::Compression::Zstd))
                    .chunk_size(Some(512 * 1024))
                    // Chunks close after every shot; per-chunk message indexes would grow the writer's summary
                    // in memory by ~2 KiB a chunk. Chunk indexes (time ranges) are kept, and readers scan chunks.
                    .emit_message_indexes(false)
                    .profile("")
                    .library(format!("impactd {}", env!("CARGO_PKG_VERSION")))
                    .create(BufWriter::new(file))
                    .map_err(err)?;
                w.write_metadata(&mcap::records::Metadata { name: "session".into(), metadata: session })
                    .map_err(err)?;
                let mut channels = Channels::default();
                let mut summary = RecorderSummary::default();
                let mut last_flush = Instant::now();
                loop {
                    match rx.recv_timeout(Duration::from_millis(200)) {
                        Ok(Record::Flush) => {
                            w.flush().map_err(err)?;
                            summary.flushes += 1;
                            last_flush = Instant::now();
                        }
                        Ok(record) => {
                            channels.write(&mut w, record).map_err(err)?;
                            summary.messages += 1;
                        }
                        Err(RecvTimeoutError::Timeout) => {}
                        Err(RecvTimeoutError::Disconnected) => break,
                    }
                    if last_flush.elapsed() >= Duration::from_millis(900) {
                        w.flush().map_err(err)?;
                        summary.flushes += 1;
                        last_flush = Instant::now();
                    }
                }
                summary.dropped = dropped_w.load(Ordering::Relaxed);
                let mut end = BTreeMap::new();
                end.insert("messages".to_string(), summary.messages.to_string());
                end.insert("dropped".to_string(), summary.dropped.to_string());
                end.insert("end_ns".to_string(), super::wall_ns().to_string());
                w.write_metadata(&mcap::records::Metadata { name: "session_end".into(), metadata: end })
                    .map_err(err)?;
                w.finish().map_err(err)?;
                Ok(summary)
            })
            .map_err(|e| DaemonError::Io { what: "starting the recorder".into(), source: e })?;
        Ok(Recorder { tx: Some(tx), dropped, join: Some(join), path: path.to_path_buf() })
    }

    /// Queues a record without blocking; a full queue drops it and counts the drop.
    pub fn send(&self, record: Record) {
        if let Some(tx) = &self.tx {
            if let Err(TrySendError::Full(_) | TrySendError::Disconnected(_)) = tx.try_send(record) {
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
        RecorderHandle { tx: self.tx.clone(), dropped: self.dropped.clone() }
    }

    /// Writes the summary and closes the file.
    pub fn finish(mut self) -> Result<RecorderSummary, DaemonError> {
        self.tx.take();
        match self.join.take().map(|j| j.join()) {
            Some(Ok(r)) => r,
            Some(Err(_)) => {
                Err(DaemonError::Mcap { path: self.path.display().to_string(), reason: "writer panicked".into() })
            }
            None => Ok(RecorderSummary::default()),
        }
    }
}

/// A cloneable sender to a [`Recorder`].
#[derive(Clone)]
pub struct RecorderHandle {
    tx: Option<SyncSender<Record>>,
    dropped: Arc<AtomicU64>,
}

impl RecorderHandle {
    /// A handle that records nothing.
    pub fn none() -> Self {
        RecorderHandle { tx: None, dropped: Arc::new(AtomicU64::new(0)) }
    }

    pub fn send(&self, record: Record) {
        if let Some(tx) = &self.tx {
            if tx.try_send(record).is_err() {
                self.dropped.fetch_add(1, Ordering::Relaxed);
            }
        }
    }

    pub fn enabled(&self) -> bool {
        self.tx.is_some()
    }

    pub fn dropped(&self) -> u64 {
        self.dropped.load(Ordering::Relaxed)
    }
}

/// The schema of a channel: a wire message type or one of Foxglove's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Schema {
    Wire(MessageType),
    PoseInFrame,
    SceneUpdate,
}

#[derive(Default)]
struct Channels {
    schemas: HashMap<Schema, u16>,
    channels: HashMap<String, u16>,
    sequence: u32,
}

fn timestamp(t_ns: u64) -> serde_json::Value {
    serde_json::json!({ "sec": t_ns / 1_000_000_000, "nsec": t_ns % 1_000_000_000 })
}

fn pose_json(p: [f64; 3], q: crate::wire::QuaternionMsg) -> serde_json::Value {
    serde_json::json!({
        "position": { "x": p[0], "y": p[1], "z": p[2] },
        "orientation": { "x": q.x, "y": q.y, "z": q.z, "w": q.w },
    })
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
        let (schema_name, data) = match schema {
            Schema::PoseInFrame => ("foxglove.PoseInFrame".to_string(), FOXGLOVE_POSE_IN_FRAME.to_string()),
            Schema::SceneUpdate => ("foxglove.SceneUpdate".to_string(), FOXGLOVE_SCENE_UPDATE.to_string()),
            Schema::Wire(t) => (t.schema_name(), t.schema()),
        };
        let id = w.add_schema(&schema_name, "jsonschema", data.as_bytes())?;
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

    fn put<W: std::io::Write + std::io::Seek>(
        &mut self,
        w: &mut mcap::Writer<W>,
        topic: &str,
        schema: Schema,
        log_time: u64,
        publish_time: u64,
        data: &[u8],
    ) -> Result<(), mcap::McapError> {
        let channel_id = self.channel(w, topic, schema)?;
        self.sequence = self.sequence.wrapping_add(1);
        w.write_to_known_channel(
            &mcap::records::MessageHeader { channel_id, sequence: self.sequence, log_time, publish_time },
            data,
        )
    }

    fn write<W: std::io::Write + std::io::Seek>(
        &mut self,
        w: &mut mcap::Writer<W>,
        record: Record,
    ) -> Result<(), mcap::McapError> {
        match record {
            Record::Message { key, message_type, log_time_ns, publish_time_ns, data } => {
                self.put(w, &format!("/{key}"), Schema::Wire(message_type), log_time_ns, publish_time_ns, &data)
            }
            Record::ClubPose { rig, t_ns, log_time_ns, world_from_club } => {
                let p = world_from_club.translation.vector;
                let msg = serde_json::json!({
                    "timestamp": timestamp(t_ns),
                    "frame_id": "world",
                    "pose": pose_json([p.x, p.y, p.z], world_from_club.rotation.into()),
                });
                let data = serde_json::to_vec(&msg).unwrap_or_default();
                self.put(
                    w,
                    &format!("/{}", crate::wire::keys::foxglove_club_pose(&rig)),
                    Schema::PoseInFrame,
                    log_time_ns,
                    t_ns,
                    &data,
                )
            }
            Record::ImpactScene { rig, t_ns, log_time_ns, ball_position_m, ball_radius_m, club } => {
                let d = 2.0 * ball_radius_m;
                let identity = crate::wire::QuaternionMsg { x: 0.0, y: 0.0, z: 0.0, w: 1.0 };
                let entity = |id: &str, spheres: serde_json::Value, cubes: serde_json::Value| {
                    serde_json::json!({
                        "timestamp": timestamp(t_ns), "frame_id": "world", "id": id,
                        "lifetime": { "sec": 0, "nsec": 0 }, "frame_locked": false, "metadata": [],
                        "arrows": [], "cubes": cubes, "spheres": spheres, "cylinders": [], "lines": [],
                        "triangles": [], "texts": [], "models": [],
                    })
                };
                let msg = serde_json::json!({
                    "deletions": [],
                    "entities": [
                        entity("ball", serde_json::json!([{ "pose": pose_json(ball_position_m, identity), "size": { "x": d, "y": d, "z": d }, "color": { "r": 1.0, "g": 1.0, "b": 1.0, "a": 1.0 } }]), serde_json::json!([])),
                        entity("club", serde_json::json!([]), serde_json::json!([{ "pose": pose_json(club.cg_position_m, club.orientation), "size": { "x": 0.10, "y": 0.05, "z": 0.11 }, "color": { "r": 0.2, "g": 0.4, "b": 0.9, "a": 0.8 } }])),
                    ],
                });
                let data = serde_json::to_vec(&msg).unwrap_or_default();
                self.put(
                    w,
                    &format!("/{}", crate::wire::keys::foxglove_impact_scene(&rig)),
                    Schema::SceneUpdate,
                    log_time_ns,
                    t_ns,
                    &data,
                )
            }
            Record::Flush => Ok(()),
        }
    }
}

const FOXGLOVE_POSE_IN_FRAME: &str = concat!(
    r#"{"title":"foxglove.PoseInFrame","description":"A timestamped pose for an object or reference frame in 3D space","type":"object","properties":{"timestamp":"#,
    r#"{"type":"object","properties":{"sec":{"type":"integer","minimum":0},"nsec":{"type":"integer","minimum":0,"maximum":999999999}}}"#,
    r#","frame_id":{"type":"string"},"pose":{"type":"object","properties":{"position":{"type":"object","properties":{"x":{"type":"number"},"y":{"type":"number"},"z":{"type":"number"}}},"orientation":{"type":"object","properties":{"x":{"type":"number"},"y":{"type":"number"},"z":{"type":"number"},"w":{"type":"number"}}}}}}}"#
);

const FOXGLOVE_SCENE_UPDATE: &str = r#"{"title":"foxglove.SceneUpdate","description":"An update to the entities displayed in a 3D scene","type":"object","properties":{"deletions":{"type":"array","items":{"type":"object"}},"entities":{"type":"array","items":{"type":"object","properties":{"timestamp":{"type":"object"},"frame_id":{"type":"string"},"id":{"type":"string"},"lifetime":{"type":"object"},"frame_locked":{"type":"boolean"},"metadata":{"type":"array"},"arrows":{"type":"array"},"cubes":{"type":"array"},"spheres":{"type":"array"},"cylinders":{"type":"array"},"lines":{"type":"array"},"triangles":{"type":"array"},"texts":{"type":"array"},"models":{"type":"array"}}}}}}"#;
