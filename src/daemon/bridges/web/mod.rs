//! `--web HOST:PORT` (or `[web] listen = ...`): the bay screen, a web page per rig served by the daemon. The
//! page's files are embedded in the binary ([`assets`]); the page talks to the daemon over a WebSocket on the
//! same port (`/ws`) carrying small JSON messages: shots, the session's per-club numbers, comparisons, labels,
//! exclusions, units and status to the page ([`feed`], [`state`]), controls from it ([`controls`]), each made
//! into the put on zenoh any program could make. A rig's session downloads as TrackMan CSV ([`download`]).
//!
//! Why its own small JSON WebSocket rather than the Foxglove server or axum: the page needs TrackMan's numbers
//! per shot, computed once for every page, not the robotics channels Foxglove's protocol carries (decoding
//! those in the page would mean a client library or a build step); and tokio-tungstenite is already built for
//! the Foxglove view, so the screen adds no dependency but `httparse` (already built for tungstenite) and no
//! compile time, where axum would bring hyper and tower to CI. The request head is peeked so the upgrade goes
//! to tungstenite untouched ([`http`]).
//!
//! Bounded like every network surface of the daemon ([`limits`]): a request head at most 8 KiB, a page's
//! message at most 4 KiB, at most 64 connections (the longest idle is closed for a newcomer), a handshake within
//! 5 s, a page that stops answering pings closed after 60 s; rejections are counted by kind in every rig's status
//! (`web`). Each rig's state keeps at most its last 5000 shots and 12 flight lines, and a page its last 1000
//! shots, so a screen left open for a day does not grow. The screen reads the bus from the daemon's zenoh
//! session through a bounded queue and its own task: pages never touch the prediction path.

pub mod assets;
pub mod controls;
pub mod download;
pub mod feed;
pub mod http;
pub mod limits;
pub mod socket;
pub mod state;

use std::net::SocketAddr;
use std::sync::Arc;

use tokio::net::{TcpListener, TcpStream};

use crate::daemon::bridges::peers::{PeerSlot, Peers};
use crate::daemon::DaemonError;
use crate::wire::LiveViewStatus;

/// The address `--web` serves on when given without one (loopback, like every surface of the daemon).
pub const DEFAULT_ADDRESS: &str = "127.0.0.1:8080";

/// A running bay screen; dropping it stops it.
pub struct WebServer {
    local_addr: SocketAddr,
    peers: Peers,
    bay: Arc<feed::Bay>,
    _feed: feed::Feed,
    acceptor: tokio::task::JoinHandle<()>,
}

impl Drop for WebServer {
    fn drop(&mut self) {
        self.acceptor.abort();
        self.bay.closing.send_replace(true);
    }
}

impl WebServer {
    /// Binds `address` and serves the screens of `rigs` (each with its flight model), reading and putting on
    /// `session`. `recording` names the recording's file in the CSV download.
    pub async fn start(
        address: &str,
        rigs: Vec<(String, crate::flight::Flight)>,
        session: &zenoh::Session,
        recording: Option<&std::path::Path>,
    ) -> Result<Self, DaemonError> {
        let io = |e| DaemonError::Io { what: format!("serving the bay screen on {address}"), source: e };
        let listener = TcpListener::bind(address).await.map_err(io)?;
        let local_addr = listener.local_addr().map_err(io)?;
        let name = recording.and_then(|p| p.file_name()).map(|n| n.to_string_lossy().into_owned());
        let bay = feed::Bay::new(rigs, name.unwrap_or_default());
        let feed = feed::Feed::start(session, bay.clone()).await?;
        let peers = Peers::new("bay screen", limits::WEB_LIMITS);
        let (peers_accept, bay_accept, session) = (peers.clone(), bay.clone(), session.clone());
        let acceptor = tokio::spawn(async move {
            loop {
                match listener.accept().await {
                    Ok((stream, peer)) => {
                        let slot = peers_accept.admit(&peer.to_string());
                        let conn = Connection {
                            peer,
                            slot,
                            peers: peers_accept.clone(),
                            bay: bay_accept.clone(),
                            session: session.clone(),
                        };
                        tokio::spawn(conn.serve(stream));
                    }
                    Err(e) => {
                        tracing::warn!("bay screen: accept: {e}");
                        tokio::time::sleep(std::time::Duration::from_millis(100)).await;
                    }
                }
            }
        });
        tracing::info!("bay screen on http://{local_addr}/");
        Ok(WebServer { local_addr, peers, bay, _feed: feed, acceptor })
    }

    /// [`WebServer::start`] when there is an address.
    pub async fn start_if(
        address: Option<&str>,
        rigs: Vec<(String, crate::flight::Flight)>,
        session: &zenoh::Session,
        recording: Option<&std::path::Path>,
    ) -> Result<Option<Self>, DaemonError> {
        match address {
            Some(a) => Ok(Some(Self::start(a, rigs, session, recording).await?)),
            None => Ok(None),
        }
    }

    pub fn local_addr(&self) -> SocketAddr {
        self.local_addr
    }

    /// The connections and rejections, for the rigs' status.
    pub fn status_source(&self) -> WebStatusSource {
        WebStatusSource { peers: self.peers.clone(), bay: self.bay.clone() }
    }
}

/// Reads the bay screen's counts for a rig's status.
#[derive(Clone)]
pub struct WebStatusSource {
    peers: Peers,
    bay: Arc<feed::Bay>,
}

impl WebStatusSource {
    pub fn status(&self) -> LiveViewStatus {
        let mut rejected = self.peers.rejected();
        let counts = [
            ("bus_payload_refused", self.bay.refused.load(std::sync::atomic::Ordering::Relaxed)),
            ("bus_queue_full", self.bay.dropped.load(std::sync::atomic::Ordering::Relaxed)),
        ];
        for (kind, n) in counts.into_iter().filter(|(_, n)| *n > 0) {
            rejected.insert(kind.to_string(), n);
        }
        LiveViewStatus { clients: self.peers.open() as u64, rejected }
    }
}

/// One accepted connection: a file request or a page.
struct Connection {
    peer: SocketAddr,
    slot: PeerSlot,
    peers: Peers,
    bay: Arc<feed::Bay>,
    session: zenoh::Session,
}

impl Connection {
    async fn serve(self, stream: TcpStream) {
        let _ = stream.set_nodelay(true);
        let peer = self.peer.to_string();
        let head = tokio::select! {
            head = http::peek_head(&stream) => head,
            cut = self.slot.cut() => {
                self.slot.report(cut, &peer);
                return;
            }
        };
        let request = match head {
            Ok(r) => r,
            Err(http::HeadError::Closed) => return,
            Err(e @ http::HeadError::TooLarge) => {
                self.peers.reject("oversized", || format!("{peer}: {e}"));
                return http::answer(stream, http::Response::text(431, "request head too large"), limits::SEND_TIMEOUT)
                    .await;
            }
            Err(e) => return self.peers.reject("protocol", || format!("{peer}: {e}")),
        };
        let response = match request {
            http::Request::Upgrade => return self.upgrade(stream).await,
            http::Request::Refused { status, kind } => {
                self.peers.reject(kind, || format!("{peer}: HTTP {status}"));
                http::Response::text(status, "refused")
            }
            http::Request::Get { path } => self.get(&path),
        };
        self.slot.touch();
        http::answer(stream, response, limits::SEND_TIMEOUT).await;
    }

    fn get(&self, path: &str) -> http::Response {
        if let Some(a) = assets::find(path) {
            return http::Response {
                status: 200,
                content_type: a.content_type,
                body: a.body.into(),
                extra: Vec::new(),
            };
        }
        if let Some(rig) = download::rig_of_path(path) {
            if let Some(csv) = download::session_csv(&self.bay, rig) {
                let disposition = format!("attachment; filename=\"{rig}-session.csv\"");
                return http::Response {
                    status: 200,
                    content_type: "text/csv; charset=utf-8",
                    body: csv.into(),
                    extra: vec![("Content-Disposition", disposition)],
                };
            }
        }
        self.peers
            .reject("not_found", || format!("{}: no page at {}", self.peer, path.chars().take(80).collect::<String>()));
        http::Response::text(404, "no such page")
    }

    async fn upgrade(self, stream: TcpStream) {
        let peer = self.peer.to_string();
        let handshake = tokio_tungstenite::accept_async_with_config(stream, Some(socket::config()));
        let ws = tokio::select! {
            done = handshake => match done {
                Ok(ws) => ws,
                Err(e) => return self.peers.reject("handshake", || format!("{peer}: handshake: {e}")),
            },
            cut = self.slot.cut() => return self.slot.report(cut, &peer),
        };
        self.slot.touch();
        tracing::info!("bay screen: page {peer} connected");
        let page =
            socket::Page { peer: self.peer, slot: self.slot, peers: self.peers, bay: self.bay, session: self.session };
        socket::serve(ws, page).await;
        tracing::info!("bay screen: page {peer} left");
    }
}
