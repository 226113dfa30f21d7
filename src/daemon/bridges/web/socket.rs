//! One page's WebSocket: on connecting it gets `hello` (the rigs) and every rig's snapshot, then every page
//! message as it comes (a page that falls [`PAGE_LAG`] messages behind gets fresh snapshots instead of the
//! ones it missed); what it sends are controls ([`Control`]), each made into its put on zenoh.

use crate::daemon::bridges::peer_rejection::PeerRejection;
use std::net::SocketAddr;
use std::sync::Arc;

use futures_util::{SinkExt, StreamExt};
use tokio::net::TcpStream;
use tokio::sync::broadcast;
use tokio_tungstenite::tungstenite::protocol::WebSocketConfig;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::WebSocketStream;

use super::controls::Control;
use super::feed::Bay;
use super::limits::{MAX_CLIENT_MESSAGE_BYTES, PAGE_LAG, PING_PERIOD, SEND_TIMEOUT};
use crate::daemon::bridges::peers::{PeerSlot, Peers};

/// A page's connection and what it may use.
pub struct Page {
    pub peer: SocketAddr,
    pub slot: PeerSlot,
    pub peers: Peers,
    pub bay: Arc<Bay>,
    pub session: zenoh::Session,
    /// Whether its controls are taken (the token was given, or none is needed); read-only otherwise.
    pub controls: bool,
}

/// The WebSocket's bounds: a page's message at most [`MAX_CLIENT_MESSAGE_BYTES`], no write buffering.
pub fn config() -> WebSocketConfig {
    WebSocketConfig::default()
        .read_buffer_size(MAX_CLIENT_MESSAGE_BYTES)
        .max_message_size(Some(MAX_CLIENT_MESSAGE_BYTES))
        .max_frame_size(Some(MAX_CLIENT_MESSAGE_BYTES))
        .write_buffer_size(0)
        .max_write_buffer_size(8 << 20)
}

async fn send(ws: &mut WebSocketStream<TcpStream>, text: &str) -> bool {
    matches!(tokio::time::timeout(SEND_TIMEOUT, ws.send(Message::text(text))).await, Ok(Ok(())))
}

async fn send_snapshots(ws: &mut WebSocketStream<TcpStream>, bay: &Bay) -> bool {
    for s in bay.snapshots() {
        if !send(ws, &s).await {
            return false;
        }
    }
    true
}

/// Serves a page until it closes, is cut (idle, evicted) or cannot keep up with a write.
pub async fn serve(mut ws: WebSocketStream<TcpStream>, page: Page) {
    let peer = page.peer.to_string();
    let mut rx = page.bay.out.subscribe();
    let hello = serde_json::json!({
        "type": "hello", "rigs": page.bay.rigs, "version": env!("CARGO_PKG_VERSION"),
        "started_ns": page.bay.clock.wall_ns(), "controls": page.controls,
    });
    if !send(&mut ws, &hello.to_string()).await || !send_snapshots(&mut ws, &page.bay).await {
        return;
    }
    // What a page takes counts as its activity, as its pongs do: a page that reads is live.
    page.slot.touch();
    let mut ping = tokio::time::interval(PING_PERIOD);
    let mut closing = page.bay.closing.subscribe();
    loop {
        tokio::select! {
            changed = closing.changed() => {
                if changed.is_ok() && !*closing.borrow() {
                    continue;
                }
                use tokio_tungstenite::tungstenite::protocol::{frame::coding::CloseCode, CloseFrame};
                let frame = CloseFrame { code: CloseCode::Away, reason: "the daemon is stopping".into() };
                let _ = tokio::time::timeout(SEND_TIMEOUT, ws.close(Some(frame))).await;
                break;
            }
            incoming = ws.next() => match incoming {
                Some(Ok(Message::Text(t))) => {
                    page.slot.touch();
                    on_control(&page, t.as_str()).await;
                }
                Some(Ok(Message::Pong(_))) => page.slot.touch(),
                Some(Err(e)) => {
                    use tokio_tungstenite::tungstenite::Error;
                    let kind = if matches!(e, Error::Capacity(_)) { PeerRejection::Oversized } else { PeerRejection::Protocol };
                    page.peers.reject(kind, || format!("{peer}: closed: {e}"));
                    break;
                }
                Some(Ok(Message::Close(_))) | None => break,
                Some(Ok(_)) => {}
            },
            cut = page.slot.cut() => {
                page.slot.report(cut, &peer);
                break;
            }
            _ = ping.tick() => {
                let ping = Message::Ping(Vec::new().into());
                if !matches!(tokio::time::timeout(SEND_TIMEOUT, ws.send(ping)).await, Ok(Ok(()))) {
                    break;
                }
            }
            out = rx.recv() => match out {
                Ok(text) => {
                    if !send(&mut ws, &text).await {
                        break;
                    }
                    page.slot.touch();
                }
                Err(broadcast::error::RecvError::Lagged(n)) => {
                    tracing::debug!("bay screen: {peer} fell {n} messages behind (more than {PAGE_LAG}): resent");
                    if !send_snapshots(&mut ws, &page.bay).await {
                        break;
                    }
                    page.slot.touch();
                }
                Err(broadcast::error::RecvError::Closed) => break,
            },
        }
    }
}

/// A page's control: refused with its kind counted, or put on zenoh.
async fn on_control(page: &Page, text: &str) {
    let peer = page.peer;
    if !page.controls {
        return page.peers.reject(PeerRejection::Unauthorized, || {
            format!("{peer}: control refused: this page has no token (open the address printed at start)")
        });
    }
    let control = match Control::parse(text, &page.bay.rigs) {
        Ok(c) => c,
        Err(e) => return page.peers.reject(e.kind(), || format!("{peer}: control refused: {e}")),
    };
    let labels =
        page.bay.states.lock().ok().and_then(|s| s.get(control.rig()).map(|r| r.labels.clone())).unwrap_or_default();
    let (key, payload) = match control.put(&labels) {
        Ok(p) => p,
        Err(e) => return page.peers.reject(e.kind(), || format!("{peer}: control refused: {e}")),
    };
    if let Err(e) = page.session.put(key.clone(), payload).await {
        page.peers.reject(PeerRejection::PutFailed, || format!("put on {key}: {e}"));
    }
}
