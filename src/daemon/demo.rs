//! `impactd demo`: the daemon and a simulated rig in one process on loopback zenoh (peer mode, no multicast),
//! printing each prediction beside the rig's truth and recording everything to an MCAP file.

use std::collections::HashMap;
use std::future::Future;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use crate::daemon::bus::{free_loopback_port, ZenohArgs};
use crate::daemon::sim::{run_sim, SimOptions};
use crate::daemon::{DaemonConfig, DaemonError, RunOptions, RunSummary};
use crate::wire::{LaunchPrediction, TruthMessage};

/// What the demo does.
#[derive(Debug, Clone)]
pub struct DemoOptions {
    pub config: DaemonConfig,
    pub sim: SimOptions,
    pub record: Option<PathBuf>,
    /// Replace an existing recording (otherwise it stops the demo).
    pub overwrite: bool,
    pub json: bool,
    /// Serve the Foxglove live view on this `HOST:PORT`.
    pub foxglove: Option<String>,
    /// Serve the bay screen on this `HOST:PORT` (the demo then runs until `shutdown`, for the page).
    pub web: Option<String>,
}

/// One readable line for a prediction, with the truth when known.
pub fn describe(l: &LaunchPrediction, truth: Option<&TruthMessage>, units: crate::session::Units) -> String {
    let m = &l.launch.launch;
    let metric = units == crate::session::Units::Metric;
    let (speed, unit, length) = if metric { (crate::units::MPS_PER_MPH, "m/s", "m ") } else { (1.0, "mph", "yd") };
    let carry = l
        .flight
        .as_ref()
        .map(|f| {
            let (carry, side) = if metric { (f.carry_m, f.offline_m) } else { (f.carry_yd, f.offline_yd) };
            format!("  carry {carry:>3.0} {length} {side:>+4.0}")
        })
        .unwrap_or_default();
    let mut s = format!(
        "{} shot {:>2}  {:<6} {:>6.1} {unit}  launch {:>5.1}°  dir {:>5.1}°  back {:>5.0} rpm  side {:>5.0} rpm{carry}  club {:>5.1} {unit}  {:>4.0} us",
        l.rig, l.shot, l.club, m.ball_speed_mph * speed, m.launch_angle_deg, m.launch_direction_deg, m.backspin_rpm, m.sidespin_rpm,
        l.delivery.club_speed_mph * speed, l.latency_us
    );
    if !l.launch.warnings.is_empty() {
        let names: Vec<&str> = l.launch.warnings.iter().map(|w| w.as_str()).collect();
        s.push_str(&format!("  WARNING {}", names.join(", ")));
    }
    if let Some(t) = truth {
        let tm = &t.launch.launch;
        s.push_str(&format!(
            "   truth {:>6.1} {unit} {:>5.1}° {:>5.1}° {:>5.0} {:>5.0}",
            tm.ball_speed_mph * speed,
            tm.launch_angle_deg,
            tm.launch_direction_deg,
            tm.backspin_rpm,
            tm.sidespin_rpm
        ));
    }
    s
}

/// Runs the demo until the rig's shots are all predicted or `shutdown` completes.
pub async fn demo(options: DemoOptions, shutdown: impl Future<Output = ()>) -> Result<RunSummary, DaemonError> {
    options.sim.check()?;
    let setups = options.config.setups()?;
    let port = free_loopback_port()?;
    let endpoint = format!("tcp/127.0.0.1:{port}");
    let daemon_session = ZenohArgs::loopback(vec![endpoint.clone()], vec![]).open().await?;
    let rig_session = ZenohArgs::loopback(vec![], vec![endpoint]).open().await?;

    let truths: Arc<Mutex<HashMap<(String, u64), TruthMessage>>> = Default::default();
    let predicted = Arc::new(tokio::sync::Notify::new());
    let count = Arc::new(std::sync::atomic::AtomicU64::new(0));
    let truths_cb = truths.clone();
    let _truth_sub = rig_session
        .declare_subscriber(crate::wire::keys::TRUTH_ALL)
        .callback(move |s| {
            if let Ok(t) = serde_json::from_slice::<TruthMessage>(&s.payload().to_bytes()) {
                if let Ok(mut m) = truths_cb.lock() {
                    m.insert((t.rig.clone(), t.shot), t);
                }
            }
        })
        .await
        .map_err(DaemonError::zenoh)?;
    let (json, notify, count_cb, truths_cb) = (options.json, predicted.clone(), count.clone(), truths.clone());
    let units = options.config.units;
    let _launch_sub = rig_session
        .declare_subscriber(crate::wire::keys::LAUNCH_ALL)
        .callback(move |s| {
            let bytes = s.payload().to_bytes();
            if json {
                println!("{}", String::from_utf8_lossy(&bytes));
            } else if let Ok(l) = serde_json::from_slice::<LaunchPrediction>(&bytes) {
                // The truth is published just after the impact frame passes; give it a moment.
                std::thread::sleep(std::time::Duration::from_millis(5));
                let truth = truths_cb.lock().ok().and_then(|m| m.get(&(l.rig.clone(), l.shot)).cloned());
                println!("{}", describe(&l, truth.as_ref(), units));
            }
            count_cb.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            notify.notify_one();
        })
        .await
        .map_err(DaemonError::zenoh)?;

    let (stop_daemon, daemon_stopped) = tokio::sync::oneshot::channel::<()>();
    let config = options.config.clone();
    let record = options.record.clone();
    let overwrite = options.overwrite;
    let foxglove = options.foxglove.clone();
    let web = options.web.clone();
    let keep_serving = web.is_some();
    let mut daemon = tokio::spawn(async move {
        let shutdown = async {
            let _ = daemon_stopped.await;
        };
        let options = RunOptions { record, overwrite, foxglove, web, ..Default::default() };
        let r = crate::daemon::run(config, setups, &daemon_session, options, shutdown).await;
        let _ = daemon_session.close().await;
        r
    });

    let expected = options.sim.shots * options.sim.rigs.len() as u64;
    let sim_options = options.sim.clone();
    let (stop_sim_tx, stop_sim_rx) = tokio::sync::oneshot::channel::<()>();
    // Said when the rig fails (a shot its club cannot swing): no prediction is coming, the demo ends at once.
    let (sim_failed_tx, mut sim_failed) = tokio::sync::oneshot::channel::<()>();
    let rig_session_c = rig_session.clone();
    let sim = tokio::spawn(async move {
        let r = run_sim(&rig_session_c, sim_options, async {
            let _ = stop_sim_rx.await;
        })
        .await;
        if r.is_err() {
            let _ = sim_failed_tx.send(());
        }
        r
    });
    let all_predicted = async {
        while count.load(std::sync::atomic::Ordering::Relaxed) < expected {
            predicted.notified().await;
        }
    };
    tokio::pin!(shutdown);
    let mut stopped = false;
    // The daemon ends on its own only when it cannot start (a recording that exists, a port in use): say so at once.
    let mut ended = None;
    let mut rig_failed = false;
    tokio::select! {
        _ = all_predicted => {}
        _ = &mut shutdown => { eprintln!("stopping"); stopped = true; }
        r = &mut daemon => { ended = Some(r); }
        Ok(()) = &mut sim_failed => { rig_failed = true; }
        _ = async {
            // The rig finished but a shot went unpredicted: give the daemon a moment, then stop.
            let _ = tokio::time::sleep(std::time::Duration::from_secs_f64(options.sim.interval_s * (options.sim.shots as f64 + 2.0) + 5.0)).await;
        } => { eprintln!("not every shot was predicted; stopping"); }
    }
    // With a bay screen the page stays up after the shots until the demo is stopped.
    if keep_serving && !stopped && ended.is_none() && !rig_failed {
        shutdown.await;
    }
    let _ = stop_sim_tx.send(());
    if ended.is_some() {
        // The rig may still be waiting for the daemon's subscriber.
        sim.abort();
    }
    let rig = sim.await;
    let _ = stop_daemon.send(());
    let summary = match ended {
        Some(r) => r,
        None => daemon.await,
    }
    .map_err(DaemonError::Task)??;
    let _ = rig_session.close().await;
    // The rig's own failure fails the demo too (a rig aborted above, after the daemon's end, is no failure).
    if let Ok(Err(e)) = rig {
        return Err(e);
    }
    Ok(summary)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::{ClubSpec, FaceOutline};

    /// A rig that cannot swing its club fails the demo with the rig's error, as soon as it fails (the demo went
    /// on to its timeout and then ended as if it had succeeded, with no shot).
    #[tokio::test(flavor = "multi_thread")]
    async fn a_rig_that_cannot_swing_fails_the_demo() {
        let mut club = ClubSpec::driver();
        club.face_outline = FaceOutline { vertices_mm: vec![[10.0, 10.0], [20.0, 10.0], [20.0, 20.0]] };
        let options = DemoOptions {
            config: DaemonConfig::default(),
            sim: SimOptions { club, shots: 1, wait_for_subscriber_s: 0.0, ..SimOptions::default() },
            record: None,
            overwrite: false,
            json: true,
            foxglove: None,
            web: None,
        };
        let r = demo(options, std::future::pending()).await;
        assert!(matches!(r, Err(DaemonError::SimSwing { shot: 1, .. })), "{r:?}");
    }
}
