//! The Open Connect client of one rig: each shot's first prediction goes to a golf simulator.
//!
//! The rig's worker hands predictions over without waiting ([`SimulatorClient::offer`] is a `try_send` on a
//! bounded queue; a full queue drops the shot and counts it), so a slow or dead simulator never delays a
//! prediction or another rig. The client's own task connects (TCP_NODELAY), writes one JSON object per write (a
//! server that parses each TCP chunk alone still reads whole shots), sends heartbeats while idle, reads replies
//! as a stream, keeps the player information of code 201, and reconnects with exponential backoff. No ghost or
//! duplicate shots: a prediction with a zero or non-finite number is refused, only the first prediction of a
//! swing goes out, a shot is written at most once (a failed write is counted, never repeated), and a shot
//! older than `max_shot_age_s` when the connection comes back is dropped and counted rather than sent late.
//! Every message both ways is recorded as `OpenConnectTraffic` on `golf/<rig>/simulator`.
//!
//! The connection, queue, ages, counts and recording are the client's; what goes on the wire is a
//! [`Protocol`]'s: Open Connect v1 ([`OpenConnect`]) or OpenGolfSim's developer API (the opengolfsim bridge).

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tokio::sync::mpsc;

use super::codec::{Reply, ShotMessage};
use super::splitter::{Frame, Splitter};
use super::{OpenConnectError, SimulatorConfig, MAX_MESSAGE_BYTES};
use crate::daemon::clock::Clock;
use crate::daemon::recording::record::Record;
use crate::daemon::recording::writer::RecorderHandle;
use crate::wire::{
    keys, ConnectionState, LaunchPrediction, Message, OpenConnectTraffic, SimulatorPlayer, SimulatorStatus,
    TrafficDirection,
};

/// Shots waiting for the simulator.
pub const QUEUE: usize = 64;
/// A write that takes longer than this means the simulator is gone.
const WRITE_TIMEOUT: Duration = Duration::from_secs(2);
const CONNECT_TIMEOUT: Duration = Duration::from_secs(3);

/// A simulator's wire protocol: the bytes of each message out and the meaning of each JSON object back.
pub trait Protocol: Send + Sync + 'static {
    /// The protocol's name in the status (`open_connect`, `opengolfsim`).
    fn name(&self) -> &'static str;
    /// Sent once each connection is up (OpenGolfSim: the device is ready).
    fn greeting(&self) -> Option<Vec<u8>>;
    /// Sent when the daemon stops with the connection up (OpenGolfSim: the device is busy).
    fn farewell(&self) -> Option<Vec<u8>>;
    /// Sent while idle every `heartbeat_s`, if the protocol has heartbeats.
    fn heartbeat(&self) -> Option<Vec<u8>>;
    /// Shot `number` (1, 2, ... on this client) of a prediction, or why it must not go out.
    fn shot(&self, launch: &LaunchPrediction, number: u64) -> Result<Vec<u8>, OpenConnectError>;
    /// What one JSON object from the simulator says, or why it is unreadable.
    fn answer(&self, object: &[u8]) -> Result<Answer, String>;
}

/// What a reply from the simulator means to the client.
#[derive(Debug, Clone, PartialEq)]
pub struct Answer {
    /// It answers the oldest shot not yet answered.
    pub answers_shot: bool,
    /// A success (counted as acknowledged) or a failure (counted as failed).
    pub success: bool,
    /// A line for the status's `last_reply` and the log.
    pub summary: String,
    pub player: Option<SimulatorPlayer>,
}

/// Open Connect v1 (GSPro's page): glued JSON objects, heartbeats, 200/201/5xx replies.
pub struct OpenConnect {
    pub device_id: String,
}

impl Protocol for OpenConnect {
    fn name(&self) -> &'static str {
        "open_connect"
    }
    fn greeting(&self) -> Option<Vec<u8>> {
        None
    }
    fn farewell(&self) -> Option<Vec<u8>> {
        None
    }
    fn heartbeat(&self) -> Option<Vec<u8>> {
        serde_json::to_vec(&ShotMessage::heartbeat(&self.device_id, true)).ok()
    }
    fn shot(&self, launch: &LaunchPrediction, number: u64) -> Result<Vec<u8>, OpenConnectError> {
        let message = ShotMessage::from_prediction(launch, &self.device_id, number)?;
        serde_json::to_vec(&message).map_err(OpenConnectError::Encode)
    }
    fn answer(&self, object: &[u8]) -> Result<Answer, String> {
        let reply = serde_json::from_slice::<Reply>(object).map_err(|e| e.to_string())?;
        Ok(Answer {
            answers_shot: reply.code != 201,
            success: reply.is_success(),
            summary: format!("{} {}", reply.code, reply.message),
            player: reply.player.map(|p| SimulatorPlayer { handed: p.handed, club: p.club }),
        })
    }
}

/// How one rig's client behaves.
#[derive(Debug, Clone)]
pub struct SimulatorOptions {
    pub rig: String,
    /// `HOST:PORT`.
    pub address: String,
    pub device_id: String,
    pub max_shot_age: Duration,
    pub heartbeat: Duration,
    pub backoff_min: Duration,
    pub backoff_max: Duration,
}

impl SimulatorOptions {
    /// The client `config` asks for, if it names a simulator.
    pub fn from_config(rig: &str, config: &SimulatorConfig) -> Option<Self> {
        Some(SimulatorOptions {
            rig: rig.to_string(),
            address: config.open_connect.clone()?,
            device_id: config.device_id.clone(),
            max_shot_age: Duration::from_secs_f64(config.max_shot_age_s),
            heartbeat: Duration::from_secs_f64(config.heartbeat_s),
            backoff_min: Duration::from_millis(100),
            backoff_max: Duration::from_secs(5),
        })
    }
}

struct Outgoing {
    launch: LaunchPrediction,
    predicted_at: Instant,
}

/// The worker's end of a rig's simulator client.
pub struct SimulatorClient {
    tx: mpsc::Sender<Outgoing>,
    status: Arc<Mutex<SimulatorStatus>>,
    last_offered: Option<u64>,
    task: tokio::task::JoinHandle<()>,
}

impl SimulatorClient {
    /// Starts an Open Connect client's task on the current tokio runtime; its traffic is recorded stamped on
    /// `clock`.
    pub fn spawn(options: SimulatorOptions, recorder: RecorderHandle, clock: Clock) -> Self {
        let protocol = OpenConnect { device_id: options.device_id.clone() };
        Self::spawn_with(options, protocol, recorder, clock)
    }

    /// Starts a client speaking `protocol` on the current tokio runtime.
    pub fn spawn_with(
        options: SimulatorOptions,
        protocol: impl Protocol,
        recorder: RecorderHandle,
        clock: Clock,
    ) -> Self {
        let (tx, rx) = mpsc::channel(QUEUE);
        let status = SimulatorStatus {
            address: options.address.clone(),
            protocol: protocol.name().to_string(),
            ..Default::default()
        };
        let status = Arc::new(Mutex::new(status));
        let key = keys::simulator_traffic(&options.rig);
        let task = Task { key, options, protocol, status: status.clone(), recorder, clock };
        let task = tokio::spawn(task.run(rx));
        SimulatorClient { tx, status, last_offered: None, task }
    }

    /// Hands a prediction to the client without waiting; only a swing's first prediction is taken.
    pub fn offer(&mut self, launch: &LaunchPrediction) {
        if self.last_offered.is_some_and(|last| launch.shot <= last) {
            return;
        }
        self.last_offered = Some(launch.shot);
        let item = Outgoing { launch: launch.clone(), predicted_at: Instant::now() };
        if self.tx.try_send(item).is_err() {
            self.update(|s| s.dropped += 1);
        }
    }

    /// Closes the queue: the task sends what is queued (if connected) and ends; its handle is returned to be
    /// awaited (or aborted).
    pub fn close(self) -> tokio::task::JoinHandle<()> {
        let SimulatorClient { tx, task, .. } = self;
        drop(tx);
        task
    }

    /// Waits a second for a closed client's queued shots to go out, then ends it (and its recorder handle).
    pub async fn finish(mut task: tokio::task::JoinHandle<()>) {
        if tokio::time::timeout(Duration::from_secs(1), &mut task).await.is_err() {
            task.abort();
            let _ = task.await;
        }
    }

    /// The client's counts and state now.
    pub fn status(&self) -> SimulatorStatus {
        self.status.lock().map(|s| s.clone()).unwrap_or_default()
    }

    fn update(&self, f: impl FnOnce(&mut SimulatorStatus)) {
        if let Ok(mut s) = self.status.lock() {
            f(&mut s);
        }
    }
}

enum End {
    /// The daemon is stopping.
    Shutdown,
    /// The connection is gone; try again.
    Lost(String),
}

struct Task<P> {
    options: SimulatorOptions,
    protocol: P,
    key: String,
    status: Arc<Mutex<SimulatorStatus>>,
    recorder: RecorderHandle,
    clock: Clock,
}

impl<P: Protocol> Task<P> {
    fn update(&self, f: impl FnOnce(&mut SimulatorStatus)) {
        if let Ok(mut s) = self.status.lock() {
            f(&mut s);
        }
    }

    fn record(&self, direction: TrafficDirection, text: &[u8], shot: Option<u64>, note: Option<String>) {
        if !self.recorder.enabled() {
            return;
        }
        let t_ns = self.clock.wall_ns();
        let keep = &text[..text.len().min(crate::wire::MAX_PAYLOAD_BYTES)];
        let msg = OpenConnectTraffic {
            rig: self.options.rig.clone(),
            t_ns,
            peer: self.options.address.clone(),
            direction,
            text: String::from_utf8_lossy(keep).into_owned(),
            shot,
            note,
        };
        let data = serde_json::to_vec(&msg).unwrap_or_default();
        self.recorder.send(Record::Message {
            key: self.key.clone(),
            message_type: OpenConnectTraffic::TYPE,
            log_time_ns: t_ns,
            publish_time_ns: t_ns,
            data,
        });
    }

    async fn run(self, mut rx: mpsc::Receiver<Outgoing>) {
        let o = self.options.clone();
        let mut backoff = o.backoff_min;
        let mut shot_number = 0u64;
        let mut was_connected = true;
        loop {
            self.update(|s| s.state = ConnectionState::Connecting);
            match tokio::time::timeout(CONNECT_TIMEOUT, TcpStream::connect(&o.address)).await {
                Ok(Ok(stream)) => {
                    if let Err(e) = stream.set_nodelay(true) {
                        tracing::warn!("rig {}: simulator {}: TCP_NODELAY: {e}", o.rig, o.address);
                    }
                    self.update(|s| {
                        s.state = ConnectionState::Connected;
                        s.connects += 1;
                    });
                    tracing::info!("rig {}: connected to the simulator at {}", o.rig, o.address);
                    backoff = o.backoff_min;
                    was_connected = true;
                    match self.session(stream, &mut rx, &mut shot_number).await {
                        End::Shutdown => return,
                        End::Lost(reason) => {
                            tracing::warn!("rig {}: simulator {}: {reason}; reconnecting", o.rig, o.address)
                        }
                    }
                }
                Ok(Err(e)) if was_connected => {
                    tracing::warn!("rig {}: simulator {}: {e}; retrying", o.rig, o.address);
                    was_connected = false;
                }
                Err(_) if was_connected => {
                    tracing::warn!("rig {}: simulator {}: no answer; retrying", o.rig, o.address);
                    was_connected = false;
                }
                _ => {}
            }
            self.update(|s| s.state = ConnectionState::Disconnected);
            if rx.is_closed() && rx.is_empty() {
                return;
            }
            tokio::time::sleep(backoff).await;
            backoff = (backoff * 2).min(o.backoff_max);
        }
    }

    /// One connection, until it is lost or the daemon stops.
    async fn session(&self, stream: TcpStream, rx: &mut mpsc::Receiver<Outgoing>, shot_number: &mut u64) -> End {
        let o = &self.options;
        let (mut rd, mut wr) = stream.into_split();
        let mut splitter = Splitter::new(MAX_MESSAGE_BYTES);
        let mut buf = vec![0u8; 8192];
        let mut frames = Vec::new();
        // Shots written and not yet answered: a 2xx or 5xx then counts for a shot, not for a heartbeat.
        let mut awaiting = 0u64;
        let start = tokio::time::Instant::now() + o.heartbeat;
        let mut heartbeat = tokio::time::interval_at(start, o.heartbeat);
        heartbeat.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
        let heartbeat_bytes = self.protocol.heartbeat();
        if let Some(bytes) = self.protocol.greeting() {
            match tokio::time::timeout(WRITE_TIMEOUT, wr.write_all(&bytes)).await {
                Ok(Ok(())) => self.record(TrafficDirection::Sent, &bytes, None, None),
                Ok(Err(e)) => return End::Lost(format!("greeting: {e}")),
                Err(_) => return End::Lost("greeting: the write timed out".into()),
            }
        }
        loop {
            tokio::select! {
                biased;
                item = rx.recv() => {
                    let Some(item) = item else {
                        if let Some(bytes) = self.protocol.farewell() {
                            if let Ok(Ok(())) = tokio::time::timeout(WRITE_TIMEOUT, wr.write_all(&bytes)).await {
                                self.record(TrafficDirection::Sent, &bytes, None, None);
                            }
                        }
                        return End::Shutdown;
                    };
                    let shot = Some(item.launch.shot);
                    let age = item.predicted_at.elapsed();
                    if age > o.max_shot_age {
                        self.update(|s| s.dropped += 1);
                        let note = format!("dropped: {:.1} s old when the simulator could take it", age.as_secs_f64());
                        tracing::warn!("rig {}: shot {}: {note}", o.rig, item.launch.shot);
                        self.record(TrafficDirection::Sent, b"", shot, Some(note));
                        continue;
                    }
                    let bytes = match self.protocol.shot(&item.launch, *shot_number + 1) {
                        Ok(m) => m,
                        Err(e) => {
                            self.update(|s| s.refused += 1);
                            tracing::warn!("rig {}: {e}", o.rig);
                            self.record(TrafficDirection::Sent, b"", shot, Some(format!("refused: {e}")));
                            continue;
                        }
                    };
                    // The number is used even if the write fails: the simulator never sees one twice.
                    *shot_number += 1;
                    match tokio::time::timeout(WRITE_TIMEOUT, wr.write_all(&bytes)).await {
                        Ok(Ok(())) => {
                            self.update(|s| s.sent += 1);
                            awaiting += 1;
                            heartbeat.reset();
                            self.record(TrafficDirection::Sent, &bytes, shot, None);
                        }
                        Ok(Err(e)) => return self.write_failed(&bytes, shot, e.to_string()),
                        Err(_) => return self.write_failed(&bytes, shot, "the write timed out".into()),
                    }
                }
                read = rd.read(&mut buf) => {
                    let n = match read {
                        Ok(0) => return End::Lost("closed by the simulator".into()),
                        Ok(n) => n,
                        Err(e) => return End::Lost(e.to_string()),
                    };
                    splitter.push(&buf[..n], &mut |f| frames.push(f));
                    for frame in frames.drain(..) {
                        self.on_reply(frame, &mut awaiting);
                    }
                }
                _ = heartbeat.tick(), if heartbeat_bytes.is_some() => {
                    let bytes = heartbeat_bytes.clone().unwrap_or_default();
                    match tokio::time::timeout(WRITE_TIMEOUT, wr.write_all(&bytes)).await {
                        Ok(Ok(())) => {
                            self.update(|s| s.heartbeats += 1);
                            self.record(TrafficDirection::Sent, &bytes, None, None);
                        }
                        Ok(Err(e)) => return End::Lost(format!("heartbeat: {e}")),
                        Err(_) => return End::Lost("heartbeat: the write timed out".into()),
                    }
                }
            }
        }
    }

    fn write_failed(&self, bytes: &[u8], shot: Option<u64>, reason: String) -> End {
        self.update(|s| s.failed += 1);
        self.record(TrafficDirection::Sent, bytes, shot, Some(format!("write failed: {reason}")));
        End::Lost(format!("writing shot {}: {reason}", shot.unwrap_or_default()))
    }

    fn on_reply(&self, frame: Frame, awaiting: &mut u64) {
        let text = match frame {
            Frame::Object(bytes) => bytes,
            Frame::Oversized { bytes } => {
                self.record(TrafficDirection::Received, b"", None, Some(format!("oversized reply: {bytes} bytes")));
                return;
            }
            Frame::Garbage { bytes } => {
                self.record(TrafficDirection::Received, b"", None, Some(format!("{bytes} bytes outside JSON")));
                return;
            }
        };
        let answer = match self.protocol.answer(&text) {
            Ok(a) => a,
            Err(e) => {
                self.record(TrafficDirection::Received, &text, None, Some(format!("unreadable reply: {e}")));
                return;
            }
        };
        self.record(TrafficDirection::Received, &text, None, None);
        let shot_answered = *awaiting > 0 && answer.answers_shot;
        if shot_answered {
            *awaiting -= 1;
        }
        if !answer.success {
            tracing::warn!("rig {}: simulator answered {}", self.options.rig, answer.summary);
        }
        self.update(|s| {
            if shot_answered && answer.success {
                s.acknowledged += 1;
            } else if shot_answered {
                s.failed += 1;
            }
            if let Some(p) = answer.player {
                s.player = Some(p);
            }
            s.last_reply = Some(answer.summary);
        });
    }
}
