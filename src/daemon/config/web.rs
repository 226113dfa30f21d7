//! `[web]` of `impactd.toml`: where the bay screen is served, the names it answers as and its controls' token.

use serde::{Deserialize, Serialize};

/// `[web]`: where the bay screen is served, the names it answers as and the token its controls need.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WebConfig {
    /// `HOST:PORT`; loopback by default (a bay's screen is usually on the same machine).
    #[serde(default = "default_web_listen")]
    pub listen: String,
    /// Host names the screen answers as besides the listen address and `localhost` (`--web-host` adds more):
    /// the name a screen in the bay opens it by (`bay1.local`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hosts: Vec<String>,
    /// The token the page's controls need (16-256 letters, digits or `-_.~`); needed on loopback too when set.
    /// Beyond loopback without one, a token is made at each start and printed. Never recorded.
    #[serde(default, skip_serializing)]
    pub token: Option<String>,
}

impl WebConfig {
    /// The names and token, for the screen.
    pub fn access(&self) -> crate::daemon::bridges::web::WebAccess {
        crate::daemon::bridges::web::WebAccess { hosts: self.hosts.clone(), token: self.token.clone() }
    }
}

fn default_web_listen() -> String {
    "127.0.0.1:8080".into()
}
