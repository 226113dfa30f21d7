//! `[rig.input]`: motion-capture clients (NatNet, QTM, Vicon, a C3D capture) feeding the rigs' queues directly.
//! Rigs reading the same server share one client (one body each). Each sample is queued decoded, as the
//! `ClubheadSampleMsg` a bridge would publish: the worker runs it without parsing and records the JSON a bridge
//! would have sent (the same bytes either way). A rig's `ball_body` is read the same way and queued as the rig's
//! tracked ball (`mocap/<rig>/ball`).

use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::SyncSender;
use std::sync::Arc;

use super::queue::{Arrival, Incoming, Stamp};
use crate::daemon::clock::Clock;
use crate::daemon::inputs::config::marker_fitter;
use crate::daemon::inputs::{InputHandle, Route as InputRoute, Source, StatusSource};
use crate::daemon::{DaemonConfig, DaemonError};

/// A rig's queue and its count of samples the full queue refused.
pub(super) type Route = (SyncSender<Incoming>, Arc<AtomicU64>);

/// What a client's route feeds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Feed {
    /// The rig's clubhead samples (`mocap/<rig>/clubhead`).
    Club,
    /// The rig's tracked ball (`mocap/<rig>/ball`).
    Ball,
}

/// A server, its routes (each with its rig), and what each route feeds (the club's samples or the rig's ball).
type Group = (Source, Vec<(InputRoute, String)>, Vec<Feed>);

/// Where a client's route delivers: the rig, its queue, sample or ball, and the body's name when the rig's
/// bodies choose its club (`[rig.clubs]`).
type Target = (Arc<str>, Option<Route>, Feed, Option<String>);

/// Starts one client per server named by the rigs' inputs; gives each such rig its status source.
pub(super) fn start(
    config: &DaemonConfig,
    routes: &HashMap<String, Route>,
    clock: &Clock,
) -> Result<(Vec<InputHandle>, HashMap<String, StatusSource>), DaemonError> {
    let mut groups: Vec<Group> = Vec::new();
    for rig in &config.rigs {
        let Some(input) = &rig.input else { continue };
        let source = input.source().map_err(|(field, reason)| DaemonError::Config {
            field: format!("rig {}: input.{field}", rig.name),
            reason,
        })?;
        let fitter = match &input.markers {
            Some(path) => Some(marker_fitter(path).map_err(|source| DaemonError::Markers {
                field: format!("rig {}: input.markers", rig.name),
                source,
            })?),
            None => None,
        };
        let club = InputRoute { body: input.body.clone(), segment: input.segment.clone(), fitter };
        let mut routes = vec![(club, Feed::Club)];
        // With `[rig.clubs]`, every club's body too: each sample then names its body.
        let clubs = rig.clubs.keys().filter(|b| **b != input.body);
        routes.extend(clubs.map(|b| (InputRoute { body: b.clone(), ..InputRoute::default() }, Feed::Club)));
        if let Some(ball) = &input.ball_body {
            routes.push((InputRoute { body: ball.clone(), ..InputRoute::default() }, Feed::Ball));
        }
        let at = match groups.iter().position(|g| g.0 == source) {
            Some(at) => at,
            None => {
                groups.push((source, Vec::new(), Vec::new()));
                groups.len() - 1
            }
        };
        for (route, kind) in routes {
            groups[at].1.push((route, rig.name.clone()));
            groups[at].2.push(kind);
        }
    }
    let mut handles = Vec::new();
    let mut sources = HashMap::new();
    for (source, group, kinds) in groups {
        let named = |rig: &str| config.rigs.iter().any(|r| r.name == rig && !r.clubs.is_empty());
        let targets: Vec<Target> = group
            .iter()
            .zip(&kinds)
            .map(|((route, rig), kind)| {
                (Arc::from(rig.as_str()), routes.get(rig).cloned(), *kind, named(rig).then(|| route.body.clone()))
            })
            .collect();
        let clock = clock.clone();
        let deliver = Box::new(move |i: usize, sample: &crate::mocap::track::BodySample, received| {
            let Some((rig, Some((tx, dropped)), feed, body)) = targets.get(i) else { return };
            let arrival = match feed {
                Feed::Ball => Arrival::DecodedBall(sample.to_ball_msg(rig)),
                Feed::Club => {
                    let mut msg = sample.to_msg(rig);
                    msg.body = body.clone();
                    Arrival::DecodedSample(Box::new(msg))
                }
            };
            let incoming = Incoming { at: Stamp { received, log_time_ns: clock.wall_ns() }, arrival };
            if tx.try_send(incoming).is_err() {
                dropped.fetch_add(1, Ordering::Relaxed);
            }
        });
        let rigs: Vec<(String, String)> = group.iter().map(|(r, rig)| (r.body.clone(), rig.clone())).collect();
        tracing::info!("reading {} at {} for {:?}", source.protocol(), source.address(), rigs);
        let handle = InputHandle::start_routes(source, group, deliver)?;
        // A rig's status shows its first body's input (`[rig.input] body`).
        for (i, ((_, rig), kind)) in rigs.iter().zip(&kinds).enumerate() {
            if *kind == Feed::Club {
                sources.entry(rig.clone()).or_insert_with(|| handle.status_source(i));
            }
        }
        handles.push(handle);
    }
    Ok((handles, sources))
}
