//! The Open Connect listener of one rig: launch monitor connectors reach impactd as they would a simulator.
//!
//! Each connection is read as a stream of JSON objects (glued together or split across reads; see
//! [`Splitter`]). A shot is answered with code 200 and published once as a
//! [`MeasuredLaunch`](crate::wire::MeasuredLaunch) on `lm/<rig>/launch` (a repeat of the same device's shot
//! number is answered 200 and not published again); a heartbeat is not answered; anything else (not JSON, not
//! a shot, impossible numbers, over 64 KiB, bytes outside any object) is answered with code 501 and the reason,
//! counted, and the connection goes on, so one bad message never costs another shot. Every message both ways is
//! recorded as `OpenConnectTraffic` on `lm/<rig>/open_connect`, each published shot on `lm/<rig>/launch`;
//! heartbeats, rejected messages and their answers within a budget per second, and the next record recorded
//! after a refusal notes how many were not.
//!
//! What a peer can make the listener keep is bounded ([`crate::daemon::bridges::peers`]): connections (at the cap the
//! longest-idle one is closed for a newcomer), time to the first shot or heartbeat and between them, a message's
//! size, a `DeviceID`'s length and the devices remembered for repeats. Rejections are counted by kind in the
//! status and logged at most once a second per kind.
//! Received bytes are acknowledged at once (`TCP_QUICKACK`), so a connector's shot split over several writes
//! is not held back 40 ms by Nagle's algorithm waiting on a delayed ACK (`tests/daemon/live_comparison.rs`).

use crate::daemon::bridges::peer_rejection::PeerRejection;
use std::collections::HashMap;
use std::net::SocketAddr;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};

use super::codec::{Reply, ShotMessage};
use super::splitter::{Frame, Splitter};
use super::{LaunchMonitorConfig, MAX_MESSAGE_BYTES};
use crate::capped::quote;
use crate::daemon::bridges::peers::{PeerSlot, Peers};
use crate::daemon::clock::Clock;
use crate::daemon::recording::record::Record;
use crate::daemon::recording::writer::RecorderHandle;
use crate::daemon::stats::Budget;
use crate::daemon::stats::{REJECTED_BYTES_PER_S, REJECTED_KEEP_BYTES, REJECTED_RECORDS_PER_S};
use crate::daemon::DaemonError;
use crate::wire::{self, keys, LaunchMonitorStatus, MeasuredLaunch, Message, OpenConnectTraffic, TrafficDirection};

/// The failure code of the Open Connect v1 replies.
pub const FAILURE: u16 = 501;
/// The longest `DeviceID` taken (bytes); connectors name themselves in a few words.
pub const MAX_DEVICE_ID_BYTES: usize = 128;
/// Devices whose last shot number is remembered (to answer a repeat without publishing it again); beyond it the
/// device heard from least recently is forgotten.
pub const MAX_DEVICES: usize = 64;

/// A running listener; [`LaunchMonitorListener::stop`] ends it and its connections (dropping it aborts them).
pub struct LaunchMonitorListener {
    status: Arc<Mutex<LaunchMonitorStatus>>,
    local_addr: SocketAddr,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    task: tokio::task::JoinHandle<()>,
}

/// Per device: its last shot number and when it was last heard from (a sequence number).
type Devices = HashMap<String, (u64, u64)>;

struct Shared {
    rig: String,
    publisher: zenoh::pubsub::Publisher<'static>,
    recorder: RecorderHandle,
    status: Arc<Mutex<LaunchMonitorStatus>>,
    traffic_key: String,
    /// The last shot number published per device, with when it was last heard from (a sequence number).
    last_shot: Mutex<(Devices, u64)>,
    peers: Peers,
    /// The recording budget of rejected messages and their answers, and how many it refused since the last
    /// record (noted on the next one).
    budget: Mutex<(Budget, u64)>,
    /// The daemon's clock: measurements and recorded traffic are stamped on it.
    clock: Clock,
}

impl LaunchMonitorListener {
    /// Binds `address` and serves connectors on the current tokio runtime, stamping on `clock`.
    pub async fn start(
        rig: &str,
        config: &LaunchMonitorConfig,
        address: &str,
        session: &zenoh::Session,
        recorder: RecorderHandle,
        clock: Clock,
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
            last_shot: Mutex::new((HashMap::new(), 0)),
            peers: Peers::new(&format!("rig {rig}: Open Connect"), config.peer_limits()),
            budget: Mutex::new((Budget::with_clock(REJECTED_RECORDS_PER_S, REJECTED_BYTES_PER_S, clock.clone()), 0)),
            clock,
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
                            let slot = shared.peers.admit(&peer.to_string());
                            shared.refresh();
                            connections.spawn(shared.clone().serve(stream, peer, slot));
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
            shared.record_what_was_left_out();
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

    /// Copies the connection count and the rejections by kind into the status.
    fn refresh(&self) {
        let (open, rejected) = (self.peers.open() as u64, self.peers.rejected());
        self.update(|s| {
            s.connections = open;
            s.rejected = rejected.to_wire();
        });
    }

    /// Records a rejected message, its answer or a heartbeat, within the budget.
    fn record_budgeted(&self, peer: &str, direction: TrafficDirection, text: &[u8], note: Option<String>) {
        if !self.recorder.enabled() {
            return;
        }
        let keep = text.len().min(REJECTED_KEEP_BYTES);
        let refused_before = {
            let Ok(mut b) = self.budget.lock() else { return };
            if !b.0.allow(keep) {
                b.1 += 1;
                let refused = b.0.refused;
                drop(b);
                self.update(|s| s.traffic_not_recorded = refused);
                return;
            }
            std::mem::take(&mut b.1)
        };
        let note = match (refused_before, note) {
            (0, note) => note,
            (n, note) => Some(format!(
                "{}{n} rejected messages and answers before this one not recorded (over the budget)",
                note.map(|n| format!("{n}; ")).unwrap_or_default()
            )),
        };
        self.record(peer, direction, &text[..keep], note);
    }

    /// At the end: the rejected traffic the budget left out since the last record, noted in a record of its own
    /// (no later record would carry it).
    fn record_what_was_left_out(&self) {
        let left = self.budget.lock().map(|mut b| std::mem::take(&mut b.1)).unwrap_or(0);
        if left > 0 {
            let note = format!("{left} rejected messages and answers at the end not recorded (over the budget)");
            self.record("", TrafficDirection::Received, b"", Some(note));
        }
    }

    fn record(&self, peer: &str, direction: TrafficDirection, text: &[u8], note: Option<String>) {
        if !self.recorder.enabled() {
            return;
        }
        let t_ns = self.clock.wall_ns();
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

    async fn serve(self: Arc<Self>, stream: TcpStream, peer: SocketAddr, slot: PeerSlot) {
        let peer = peer.to_string();
        let _ = stream.set_nodelay(true);
        tracing::debug!("rig {}: Open Connect client {peer} connected", self.rig);
        quick_ack(&stream);
        let (mut rd, mut wr) = stream.into_split();
        let mut splitter = Splitter::new(MAX_MESSAGE_BYTES);
        let mut buf = vec![0u8; 8192];
        let mut frames = Vec::new();
        'conn: loop {
            let n = tokio::select! {
                read = rd.read(&mut buf) => match read {
                    Ok(0) | Err(_) => break,
                    Ok(n) => n,
                },
                cut = slot.cut() => {
                    slot.report(cut, &peer);
                    break;
                }
            };
            quick_ack(rd.as_ref());
            splitter.push(&buf[..n], &mut |f| frames.push(f));
            for frame in std::mem::take(&mut frames) {
                let (reply, useful) = self.on_frame(frame, &peer).await;
                if useful {
                    slot.touch();
                }
                let Some(reply) = reply else { continue };
                let bytes = serde_json::to_vec(&reply).unwrap_or_default();
                if useful {
                    self.record(&peer, TrafficDirection::Sent, &bytes, None);
                } else {
                    self.record_budgeted(&peer, TrafficDirection::Sent, &bytes, None);
                }
                match tokio::time::timeout(Duration::from_secs(2), wr.write_all(&bytes)).await {
                    Ok(Ok(())) => {}
                    _ => break 'conn,
                }
            }
        }
        drop(slot);
        self.refresh();
        tracing::debug!("rig {}: Open Connect client {peer} disconnected", self.rig);
    }

    /// Remembers the device's shot number; whether it repeats the last one. At most [`MAX_DEVICES`] devices are
    /// remembered: a new one beyond them makes the listener forget the device heard from least recently.
    fn remember(&self, device_id: &str, shot_number: u64) -> bool {
        let Ok(mut last) = self.last_shot.lock() else { return false };
        let (devices, heard) = &mut *last;
        *heard += 1;
        let repeated = shot_number != 0 && devices.get(device_id).is_some_and(|(shot, _)| *shot == shot_number);
        if devices.len() >= MAX_DEVICES && !devices.contains_key(device_id) {
            let least_recent = devices.iter().min_by_key(|(_, (_, seq))| *seq).map(|(id, _)| id.clone());
            if let Some(id) = least_recent {
                devices.remove(&id);
            }
        }
        devices.insert(device_id.to_string(), (shot_number, *heard));
        repeated
    }

    /// Counts the rejection by kind (logged at most once a second per kind) and answers it.
    fn reject(&self, peer: &str, reason: PeerRejection, message: String) -> (Option<Reply>, bool) {
        self.peers.reject(reason, || format!("client {peer}: {message}"));
        self.refresh();
        (Some(Reply::new(FAILURE, message)), false)
    }

    /// The reply to one frame, if it gets one, and whether the frame was a useful message (a shot or a
    /// heartbeat: it keeps the connection from idling out).
    async fn on_frame(&self, frame: Frame, peer: &str) -> (Option<Reply>, bool) {
        let text = match frame {
            Frame::Object(text) => text,
            Frame::Oversized { bytes } => {
                let note = Some(format!("oversized: over {} bytes", bytes.saturating_sub(1)));
                self.record_budgeted(peer, TrafficDirection::Received, b"", note);
                let m = format!("message over the {MAX_MESSAGE_BYTES}-byte limit; discarded up to its end");
                return self.reject(peer, PeerRejection::Oversized, m);
            }
            Frame::Garbage { bytes } => {
                self.record_budgeted(
                    peer,
                    TrafficDirection::Received,
                    b"",
                    Some(format!("{bytes} bytes outside JSON")),
                );
                return self.reject(
                    peer,
                    PeerRejection::NotJson,
                    format!("{bytes} bytes outside any JSON object skipped"),
                );
            }
        };
        let message = match serde_json::from_slice::<ShotMessage>(&text) {
            Ok(m) => m,
            Err(e) => {
                self.record_budgeted(peer, TrafficDirection::Received, &text, None);
                let e = e.to_string();
                return self.reject(
                    peer,
                    PeerRejection::Malformed,
                    format!("not an Open Connect v1 message: {}", quote(&e)),
                );
            }
        };
        if message.device_id.len() > MAX_DEVICE_ID_BYTES {
            self.record_budgeted(peer, TrafficDirection::Received, &text, None);
            let m = format!(
                "DeviceID of {} bytes is over the {MAX_DEVICE_ID_BYTES}-byte limit: {}",
                message.device_id.len(),
                quote(&message.device_id)
            );
            return self.reject(peer, PeerRejection::DeviceId, m);
        }
        if message.is_heartbeat() {
            // Heartbeats are recorded within the budget too: a flood of them is a flood.
            self.record_budgeted(peer, TrafficDirection::Received, &text, None);
            self.update(|s| s.heartbeats += 1);
            return (None, true);
        }
        let t_ns = self.clock.wall_ns();
        let measured = match message.to_measured(&self.rig, t_ns) {
            Ok(m) => {
                self.record(peer, TrafficDirection::Received, &text, None);
                m
            }
            Err(e) => {
                self.record_budgeted(peer, TrafficDirection::Received, &text, None);
                let e = e.to_string();
                return self.reject(
                    peer,
                    PeerRejection::Invalid,
                    format!("shot {}: {}", message.shot_number, quote(&e)),
                );
            }
        };
        let repeated = self.remember(&message.device_id, message.shot_number);
        if repeated {
            self.update(|s| s.duplicates += 1);
            return (Some(Reply::new(200, format!("Shot {} already received", message.shot_number))), true);
        }
        // Recorded by the rig's worker, which records every measured launch on the key, whatever its source.
        let data = serde_json::to_vec(&measured).unwrap_or_default();
        if let Err(e) = self.publisher.put(data).await {
            return self.reject(
                peer,
                PeerRejection::Publish,
                format!("shot {} not published: {e}", message.shot_number),
            );
        }
        self.update(|s| s.shots += 1);
        (Some(Reply::new(200, "Shot received successfully")), true)
    }
}
