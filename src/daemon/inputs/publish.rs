//! `impactd bridge natnet|qtm|vicon`: a motion-capture client publishing each mapped body's frames as clubhead
//! samples on `mocap/<rig>/clubhead` (the JSON any rig publishes) and its health on `mocap/<rig>/input` once
//! a second. [`run_bridge`] runs until `shutdown` completes, so tests start and stop it in-process.

use std::future::Future;
use std::time::Duration;

use zenoh::Wait;

use super::{InputHandle, Route, Source};
use crate::daemon::DaemonError;
use crate::kinematics::MarkerFitter;
use crate::wire::{keys, MessageType, MocapInputStatus};

/// Runs a bridge from `source` for `routes` (`(body, rig)`) on `session` until `shutdown`; returns each
/// route's final status.
pub async fn run_bridge(
    session: &zenoh::Session,
    source: Source,
    routes: Vec<(String, String)>,
    shutdown: impl Future<Output = ()>,
) -> Result<Vec<MocapInputStatus>, DaemonError> {
    run_bridge_with_balls(session, source, routes, Vec::new(), shutdown).await
}

/// [`run_bridge`], with `balls` (`(body, rig)`): bodies whose origin is a ball's centre, published as the rig's
/// tracked ball on `mocap/<rig>/ball`. Statuses are returned for the clubs' routes, then the balls'.
pub async fn run_bridge_with_balls(
    session: &zenoh::Session,
    source: Source,
    routes: Vec<(String, String)>,
    balls: Vec<(String, String)>,
    shutdown: impl Future<Output = ()>,
) -> Result<Vec<MocapInputStatus>, DaemonError> {
    let fitters = vec![None; routes.len()];
    run_bridge_fitted(session, source, routes, fitters, balls, shutdown).await
}

/// [`run_bridge_with_balls`], with a marker set per club route (`Some`: that set fitted to the server's
/// labelled markers each frame, as `[rig.input] markers` does, so the body needs no rigid body defined).
pub async fn run_bridge_fitted(
    session: &zenoh::Session,
    source: Source,
    routes: Vec<(String, String)>,
    fitters: Vec<Option<MarkerFitter>>,
    balls: Vec<(String, String)>,
    shutdown: impl Future<Output = ()>,
) -> Result<Vec<MocapInputStatus>, DaemonError> {
    let mut fitters = fitters.into_iter();
    let routes = routes
        .into_iter()
        .map(|(body, rig)| (Route { body, segment: None, fitter: fitters.next().flatten() }, rig))
        .collect();
    let balls = balls.into_iter().map(|(body, rig)| (Route { body, ..Route::default() }, rig)).collect();
    run_bridge_routes(session, source, routes, balls, shutdown).await
}

/// The bridge for any protocol: club `routes` and `balls`, each a [`Route`] (a body, a segment of it, a marker
/// set) and its rig.
pub async fn run_bridge_routes(
    session: &zenoh::Session,
    source: Source,
    routes: Vec<(Route, String)>,
    balls: Vec<(Route, String)>,
    shutdown: impl Future<Output = ()>,
) -> Result<Vec<MocapInputStatus>, DaemonError> {
    let mut samples = Vec::new();
    let mut statuses = Vec::new();
    let clubs = routes.len();
    let routes: Vec<(Route, String)> = routes.into_iter().chain(balls).collect();
    for (i, (_, rig)) in routes.iter().enumerate() {
        if !keys::valid_rig_name(rig) {
            return Err(DaemonError::BadRigName(rig.clone()));
        }
        let (key, message) = if i < clubs {
            (keys::clubhead(rig), MessageType::ClubheadSample)
        } else {
            (keys::ball(rig), MessageType::BallSample)
        };
        samples.push(session.declare_publisher(key).encoding(message.encoding()).await.map_err(DaemonError::zenoh)?);
        if i >= clubs {
            continue;
        }
        statuses.push(
            session
                .declare_publisher(keys::mocap_input(rig))
                .encoding(MessageType::MocapInputStatus.encoding())
                .await
                .map_err(DaemonError::zenoh)?,
        );
    }
    let rigs: Vec<String> = routes.iter().map(|r| r.1.clone()).collect();
    let deliver = Box::new(move |i: usize, sample: &crate::mocap::track::BodySample, _received| {
        let (Some(publisher), Some(rig)) = (samples.get(i), rigs.get(i)) else { return };
        let payload = if i < clubs {
            serde_json::to_vec(&sample.to_msg(rig))
        } else {
            serde_json::to_vec(&sample.to_ball_msg(rig))
        };
        if let Err(e) = publisher.put(payload.unwrap_or_default()).wait() {
            tracing::warn!("rig {rig}: publishing a sample: {e}");
        }
    });
    let named: Vec<(&str, &str)> = routes.iter().map(|(r, rig)| (r.body.as_str(), rig.as_str())).collect();
    tracing::info!("bridging {} at {} for {:?}", source.protocol(), source.address(), named);
    let handle = InputHandle::start_routes(source, routes, deliver)?;
    tokio::pin!(shutdown);
    let mut tick = tokio::time::interval(Duration::from_secs(1));
    loop {
        tokio::select! {
            _ = &mut shutdown => break,
            _ = tick.tick() => {
                for (i, publisher) in statuses.iter().enumerate() {
                    let status = handle.status(i);
                    if let Err(e) = publisher.put(serde_json::to_vec(&status).unwrap_or_default()).await {
                        tracing::warn!("rig {}: publishing the input status: {e}", status.rig);
                    }
                }
            }
        }
    }
    let out = (0..handle.routes()).map(|i| handle.status(i)).collect();
    tokio::task::spawn_blocking(move || handle.stop()).await.map_err(DaemonError::Task)?;
    Ok(out)
}
