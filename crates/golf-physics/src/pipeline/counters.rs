//! A rig's counters by kind: why samples were refused (a status's `rejected`), why impacts have no prediction
//! (`failed`) and which sanity flags predictions raised (`flagged`). Each kind is an enum with its wire name,
//! counted in a [`Tally`], so a count cannot be filed under a misspelt key; a status carries the wire names
//! ([`Tally::to_wire`]), so its JSON is unchanged.

use std::collections::BTreeMap;

use crate::impact::LaunchWarning;
use crate::kinematics::{EstimateError, Reject};

/// A kind of count and its key in a rig's status.
pub trait CounterKind: Copy + Ord {
    /// The kind's key in the status JSON (`malformed`, `too_few_frames`, `smash_out_of_range`).
    fn wire_name(self) -> &'static str;
}

/// Counts by kind (only kinds counted at least once are held).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Tally<K: Ord>(BTreeMap<K, u64>);

impl<K: Ord> Default for Tally<K> {
    fn default() -> Self {
        Tally(BTreeMap::new())
    }
}

impl<K: CounterKind> Tally<K> {
    /// Counts one of `kind`.
    pub fn add(&mut self, kind: K) {
        *self.0.entry(kind).or_default() += 1;
    }

    /// Counts `n` of `kind` (nothing when `n` is 0: a tally holds only kinds counted).
    pub fn add_n(&mut self, kind: K, n: u64) {
        if n > 0 {
            *self.0.entry(kind).or_default() += n;
        }
    }

    /// How many of `kind` were counted.
    pub fn get(&self, kind: K) -> u64 {
        self.0.get(&kind).copied().unwrap_or(0)
    }

    /// Whether nothing was counted.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The count over every kind.
    pub fn total(&self) -> u64 {
        self.0.values().sum()
    }

    /// Each kind counted, with its count.
    pub fn iter(&self) -> impl Iterator<Item = (K, u64)> + '_ {
        self.0.iter().map(|(k, n)| (*k, *n))
    }

    /// The counts under their wire names, as a status carries them (kinds that share a wire name summed).
    pub fn to_wire(&self) -> BTreeMap<String, u64> {
        let mut out = BTreeMap::new();
        for (k, n) in &self.0 {
            *out.entry(k.wire_name().to_string()).or_default() += *n;
        }
        out
    }
}

/// Counters of one rig's pipeline.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Counts {
    /// Samples fed (good or bad).
    pub samples: u64,
    /// Samples the track accepted.
    pub accepted: u64,
    /// Samples flagged occluded.
    pub occluded: u64,
    /// Frames missing from the frame numbering.
    pub dropped: u64,
    /// Time bases or frame counts the track moved onto (publisher restarts, wrapped counters).
    pub resets: u64,
    /// Samples refused, by reason.
    pub rejected: Tally<Rejection>,
    /// Impacts found.
    pub shots: u64,
    /// Launches predicted (one per model per impact).
    pub predictions: u64,
    /// Impacts without a prediction, by reason.
    pub failed: Tally<Failure>,
    /// Predictions that raised each sanity flag (`impact::sanity`).
    pub flagged: Tally<crate::impact::LaunchWarning>,
    /// Swings that found no impact (`Event::Missed`).
    pub missed_swings: u64,
}

/// Why a sample was not used (a status's `rejected`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Rejection {
    /// A payload over the wire's limit.
    Oversized,
    /// A payload of another version of the sample's schema.
    WrongVersion,
    /// A payload that is not a sample's JSON.
    Malformed,
    /// A sample naming another rig than its key.
    RigMismatch,
    /// The track refused it: a number not finite.
    NonFinite,
    /// The track refused it: the orientation is not a unit quaternion.
    NotUnitQuaternion,
    /// The track refused it: too far from the lab's origin.
    OutOfRange,
    /// The track refused it: a frame already had.
    Duplicate,
    /// The track refused it: back in time.
    Backwards,
    /// The track refused it: an implausible jump.
    Jump,
    /// The track held it as an outlier.
    Outlier,
    /// The track is waiting for a new time base to be confirmed.
    Resyncing,
    /// A body no `[rig.clubs]` entry names.
    UnknownBody,
    /// Another club's body while the current one is in view.
    OtherBody,
    /// The rig's queue was full (counted before the pipeline).
    QueueFull,
}

impl CounterKind for Rejection {
    fn wire_name(self) -> &'static str {
        match self {
            Rejection::Oversized => "oversized",
            Rejection::WrongVersion => "wrong_version",
            Rejection::Malformed => "malformed",
            Rejection::RigMismatch => "rig_mismatch",
            Rejection::NonFinite => "non_finite",
            Rejection::NotUnitQuaternion => "not_unit_quaternion",
            Rejection::OutOfRange => "out_of_range",
            Rejection::Duplicate => "duplicate",
            Rejection::Backwards => "backwards",
            Rejection::Jump => "jump",
            Rejection::Outlier => "outlier",
            Rejection::Resyncing => "resyncing",
            Rejection::UnknownBody => "unknown_body",
            Rejection::OtherBody => "other_body",
            Rejection::QueueFull => "queue_full",
        }
    }
}

impl From<&Reject> for Rejection {
    fn from(r: &Reject) -> Self {
        match r {
            Reject::NonFinite { .. } => Rejection::NonFinite,
            Reject::NotUnitQuaternion { .. } => Rejection::NotUnitQuaternion,
            Reject::OutOfRange { .. } => Rejection::OutOfRange,
            Reject::Duplicate { .. } => Rejection::Duplicate,
            Reject::Backwards { .. } => Rejection::Backwards,
            Reject::Jump { .. } => Rejection::Jump,
            Reject::Outlier { .. } => Rejection::Outlier,
            Reject::Resyncing { .. } => Rejection::Resyncing,
        }
    }
}

/// Why an impact has no prediction (a status's `failed`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Failure {
    /// Too few good frames before the impact.
    TooFewFrames,
    /// The newest frame before the impact is too old.
    StaleFrames,
    /// The fit of the frames before the impact is singular.
    SingularFit,
    /// The fitted motion does not reach the ball.
    NoContact,
    /// The model refused the impact.
    ModelRefused,
    /// The head moved faster than any golfer swings (`kinematics::guards`).
    HeadSpeedBeyondBound,
}

impl CounterKind for Failure {
    fn wire_name(self) -> &'static str {
        match self {
            Failure::TooFewFrames => "too_few_frames",
            Failure::StaleFrames => "stale_frames",
            Failure::SingularFit => "singular_fit",
            Failure::NoContact => "no_contact",
            Failure::ModelRefused => "model_refused",
            Failure::HeadSpeedBeyondBound => "head_speed_beyond_bound",
        }
    }
}

impl From<&EstimateError> for Failure {
    fn from(e: &EstimateError) -> Self {
        match e {
            EstimateError::TooFewFrames { .. } => Failure::TooFewFrames,
            EstimateError::StaleFrames { .. } => Failure::StaleFrames,
            EstimateError::SingularFit => Failure::SingularFit,
            EstimateError::NoContact { .. } => Failure::NoContact,
        }
    }
}

impl CounterKind for LaunchWarning {
    fn wire_name(self) -> &'static str {
        self.as_str()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_kind_keeps_the_key_it_had() {
        // The track's and the estimator's own keys name the same counts.
        let rejects = [
            Reject::NonFinite { field: "x" },
            Reject::NotUnitQuaternion { norm: 2.0 },
            Reject::OutOfRange { distance_m: 100.0 },
            Reject::Duplicate { frame: 1, t_ns: 1 },
            Reject::Backwards { frame: 1, back_ns: 1 },
            Reject::Jump { speed_mps: 1e3 },
            Reject::Outlier { frame: 1, ahead_ns: 1 },
            Reject::Resyncing { frame: 1 },
        ];
        for r in &rejects {
            assert_eq!(Rejection::from(r).wire_name(), r.key());
        }
        let estimates = [
            EstimateError::TooFewFrames { have: 1, need: 2 },
            EstimateError::StaleFrames { gap_ms: 1.0, limit_ms: 0.5 },
            EstimateError::SingularFit,
            EstimateError::NoContact { gap_mm: 1.0, h_mm: 0.0, v_mm: 0.0, past: false },
        ];
        for e in &estimates {
            assert_eq!(Failure::from(e).wire_name(), e.key());
        }
        let mut t = Tally::default();
        t.add(Rejection::QueueFull);
        t.add(Rejection::Malformed);
        t.add(Rejection::Malformed);
        let wire: Vec<(String, u64)> = t.to_wire().into_iter().collect();
        assert_eq!(wire, [("malformed".to_string(), 2), ("queue_full".to_string(), 1)]);
        assert_eq!((t.get(Rejection::Malformed), t.get(Rejection::Jump), t.total()), (2, 0, 3));
    }
}
