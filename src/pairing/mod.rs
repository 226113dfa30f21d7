//! Pairing a launch monitor's measured shots with the rig's predictions of the same swings (seed section 3.1.3:
//! the clubhead's motion and the launch monitor's measurement of each shot, side by side).
//!
//! A measurement at `t_ns` belongs to the predicted shot whose impact `t_impact_ns` precedes it by a delay within
//! the window (default 0.05-5 s: a monitor reports after the ball has left, within seconds); of several such
//! shots, the latest. Each shot pairs with at most one measurement and each measurement with one shot; every
//! model's prediction of that shot is compared with it (a rig running two models gives two comparisons). Either
//! side may arrive first: a measurement waits for its prediction, a prediction for its measurement, until the
//! window has passed, and is then counted unpaired. Both times must be on one clock (the synthetic rig and the
//! Open Connect listener both stamp the host's wall clock).
//!
//! Pure: no clocks, no IO. The caller passes the current time to [`Pairer::expire`].

use crate::pipeline::{CounterKind, Tally};
use std::collections::{BTreeMap, VecDeque};

use crate::math::Real;
use crate::wire::{ComparisonMessage, ComparisonStatus, LaunchFields, LaunchPrediction, MeasuredLaunch};

mod dataset_line;
pub mod fields;

pub use dataset_line::DatasetLine;

use fields::{fields_of_launch, fields_of_measured, launch_fields};

/// The delays (s) from impact to measurement that pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairWindow {
    pub min_s: Real,
    pub max_s: Real,
}

impl Default for PairWindow {
    fn default() -> Self {
        PairWindow { min_s: 0.05, max_s: 5.0 }
    }
}

impl PairWindow {
    fn contains(&self, t_impact_ns: u64, measured_t_ns: u64) -> bool {
        let delay_s = (measured_t_ns as i128 - t_impact_ns as i128) as Real * 1e-9;
        delay_s >= self.min_s && delay_s <= self.max_s
    }
    fn max_ns(&self) -> u64 {
        (self.max_s * 1e9) as u64
    }
}

/// Why a measurement cannot be paired at all.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeasuredError {
    #[error("the measurement has neither backspin and sidespin nor total spin and spin axis")]
    NoSpin,
    #[error("field `{0}` is not finite")]
    NotFinite(&'static str),
    #[error("the measurement names rig `{got}`, not `{expected}`")]
    WrongRig { got: String, expected: String },
}

impl MeasuredError {
    /// The kind counted in the status's `rejected`.
    pub fn kind(&self) -> MeasuredRejection {
        match self {
            MeasuredError::NoSpin => MeasuredRejection::NoSpin,
            MeasuredError::NotFinite(_) => MeasuredRejection::NotFinite,
            MeasuredError::WrongRig { .. } => MeasuredRejection::WrongRig,
        }
    }
}

/// Why a measurement was not paired (a comparison status's `rejected`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum MeasuredRejection {
    /// A payload over the wire's limit.
    Oversized,
    /// A payload that is not a measured launch's JSON.
    NotMeasuredLaunch,
    /// [`MeasuredError::NoSpin`].
    NoSpin,
    /// [`MeasuredError::NotFinite`].
    NotFinite,
    /// [`MeasuredError::WrongRig`].
    WrongRig,
}

impl CounterKind for MeasuredRejection {
    fn wire_name(self) -> &'static str {
        match self {
            MeasuredRejection::Oversized => "oversized",
            MeasuredRejection::NotMeasuredLaunch => "not_measured_launch",
            MeasuredRejection::NoSpin => "no_spin",
            MeasuredRejection::NotFinite => "not_finite",
            MeasuredRejection::WrongRig => "wrong_rig",
        }
    }
}

#[derive(Debug, Clone)]
struct PendingShot {
    shot: u64,
    t_impact_ns: u64,
    predictions: Vec<LaunchPrediction>,
    /// The measurement it was paired with (kept until the window passes, for a late second model).
    measured: Option<MeasuredLaunch>,
}

#[derive(Debug, Clone, Default)]
struct RunningMae {
    n: u64,
    sum_abs: [Real; 5],
}

/// The pairing state of one rig.
#[derive(Debug, Clone)]
pub struct Pairer {
    rig: String,
    window: PairWindow,
    shots: VecDeque<PendingShot>,
    measured: VecDeque<MeasuredLaunch>,
    status: ComparisonStatus,
    /// Measurements not paired, by reason (the status's `rejected`).
    rejected: Tally<MeasuredRejection>,
    mae: BTreeMap<String, RunningMae>,
}

impl Pairer {
    pub fn new(rig: &str, window: PairWindow) -> Self {
        Pairer {
            rig: rig.to_string(),
            window,
            shots: VecDeque::new(),
            measured: VecDeque::new(),
            status: ComparisonStatus::default(),
            rejected: Tally::default(),
            mae: BTreeMap::new(),
        }
    }

    /// A prediction: compared at once if its shot is already paired or a waiting measurement fits.
    pub fn on_prediction(&mut self, prediction: &LaunchPrediction) -> Vec<ComparisonMessage> {
        if let Some(i) = self.shots.iter().position(|s| s.shot == prediction.shot) {
            self.shots[i].predictions.push(prediction.clone());
            return match self.shots[i].measured.clone() {
                Some(m) => vec![self.compare(prediction, &m)],
                None => vec![],
            };
        }
        let mut pending = PendingShot {
            shot: prediction.shot,
            t_impact_ns: prediction.t_impact_ns,
            predictions: vec![prediction.clone()],
            measured: None,
        };
        // The earliest waiting measurement in this shot's window.
        let found = self
            .measured
            .iter()
            .enumerate()
            .filter(|(_, m)| self.window.contains(prediction.t_impact_ns, m.t_ns))
            .min_by_key(|(_, m)| m.t_ns)
            .map(|(i, _)| i);
        let mut out = vec![];
        if let Some(m) = found.and_then(|i| self.measured.remove(i)) {
            self.status.paired += 1;
            out.push(self.compare(prediction, &m));
            pending.measured = Some(m);
        }
        self.shots.push_back(pending);
        out
    }

    /// A measurement: compared with every model's prediction of the latest unpaired shot in its window, or kept
    /// waiting for one.
    pub fn on_measured(&mut self, measured: &MeasuredLaunch) -> Result<Vec<ComparisonMessage>, MeasuredError> {
        self.status.measured += 1;
        if let Err(e) = self.check(measured) {
            self.rejected.add(e.kind());
            return Err(e);
        }
        let found = self
            .shots
            .iter()
            .enumerate()
            .filter(|(_, s)| s.measured.is_none() && self.window.contains(s.t_impact_ns, measured.t_ns))
            .max_by_key(|(_, s)| s.t_impact_ns)
            .map(|(i, _)| i);
        let Some(i) = found else {
            self.measured.push_back(measured.clone());
            return Ok(vec![]);
        };
        self.status.paired += 1;
        self.shots[i].measured = Some(measured.clone());
        let predictions = self.shots[i].predictions.clone();
        Ok(predictions.iter().map(|p| self.compare(p, measured)).collect())
    }

    /// A measurement that could not even be read (counted under `kind`).
    pub fn reject(&mut self, kind: MeasuredRejection) {
        self.status.measured += 1;
        self.rejected.add(kind);
    }

    fn check(&self, m: &MeasuredLaunch) -> Result<(), MeasuredError> {
        if m.rig != self.rig {
            return Err(MeasuredError::WrongRig { got: m.rig.clone(), expected: self.rig.clone() });
        }
        let fields = fields_of_measured(m).ok_or(MeasuredError::NoSpin)?;
        if let Some(i) = fields.iter().position(|v| !v.is_finite()) {
            return Err(MeasuredError::NotFinite(fields::FIELDS[i].0));
        }
        Ok(())
    }

    /// Forgets what the window has passed, counting the unpaired.
    pub fn expire(&mut self, now_ns: u64) {
        let max = self.window.max_ns();
        while let Some(s) = self.shots.front() {
            if now_ns.saturating_sub(s.t_impact_ns) <= max {
                break;
            }
            if s.measured.is_none() {
                self.status.unpaired_predictions += 1;
            }
            self.shots.pop_front();
        }
        let before = self.measured.len();
        self.measured.retain(|m| now_ns.saturating_sub(m.t_ns) <= max);
        self.status.unpaired_measured += (before - self.measured.len()) as u64;
    }

    /// Counts and running mean absolute errors.
    pub fn status(&self) -> ComparisonStatus {
        let mut s = self.status.clone();
        s.rejected = self.rejected.to_wire();
        s.mae = self
            .mae
            .iter()
            .map(|(model, m)| (model.clone(), launch_fields(&m.sum_abs.map(|v| v / m.n.max(1) as Real))))
            .collect();
        s
    }

    fn compare(&mut self, prediction: &LaunchPrediction, measured: &MeasuredLaunch) -> ComparisonMessage {
        let l = &prediction.launch.launch;
        let predicted = LaunchFields {
            ball_speed_mph: l.ball_speed_mph,
            launch_angle_deg: l.launch_angle_deg,
            launch_direction_deg: l.launch_direction_deg,
            backspin_rpm: l.backspin_rpm,
            sidespin_rpm: l.sidespin_rpm,
            carry_yd: prediction.flight.as_ref().map(|f| f.carry_yd),
        };
        let m = fields_of_measured(measured).unwrap_or([Real::NAN; 5]);
        let mut measured_fields = launch_fields(&m);
        measured_fields.carry_yd = measured.carry_yd;
        let p = fields_of_launch(&predicted);
        let mut residual = launch_fields(&std::array::from_fn(|i| p[i] - m[i]));
        residual.carry_yd = predicted.carry_yd.zip(measured.carry_yd).map(|(a, b)| a - b);
        let acc = self.mae.entry(prediction.model.clone()).or_default();
        acc.n += 1;
        for (s, r) in acc.sum_abs.iter_mut().zip(fields_of_launch(&residual)) {
            *s += r.abs();
        }
        ComparisonMessage {
            rig: self.rig.clone(),
            shot: prediction.shot,
            model: prediction.model.clone(),
            t_impact_ns: prediction.t_impact_ns,
            measured_t_ns: measured.t_ns,
            device: measured.device.clone(),
            predicted,
            measured: measured_fields,
            residual,
            delay_s: (measured.t_ns as i128 - prediction.t_impact_ns as i128) as Real * 1e-9,
            latency_us: 0.0,
        }
    }
}
