//! What a TrackMan shot read for comparison carries beside its delivery and measured launch ([`RowLabels`]), and
//! the rows left out by reason ([`SkippedRows`]); shared by the CSV export's reader (`csv`) and the
//! report JSON's (`report`).

/// What a row of an export says about its shot beyond the delivery and the launch: TrackMan's club name, whether
/// its spin was measured (`Spin Rate Type` `Measured`, or no such column) rather than estimated by TrackMan's
/// launch model, whether its spin axis was (a measured spin with an axis), and whether it has an impact location
/// (`Impact Height` filled).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RowLabels {
    pub club: Option<String>,
    pub spin_measured: bool,
    pub axis_measured: bool,
    pub impact_located: bool,
}

/// Rows (or strokes) read and left out: without club speed or ball speed; with a club speed but not all of the
/// club data a delivery needs (attack angle, club path, face angle, dynamic loft), which are never read as 0.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct SkippedRows {
    pub without_club_or_ball: usize,
    pub incomplete_club_data: usize,
}

impl SkippedRows {
    pub fn total(&self) -> usize {
        self.without_club_or_ball + self.incomplete_club_data
    }

    /// One line saying what was skipped ("" when nothing was).
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        if self.without_club_or_ball > 0 {
            parts.push(format!("{} without club or ball speed", self.without_club_or_ball));
        }
        if self.incomplete_club_data > 0 {
            parts.push(format!(
                "{} with club speed but no attack angle, club path, face angle or dynamic loft",
                self.incomplete_club_data
            ));
        }
        if parts.is_empty() {
            String::new()
        } else {
            format!("rows skipped: {}", parts.join("; "))
        }
    }
}
