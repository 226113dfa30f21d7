//! The Open Connect listener of one rig: launch monitor connectors reach impactd as they would a simulator.
//!
//! Each connection is read as a stream of JSON objects (glued together or split across reads; see
//! [`Splitter`]). A shot is answered with code 200 and published once as a
//! [`MeasuredLaunch`](crate::wire::MeasuredLaunch) on `lm/<rig>/launch` (a repeat of the same device's shot
//! number is answered 200 and not published again); a heartbeat is not answered; anything else (not JSON, not
//! a shot, impossible numbers, over 64 KiB, bytes outside any object) is answered with code 501 and the reason,
//! counted, and the connection goes on, so one bad message never costs another shot. Every message both ways is
//! recorded as `OpenConnectTraffic` on `lm/<rig>/open_connect`, each published shot on `lm/<rig>/launch`.
//! Received bytes are acknowledged at once (`TCP_QUICKACK`), so a connector's shot split over several writes
//! is not held back 40 ms by Nagle's algorithm waiting on a delayed ACK (`tests/live_comparison.rs`).

use std::collections::HashMap;
use std::net::SocketAddr;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};

use super::codec::{Reply, ShotMessage};
use super::splitter::{Frame, Splitter};
use super::MAX_MESSAGE_BYTES;
use crate::daemon::recording::record::Record;
use crate::daemon::recording::writer::RecorderHandle;
use crate::daemon::{wall_ns, DaemonError};
use crate::wire::{self, keys, LaunchMonitorStatus, MeasuredLaunch, Message, OpenConnectTraffic, TrafficDirection};

/// The failure code of the Open Connect v1 replies.
pub const FAILURE: u16 = 501;

/// A running listener; [`LaunchMonitorListener::stop`] ends it and its connections (dropping it aborts them).
pub struct LaunchMonitorListener {
    status: Arc<Mutex<LaunchMonitorStatus>>,
    local_addr: SocketAddr,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    task: tokio::task::JoinHandle<()>,
}

struct Shared {
    rig: String,
    publisher: zenoh::pubsub::Publisher<'static>,
    recorder: RecorderHandle,
    status: Arc<Mutex<LaunchMonitorStatus>>,
    traffic_key: String,
    /// The last shot number published per device.
    last_shot: Mutex<HashMap<String, u64>>,
}

impl LaunchMonitorListener {
    /// Binds `address` and serves connectors on the current tokio runtime.
    pub async fn start(
        rig: &str,
        address: &str,
        session: &zenoh::Session,
        recorder: RecorderHandle,
    ) -> Result<Self, DaemonError> {
        let io = |e| DaemonError::Io { what: format!("listening for Open Connect clients on {address}"), source: e };
        let listener = TcpListener::bind(address).await.map_err(io)?;
        let local_addr = listener.local_addr().map_err(io)?;
        let publisher = session
            .declare_publisher(keys::measured_launch(rig))
            .encoding(MeasuredLaunch::TYPE.encoding())
            .await
            .map_err(DaemonError::zenoh)?;
        let status = Arc::new(Mutex::new(LaunchMonitorStatus { listen: local_addr.to_string(), ..Default::default() }));
        let shared = Arc::new(Shared {
            rig: rig.to_string(),
            publisher,
            recorder,
            status: status.clone(),
            traffic_key: keys::launch_monitor_traffic(rig),
            last_shot: Mutex::new(HashMap::new()),
        });
        tracing::info!("rig {rig}: Open Connect listener on {local_addr}");
        let (stop, mut stopped) = tokio::sync::oneshot::channel::<()>();
        let task = tokio::spawn(async move {
            let mut connections = tokio::task::JoinSet::new();
            loop {
                tokio::select! {
                    _ = &mut stopped => break,
                    accepted = listener.accept() => match accepted {
                        Ok((stream, peer)) => {
                            connections.spawn(shared.clone().serve(stream, peer));
                        }
                        Err(e) => {
                            tracing::warn!("rig {}: Open Connect accept: {e}", shared.rig);
                            tokio::time::sleep(Duration::from_millis(100)).await;
                        }
                    },
                    Some(_) = connections.join_next() => {}
                }
            }
            // Every connection ends before the listener does, so nothing outlives the daemon's recording.
            connections.shutdown().await;
        });
        Ok(LaunchMonitorListener { status, local_addr, stop: Some(stop), task })
    }

    /// The bound address (useful with port 0).
    pub fn local_addr(&self) -> SocketAddr {
        self.local_addr
    }

    /// The shared counts, for a status message.
    pub fn status_handle(&self) -> Arc<Mutex<LaunchMonitorStatus>> {
        self.status.clone()
    }

    pub fn status(&self) -> LaunchMonitorStatus {
        self.status.lock().map(|s| s.clone()).unwrap_or_default()
    }
}

impl LaunchMonitorListener {
    /// Closes the listener and every connection, and waits until they are gone.
    pub async fn stop(mut self) {
        if let Some(stop) = self.stop.take() {
            let _ = stop.send(());
        }
        let _ = (&mut self.task).await;
    }
}

impl Drop for LaunchMonitorListener {
    fn drop(&mut self) {
        self.task.abort();
    }
}

/// Acknowledges received bytes at once rather than after the kernel's delayed-ACK timer (40 ms on Linux).
/// A connector that writes a shot in pieces without `TCP_NODELAY` has each later piece held back by Nagle's
/// algorithm until the previous one is acknowledged, so a delayed ACK would add 40 ms to the shot's arrival.
/// Linux drops out of quick-ACK mode by itself, so this is set again after every read.
fn quick_ack(stream: &TcpStream) {
    #[cfg(target_os = "linux")]
    let _ = socket2::SockRef::from(stream).set_tcp_quickack(true);
    #[cfg(not(target_os = "linux"))]
    let _ = stream;
}

impl Shared {
    fn update(&self, f: impl FnOnce(&mut LaunchMonitorStatus)) {
        if let Ok(mut s) = self.status.lock() {
            f(&mut s);
        }
    }

    fn record(&self, peer: &str, direction: TrafficDirection, text: &[u8], note: Option<String>) {
        if !self.recorder.enabled() {
            return;
        }
        let t_ns = wall_ns();
        let keep = &text[..text.len().min(wire::MAX_PAYLOAD_BYTES)];
        let msg = OpenConnectTraffic {
            rig: self.rig.clone(),
            t_ns,
            peer: peer.to_string(),
            direction,
            text: String::from_utf8_lossy(keep).into_owned(),
            shot: None,
            note,
        };
        self.recorder.send(Record::Message {
            key: self.traffic_key.clone(),
            message_type: OpenConnectTraffic::TYPE,
            log_time_ns: t_ns,
            publish_time_ns: t_ns,
            data: serde_json::to_vec(&msg).unwrap_or_default(),
        });
    }

    async fn serve(self: Arc<Self>, stream: TcpStream, peer: SocketAddr) {
        let peer = peer.to_string();
        let _ = stream.set_nodelay(true);
        self.update(|s| s.connections += 1);
        tracing::info!("rig {}: Open Connect client {peer} connected", self.rig);
        quick_ack(&stream);
        let (mut rd, mut wr) = stream.into_split();
        let mut splitter = Splitter::new(MAX_MESSAGE_BYTES);
        let mut buf = vec![0u8; 8192];
        let mut frames = Vec::new();
        'conn: loop {
            let n = match rd.read(&mut buf).await {
                Ok(0) | Err(_) => break,
                Ok(n) => n,
            };
            quick_ack(rd.as_ref());
            splitter.push(&buf[..n], &mut |f| frames.push(f));
            for frame in std::mem::take(&mut frames) {
                let Some(reply) = self.on_frame(frame, &peer).await else { continue };
                let bytes = serde_json::to_vec(&reply).unwrap_or_default();
                self.record(&peer, TrafficDirection::Sent, &bytes, None);
                match tokio::time::timeout(Duration::from_secs(2), wr.write_all(&bytes)).await {
                    Ok(Ok(())) => {}
                    _ => break 'conn,
                }
            }
        }
        self.update(|s| s.connections = s.connections.saturating_sub(1));
        tracing::info!("rig {}: Open Connect client {peer} disconnected", self.rig);
    }

    fn reject(&self, peer: &str, reason: &str, message: String) -> Option<Reply> {
        self.update(|s| *s.rejected.entry(reason.to_string()).or_default() += 1);
        tracing::warn!("rig {}: Open Connect client {peer}: {message}", self.rig);
        Some(Reply::new(FAILURE, message))
    }

    /// The reply to one frame, if it gets one.
    async fn on_frame(&self, frame: Frame, peer: &str) -> Option<Reply> {
        let text = match frame {
            Frame::Object(text) => text,
            Frame::Oversized { bytes } => {
                self.record(peer, TrafficDirection::Received, b"", Some(format!("oversized: {bytes} bytes")));
                let m = format!("message of {bytes} bytes is over the {MAX_MESSAGE_BYTES}-byte limit; discarded");
                return self.reject(peer, "oversized", m);
            }
            Frame::Garbage { bytes } => {
                self.record(peer, TrafficDirection::Received, b"", Some(format!("{bytes} bytes outside JSON")));
                return self.reject(peer, "not_json", format!("{bytes} bytes outside any JSON object skipped"));
            }
        };
        self.record(peer, TrafficDirection::Received, &text, None);
        let message = match serde_json::from_slice::<ShotMessage>(&text) {
            Ok(m) => m,
            Err(e) => return self.reject(peer, "malformed", format!("not an Open Connect v1 message: {e}")),
        };
        if message.is_heartbeat() {
            self.update(|s| s.heartbeats += 1);
            return None;
        }
        let t_ns = wall_ns();
        let measured = match message.to_measured(&self.rig, t_ns) {
            Ok(m) => m,
            Err(e) => return self.reject(peer, "invalid", format!("shot {}: {e}", message.shot_number)),
        };
        let repeated = {
            let mut last = self.last_shot.lock().ok()?;
            let repeated = message.shot_number != 0 && last.get(&message.device_id) == Some(&message.shot_number);
            last.insert(message.device_id.clone(), message.shot_number);
            repeated
        };
        if repeated {
            self.update(|s| s.duplicates += 1);
            return Some(Reply::new(200, format!("Shot {} already received", message.shot_number)));
        }
        // Recorded by the rig's worker, which records every measured launch on the key, whatever its source.
        let data = serde_json::to_vec(&measured).unwrap_or_default();
        if let Err(e) = self.publisher.put(data).await {
            return self.reject(peer, "publish", format!("shot {} not published: {e}", message.shot_number));
        }
        self.update(|s| s.shots += 1);
        Some(Reply::new(200, "Shot received successfully"))
    }
}
