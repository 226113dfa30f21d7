//! `[rig.input]`: which server a rig's samples come from, in one form for every protocol, and the marker set
//! file a route may fit.
//!
//! ```toml
//! [rig.input]
//! protocol = "vicon"         # natnet | qtm | vicon (daemon::inputs::PROTOCOLS)
//! server = "192.168.1.20"    # HOST or HOST:PORT (the protocol's port when none)
//! subject = "driver"         # the tracked body: `body` for NatNet and QTM, `subject` for Vicon
//! ball_body = "ball"         # optional: a body whose origin is the ball's centre (mocap/<rig>/ball)
//! markers = "club.toml"      # optional: fit this marker set to the labelled markers instead of a body
//! # the protocol's own keys: NatNet unicast, data_port, multicast_group; Vicon segment
//! ```
//!
//! The protocol's name as the key (`vicon = "HOST[:PORT]"`, and the older `natnet = "HOST"`, `qtm = "HOST"`)
//! reads as `protocol` and `server`; for NatNet and QTM a note says once that the form is deprecated.

use std::collections::BTreeSet;
use std::net::{SocketAddr, ToSocketAddrs};
use std::sync::Mutex;

use serde::{Deserialize, Serialize};

use super::protocol::{host_port, Protocol, Source};
use super::registry::{names, protocol};
use crate::daemon::DaemonError;

/// The keys every protocol's `[rig.input]` has (beside its body key).
const COMMON: [&str; 5] = ["protocol", "server", "ball_body", "markers", "segment"];
/// The protocols whose name-as-key form is deprecated (it predates `protocol`).
const DEPRECATED_KEYS: [&str; 2] = ["natnet", "qtm"];

/// `[rig.input]`: the rig's samples come straight from a motion-capture server.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MocapInputConfig {
    /// A name in [`super::PROTOCOLS`].
    pub protocol: String,
    /// `HOST` or `HOST:PORT`.
    pub server: String,
    /// The tracked body (`body`, or Vicon's `subject`).
    pub body: String,
    /// A body (a marker or a rigid body) whose origin is the ball's centre: its frames are the rig's tracked ball,
    /// which sets each shot's ball position (`mocap/<rig>/ball`).
    pub ball_body: Option<String>,
    /// A marker set file (`[markers]`, as `impactd import` takes): the club's pose is that set fitted to the
    /// server's labelled markers each frame, so the capture software needs no rigid body. QTM: the labels are
    /// its 3D labels and `body` names the route in the status; NatNet: `body` names Motive's asset (its marker
    /// set) and the labels are the marker names within it; Vicon: the subject's markers.
    pub markers: Option<String>,
    /// A part of the body (Vicon: the subject's segment; its root when `None`).
    pub segment: Option<String>,
    /// The protocol's own keys.
    pub options: toml::Table,
    /// What was wrong with the table as read (field, reason): [`MocapInputConfig::source`] says it, so the
    /// configuration's error names the field.
    invalid: Option<(String, String)>,
}

static DEPRECATION_NOTED: Mutex<BTreeSet<&'static str>> = Mutex::new(BTreeSet::new());

/// Logs once per process that `key = "HOST"` is the old form.
fn note_deprecated(key: &'static str, server: &str) {
    let mut noted = DEPRECATION_NOTED.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if noted.insert(key) {
        tracing::warn!(
            "[rig.input] {key} = \"{server}\" is deprecated: write protocol = \"{key}\" and server = \"{server}\""
        );
    }
}

impl MocapInputConfig {
    /// The protocol, or why the name is not one.
    pub fn protocol(&self) -> Result<&'static dyn Protocol, (String, String)> {
        protocol(&self.protocol).ok_or_else(|| {
            ("protocol".into(), format!("`{}` is not a protocol impactd reads ({})", self.protocol, names()))
        })
    }

    /// Reads a `[rig.input]` table; what is wrong is kept for [`MocapInputConfig::source`] to say.
    pub fn from_table(t: toml::Table) -> Self {
        let raw = t.clone();
        Self::read(t).unwrap_or_else(|invalid| MocapInputConfig {
            options: raw,
            invalid: Some(invalid),
            ..Self::default()
        })
    }

    fn read(mut t: toml::Table) -> Result<Self, (String, String)> {
        let text = |t: &mut toml::Table, key: &str| -> Result<Option<String>, (String, String)> {
            match t.remove(key) {
                None => Ok(None),
                Some(toml::Value::String(s)) => Ok(Some(s)),
                Some(v) => Err((key.to_string(), format!("must be a string, not {}", v.type_str()))),
            }
        };
        let e = |field: &str, reason: String| Err((field.to_string(), reason));
        let named: Vec<&'static dyn Protocol> =
            super::PROTOCOLS.iter().copied().filter(|p| t.contains_key(p.name())).collect();
        let (protocol, server) = match (text(&mut t, "protocol")?, named.as_slice()) {
            (Some(p), []) => {
                let Some(server) = text(&mut t, "server")? else {
                    return e("server", format!("must name the {p} server (HOST or HOST:PORT)"));
                };
                (p, server)
            }
            (None, [p]) => {
                if t.contains_key("server") {
                    return e(p.name(), "and `server` both name the server: keep `server`".into());
                }
                let server = text(&mut t, p.name())?.unwrap_or_default();
                if let Some(key) = DEPRECATED_KEYS.iter().find(|k| **k == p.name()) {
                    note_deprecated(key, &server);
                }
                (p.name().to_string(), server)
            }
            (Some(_), [p, ..]) => return e("protocol", format!("and `{}` exclude each other", p.name())),
            (None, [a, b, ..]) => return e(a.name(), format!("and `{}` exclude each other", b.name())),
            (None, []) => return e("protocol", format!("must name the server's protocol ({})", names())),
        };
        let key = super::registry::protocol(&protocol).map_or("body", |p| p.body_key());
        let Some(body) = text(&mut t, key)? else { return e(key, "must name the tracked body".into()) };
        Ok(MocapInputConfig {
            protocol,
            server,
            body,
            ball_body: text(&mut t, "ball_body")?,
            markers: text(&mut t, "markers")?,
            segment: text(&mut t, "segment")?,
            options: t,
            invalid: None,
        })
    }

    /// The table it reads from, in the `protocol` form (as written, when it was not valid).
    pub fn to_table(&self) -> toml::Table {
        let mut t = self.options.clone();
        if self.invalid.is_some() {
            return t;
        }
        let key = protocol(&self.protocol).map_or("body", |p| p.body_key());
        let mut put = |k: &str, v: &Option<String>| {
            if let Some(v) = v {
                t.insert(k.to_string(), toml::Value::String(v.clone()));
            }
        };
        put("protocol", &Some(self.protocol.clone()));
        put("server", &Some(self.server.clone()));
        put(key, &Some(self.body.clone()));
        put("ball_body", &self.ball_body);
        put("markers", &self.markers);
        put("segment", &self.segment);
        t
    }

    /// The server, or the field that is wrong and why.
    pub fn source(&self) -> Result<Source, (String, String)> {
        self.source_in(super::PROTOCOLS)
    }

    /// [`MocapInputConfig::source`] with the protocols of `list` (entries like [`super::PROTOCOLS`]).
    pub fn source_in(&self, list: &[&'static dyn Protocol]) -> Result<Source, (String, String)> {
        if let Some(invalid) = &self.invalid {
            return Err(invalid.clone());
        }
        let p = super::protocol::protocol_in(list, &self.protocol).ok_or_else(|| {
            ("protocol".to_string(), format!("`{}` is not a protocol impactd reads ({})", self.protocol, names()))
        })?;
        let key = p.body_key();
        if self.body.trim().is_empty() {
            return Err((key.into(), "must name the tracked body".into()));
        }
        if let Some(b) = &self.ball_body {
            if b.trim().is_empty() || *b == self.body {
                return Err(("ball_body".into(), format!("must name a body other than the club's {key}")));
            }
        }
        if self.segment.is_some() && !p.segments() {
            return Err(("segment".into(), format!("is Vicon's (a subject's segment); {} has none", p.name())));
        }
        if let Some(k) = self.options.keys().find(|k| COMMON.contains(&k.as_str())) {
            return Err((k.clone(), "is given twice".into()));
        }
        let (host, port) = host_port(&self.server).map_err(|e| ("server".to_string(), e))?;
        p.source(host, port, &self.options)
    }
}

impl Serialize for MocapInputConfig {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.to_table().serialize(s)
    }
}

impl<'de> Deserialize<'de> for MocapInputConfig {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Ok(MocapInputConfig::from_table(toml::Table::deserialize(d)?))
    }
}

/// A marker set file as a live fitter (3 mm rejection, as `impactd import`'s default), or why it cannot be read.
pub fn marker_fitter(path: &str) -> Result<crate::kinematics::MarkerFitter, MarkerFileError> {
    let text =
        std::fs::read_to_string(path).map_err(|source| MarkerFileError::Read { path: path.to_string(), source })?;
    let set = crate::kinematics::MarkerSet::from_toml(&text)
        .map_err(|source| MarkerFileError::Parse { path: path.to_string(), source })?;
    Ok(crate::kinematics::MarkerFitter::new(set).with_reject_m(3e-3))
}

/// A marker set file (`input.markers`, `bridge --markers`) that cannot be read or holds no marker set.
#[derive(Debug, thiserror::Error)]
pub enum MarkerFileError {
    #[error("reading {path}: {source}")]
    Read {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: {source}")]
    Parse {
        path: String,
        #[source]
        source: crate::kinematics::MarkerSetError,
    },
}

/// The server's first IPv4 address.
pub fn resolve(host: &str, port: u16) -> Result<SocketAddr, DaemonError> {
    let io = |source| DaemonError::Io { what: format!("resolving {host}"), source };
    (host, port)
        .to_socket_addrs()
        .map_err(io)?
        .find(SocketAddr::is_ipv4)
        .ok_or_else(|| io(std::io::Error::other("no IPv4 address")))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input(text: &str) -> MocapInputConfig {
        MocapInputConfig::from_table(toml::from_str(text).unwrap())
    }

    /// `protocol` and `server` name every protocol's server; the protocol's name as the key reads the same;
    /// each protocol checks its own keys, and Vicon's body is its `subject`.
    #[test]
    fn the_protocol_form_and_the_name_as_key_read_the_same() {
        let vicon = input("protocol = \"vicon\"\nserver = \"10.0.0.5\"\nsubject = \"club\"\nsegment = \"head\"");
        assert_eq!(vicon, input("vicon = \"10.0.0.5\"\nsubject = \"club\"\nsegment = \"head\""));
        assert_eq!(vicon.source().unwrap(), Source::new("vicon", "10.0.0.5", 801));
        assert_eq!(input("vicon = \"h:8010\"\nsubject = \"c\"").source().unwrap().port, 8010);
        let old = input("natnet = \"h\"\nbody = \"c\"\nunicast = true\ndata_port = 0");
        assert_eq!(old, input("protocol = \"natnet\"\nserver = \"h\"\nbody = \"c\"\nunicast = true\ndata_port = 0"));
        assert_eq!(old.source().unwrap(), Source::new("natnet", "h", 1510).with("data_port", 0).with("unicast", true));
        let qtm = input("qtm = \"h\"\nbody = \"c\"\nport = 22224");
        assert_eq!(qtm.source().unwrap(), Source::new("qtm", "h", 22224));
        let err = |text: &str| input(text).source().unwrap_err().0;
        assert_eq!(err("vicon = \"h\"\nbody = \"c\""), "subject");
        assert_eq!(err("qtm = \"h\"\nbody = \"c\"\nsegment = \"s\""), "segment");
        assert_eq!(err("protocol = \"optitrack\"\nserver = \"h\"\nbody = \"c\""), "protocol");
        assert_eq!(err("vicon = \"h\"\nsubject = \"c\"\nunicast = true"), "unicast");
        assert_eq!(err("protocol = \"vicon\"\nsubject = \"c\""), "server");
        assert_eq!(err("vicon = \"h:port\"\nsubject = \"c\""), "server");
        // Written back in the protocol form.
        let t = old.to_table();
        assert_eq!((t["protocol"].as_str(), t["server"].as_str()), (Some("natnet"), Some("h")));
    }

    /// A marker file that is not there, or is no marker set, keeps its cause: the IO error or the marker set's
    /// error, reachable from the daemon's error through `source()`, and says it once.
    #[test]
    fn a_bad_marker_file_keeps_its_cause() {
        use std::error::Error;
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("none.toml");
        let e = marker_fitter(missing.to_str().unwrap()).unwrap_err();
        assert!(matches!(&e, MarkerFileError::Read { source, .. } if source.kind() == std::io::ErrorKind::NotFound));
        let bad = dir.path().join("bad.toml");
        std::fs::write(&bad, "[[marker]]\nname = 3\n").unwrap();
        let e = marker_fitter(bad.to_str().unwrap()).unwrap_err();
        assert!(matches!(&e, MarkerFileError::Parse { .. }), "{e:?}");
        let text = e.to_string();
        let daemon = DaemonError::Markers { field: "rig a: input.markers".into(), source: e };
        assert_eq!(daemon.to_string(), format!("config field `rig a: input.markers` {text}"));
        let cause = daemon.source().and_then(|s| s.source()).unwrap();
        assert!(cause.downcast_ref::<crate::kinematics::MarkerSetError>().is_some(), "{cause:?}");
    }
}
