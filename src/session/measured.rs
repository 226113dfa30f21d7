//! The one place a launch monitor's file is recognised and read as measured shots for `compare` and `fit`:
//! TrackMan's report JSON and CSV export, Foresight's FSX CSV, Uneekor's shot CSV. [`format_of`] tells them
//! apart from the start of the file; [`read_labelled`] reads a whole file of that format.

use crate::pairing::DatasetLine;

use super::trackman_rows::{RowLabels, SkippedRows};
use super::{foresight, labelled_rows, trackman_csv, trackman_report, uneekor};

/// A launch monitor's export impactd reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MonitorFormat {
    TrackmanReport,
    TrackmanCsv,
    ForesightCsv,
    UneekorCsv,
}

impl MonitorFormat {
    pub fn describe(&self) -> &'static str {
        match self {
            MonitorFormat::TrackmanReport => "TrackMan report JSON",
            MonitorFormat::TrackmanCsv => "TrackMan CSV export",
            MonitorFormat::ForesightCsv => "Foresight FSX CSV export",
            MonitorFormat::UneekorCsv => "Uneekor shot CSV",
        }
    }
}

/// Why a launch monitor's file cannot be read: the reader's own error.
#[derive(Debug, thiserror::Error)]
pub enum MeasuredFileError {
    #[error(transparent)]
    TrackmanReport(#[from] trackman_report::TrackmanReportError),
    #[error(transparent)]
    TrackmanCsv(#[from] trackman_csv::TrackmanCsvError),
    /// Foresight's or Uneekor's labelled-column CSV.
    #[error(transparent)]
    LabelledCsv(#[from] labelled_rows::LabelledCsvError),
}

/// The format of a file whose text starts with `head`, or `None` (JSONL deliveries, or no monitor's). Foresight's
/// header is tested before TrackMan's CSV, whose test (`Club Speed` and `Ball Speed` in the first line) it passes.
pub fn format_of(head: &str) -> Option<MonitorFormat> {
    if trackman_report::is_trackman_report(head) {
        Some(MonitorFormat::TrackmanReport)
    } else if foresight::is_foresight_csv(head) {
        Some(MonitorFormat::ForesightCsv)
    } else if uneekor::is_uneekor_csv(head) {
        Some(MonitorFormat::UneekorCsv)
    } else if trackman_csv::is_trackman_csv(head) {
        Some(MonitorFormat::TrackmanCsv)
    } else {
        None
    }
}

/// Every measured shot of `text` (a file of `format`) with its labels, and the rows skipped by reason.
pub fn read_labelled(
    format: MonitorFormat,
    text: &str,
) -> Result<(Vec<(DatasetLine, RowLabels)>, SkippedRows), MeasuredFileError> {
    Ok(match format {
        MonitorFormat::TrackmanReport => trackman_report::read_labelled(text)?,
        MonitorFormat::TrackmanCsv => trackman_csv::read_labelled(text)?,
        MonitorFormat::ForesightCsv => foresight::read_labelled(text)?,
        MonitorFormat::UneekorCsv => uneekor::read_labelled(text)?,
    })
}
