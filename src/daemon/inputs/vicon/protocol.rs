//! Vicon DataStream's entry in [`crate::daemon::inputs::PROTOCOLS`]: `server = "HOST[:PORT]"` (port 801), the
//! tracked body called `subject`, a `segment` per route (the subject's root when none), and its client.

use std::thread::JoinHandle;

use clap::ArgMatches;
use serde::Deserialize;

use super::super::protocol::{typed, FieldError, Protocol, Source, Start};
use crate::daemon::DaemonError;
use crate::mocap::vicon::DEFAULT_PORT;

pub struct Vicon;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Options {}

impl Protocol for Vicon {
    fn name(&self) -> &'static str {
        "vicon"
    }

    fn summary(&self) -> &'static str {
        "Vicon Nexus, Tracker or Shogun (DataStream, ServerPush): each mapped subject's segment on \
         mocap/<RIG>/clubhead."
    }

    fn default_port(&self) -> u16 {
        DEFAULT_PORT
    }

    fn body_key(&self) -> &'static str {
        "subject"
    }

    fn body_help(&self) -> &'static str {
        "A subject and the rig it feeds, NAME=RIG (repeatable; several rigs share the connection): its root \
         segment, or --segment's."
    }

    fn segments(&self) -> bool {
        true
    }

    fn source(&self, host: &str, port: Option<u16>, options: &toml::Table) -> Result<Source, FieldError> {
        let _: Options = typed(options)?;
        Ok(Source::new("vicon", host, port.unwrap_or(DEFAULT_PORT)))
    }

    fn bridge_source(&self, host: &str, port: Option<u16>, _: &ArgMatches) -> Result<Source, String> {
        Ok(Source::new("vicon", host, port.unwrap_or(DEFAULT_PORT)))
    }

    fn start(&self, s: Start) -> Result<Vec<JoinHandle<()>>, DaemonError> {
        super::start(s.server, s.routes, s.shared, s.stop)
    }
}
