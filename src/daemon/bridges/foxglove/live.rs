//! `--foxglove HOST:PORT`: the live view, a server of the Foxglove WebSocket protocol (`foxglove.websocket.v1`,
//! github.com/foxglove/ws-protocol) that Foxglove opens with "Open connection" -> "Foxglove WebSocket".
//!
//! It advertises every rig's channels ([`crate::daemon::recording::channels::rig_channels`]: clubhead samples, impact, launch,
//! status, measured launches, club pose, impact scene and the predicted ball flight) with their JSON Schemas and
//! streams the messages of the channels a client subscribes to: server info and advertise as JSON text, data
//! as binary frames (opcode 1, subscription id u32 LE, log time ns u64 LE, the JSON payload). The records come
//! from the daemon's `RecorderHandle` (recording/writer.rs) through a [`LiveTap`], a non-blocking
//! bounded queue: the view is encoded on its own task (the same encoder as the recording), a slow or absent
//! viewer never delays a prediction, and a viewer that falls behind skips messages rather than grow memory.
//!
//! What a client can make the server keep is bounded: a client message is at most [`MAX_CLIENT_MESSAGE_BYTES`]
//! (fragments included), subscriptions only to advertised channels (one per channel), at most
//! [`LIVE_VIEW_LIMITS`]`.max_connections` viewers (at the cap the longest-idle one is closed for a newcomer), a
//! handshake within its timeout, and a viewer that stops answering the server's pings is closed. Rejections are
//! counted by kind in every rig's status (`live_view`) and logged at most once a second per kind.

use crate::daemon::bridges::peer_rejection::PeerRejection;
use crate::daemon::clock::Clock;
use std::collections::HashMap;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;

use futures_util::{SinkExt, StreamExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{broadcast, mpsc};
use tokio_tungstenite::tungstenite::handshake::server::{ErrorResponse, Request, Response};
use tokio_tungstenite::tungstenite::http::{HeaderValue, StatusCode};
use tokio_tungstenite::tungstenite::protocol::WebSocketConfig;
use tokio_tungstenite::tungstenite::Message;

use crate::daemon::bridges::peers::{PeerLimits, PeerSlot, Peers};
use crate::daemon::recording::channels::{encode, rig_channels};
use crate::daemon::recording::record::Record;
use crate::daemon::recording::writer::RecordTap;
use crate::daemon::DaemonError;
use crate::wire::LiveViewStatus;

/// The WebSocket subprotocol.
pub const SUBPROTOCOL: &str = "foxglove.websocket.v1";
/// Records waiting to be encoded for the view.
const TAP_QUEUE: usize = 1 << 12;
/// Encoded messages a slow viewer may lag behind before it skips some.
const VIEWER_LAG: usize = 1 << 10;
/// The largest client message (a `subscribe` of every channel of 16 rigs is about 5 KiB).
pub const MAX_CLIENT_MESSAGE_BYTES: usize = 16 * 1024;
/// Viewers at once, the handshake's time, and the longest silence (no message, no answer to a ping).
pub const LIVE_VIEW_LIMITS: PeerLimits =
    PeerLimits { max_connections: 16, handshake: Duration::from_secs(5), idle: Duration::from_secs(60) };
/// How often a viewer is pinged (its pong keeps it from idling out).
const PING_PERIOD: Duration = Duration::from_secs(15);
/// The longest a frame to one viewer may take to write before the viewer is dropped.
const SEND_TIMEOUT: Duration = Duration::from_secs(5);

/// The daemon's side of the live view: hands records over without waiting.
#[derive(Clone)]
pub struct LiveTap {
    tx: mpsc::Sender<Record>,
    dropped: Arc<AtomicU64>,
}

impl RecordTap for LiveTap {
    fn send(&self, record: Record) {
        if self.tx.try_send(record).is_err() {
            self.dropped.fetch_add(1, Ordering::Relaxed);
        }
    }
}

/// A running live view; dropping it stops it.
pub struct FoxgloveServer {
    local_addr: SocketAddr,
    tap: LiveTap,
    peers: Peers,
    tasks: Vec<tokio::task::JoinHandle<()>>,
}

impl Drop for FoxgloveServer {
    fn drop(&mut self) {
        for t in &self.tasks {
            t.abort();
        }
    }
}

/// One message on its way to viewers.
struct Outgoing {
    channel: u32,
    log_time_ns: u64,
    data: Vec<u8>,
}

impl FoxgloveServer {
    /// Binds `address` and serves the channels of the named rigs on the current tokio runtime; a viewer's
    /// session is named for when it joined on `clock`.
    pub async fn start(address: &str, rigs: &[&str], clock: Clock) -> Result<Self, DaemonError> {
        let io = |e| DaemonError::Io { what: format!("serving the Foxglove live view on {address}"), source: e };
        let listener = TcpListener::bind(address).await.map_err(io)?;
        let local_addr = listener.local_addr().map_err(io)?;
        let mut topics = HashMap::new();
        let mut channels = Vec::new();
        for (topic, schema) in rigs.iter().flat_map(|rig| rig_channels(rig)) {
            let id = channels.len() as u32 + 1;
            channels.push(serde_json::json!({
                "id": id, "topic": topic, "encoding": "json", "schemaName": schema.name(),
                "schema": schema.text(), "schemaEncoding": "jsonschema",
            }));
            topics.insert(topic, id);
        }
        let advertise = Arc::new(serde_json::json!({ "op": "advertise", "channels": channels }).to_string());
        let channel_count = channels.len() as u32;
        let peers = Peers::new("Foxglove live view", LIVE_VIEW_LIMITS);
        let peers_accept = peers.clone();
        let (tx, mut rx) = mpsc::channel::<Record>(TAP_QUEUE);
        let (out, _) = broadcast::channel::<Arc<Outgoing>>(VIEWER_LAG);
        let out_enc = out.clone();
        let encoder = tokio::spawn(async move {
            while let Some(record) = rx.recv().await {
                let Some(e) = encode(record) else { continue };
                if let Some(&channel) = topics.get(&e.topic) {
                    // No viewer is not an error.
                    let _ = out_enc.send(Arc::new(Outgoing { channel, log_time_ns: e.log_time_ns, data: e.data }));
                }
            }
        });
        let acceptor = tokio::spawn(async move {
            loop {
                match listener.accept().await {
                    Ok((stream, peer)) => {
                        let slot = peers_accept.admit(&peer.to_string());
                        let client = Client {
                            peer,
                            slot,
                            channels: channel_count,
                            peers: peers_accept.clone(),
                            clock: clock.clone(),
                        };
                        tokio::spawn(serve(stream, client, advertise.clone(), out.subscribe()));
                    }
                    Err(e) => {
                        tracing::warn!("Foxglove live view: accept: {e}");
                        tokio::time::sleep(std::time::Duration::from_millis(100)).await;
                    }
                }
            }
        });
        tracing::info!("Foxglove live view on ws://{local_addr}");
        Ok(FoxgloveServer {
            local_addr,
            tap: LiveTap { tx, dropped: Arc::new(AtomicU64::new(0)) },
            peers,
            tasks: vec![encoder, acceptor],
        })
    }

    pub fn local_addr(&self) -> SocketAddr {
        self.local_addr
    }

    pub fn tap(&self) -> Arc<dyn RecordTap> {
        Arc::new(self.tap.clone())
    }

    /// Records the view could not keep up with.
    pub fn dropped(&self) -> u64 {
        self.tap.dropped.load(Ordering::Relaxed)
    }

    /// The viewers and rejections, for a status message.
    pub fn status_source(&self) -> LiveViewSource {
        LiveViewSource(self.peers.clone())
    }
}

/// Reads the live view's counts for a rig's status.
#[derive(Clone)]
pub struct LiveViewSource(Peers);

impl LiveViewSource {
    pub fn status(&self) -> LiveViewStatus {
        LiveViewStatus { clients: self.0.open() as u64, rejected: self.0.rejected().to_wire() }
    }
}

/// Accepts the handshake only for clients that speak the protocol, and names it in the answer.
#[allow(clippy::result_large_err)] // the handshake's callback signature
fn select_subprotocol(request: &Request, mut response: Response) -> Result<Response, ErrorResponse> {
    let offered = request
        .headers()
        .get_all("Sec-WebSocket-Protocol")
        .iter()
        .filter_map(|v| v.to_str().ok())
        .flat_map(|v| v.split(','))
        .any(|p| p.trim() == SUBPROTOCOL);
    if !offered {
        let mut refusal = ErrorResponse::new(Some(format!("this server speaks {SUBPROTOCOL} only")));
        *refusal.status_mut() = StatusCode::BAD_REQUEST;
        return Err(refusal);
    }
    response.headers_mut().insert("Sec-WebSocket-Protocol", HeaderValue::from_static(SUBPROTOCOL));
    Ok(response)
}

/// Why a client message was refused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ClientReject {
    /// Not a JSON object with an `op`.
    Malformed,
    /// An operation this server does not support.
    UnknownOp,
    /// A subscription to a channel that was never advertised, or a malformed subscription entry.
    UnknownChannel { refused: usize },
}

impl ClientReject {
    pub fn kind(&self) -> PeerRejection {
        match self {
            ClientReject::Malformed => PeerRejection::Malformed,
            ClientReject::UnknownOp => PeerRejection::UnknownOp,
            ClientReject::UnknownChannel { .. } => PeerRejection::UnknownChannel,
        }
    }
}

/// Applies a client's `subscribe` or `unsubscribe` to its subscription ids by channel id (channels are
/// `1..=channels`). Only advertised channels are taken, one subscription each, so the map never holds more
/// than the channels advertised whatever the client sends.
pub fn on_client_text(text: &str, channels: u32, subscriptions: &mut HashMap<u32, u32>) -> Result<(), ClientReject> {
    let Ok(v) = serde_json::from_str::<serde_json::Value>(text) else { return Err(ClientReject::Malformed) };
    let ids = |key: &str| v[key].as_array().map(Vec::as_slice).unwrap_or_default();
    match v["op"].as_str() {
        Some("subscribe") => {
            let mut refused = 0;
            for s in ids("subscriptions") {
                let id = s["id"].as_u64().and_then(|i| u32::try_from(i).ok());
                let channel = s["channelId"].as_u64().and_then(|c| u32::try_from(c).ok());
                match (id, channel) {
                    (Some(id), Some(channel)) if (1..=channels).contains(&channel) => {
                        subscriptions.insert(channel, id);
                    }
                    _ => refused += 1,
                }
            }
            if refused > 0 {
                return Err(ClientReject::UnknownChannel { refused });
            }
            Ok(())
        }
        Some("unsubscribe") => {
            let gone: std::collections::HashSet<u64> =
                ids("subscriptionIds").iter().filter_map(|i| i.as_u64()).collect();
            subscriptions.retain(|_, s| !gone.contains(&u64::from(*s)));
            Ok(())
        }
        Some(_) => Err(ClientReject::UnknownOp),
        None => Err(ClientReject::Malformed),
    }
}

/// One viewer's connection.
struct Client {
    peer: SocketAddr,
    slot: PeerSlot,
    channels: u32,
    peers: Peers,
    clock: Clock,
}

async fn serve(stream: TcpStream, client: Client, advertise: Arc<String>, rx: broadcast::Receiver<Arc<Outgoing>>) {
    let peer = client.peer;
    let _ = stream.set_nodelay(true);
    let config = WebSocketConfig::default()
        .read_buffer_size(MAX_CLIENT_MESSAGE_BYTES)
        .max_message_size(Some(MAX_CLIENT_MESSAGE_BYTES))
        .max_frame_size(Some(MAX_CLIENT_MESSAGE_BYTES))
        .write_buffer_size(0)
        .max_write_buffer_size(4 << 20);
    let handshake = tokio_tungstenite::accept_hdr_async_with_config(stream, select_subprotocol, Some(config));
    let ws = tokio::select! {
        done = handshake => match done {
            Ok(ws) => ws,
            Err(e) => {
                client.peers.reject(PeerRejection::Handshake, || format!("{peer}: handshake: {e}"));
                return;
            }
        },
        cut = client.slot.cut() => {
            client.slot.report(cut, &peer.to_string());
            return;
        }
    };
    client.slot.touch();
    tracing::info!("Foxglove live view: {peer} connected");
    stream_to(ws, &client, &advertise, rx).await;
    tracing::info!("Foxglove live view: {peer} disconnected");
}

async fn send(ws: &mut tokio_tungstenite::WebSocketStream<TcpStream>, m: Message) -> bool {
    matches!(tokio::time::timeout(SEND_TIMEOUT, ws.send(m)).await, Ok(Ok(())))
}

async fn stream_to(
    mut ws: tokio_tungstenite::WebSocketStream<TcpStream>,
    client: &Client,
    advertise: &str,
    mut rx: broadcast::Receiver<Arc<Outgoing>>,
) {
    let peer = client.peer.to_string();
    let info = serde_json::json!({
        "op": "serverInfo", "name": format!("impactd {}", env!("CARGO_PKG_VERSION")),
        "capabilities": [], "supportedEncodings": ["json"], "metadata": {},
        "sessionId": client.clock.wall_ns().to_string(),
    });
    if !send(&mut ws, Message::text(info.to_string())).await || !send(&mut ws, Message::text(advertise)).await {
        return;
    }
    let mut subscriptions: HashMap<u32, u32> = HashMap::new();
    let mut ping = tokio::time::interval(PING_PERIOD);
    loop {
        tokio::select! {
            incoming = ws.next() => match incoming {
                Some(Ok(Message::Text(t))) => match on_client_text(t.as_str(), client.channels, &mut subscriptions) {
                    Ok(()) => client.slot.touch(),
                    Err(r) => client.peers.reject(r.kind(), || format!("{peer}: client message refused: {r:?}")),
                },
                Some(Ok(Message::Pong(_))) => client.slot.touch(),
                Some(Err(e)) => {
                    use tokio_tungstenite::tungstenite::protocol::{frame::coding::CloseCode, CloseFrame};
                    use tokio_tungstenite::tungstenite::Error;
                    let oversized = matches!(e, Error::Capacity(_));
                    let kind = if oversized { PeerRejection::Oversized } else { PeerRejection::Protocol };
                    client.peers.reject(kind, || format!("{peer}: closed: {e}"));
                    if oversized {
                        let reason = format!("a client message is at most {MAX_CLIENT_MESSAGE_BYTES} bytes");
                        let frame = CloseFrame { code: CloseCode::Size, reason: reason.into() };
                        let _ = tokio::time::timeout(SEND_TIMEOUT, ws.close(Some(frame))).await;
                    }
                    break;
                }
                Some(Ok(Message::Close(_))) | None => break,
                Some(Ok(_)) => {}
            },
            cut = client.slot.cut() => {
                client.slot.report(cut, &peer);
                break;
            }
            _ = ping.tick() => {
                if !send(&mut ws, Message::Ping(Vec::new().into())).await {
                    break;
                }
            }
            outgoing = rx.recv() => match outgoing {
                Ok(m) => {
                    let Some(&subscription) = subscriptions.get(&m.channel) else { continue };
                    let mut frame = Vec::with_capacity(13 + m.data.len());
                    frame.push(1u8);
                    frame.extend_from_slice(&subscription.to_le_bytes());
                    frame.extend_from_slice(&m.log_time_ns.to_le_bytes());
                    frame.extend_from_slice(&m.data);
                    if !send(&mut ws, Message::binary(frame)).await {
                        break;
                    }
                }
                Err(broadcast::error::RecvError::Lagged(n)) => {
                    tracing::debug!("Foxglove live view: {peer} skipped {n} messages");
                }
                Err(broadcast::error::RecvError::Closed) => break,
            },
        }
    }
}
