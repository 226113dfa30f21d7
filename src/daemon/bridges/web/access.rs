//! Who may use the bay screen (docs/bay-screen.md, "Threat model"): every request must name in `Host` a name
//! the server listens as (so a DNS-rebinding page, whose requests name its own host, is answered 421); a
//! WebSocket upgrade from a browser must come from the page's own origin (`Origin` equal to `http://` + `Host`,
//! so a page on another site cannot open the socket, 403); and where the screen listens beyond loopback (or a
//! token is configured) a page's controls need the token: the screen itself stays open to read.
//!
//! The token reaches a screen once, in the address printed at start (`http://HOST:PORT/?token=T`): the server
//! answers it with a cookie (`impactd_token`, HttpOnly, SameSite=Strict) and a redirect to the same page
//! without the token, and the page's WebSocket upgrade carries the cookie. A program may send the cookie or
//! `?token=T` on `/ws` itself.

use crate::daemon::bridges::peer_rejection::PeerRejection;
use std::net::{IpAddr, SocketAddr};

use crate::daemon::DaemonError;

/// The cookie that carries the token.
pub const TOKEN_COOKIE: &str = "impactd_token";
/// A configured token's length bounds and its characters (safe in a cookie and an address unescaped).
const TOKEN_MIN: usize = 16;
const TOKEN_MAX: usize = 256;

/// What the bay screen answers and to whom.
#[derive(Debug, Clone)]
pub struct Access {
    /// The address it is bound to.
    bound: IpAddr,
    /// Host names answered besides IP literals: `localhost`, the listen address's name, the user's.
    names: Vec<String>,
    /// The token controls need, when they need one.
    token: Option<String>,
    /// Whether the token was made at this start (and so is printed) rather than configured.
    made: bool,
}

/// Why a request was refused: its status, the kind counted and a short reason for the client.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refusal {
    pub status: u16,
    pub kind: PeerRejection,
    pub reason: String,
}

impl Access {
    /// The rules of a screen bound to `bound` as `listen` (as given: `localhost:8080`), answering also as
    /// `hosts`, with `token` configured (else one is made when `bound` is beyond loopback).
    pub fn new(listen: &str, bound: SocketAddr, hosts: &[String], token: Option<&str>) -> Result<Access, DaemonError> {
        let mut names = vec!["localhost".to_string()];
        let (listen_host, _) = split_host(listen);
        if listen_host.parse::<IpAddr>().is_err() && !listen_host.is_empty() {
            names.push(normal(listen_host));
        }
        for h in hosts {
            let n = normal(h);
            if n.is_empty() || n.contains(['/', ' ', '@']) || n.contains(':') && n.parse::<IpAddr>().is_err() {
                return Err(DaemonError::Config {
                    field: "web.hosts".into(),
                    reason: format!("`{h}` is not a host name (a name or an address, without a port)"),
                });
            }
            names.push(n);
        }
        let (token, made) = match token {
            Some(t) => (Some(check_token(t)?), false),
            None if !bound.ip().is_loopback() => (Some(new_token()?), true),
            None => (None, false),
        };
        Ok(Access { bound: bound.ip(), names, token, made })
    }

    /// The token controls need, when they need one.
    pub fn token(&self) -> Option<&str> {
        self.token.as_deref()
    }

    /// Whether the token was made at this start (then it is printed; a configured one is not).
    pub fn token_made(&self) -> bool {
        self.made
    }

    /// Whether `Host` names this server: an IP literal it listens on (any when it listens on every address;
    /// a loopback address when it listens on loopback), `localhost`, the listen address's name or a name the
    /// user added (`--web-host`, `[web] hosts`). The port is not compared.
    pub fn check_host(&self, host: Option<&str>) -> Result<(), Refusal> {
        let Some(host) = host else {
            return Err(Refusal {
                status: 400,
                kind: PeerRejection::NoHost,
                reason: "a request must name its Host".into(),
            });
        };
        let (name, _) = split_host(host);
        let name = normal(name);
        let ok = match name.trim_start_matches('[').trim_end_matches(']').parse::<IpAddr>() {
            Ok(ip) => self.bound.is_unspecified() || ip == self.bound || (self.bound.is_loopback() && ip.is_loopback()),
            Err(_) => self.names.contains(&name),
        };
        if ok {
            return Ok(());
        }
        Err(Refusal {
            status: 421,
            kind: PeerRejection::WrongHost,
            reason: format!(
                "this server does not answer as `{}` (add it with --web-host or [web] hosts)",
                crate::daemon::peer_log::escaped(host, 80)
            ),
        })
    }

    /// Whether a WebSocket upgrade's `Origin` is the page's own (`http://` or `https://` followed by the
    /// request's `Host`). No `Origin` is a program, not a browser (browsers always send it on an upgrade).
    pub fn check_origin(&self, origin: Option<&str>, host: &str) -> Result<(), Refusal> {
        let Some(origin) = origin else { return Ok(()) };
        let origin = origin.trim().to_ascii_lowercase();
        let host = normal(host);
        let own = origin.strip_prefix("http://").or_else(|| origin.strip_prefix("https://"));
        if own.is_some_and(|o| normal(o) == host) {
            return Ok(());
        }
        Err(Refusal {
            status: 403,
            kind: PeerRejection::CrossOrigin,
            reason: format!(
                "a page from `{}` may not use this bay screen",
                crate::daemon::peer_log::escaped(&origin, 80)
            ),
        })
    }

    /// Whether a request carrying these tokens (the cookie's, the query's) may send controls.
    pub fn allows_controls(&self, cookie: Option<&str>, query: Option<&str>) -> bool {
        match &self.token {
            None => true,
            Some(t) => [cookie, query].into_iter().flatten().any(|given| same(given.as_bytes(), t.as_bytes())),
        }
    }

    /// Whether `given` is the token (`true` when none is needed).
    pub fn is_token(&self, given: &str) -> bool {
        self.token.as_deref().is_none_or(|t| same(given.as_bytes(), t.as_bytes()))
    }
}

/// Compares every byte whatever the first difference (no early exit for a guess to time).
fn same(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

/// The host part of `HOST[:PORT]` or `[V6][:PORT]`, and the port part.
fn split_host(authority: &str) -> (&str, Option<&str>) {
    if let Some(rest) = authority.strip_prefix('[') {
        return match rest.find(']') {
            Some(end) => (&authority[..end + 2], rest[end + 1..].strip_prefix(':')),
            None => (authority, None),
        };
    }
    match authority.rsplit_once(':') {
        // One colon: a port; more: an IPv6 address without brackets.
        Some((h, p)) if !h.contains(':') => (h, Some(p)),
        _ => (authority, None),
    }
}

/// A host name compared as DNS does: lower case, without the root's trailing dot.
fn normal(host: &str) -> String {
    host.trim().trim_end_matches('.').to_ascii_lowercase()
}

fn check_token(t: &str) -> Result<String, DaemonError> {
    let ok = (TOKEN_MIN..=TOKEN_MAX).contains(&t.len())
        && t.bytes().all(|b| b.is_ascii_alphanumeric() || b"-_.~".contains(&b));
    if ok {
        return Ok(t.to_string());
    }
    Err(DaemonError::Config {
        field: "web.token".into(),
        reason: format!("must be {TOKEN_MIN} to {TOKEN_MAX} letters, digits or `-_.~`"),
    })
}

/// 128 random bits from the operating system, in hex.
fn new_token() -> Result<String, DaemonError> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes).map_err(|e| DaemonError::Io {
        what: "making the bay screen's token".into(),
        source: std::io::Error::other(e.to_string()),
    })?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn access(listen: &str, hosts: &[&str]) -> Access {
        let bound: SocketAddr = listen.replace("localhost", "127.0.0.1").parse().unwrap();
        let hosts: Vec<String> = hosts.iter().map(|h| h.to_string()).collect();
        Access::new(listen, bound, &hosts, None).unwrap()
    }

    #[test]
    fn only_the_names_the_server_listens_as_are_answered() {
        let a = access("127.0.0.1:8080", &["Bay-Screen.local"]);
        for ok in ["127.0.0.1:8080", "localhost:8080", "LOCALHOST.", "[::1]:8080", "127.0.0.2", "bay-screen.local:80"] {
            assert_eq!(a.check_host(Some(ok)), Ok(()), "{ok}");
        }
        for bad in ["evil.example:8080", "evil.example", "10.0.0.1:8080", "localhost.evil.example"] {
            assert_eq!(a.check_host(Some(bad)).unwrap_err().status, 421, "{bad}");
        }
        assert_eq!(a.check_host(None).unwrap_err().status, 400);
        // A name the listen address gives is answered; on every address, any IP literal is.
        assert!(access("localhost:8080", &[]).check_host(Some("localhost:8080")).is_ok());
        let wide = Access::new("0.0.0.0:8080", "0.0.0.0:8080".parse().unwrap(), &[], None).unwrap();
        assert!(wide.check_host(Some("192.168.1.20:8080")).is_ok());
        assert!(wide.check_host(Some("bay.example:8080")).is_err());
        let e = Access::new("127.0.0.1:1", "127.0.0.1:1".parse().unwrap(), &["a/b".into()], None).unwrap_err();
        assert!(e.to_string().contains("web.hosts"), "{e}");
    }

    #[test]
    fn an_upgrade_must_come_from_the_pages_own_origin() {
        let a = access("127.0.0.1:8080", &[]);
        assert_eq!(a.check_origin(Some("http://127.0.0.1:8080"), "127.0.0.1:8080"), Ok(()));
        assert_eq!(a.check_origin(Some("HTTP://LocalHost:8080"), "localhost:8080"), Ok(()));
        assert_eq!(a.check_origin(None, "127.0.0.1:8080"), Ok(()), "a program sends no Origin");
        for bad in
            ["http://evil.example:8080", "http://127.0.0.1:9999", "null", "file://", "http://127.0.0.1:8080.evil"]
        {
            assert_eq!(a.check_origin(Some(bad), "127.0.0.1:8080").unwrap_err().status, 403, "{bad}");
        }
    }

    #[test]
    fn beyond_loopback_controls_need_the_token() {
        assert!(access("127.0.0.1:8080", &[]).token().is_none());
        assert!(access("127.0.0.1:8080", &[]).allows_controls(None, None));
        let wide = Access::new("0.0.0.0:8080", "0.0.0.0:8080".parse().unwrap(), &[], None).unwrap();
        let t = wide.token().unwrap().to_string();
        assert_eq!(t.len(), 32);
        assert!(!wide.allows_controls(None, None));
        assert!(!wide.allows_controls(Some("wrong"), None));
        assert!(wide.allows_controls(Some(&t), None) && wide.allows_controls(None, Some(&t)));
        let other = Access::new("0.0.0.0:8080", "0.0.0.0:8080".parse().unwrap(), &[], None).unwrap();
        assert_ne!(other.token(), wide.token(), "each start makes its own");
        // A configured token is needed on loopback too; a short one is refused.
        let set = Access::new("127.0.0.1:1", "127.0.0.1:1".parse().unwrap(), &[], Some("bay-screen-token-1")).unwrap();
        assert!(set.is_token("bay-screen-token-1") && !set.is_token("bay-screen-token-2"));
        let e = Access::new("127.0.0.1:1", "127.0.0.1:1".parse().unwrap(), &[], Some("short")).unwrap_err();
        assert!(e.to_string().contains("web.token"), "{e}");
    }
}
