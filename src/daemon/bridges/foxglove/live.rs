//! `--foxglove HOST:PORT`: the live view, a server of the Foxglove WebSocket protocol (`foxglove.websocket.v1`,
//! github.com/foxglove/ws-protocol) that Foxglove opens with "Open connection" -> "Foxglove WebSocket".
//!
//! It advertises every rig's channels ([`crate::daemon::bridges::foxglove::server::rig_channels`]: clubhead samples, impact, launch,
//! status, measured launches, club pose, impact scene and the predicted ball flight) with their JSON Schemas and
//! streams the messages of the channels a client subscribes to: server info and advertise as JSON text, data
//! as binary frames (opcode 1, subscription id u32 LE, log time ns u64 LE, the JSON payload). The records come
//! from the daemon's [`RecorderHandle`](crate::daemon::recording::writer::RecorderHandle) through a [`LiveTap`], a non-blocking
//! bounded queue: the view is encoded on its own task (the same encoder as the recording), a slow or absent
//! viewer never delays a prediction, and a viewer that falls behind skips messages rather than grow memory.

use std::collections::HashMap;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use futures_util::{SinkExt, StreamExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{broadcast, mpsc};
use tokio_tungstenite::tungstenite::handshake::server::{ErrorResponse, Request, Response};
use tokio_tungstenite::tungstenite::http::{HeaderValue, StatusCode};
use tokio_tungstenite::tungstenite::Message;

use crate::daemon::bridges::foxglove::server::{encode, rig_channels};
use crate::daemon::recording::record::Record;
use crate::daemon::DaemonError;

/// The WebSocket subprotocol.
pub const SUBPROTOCOL: &str = "foxglove.websocket.v1";
/// Records waiting to be encoded for the view.
const TAP_QUEUE: usize = 1 << 12;
/// Encoded messages a slow viewer may lag behind before it skips some.
const VIEWER_LAG: usize = 1 << 10;

/// The daemon's side of the live view: hands records over without waiting.
#[derive(Clone)]
pub struct LiveTap {
    tx: mpsc::Sender<Record>,
    dropped: Arc<AtomicU64>,
}

impl LiveTap {
    pub fn send(&self, record: Record) {
        if self.tx.try_send(record).is_err() {
            self.dropped.fetch_add(1, Ordering::Relaxed);
        }
    }
}

/// A running live view; dropping it stops it.
pub struct FoxgloveServer {
    local_addr: SocketAddr,
    tap: LiveTap,
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
    /// Binds `address` and serves the channels of the configuration's rigs on the current tokio runtime.
    pub async fn start(address: &str, config: &crate::daemon::DaemonConfig) -> Result<Self, DaemonError> {
        let io = |e| DaemonError::Io { what: format!("serving the Foxglove live view on {address}"), source: e };
        let listener = TcpListener::bind(address).await.map_err(io)?;
        let local_addr = listener.local_addr().map_err(io)?;
        let mut topics = HashMap::new();
        let mut channels = Vec::new();
        for (topic, schema) in config.rigs.iter().flat_map(|r| rig_channels(&r.name)) {
            let id = channels.len() as u32 + 1;
            channels.push(serde_json::json!({
                "id": id, "topic": topic, "encoding": "json", "schemaName": schema.name(),
                "schema": schema.text(), "schemaEncoding": "jsonschema",
            }));
            topics.insert(topic, id);
        }
        let advertise = Arc::new(serde_json::json!({ "op": "advertise", "channels": channels }).to_string());
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
                        tokio::spawn(serve(stream, peer, advertise.clone(), out.subscribe()));
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
            tasks: vec![encoder, acceptor],
        })
    }

    pub fn local_addr(&self) -> SocketAddr {
        self.local_addr
    }

    pub fn tap(&self) -> LiveTap {
        self.tap.clone()
    }

    /// Records the view could not keep up with.
    pub fn dropped(&self) -> u64 {
        self.tap.dropped.load(Ordering::Relaxed)
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

/// Subscription ids by channel id, from the client's `subscribe` and `unsubscribe` operations.
fn on_client_text(text: &str, subscriptions: &mut HashMap<u32, u32>) {
    let Ok(v) = serde_json::from_str::<serde_json::Value>(text) else { return };
    let ids = |key: &str| v[key].as_array().cloned().unwrap_or_default();
    match v["op"].as_str() {
        Some("subscribe") => {
            for s in ids("subscriptions") {
                if let (Some(id), Some(channel)) = (s["id"].as_u64(), s["channelId"].as_u64()) {
                    subscriptions.insert(channel as u32, id as u32);
                }
            }
        }
        Some("unsubscribe") => {
            for id in ids("subscriptionIds").iter().filter_map(|i| i.as_u64()) {
                subscriptions.retain(|_, s| u64::from(*s) != id);
            }
        }
        _ => {}
    }
}

async fn serve(
    stream: TcpStream,
    peer: SocketAddr,
    advertise: Arc<String>,
    mut rx: broadcast::Receiver<Arc<Outgoing>>,
) {
    let _ = stream.set_nodelay(true);
    let mut ws = match tokio_tungstenite::accept_hdr_async(stream, select_subprotocol).await {
        Ok(ws) => ws,
        Err(e) => {
            tracing::debug!("Foxglove live view: {peer}: handshake: {e}");
            return;
        }
    };
    tracing::info!("Foxglove live view: {peer} connected");
    let info = serde_json::json!({
        "op": "serverInfo", "name": format!("impactd {}", env!("CARGO_PKG_VERSION")),
        "capabilities": [], "supportedEncodings": ["json"], "metadata": {},
        "sessionId": crate::daemon::wall_ns().to_string(),
    });
    if ws.send(Message::text(info.to_string())).await.is_err()
        || ws.send(Message::text(advertise.as_str())).await.is_err()
    {
        return;
    }
    let mut subscriptions: HashMap<u32, u32> = HashMap::new();
    loop {
        tokio::select! {
            incoming = ws.next() => match incoming {
                Some(Ok(Message::Text(t))) => on_client_text(t.as_str(), &mut subscriptions),
                Some(Ok(Message::Close(_))) | None | Some(Err(_)) => break,
                Some(Ok(_)) => {}
            },
            outgoing = rx.recv() => match outgoing {
                Ok(m) => {
                    let Some(&subscription) = subscriptions.get(&m.channel) else { continue };
                    let mut frame = Vec::with_capacity(13 + m.data.len());
                    frame.push(1u8);
                    frame.extend_from_slice(&subscription.to_le_bytes());
                    frame.extend_from_slice(&m.log_time_ns.to_le_bytes());
                    frame.extend_from_slice(&m.data);
                    if ws.send(Message::binary(frame)).await.is_err() {
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
    tracing::info!("Foxglove live view: {peer} disconnected");
}
