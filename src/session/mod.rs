//! A fitting session as coaches read it: the shots of one or more recordings grouped by club, player or tag,
//! TrackMan's metrics per group (count, mean, SD, median), the gaps between clubs, and the mishits flagged (and,
//! when the user says so, excluded). Pure: the shots come in as [`LaunchPrediction`]s, read by the caller.

pub mod foresight;
pub mod labelled_header;
pub mod labelled_rows;
pub mod measured;
pub mod metrics;
pub mod shot_table;
pub mod sigma;
pub mod stats;
pub mod trackman;
pub mod uneekor;

// TrackMan's readers and writer under their paths before they became `trackman/`'s files.
pub use trackman::{csv as trackman_csv, report as trackman_report, rows as trackman_rows};

pub use metrics::{Metric, Quantity, Units, METRICS};
pub use stats::{summarize, Gap, GroupBy, GroupSummary, MetricStats, Outlier, SessionSummary, ShotId};

use crate::wire::LaunchPrediction;

/// The club a shot is grouped under: its label, else the club file's name.
pub fn club_of(p: &LaunchPrediction) -> &str {
    p.labels.club.as_deref().unwrap_or(&p.club)
}
