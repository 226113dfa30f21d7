//! `impactd bridge natnet|qtm`: Motive's or QTM's rigid bodies (or marker sets fitted to their labelled
//! markers) as clubhead samples on zenoh.

use std::net::Ipv4Addr;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::{Args, Subcommand};
use impactd::daemon::bridges::mocap::input::marker_fitter;
use impactd::daemon::bridges::mocap::input::{NATNET_COMMAND_PORT, NATNET_DATA_PORT, NATNET_MULTICAST_GROUP, QTM_PORT};
use impactd::daemon::bridges::mocap::{run_bridge_fitted, Source};
use impactd::kinematics::MarkerFitter;

use super::args::ZenohArgs;
use super::run::{runtime, shutdown_signal};

#[derive(Debug, Subcommand)]
pub enum BridgeCommand {
    /// OptiTrack Motive (NatNet 3.x/4.x): each mapped rigid body's frames on mocap/<RIG>/clubhead.
    Natnet(NatNetArgs),
    /// Qualisys QTM (real-time protocol 1.2x, 6D): each mapped body's frames on mocap/<RIG>/clubhead.
    Qtm(QtmArgs),
}

#[derive(Debug, Args)]
pub struct NatNetArgs {
    /// Motive's address (host name or IPv4).
    #[arg(long)]
    pub server: String,
    /// A rigid body and the rig it feeds, NAME=RIG (repeatable; several rigs share the connection).
    #[arg(long = "body", value_name = "NAME=RIG", required = true)]
    pub body: Vec<String>,
    /// A body whose origin is a ball's centre and the rig whose ball it is, NAME=RIG (repeatable): published on
    /// mocap/<RIG>/ball, it sets each shot's ball position.
    #[arg(long = "ball", value_name = "NAME=RIG")]
    pub ball: Vec<String>,
    /// A body tracked as a marker set, NAME=SET.toml (repeatable; NAME one of --body's): the set fitted to the
    /// labelled markers each frame (Motive: the markers of its asset NAME; QTM: its 3D labels), so NAME needs no
    /// rigid body in the capture software.
    #[arg(long = "markers", value_name = "NAME=SET.toml")]
    pub markers: Vec<String>,
    /// Motive's command port.
    #[arg(long, default_value_t = NATNET_COMMAND_PORT)]
    pub command_port: u16,
    /// The data port the bridge binds (frames; 0: any free port, unicast only).
    #[arg(long, default_value_t = NATNET_DATA_PORT)]
    pub data_port: u16,
    /// Unicast: Motive sends frames to this bridge's address (default: multicast, Motive's default).
    #[arg(long, conflicts_with = "multicast_group")]
    pub unicast: bool,
    /// The multicast group Motive streams to.
    #[arg(long, value_name = "ADDR", default_value_t = NATNET_MULTICAST_GROUP)]
    pub multicast_group: Ipv4Addr,
    #[command(flatten)]
    pub zenoh: ZenohArgs,
}

#[derive(Debug, Args)]
pub struct QtmArgs {
    /// QTM's address (host name or IPv4).
    #[arg(long)]
    pub server: String,
    /// QTM's little-endian real-time port.
    #[arg(long, default_value_t = QTM_PORT)]
    pub port: u16,
    /// A 6DOF body and the rig it feeds, NAME=RIG (repeatable; several rigs share the connection).
    #[arg(long = "body", value_name = "NAME=RIG", required = true)]
    pub body: Vec<String>,
    /// A body whose origin is a ball's centre and the rig whose ball it is, NAME=RIG (repeatable): published on
    /// mocap/<RIG>/ball, it sets each shot's ball position.
    #[arg(long = "ball", value_name = "NAME=RIG")]
    pub ball: Vec<String>,
    /// A body tracked as a marker set, NAME=SET.toml (repeatable; NAME one of --body's): the set fitted to the
    /// labelled markers each frame (Motive: the markers of its asset NAME; QTM: its 3D labels), so NAME needs no
    /// rigid body in the capture software.
    #[arg(long = "markers", value_name = "NAME=SET.toml")]
    pub markers: Vec<String>,
    #[command(flatten)]
    pub zenoh: ZenohArgs,
}

fn routes(flag: &str, bodies: &[String]) -> Result<Vec<(String, String)>> {
    bodies
        .iter()
        .map(|b| match b.split_once('=') {
            Some((name, rig)) if !name.is_empty() && !rig.is_empty() => Ok((name.to_string(), rig.to_string())),
            _ => bail!("{flag} {b}: expected NAME=RIG (the body's name in the capture software, then the rig)"),
        })
        .collect()
}

/// Each club route's marker set from `--markers NAME=SET.toml` (None: the body's own pose).
fn fitters(markers: &[String], routes: &[(String, String)]) -> Result<Vec<Option<MarkerFitter>>> {
    let mut out = vec![None; routes.len()];
    for m in markers {
        let Some((name, path)) = m.split_once('=').filter(|(n, p)| !n.is_empty() && !p.is_empty()) else {
            bail!("--markers {m}: expected NAME=SET.toml (a --body name, then its marker set file)")
        };
        let Some(i) = routes.iter().position(|r| r.0 == name) else {
            bail!("--markers {m}: `{name}` is not one of the --body names")
        };
        out[i] = Some(marker_fitter(path).map_err(|e| anyhow::anyhow!("--markers {m}: {e}"))?);
    }
    Ok(out)
}

pub fn run(command: &BridgeCommand) -> Result<ExitCode> {
    let (source, routes, balls, markers, zenoh) = match command {
        BridgeCommand::Natnet(a) => {
            if !a.unicast && !a.multicast_group.is_multicast() {
                bail!("--multicast-group {} is not a multicast address", a.multicast_group);
            }
            if !a.unicast && a.data_port == 0 {
                bail!("--data-port 0 is for unicast: multicast frames arrive on Motive's data port");
            }
            let source = Source::NatNet {
                host: a.server.clone(),
                command_port: a.command_port,
                data_port: a.data_port,
                multicast_group: (!a.unicast).then_some(a.multicast_group),
            };
            (source, routes("--body", &a.body)?, routes("--ball", &a.ball)?, &a.markers, &a.zenoh)
        }
        BridgeCommand::Qtm(a) => {
            let source = Source::Qtm { host: a.server.clone(), port: a.port };
            (source, routes("--body", &a.body)?, routes("--ball", &a.ball)?, &a.markers, &a.zenoh)
        }
    };
    let fitters = fitters(markers, &routes)?;
    let rt = runtime()?;
    rt.block_on(async {
        let session = zenoh.open_as(impactd::daemon::bus::Role::Join).await?;
        let statuses =
            run_bridge_fitted(&session, source, routes, fitters, balls, shutdown_signal()).await.context("bridge")?;
        let _ = session.close().await;
        for s in statuses {
            eprintln!(
                "{} -> {}: {} frames, {} published, {} occluded, {} dropped, {} out of order, rejected {:?}",
                s.body, s.rig, s.frames, s.published, s.occluded, s.dropped, s.out_of_order, s.rejected
            );
        }
        Ok(ExitCode::SUCCESS)
    })
}
