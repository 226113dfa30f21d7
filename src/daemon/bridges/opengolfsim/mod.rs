//! OpenGolfSim's developer API as a simulator target: `[rig.simulator] opengolfsim = "HOST:3111"`.
//!
//! The client is the Open Connect one (`open_connect::client`: queue, no ghost or duplicate shots, stale shots
//! dropped, reconnects, every message both ways recorded on `golf/<rig>/simulator`) speaking this protocol
//! ([`codec`]): `device` `ready` on each connection and `busy` when the daemon stops, one `shot` per swing in
//! the configured unit, and the simulator's `result` counted as the shot's acknowledgement. The API has no
//! heartbeat.

pub mod codec;

use std::time::Duration;

use codec::{encode, DeviceStatus, Incoming, Outgoing, Shot, Unit};

use crate::daemon::bridges::open_connect::client::{Answer, Protocol, SimulatorClient, SimulatorOptions};
use crate::daemon::bridges::open_connect::{OpenConnectError, SimulatorConfig};
use crate::daemon::recording::writer::RecorderHandle;
use crate::wire::LaunchPrediction;

/// OpenGolfSim's developer API.
pub struct OpenGolfSim {
    pub unit: Unit,
}

impl Protocol for OpenGolfSim {
    fn name(&self) -> &'static str {
        "opengolfsim"
    }
    fn greeting(&self) -> Option<Vec<u8>> {
        encode(&Outgoing::Device { status: DeviceStatus::Ready }).ok()
    }
    fn farewell(&self) -> Option<Vec<u8>> {
        encode(&Outgoing::Device { status: DeviceStatus::Busy }).ok()
    }
    fn heartbeat(&self) -> Option<Vec<u8>> {
        None
    }
    fn shot(&self, launch: &LaunchPrediction, _number: u64) -> Result<Vec<u8>, OpenConnectError> {
        encode(&Outgoing::Shot { unit: self.unit, shot: Shot::from_prediction(launch, self.unit)? })
    }
    fn answer(&self, object: &[u8]) -> Result<Answer, String> {
        let m = serde_json::from_slice::<Incoming>(object).map_err(|e| e.to_string())?;
        let summary = match (&m.kind[..], m.data.as_ref().map(|d| &d.result)) {
            ("result", Some(r)) => format!(
                "result: carry {:.1} m, total {:.1} m, lateral {:.1} m",
                r.carry.unwrap_or(f64::NAN),
                r.total.unwrap_or(f64::NAN),
                r.lateral.unwrap_or(f64::NAN)
            ),
            (kind, _) => kind.to_string(),
        };
        Ok(Answer { answers_shot: m.kind == "result", success: true, summary, player: None })
    }
}

/// The OpenGolfSim client `config` asks for, started on the current tokio runtime, stamping on `clock`.
pub fn spawn(
    rig: &str,
    config: &SimulatorConfig,
    recorder: &RecorderHandle,
    clock: &crate::daemon::clock::Clock,
) -> Option<SimulatorClient> {
    let unit = match config.opengolfsim_unit.as_deref() {
        Some("imperial") => Unit::Imperial,
        _ => Unit::Metric,
    };
    let options = SimulatorOptions {
        rig: rig.to_string(),
        address: config.opengolfsim.clone()?,
        device_id: config.device_id.clone(),
        max_shot_age: Duration::from_secs_f64(config.max_shot_age_s),
        heartbeat: Duration::from_secs_f64(config.heartbeat_s),
        backoff_min: Duration::from_millis(100),
        backoff_max: Duration::from_secs(5),
    };
    Some(SimulatorClient::spawn_with(options, OpenGolfSim { unit }, recorder.clone(), clock.clone()))
}
