//! The bay screen's HTTP side: a request head is peeked (not consumed) so a WebSocket upgrade can go to
//! tungstenite's handshake untouched; any other request is answered here: the embedded page files, a rig's
//! session as TrackMan CSV, 404 and 405, and every answer closes the connection (a page is five small files).
//!
//! Written here rather than with an HTTP framework (axum, hyper): the page needs GET of fixed paths and one
//! upgrade, and tungstenite already parses the upgrade; hyper and axum would add a service stack and minutes of
//! compile time to CI for that.

use crate::daemon::bridges::peer_rejection::PeerRejection;
use std::time::Duration;

use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

/// The largest request head read (a browser's is under 2 KiB).
pub const MAX_REQUEST_HEAD_BYTES: usize = 8 * 1024;
/// The most headers parsed.
const MAX_HEADERS: usize = 48;

/// What a client asked for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Request {
    /// A WebSocket upgrade of `/ws`: tungstenite takes the connection as it is.
    Upgrade(Head),
    /// A GET of a path (the query string removed).
    Get(Head),
    /// Anything else: answered with this status.
    Refused { status: u16, kind: PeerRejection },
}

/// The parts of a request head the screen looks at (each bounded by the head's size).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Head {
    /// The path, without its query string.
    pub path: String,
    pub host: Option<String>,
    pub origin: Option<String>,
    /// `token=` in the query string.
    pub query_token: Option<String>,
    /// The token cookie ([`super::access::TOKEN_COOKIE`]).
    pub cookie_token: Option<String>,
}

/// Why a request head could not be read.
#[derive(Debug, thiserror::Error)]
pub enum HeadError {
    #[error("the connection closed before a request")]
    Closed,
    #[error("a request head over {MAX_REQUEST_HEAD_BYTES} bytes")]
    TooLarge,
    #[error("reading the request: {0}")]
    Io(#[from] std::io::Error),
}

/// Parses a complete request head.
pub fn classify(head: &[u8]) -> Request {
    let mut headers = [httparse::EMPTY_HEADER; MAX_HEADERS];
    let mut req = httparse::Request::new(&mut headers);
    match req.parse(head) {
        Ok(httparse::Status::Complete(_)) => {}
        Ok(httparse::Status::Partial) | Err(_) => {
            return Request::Refused { status: 400, kind: PeerRejection::BadRequest }
        }
    }
    if req.method != Some("GET") {
        return Request::Refused { status: 405, kind: PeerRejection::Method };
    }
    let target = req.path.unwrap_or("/");
    let target = target.split('#').next().unwrap_or("/");
    let (path, query) = target.split_once('?').unwrap_or((target, ""));
    let value = |name: &str| {
        req.headers.iter().find(|h| h.name.eq_ignore_ascii_case(name)).and_then(|h| std::str::from_utf8(h.value).ok())
    };
    let cookie_token = req
        .headers
        .iter()
        .filter(|h| h.name.eq_ignore_ascii_case("cookie"))
        .filter_map(|h| std::str::from_utf8(h.value).ok())
        .flat_map(|v| v.split(';'))
        .find_map(|c| c.trim().strip_prefix(super::access::TOKEN_COOKIE)?.strip_prefix('='))
        .map(String::from);
    let head = Head {
        path: path.to_string(),
        host: value("host").map(String::from),
        origin: value("origin").map(String::from),
        query_token: query.split('&').find_map(|p| p.strip_prefix("token=")).map(String::from),
        cookie_token,
    };
    let upgrade = value("upgrade").is_some_and(|v| v.eq_ignore_ascii_case("websocket"));
    if upgrade {
        return if head.path == "/ws" {
            Request::Upgrade(head)
        } else {
            Request::Refused { status: 404, kind: PeerRejection::NotFound }
        };
    }
    Request::Get(head)
}

/// Waits for a whole request head without consuming it.
///
/// `peek` returns at once while any byte is waiting, so an incomplete head is peeked again after a short sleep
/// (a browser sends its head in one segment: the first peek almost always has it). The caller bounds the wait
/// with the handshake timeout.
/// Returns the request and the head's length.
pub async fn peek_head(stream: &TcpStream) -> Result<(Request, usize), HeadError> {
    let mut buf = vec![0u8; MAX_REQUEST_HEAD_BYTES];
    loop {
        let n = stream.peek(&mut buf).await?;
        if n == 0 {
            return Err(HeadError::Closed);
        }
        if let Some(end) = buf[..n].windows(4).position(|w| w == b"\r\n\r\n") {
            return Ok((classify(&buf[..end + 4]), end + 4));
        }
        if n == buf.len() {
            return Err(HeadError::TooLarge);
        }
        tokio::time::sleep(Duration::from_millis(2)).await;
    }
}

/// A response: status, content type, body and extra headers.
pub struct Response {
    pub status: u16,
    pub content_type: &'static str,
    pub body: std::borrow::Cow<'static, [u8]>,
    pub extra: Vec<(&'static str, String)>,
}

impl Response {
    pub fn text(status: u16, text: &str) -> Self {
        Response {
            status,
            content_type: "text/plain; charset=utf-8",
            body: text.as_bytes().to_vec().into(),
            extra: Vec::new(),
        }
    }

    fn reason(&self) -> &'static str {
        match self.status {
            200 => "OK",
            303 => "See Other",
            400 => "Bad Request",
            403 => "Forbidden",
            404 => "Not Found",
            405 => "Method Not Allowed",
            421 => "Misdirected Request",
            431 => "Request Header Fields Too Large",
            503 => "Service Unavailable",
            _ => "Error",
        }
    }

    /// The head and body as sent.
    pub fn bytes(&self) -> Vec<u8> {
        let mut head = format!(
            "HTTP/1.1 {} {}\r\nContent-Type: {}\r\nContent-Length: {}\r\nCache-Control: no-store\r\n\
             X-Content-Type-Options: nosniff\r\nContent-Security-Policy: default-src 'self'; img-src 'self' data:\r\n\
             Connection: close\r\n",
            self.status,
            self.reason(),
            self.content_type,
            self.body.len()
        );
        for (name, value) in &self.extra {
            head.push_str(&format!("{name}: {value}\r\n"));
        }
        head.push_str("\r\n");
        let mut out = head.into_bytes();
        out.extend_from_slice(&self.body);
        out
    }
}

/// Sends `response` and closes the connection (the unread request is dropped with it).
pub async fn answer(stream: TcpStream, response: Response, timeout: Duration) {
    answer_after(stream, 0, response, timeout).await;
}

/// Reads the `head` bytes peeked (so the close that follows is a clean one, not a reset that could lose the
/// answer), then sends `response` and closes the connection.
pub async fn answer_after(mut stream: TcpStream, head: usize, response: Response, timeout: Duration) {
    let write = async {
        let mut left = head;
        let mut buf = [0u8; 1024];
        while left > 0 {
            let n = stream.read(&mut buf[..left.min(1024)]).await?;
            if n == 0 {
                break;
            }
            left -= n;
        }
        stream.write_all(&response.bytes()).await?;
        stream.shutdown().await
    };
    let _ = tokio::time::timeout(timeout, write).await;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_are_told_apart() {
        let get = b"GET /app.js?v=1&token=abc HTTP/1.1\r\nHost: x\r\nCookie: a=b; impactd_token=t1\r\n\r\n";
        let head = Head {
            path: "/app.js".into(),
            host: Some("x".into()),
            query_token: Some("abc".into()),
            cookie_token: Some("t1".into()),
            ..Default::default()
        };
        assert_eq!(classify(get), Request::Get(head));
        let ws =
            b"GET /ws HTTP/1.1\r\nHost: x\r\nOrigin: http://x\r\nUpgrade: WebSocket\r\nConnection: Upgrade\r\n\r\n";
        let Request::Upgrade(head) = classify(ws) else { panic!("not an upgrade") };
        assert_eq!((head.host.as_deref(), head.origin.as_deref()), (Some("x"), Some("http://x")));
        let ws_elsewhere = b"GET /other HTTP/1.1\r\nUpgrade: websocket\r\n\r\n";
        assert_eq!(classify(ws_elsewhere), Request::Refused { status: 404, kind: PeerRejection::NotFound });
        assert_eq!(classify(b"POST / HTTP/1.1\r\n\r\n"), Request::Refused { status: 405, kind: PeerRejection::Method });
        assert_eq!(
            classify(b"\x00\x01garbage\r\n\r\n"),
            Request::Refused { status: 400, kind: PeerRejection::BadRequest }
        );
        let r = Response::text(404, "no such page").bytes();
        let text = String::from_utf8(r).unwrap();
        assert!(text.starts_with("HTTP/1.1 404 Not Found\r\n") && text.contains("Content-Length: 12\r\n"));
    }
}
