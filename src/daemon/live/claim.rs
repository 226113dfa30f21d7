//! A daemon's presence on its rigs, and one daemon per rig. A daemon serving a rig declares its liveliness token
//! `golf/<rig>/impactd/alive` and its configuration's queryable `golf/<rig>/impactd/config`. Before it serves a rig, a daemon looks for another daemon's liveliness token on
//! `golf/<rig>/impactd/alive`; when there is one it asks it, on `golf/<rig>/impactd/serve`, who it is and, with
//! `--take-over`, to hand the rig over. Without `--take-over` the newcomer refuses to start (two daemons on one
//! rig predict every shot twice) and the daemon serving the rig says it refused one; with it, the daemon serving
//! the rig stops (its recording closed, its ports released, its token dropped last) and the newcomer starts once
//! its token is gone. A daemon also declares `golf/<rig>/impactd/daemon/<zenoh id>` and watches the others', so
//! two that started at the same moment (or whose networks joined later) say so.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};
use zenoh::Wait;

use crate::daemon::config::RigConfig;
use crate::daemon::peer_log::PeerLog;
use crate::daemon::DaemonError;
use crate::wire::keys;

/// How long a daemon waits for answers about a rig.
const ASK_FOR: Duration = Duration::from_secs(2);
/// How long a daemon taking a rig over waits for the one serving it to let go.
pub const TAKE_OVER_WAIT: Duration = Duration::from_secs(15);

/// A daemon asking to serve a rig (the payload of a query on `golf/<rig>/impactd/serve`).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ServeRequest {
    /// The asking daemon.
    pub from: DaemonId,
    /// Whether it takes the rig over (`--take-over`).
    pub take_over: bool,
}

/// The answer of the daemon serving the rig.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ServeAnswer {
    pub from: DaemonId,
    /// It stops, so that the asker can serve the rig.
    pub handing_over: bool,
}

/// Who a daemon is, in words people can act on.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct DaemonId {
    pub zid: String,
    pub pid: u32,
    pub version: String,
}

impl DaemonId {
    pub fn of(session: &zenoh::Session) -> DaemonId {
        DaemonId { zid: session.zid().to_string(), pid: std::process::id(), version: env!("CARGO_PKG_VERSION").into() }
    }
}

impl std::fmt::Display for DaemonId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "impactd {} (pid {}, zenoh id {})", self.version, self.pid, self.zid)
    }
}

/// Liveliness tokens of daemons serving `rig`, this session's own excepted (it has declared none yet).
async fn served_by_others(session: &zenoh::Session, rig: &str) -> Result<usize, DaemonError> {
    let replies = session.liveliness().get(keys::alive(rig)).timeout(ASK_FOR).await.map_err(DaemonError::zenoh)?;
    let mut n = 0;
    while let Ok(reply) = replies.recv_async().await {
        n += usize::from(reply.result().is_ok());
    }
    Ok(n)
}

/// Makes sure no other daemon serves any of `rigs` before this one does: refuses when one does, unless
/// `take_over`, when it asks that one to stop and waits until it has.
pub async fn claim(session: &zenoh::Session, rigs: &[String], take_over: bool) -> Result<(), DaemonError> {
    let me = DaemonId::of(session);
    for rig in rigs {
        if served_by_others(session, rig).await? == 0 {
            continue;
        }
        let request = serde_json::to_vec(&ServeRequest { from: me.clone(), take_over }).unwrap_or_default();
        let replies =
            session.get(keys::serve(rig)).payload(request).timeout(ASK_FOR).await.map_err(DaemonError::zenoh)?;
        let mut answers = Vec::new();
        while let Ok(reply) = replies.recv_async().await {
            let answer =
                reply.result().ok().and_then(|s| serde_json::from_slice::<ServeAnswer>(&s.payload().to_bytes()).ok());
            answers.extend(answer);
        }
        let by = if answers.is_empty() {
            "a daemon that does not say who it is (an older impactd?)".to_string()
        } else {
            answers.iter().map(|a| a.from.to_string()).collect::<Vec<_>>().join(", ")
        };
        if !take_over {
            return Err(DaemonError::RigServed { rig: rig.clone(), by });
        }
        if answers.is_empty() || !answers.iter().all(|a| a.handing_over) {
            return Err(DaemonError::TakeOver {
                rig: rig.clone(),
                by,
                reason: "it cannot be asked to hand the rig over",
            });
        }
        tracing::warn!("rig {rig}: taking it over from {by} (--take-over); waiting for it to stop");
        let deadline = Instant::now() + TAKE_OVER_WAIT;
        while served_by_others(session, rig).await? > 0 {
            if Instant::now() > deadline {
                return Err(DaemonError::TakeOver { rig: rig.clone(), by, reason: "it did not stop in time" });
            }
            tokio::time::sleep(Duration::from_millis(100)).await;
        }
        tracing::warn!("rig {rig}: taken over from {by}");
    }
    Ok(())
}

/// What a daemon serving rigs declares so that others find it: per rig, its liveliness tokens, the queryables
/// of its configuration and answering newcomers, and the watch on other daemons' tokens.
pub struct Claims {
    _queryables: Vec<zenoh::query::Queryable<()>>,
    _tokens: Vec<zenoh::liveliness::LivelinessToken>,
    _watches: Vec<zenoh::pubsub::Subscriber<()>>,
}

/// Declares the daemon on `rigs` (its tokens, its configuration's queryable) and answers newcomers asking to
/// serve them: one taking a rig over gets `handing_over` and `taken` is called once (the daemon then stops); one
/// that is not is told who serves the rig, and both say so in the log.
pub async fn declare(
    session: &zenoh::Session,
    rigs: &[RigConfig],
    taken: impl Fn(String) + Send + Sync + 'static,
) -> Result<Claims, DaemonError> {
    let me = DaemonId::of(session);
    let taken = Arc::new(taken);
    let stopping = Arc::new(AtomicBool::new(false));
    // What peers make this daemon say (asking for its rigs, declaring themselves on them): one line a second per
    // kind, each cut, whatever a peer sends.
    let log = Arc::new(Mutex::new(PeerLog::new()));
    let mut claims = Claims { _queryables: Vec::new(), _tokens: Vec::new(), _watches: Vec::new() };
    for rig_config in rigs {
        let rig = &rig_config.name;
        claims._tokens.push(session.liveliness().declare_token(keys::alive(rig)).await.map_err(DaemonError::zenoh)?);
        let (config_json, config_key) = (serde_json::to_vec(rig_config).unwrap_or_default(), keys::config(rig));
        let config = session
            .declare_queryable(config_key.clone())
            .callback(move |query| {
                if let Err(e) = query.reply(config_key.clone(), config_json.clone()).encoding("application/json").wait()
                {
                    tracing::warn!("config query: {e}");
                }
            })
            .await
            .map_err(DaemonError::zenoh)?;
        claims._queryables.push(config);
        let (me_q, rig_q, taken, stopping, log_q) =
            (me.clone(), rig.clone(), taken.clone(), stopping.clone(), log.clone());
        let key = keys::serve(rig);
        let queryable = session
            .declare_queryable(key.clone())
            .callback(move |query| {
                let Some(request) =
                    query.payload().and_then(|p| serde_json::from_slice::<ServeRequest>(&p.to_bytes()).ok())
                else {
                    return;
                };
                if request.from.zid == me_q.zid {
                    return;
                }
                let handing_over = request.take_over;
                let answer = serde_json::to_vec(&ServeAnswer { from: me_q.clone(), handing_over }).unwrap_or_default();
                if let Err(e) = query.reply(key.clone(), answer).wait() {
                    peer(&log_q)
                        .warn("serve_answer_failed", || format!("rig {rig_q}: answering {}: {e}", request.from));
                }
                if !handing_over {
                    peer(&log_q).warn("serve_refused", || {
                        format!(
                            "rig {rig_q}: {} asked to serve it too and was refused: this daemon serves it (`impactd \
                             run --take-over` hands it over)",
                            request.from
                        )
                    });
                } else if !stopping.swap(true, Ordering::Relaxed) {
                    tracing::warn!("rig {rig_q}: {} takes it over (--take-over); this daemon stops", request.from);
                    taken(format!("rig {rig_q} taken over by {}", request.from));
                }
            })
            .await
            .map_err(DaemonError::zenoh)?;
        claims._queryables.push(queryable);
        let own = keys::daemon_token(rig, &me.zid);
        claims._tokens.push(session.liveliness().declare_token(own.clone()).await.map_err(DaemonError::zenoh)?);
        let (rig_w, log_w) = (rig.clone(), log.clone());
        let watch = session
            .liveliness()
            .declare_subscriber(keys::daemon_token(rig, "*"))
            .callback(move |sample| {
                if sample.kind() == zenoh::sample::SampleKind::Put && sample.key_expr().as_str() != own {
                    let other = sample.key_expr().as_str().rsplit('/').next().unwrap_or_default().to_string();
                    peer(&log_w).warn("another_daemon", || {
                        format!(
                            "rig {rig_w}: another daemon (zenoh id {other}) serves it too: every shot is predicted \
                             twice until one of them stops"
                        )
                    });
                }
            })
            .await
            .map_err(DaemonError::zenoh)?;
        claims._watches.push(watch);
    }
    Ok(claims)
}

/// The claims' peer log, whatever a panicking holder left.
fn peer(log: &Mutex<PeerLog>) -> MutexGuard<'_, PeerLog> {
    log.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}
