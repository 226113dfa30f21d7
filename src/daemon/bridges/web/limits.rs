//! What a page (or anything else connecting to the bay screen's port) can make the daemon keep or wait for.

use std::time::Duration;

use crate::daemon::bridges::peers::PeerLimits;

/// The largest message a page may send (a control is under 300 bytes; fragments included).
pub const MAX_CLIENT_MESSAGE_BYTES: usize = 4 * 1024;
/// Connections at once (pages and file requests together). At the cap an unfinished handshake is closed for a
/// newcomer, else a page idle for [`STALE_AFTER`], else the newcomer is refused (503: the page backs off and
/// tries again) rather than a live page closed. The handshake (a request head, then for a page the WebSocket
/// handshake) must finish in time, and a page that stops reading and answering pings is closed.
pub const WEB_LIMITS: PeerLimits =
    PeerLimits { max_connections: 64, handshake: Duration::from_secs(5), idle: Duration::from_secs(60) };
/// How often a page is pinged (a browser answers by itself; its pong, like every message it takes, keeps the
/// page from idling out).
pub const PING_PERIOD: Duration = Duration::from_secs(15);
/// A page that has taken nothing and answered no ping for this long (two pings) may be closed for a newcomer
/// at the cap.
pub const STALE_AFTER: Duration = Duration::from_secs(30);
/// Connections refused at the cap being answered at once; beyond them a newcomer is closed unanswered.
pub const MAX_REFUSING: usize = 64;
/// How long a refused newcomer's request head is waited for before it is answered (503).
pub const REFUSAL_WAIT: Duration = Duration::from_secs(1);
/// How often the screen's log says what it suppressed.
pub const LOG_FLUSH: Duration = Duration::from_secs(1);
/// The longest one message to one page may take to write before the page is dropped.
pub const SEND_TIMEOUT: Duration = Duration::from_secs(5);
/// Page messages a slow page may lag behind before it is sent a fresh snapshot instead.
pub const PAGE_LAG: usize = 256;
/// Bus messages waiting for the feed (a full queue drops and counts them; it never blocks zenoh).
pub const FEED_QUEUE: usize = 4096;
