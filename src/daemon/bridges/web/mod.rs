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
//! Answered only as the names it listens as, upgraded only from its own page's origin, its controls behind a
//! token beyond loopback ([`access`]; docs/bay-screen.md, "Threat model"). Bounded like every network surface
//! of the daemon ([`limits`]): a request head at most 8 KiB, a page's message at most 4 KiB, at most 64
//! connections (at the cap an unfinished handshake is closed for a newcomer, else a stale page, else the newcomer
//! is refused and backs off), a handshake within 5 s, a page that stops reading and answering pings closed after
//! 60 s; rejections are counted by kind in every rig's status (`web`), their log lines one a second per kind. Each rig's state keeps at most its last 5000 shots and 12 flight lines, and a page its last 1000
//! shots, so a screen left open for a day does not grow. The screen reads the bus from the daemon's zenoh
//! session through a bounded queue and its own task: pages never touch the prediction path.

pub mod access;
pub mod assets;
pub mod controls;
pub mod download;
pub mod feed;
pub mod http;
pub mod limits;
pub mod socket;
pub mod state;

use crate::daemon::bridges::peer_rejection::PeerRejection;
use crate::daemon::clock::Clock;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use tokio::net::{TcpListener, TcpStream};

use crate::daemon::bridges::peers::{PeerSlot, Peers};
use crate::daemon::DaemonError;
use crate::wire::LiveViewStatus;

/// The address `--web` serves on when given without one (loopback, like every surface of the daemon).
pub const DEFAULT_ADDRESS: &str = "127.0.0.1:8080";

/// Who the screen answers besides its listen address and `localhost` (`--web-host`, `[web] hosts`), and the
/// token its controls need (`[web] token`; made at start when it listens beyond loopback and none is set).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct WebAccess {
    pub hosts: Vec<String>,
    pub token: Option<String>,
}

/// A running bay screen; dropping it stops it.
pub struct WebServer {
    local_addr: SocketAddr,
    peers: Peers,
    bay: Arc<feed::Bay>,
    access: Arc<access::Access>,
    _feed: feed::Feed,
    acceptor: tokio::task::JoinHandle<()>,
    log_flush: tokio::task::JoinHandle<()>,
}

impl Drop for WebServer {
    fn drop(&mut self) {
        self.acceptor.abort();
        self.log_flush.abort();
        self.bay.closing.send_replace(true);
    }
}

impl WebServer {
    /// Binds `address` and serves the screens of `rigs`, reading and putting on
    /// `session`, answering as `web` says. `recording` names the recording's file in the CSV download; what
    /// arrives is stamped on `clock`.
    pub async fn start(
        address: &str,
        web: &WebAccess,
        rigs: Vec<String>,
        session: &zenoh::Session,
        recording: Option<&std::path::Path>,
        clock: Clock,
    ) -> Result<Self, DaemonError> {
        let io = |e| DaemonError::Io { what: format!("serving the bay screen on {address}"), source: e };
        let listener = TcpListener::bind(address).await.map_err(io)?;
        let local_addr = listener.local_addr().map_err(io)?;
        let access = Arc::new(access::Access::new(address, local_addr, &web.hosts, web.token.as_deref())?);
        let name = recording.and_then(|p| p.file_name()).map(|n| n.to_string_lossy().into_owned());
        let bay = feed::Bay::new(rigs, name.unwrap_or_default(), clock);
        let feed = feed::Feed::start(session, bay.clone()).await?;
        let peers = Peers::new("bay screen", limits::WEB_LIMITS);
        let (peers_accept, bay_accept, session, access_accept) =
            (peers.clone(), bay.clone(), session.clone(), access.clone());
        let refusing = Arc::new(AtomicUsize::new(0));
        let acceptor = tokio::spawn(async move {
            loop {
                match listener.accept().await {
                    Ok((stream, peer)) => {
                        let Some(slot) = peers_accept.admit_unless_full(&peer.to_string(), limits::STALE_AFTER) else {
                            refuse_at_cap(stream, &refusing);
                            continue;
                        };
                        let conn = Connection {
                            peer,
                            slot,
                            peers: peers_accept.clone(),
                            bay: bay_accept.clone(),
                            session: session.clone(),
                            access: access_accept.clone(),
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
        let peers_flush = peers.clone();
        let log_flush = tokio::spawn(async move {
            let mut tick = tokio::time::interval(limits::LOG_FLUSH);
            loop {
                tick.tick().await;
                peers_flush.flush_log();
            }
        });
        match access.token() {
            Some(token) if access.token_made() => {
                let shown = if local_addr.ip().is_unspecified() {
                    format!("THIS-MACHINE:{}", local_addr.port())
                } else {
                    local_addr.to_string()
                };
                tracing::warn!(
                    "bay screen on http://{local_addr}/, beyond loopback: its controls need this start's token; \
                     open http://{shown}/?token={token} once on each screen (read-only without it; set \
                     [web] token to keep one across starts)"
                );
            }
            Some(_) => tracing::info!(
                "bay screen on http://{local_addr}/: its controls need [web] token (open /?token=... once on each \
                 screen; read-only without it)"
            ),
            None => tracing::info!("bay screen on http://{local_addr}/"),
        }
        Ok(WebServer { local_addr, peers, bay, access, _feed: feed, acceptor, log_flush })
    }

    /// [`WebServer::start`] when there is an address.
    pub async fn start_if(
        address: Option<&str>,
        web: &WebAccess,
        rigs: Vec<String>,
        session: &zenoh::Session,
        recording: Option<&std::path::Path>,
        clock: Clock,
    ) -> Result<Option<Self>, DaemonError> {
        match address {
            Some(a) => Ok(Some(Self::start(a, web, rigs, session, recording, clock).await?)),
            None => Ok(None),
        }
    }

    pub fn local_addr(&self) -> SocketAddr {
        self.local_addr
    }

    /// The token the screen's controls need, when they need one.
    pub fn token(&self) -> Option<&str> {
        self.access.token()
    }

    /// The connections and rejections, for the rigs' status.
    pub fn status_source(&self) -> WebStatusSource {
        WebStatusSource { peers: self.peers.clone(), bay: self.bay.clone() }
    }
}

/// A newcomer refused at the cap (every connection there live): answered 503 with a `Retry-After` (the page
/// backs off and tries again), by a task of its own while fewer than [`limits::MAX_REFUSING`] are; beyond them
/// closed unanswered.
fn refuse_at_cap(stream: TcpStream, refusing: &Arc<AtomicUsize>) {
    if refusing.fetch_add(1, Ordering::Relaxed) >= limits::MAX_REFUSING {
        refusing.fetch_sub(1, Ordering::Relaxed);
        return;
    }
    let refusing = refusing.clone();
    tokio::spawn(async move {
        let head = tokio::time::timeout(limits::REFUSAL_WAIT, http::peek_head(&stream)).await;
        let len = match head {
            Ok(Ok((_, len))) => len,
            _ => 0,
        };
        let max = limits::WEB_LIMITS.max_connections;
        let mut response =
            http::Response::text(503, &format!("the bay screen is serving its {max} connections: try again soon"));
        response.extra.push(("Retry-After", "2".into()));
        http::answer_after(stream, len, response, limits::SEND_TIMEOUT).await;
        refusing.fetch_sub(1, Ordering::Relaxed);
    });
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
        rejected.add_n(PeerRejection::BusPayloadRefused, self.bay.refused.load(std::sync::atomic::Ordering::Relaxed));
        rejected.add_n(PeerRejection::BusQueueFull, self.bay.dropped.load(std::sync::atomic::Ordering::Relaxed));
        LiveViewStatus { clients: self.peers.open() as u64, rejected: rejected.to_wire() }
    }
}

/// One accepted connection: a file request or a page.
struct Connection {
    peer: SocketAddr,
    slot: PeerSlot,
    peers: Peers,
    bay: Arc<feed::Bay>,
    session: zenoh::Session,
    access: Arc<access::Access>,
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
        let (request, len) = match head {
            Ok(r) => r,
            Err(http::HeadError::Closed) => return,
            Err(e @ http::HeadError::TooLarge) => {
                self.peers.reject(PeerRejection::Oversized, || format!("{peer}: {e}"));
                return http::answer(stream, http::Response::text(431, "request head too large"), limits::SEND_TIMEOUT)
                    .await;
            }
            Err(e) => return self.peers.reject(PeerRejection::Protocol, || format!("{peer}: {e}")),
        };
        let response = match request {
            http::Request::Refused { status, kind } => {
                self.peers.reject(kind, || format!("{peer}: HTTP {status}"));
                http::Response::text(status, "refused")
            }
            http::Request::Upgrade(head) => match self.admitted(&head, true) {
                Ok(()) => {
                    let controls =
                        self.access.allows_controls(head.cookie_token.as_deref(), head.query_token.as_deref());
                    return self.upgrade(stream, controls).await;
                }
                Err(refused) => refused,
            },
            http::Request::Get(head) => match self.admitted(&head, false) {
                Ok(()) => self.get(&head),
                Err(refused) => refused,
            },
        };
        self.slot.touch();
        http::answer_after(stream, len, response, limits::SEND_TIMEOUT).await;
    }

    /// Whether the request names this server in `Host` and, for an upgrade, comes from the page's own origin;
    /// else the answer (421, 403), counted by kind.
    fn admitted(&self, head: &http::Head, upgrade: bool) -> Result<(), http::Response> {
        let host = self.access.check_host(head.host.as_deref());
        let checked = host.and_then(|()| match upgrade {
            true => self.access.check_origin(head.origin.as_deref(), head.host.as_deref().unwrap_or_default()),
            false => Ok(()),
        });
        checked.map_err(|r| {
            self.peers.reject(r.kind, || format!("{}: HTTP {}: {}", self.peer, r.status, r.reason));
            http::Response::text(r.status, &r.reason)
        })
    }

    fn get(&self, head: &http::Head) -> http::Response {
        let path = head.path.as_str();
        // The token in the address: kept as a cookie for the page's socket, and the address shown without it.
        if let (Some(given), Some(_)) = (head.query_token.as_deref(), self.access.token()) {
            if !self.access.is_token(given) {
                self.peers.reject(PeerRejection::BadToken, || format!("{}: a wrong token", self.peer));
                return http::Response::text(403, "wrong token: use the address the daemon printed at start");
            }
            let cookie =
                format!("{}={given}; Path=/; Max-Age=34560000; HttpOnly; SameSite=Strict", access::TOKEN_COOKIE);
            let mut r = http::Response::text(303, "the token is kept; on to the page");
            r.extra = vec![("Location", path.to_string()), ("Set-Cookie", cookie)];
            return r;
        }
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
        self.peers.reject(PeerRejection::NotFound, || {
            format!("{}: no page at {}", self.peer, crate::daemon::peer_log::escaped(path, 80))
        });
        http::Response::text(404, "no such page")
    }

    async fn upgrade(self, stream: TcpStream, controls: bool) {
        let peer = self.peer.to_string();
        let handshake = tokio_tungstenite::accept_async_with_config(stream, Some(socket::config()));
        let ws = tokio::select! {
            done = handshake => match done {
                Ok(ws) => ws,
                Err(e) => return self.peers.reject(PeerRejection::Handshake, || format!("{peer}: handshake: {e}")),
            },
            cut = self.slot.cut() => return self.slot.report(cut, &peer),
        };
        self.slot.touch();
        let mode = if controls { "" } else { " (read-only: no token)" };
        self.peers.info("page_connected", || format!("page connected: {peer}{mode}"));
        let page = socket::Page {
            peer: self.peer,
            slot: self.slot,
            peers: self.peers.clone(),
            bay: self.bay,
            session: self.session,
            controls,
        };
        socket::serve(ws, page).await;
        self.peers.info("page_left", || format!("page left: {peer}"));
    }
}
