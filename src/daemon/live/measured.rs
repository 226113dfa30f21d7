//! A rig worker's measured launches: taken from `lm/<rig>/launch` into the rig's queue, recorded, paired with the
//! rig's predictions, and each comparison published on `golf/<rig>/comparison` at once.

use super::{Stamp, Worker};

use crate::pairing::MeasuredRejection;
use crate::pipeline::CounterKind;
use crate::wire::{self, ComparisonMessage, MeasuredLaunch};

impl Worker {
    /// A measured launch: recorded, paired, and each comparison published at once.
    pub(super) fn on_measured(&mut self, at: Stamp, payload: Vec<u8>) {
        let parsed = if payload.len() > wire::MAX_PAYLOAD_BYTES {
            Err((MeasuredRejection::Oversized, format!("{} bytes is over {}", payload.len(), wire::MAX_PAYLOAD_BYTES)))
        } else {
            serde_json::from_slice::<MeasuredLaunch>(&payload)
                .map_err(|e| (MeasuredRejection::NotMeasuredLaunch, e.to_string()))
        };
        let measured = match parsed {
            Ok(m) => m,
            Err((key, reason)) => {
                self.pairer.reject(key);
                self.warn(key.wire_name(), || format!("rejected measured launch: {reason}"));
                let keep = &payload[..payload.len().min(wire::MAX_PAYLOAD_BYTES)];
                let rejected = wire::RejectedInput {
                    reason,
                    bytes: payload.len(),
                    payload: String::from_utf8_lossy(keep).into_owned(),
                };
                self.sinks.measured_rejected(at.log_time_ns, &rejected);
                return;
            }
        };
        self.sinks.measured(at.log_time_ns, measured.t_ns, payload);
        match self.pairer.on_measured(&measured) {
            Ok(comparisons) => {
                for c in comparisons {
                    self.publish_comparison(c, at.received);
                }
            }
            Err(e) => self.warn(e.kind().wire_name(), || format!("measured launch not paired: {e}")),
        }
    }

    /// Publishes and records a comparison; its latency is measured from `received`.
    pub(super) fn publish_comparison(&mut self, mut c: ComparisonMessage, received: std::time::Instant) {
        c.latency_us = self.clock.since(received).as_nanos() as f64 / 1e3;
        self.sinks.comparison(&c, self.clock.wall_ns());
        tracing::info!("{}", super::shot_log::comparison(&self.rig, &c, self.units));
    }
}
