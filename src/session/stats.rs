//! Per-group statistics of a session: count, mean, sample SD and median of each metric; the carry gaps between
//! clubs; mishits flagged where ball speed, smash factor, carry or side lies beyond
//! [`OUTLIER_MADS`] robust SDs (1.4826 median absolute deviations) from its group's median.

use std::collections::{BTreeMap, BTreeSet};

use serde::{Deserialize, Serialize};

use super::metrics::{Units, BALL_SPEED, CARRY, METRICS, SIDE, SMASH};
use crate::math::Real;
use crate::wire::LaunchPrediction;

/// How shots are grouped.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "snake_case")]
pub enum GroupBy {
    /// The club label, else the club file.
    #[default]
    Club,
    /// The player label (`-` for none).
    Player,
    /// Each tag (a shot with two tags is in two groups; `-` for none).
    Tag,
}

/// A shot of a recording: its rig and shot number.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct ShotId {
    pub rig: String,
    pub shot: u64,
}

impl std::fmt::Display for ShotId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.rig, self.shot)
    }
}

impl std::str::FromStr for ShotId {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (rig, shot) = s.rsplit_once(':').ok_or_else(|| format!("`{s}` is not RIG:SHOT"))?;
        let shot = shot.parse().map_err(|_| format!("`{s}`: the shot number `{shot}` is not a whole number"))?;
        if rig.is_empty() {
            return Err(format!("`{s}`: no rig before the `:`"));
        }
        Ok(ShotId { rig: rig.to_string(), shot })
    }
}

/// Count, mean, sample SD (0 below two shots) and median of one metric, in its base unit.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MetricStats {
    pub count: usize,
    pub mean: Real,
    pub sd: Real,
    pub median: Real,
}

impl MetricStats {
    /// The statistics of `values` (empty: count 0 and NaN).
    pub fn of(values: &mut [Real]) -> Self {
        let n = values.len();
        if n == 0 {
            return MetricStats { count: 0, mean: Real::NAN, sd: Real::NAN, median: Real::NAN };
        }
        let mean = values.iter().sum::<Real>() / n as Real;
        let sd = if n > 1 {
            (values.iter().map(|v| (v - mean).powi(2)).sum::<Real>() / (n - 1) as Real).sqrt()
        } else {
            0.0
        };
        MetricStats { count: n, mean, sd, median: median(values) }
    }

    /// The same statistics in another unit (`factor` of it per base unit).
    pub fn scaled(&self, factor: Real) -> Self {
        MetricStats { count: self.count, mean: self.mean * factor, sd: self.sd * factor, median: self.median * factor }
    }
}

/// The median (sorts `values`).
fn median(values: &mut [Real]) -> Real {
    values.sort_unstable_by(|a, b| a.total_cmp(b));
    let n = values.len();
    if n == 0 {
        Real::NAN
    } else if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// One group's numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct GroupSummary {
    pub group: String,
    /// Shots counted (excluded shots are not).
    pub shots: usize,
    /// Per metric, in the order of [`METRICS`].
    pub metrics: Vec<MetricStats>,
    /// The shots of the group, in recording order.
    pub members: Vec<ShotId>,
}

/// The carry gap from one club to the next shorter one (by mean carry).
#[derive(Debug, Clone, PartialEq)]
pub struct Gap {
    pub club: String,
    pub next: String,
    /// Mean carry of `club` minus that of `next` (m).
    pub gap_m: Real,
}

/// A shot flagged as a mishit, with the metric that gave it away.
#[derive(Debug, Clone, PartialEq)]
pub struct Outlier {
    pub shot: ShotId,
    pub group: String,
    /// The metric's base key (`ball_speed`, `smash_factor`, `carry`, `side`).
    pub metric: &'static str,
    /// How many robust SDs from the group's median.
    pub robust_sds: Real,
    /// Whether the shot is left out of the numbers.
    pub excluded: bool,
}

/// The whole summary.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SessionSummary {
    pub by: GroupBy,
    pub groups: Vec<GroupSummary>,
    /// With `by = club`: clubs by mean carry, longest first, each with its gap to the next.
    pub gapping: Vec<Gap>,
    pub outliers: Vec<Outlier>,
    /// Shots left out of the numbers (the user's exclusions, and the flagged ones when asked).
    pub excluded: Vec<ShotId>,
}

/// Robust SDs from the median beyond which a shot is a mishit.
pub const OUTLIER_MADS: Real = 3.5;
/// Fewest shots in a group for flagging its mishits.
pub const OUTLIER_MIN_SHOTS: usize = 8;

/// The groups a shot belongs to.
fn groups_of(p: &LaunchPrediction, by: GroupBy) -> Vec<String> {
    match by {
        GroupBy::Club => vec![super::club_of(p).to_string()],
        GroupBy::Player => vec![p.labels.player.clone().unwrap_or_else(|| "-".into())],
        GroupBy::Tag if p.labels.tags.is_empty() => vec!["-".into()],
        GroupBy::Tag => p.labels.tags.iter().cloned().collect::<BTreeSet<_>>().into_iter().collect(),
    }
}

/// Summarizes `shots` (one prediction per shot, in recording order). `excluded` are left out; with
/// `exclude_outliers` the flagged mishits are too.
pub fn summarize(
    shots: &[LaunchPrediction],
    by: GroupBy,
    excluded: &BTreeSet<ShotId>,
    exclude_outliers: bool,
) -> SessionSummary {
    let mut grouped: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    let mut order: Vec<String> = Vec::new();
    for (i, p) in shots.iter().enumerate() {
        for g in groups_of(p, by) {
            let members = grouped.entry(g.clone()).or_insert_with(|| {
                order.push(g.clone());
                Vec::new()
            });
            members.push(i);
        }
    }
    let id = |p: &LaunchPrediction| ShotId { rig: p.rig.clone(), shot: p.shot };
    let mut summary = SessionSummary { by, ..Default::default() };
    let mut left_out: BTreeSet<ShotId> = excluded.clone();
    let mut values: Vec<Real> = Vec::with_capacity(shots.len());
    for g in &order {
        let members = &grouped[g];
        let kept: Vec<usize> = members.iter().copied().filter(|&i| !excluded.contains(&id(&shots[i]))).collect();
        if kept.len() >= OUTLIER_MIN_SHOTS {
            for m in [BALL_SPEED, SMASH, CARRY, SIDE] {
                for (i, robust_sds) in flag(shots, &kept, m, &mut values) {
                    let shot = id(&shots[i]);
                    if exclude_outliers {
                        left_out.insert(shot.clone());
                    }
                    let metric = METRICS[m].base;
                    summary.outliers.push(Outlier { shot, group: g.clone(), metric, robust_sds, excluded: false });
                }
            }
        }
        let counted: Vec<usize> = kept.into_iter().filter(|&i| !left_out.contains(&id(&shots[i]))).collect();
        let metrics = METRICS
            .iter()
            .map(|metric| {
                values.clear();
                values.extend(counted.iter().filter_map(|&i| (metric.value)(&shots[i])).filter(|v| v.is_finite()));
                MetricStats::of(&mut values)
            })
            .collect();
        let members = members.iter().map(|&i| id(&shots[i])).collect();
        summary.groups.push(GroupSummary { group: g.clone(), shots: counted.len(), metrics, members });
    }
    for o in &mut summary.outliers {
        o.excluded = left_out.contains(&o.shot);
    }
    summary.excluded = left_out.into_iter().collect();
    if by == GroupBy::Club {
        summary.gapping = gapping(&summary.groups);
    }
    summary
}

/// The members of `kept` whose metric `m` lies beyond [`OUTLIER_MADS`] robust SDs of the group's median.
fn flag(shots: &[LaunchPrediction], kept: &[usize], m: usize, scratch: &mut Vec<Real>) -> Vec<(usize, Real)> {
    let value = METRICS[m].value;
    scratch.clear();
    scratch.extend(kept.iter().filter_map(|&i| value(&shots[i])).filter(|v| v.is_finite()));
    if scratch.len() < OUTLIER_MIN_SHOTS {
        return Vec::new();
    }
    let mid = median(scratch);
    for v in scratch.iter_mut() {
        *v = (*v - mid).abs();
    }
    let robust_sd = 1.4826 * median(scratch);
    if robust_sd <= 0.0 {
        return Vec::new();
    }
    kept.iter()
        .filter_map(|&i| {
            let d = (value(&shots[i])? - mid).abs() / robust_sd;
            (d > OUTLIER_MADS).then_some((i, d))
        })
        .collect()
}

/// Clubs by mean carry, longest first, with the gap to the next (clubs without a carry are left out).
fn gapping(groups: &[GroupSummary]) -> Vec<Gap> {
    let mut clubs: Vec<(&str, Real)> = groups
        .iter()
        .filter(|g| g.metrics[CARRY].count > 0)
        .map(|g| (g.group.as_str(), g.metrics[CARRY].mean))
        .collect();
    clubs.sort_by(|a, b| b.1.total_cmp(&a.1));
    clubs
        .windows(2)
        .map(|w| Gap { club: w[0].0.to_string(), next: w[1].0.to_string(), gap_m: w[0].1 - w[1].1 })
        .collect()
}

impl SessionSummary {
    /// A metric's statistics of a group in `units`, with the unit's name.
    pub fn stats_in(&self, group: &GroupSummary, m: usize, units: Units) -> (MetricStats, &'static str) {
        let (unit, factor) = METRICS[m].quantity.unit(units);
        (group.metrics[m].scaled(factor), unit)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_of_a_few_numbers() {
        let s = MetricStats::of(&mut [3.0, 1.0, 2.0, 10.0]);
        assert_eq!(s.count, 4);
        assert_eq!(s.mean, 4.0);
        assert_eq!(s.median, 2.5);
        // Sample SD: sqrt((1 + 9 + 4 + 36) / 3).
        assert!((s.sd - (50.0f64 / 3.0).sqrt()).abs() < 1e-12);
        assert_eq!(MetricStats::of(&mut [7.0]).sd, 0.0);
        assert!(MetricStats::of(&mut []).mean.is_nan());
    }

    #[test]
    fn shot_ids_parse_with_reasons() {
        assert_eq!("bay1:12".parse::<ShotId>(), Ok(ShotId { rig: "bay1".into(), shot: 12 }));
        assert!("bay1".parse::<ShotId>().unwrap_err().contains("RIG:SHOT"));
        assert!("bay1:x".parse::<ShotId>().unwrap_err().contains("whole number"));
    }
}
