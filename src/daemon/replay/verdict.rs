//! Whether a replay reproduced its recording: identity is claimed only over a file read whole.

use super::ReplayInput;

/// How a replay's predictions compare with the recorded ones.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Verdict {
    /// Nothing was recorded to compare with.
    NothingRecorded,
    /// The whole file was read and every recorded prediction was produced again, byte for byte.
    Identical { predictions: usize },
    /// The whole file was read and the predictions differ.
    Differ { same: usize, recorded: usize, produced: usize },
    /// Part of the file could not be read: no claim of identity is made.
    Damaged { same: usize, recorded: usize, produced: usize },
}

impl Verdict {
    /// Compares `produced` with the recording's predictions, claiming identity only over a file read whole.
    pub fn of(input: &ReplayInput, produced: &[Vec<u8>]) -> Verdict {
        let recorded = input.recorded_launches.len();
        let same = produced.iter().zip(&input.recorded_launches).filter(|(a, b)| a == b).count();
        if !input.damage.is_empty() {
            return Verdict::Damaged { same, recorded, produced: produced.len() };
        }
        if recorded == 0 {
            return Verdict::NothingRecorded;
        }
        if same == recorded && produced.len() == recorded {
            Verdict::Identical { predictions: recorded }
        } else {
            Verdict::Differ { same, recorded, produced: produced.len() }
        }
    }

    /// Replays that reproduce the recording (or had nothing to compare) succeed.
    pub fn success(&self) -> bool {
        matches!(self, Verdict::NothingRecorded | Verdict::Identical { .. })
    }
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Verdict::NothingRecorded => write!(f, "no recorded predictions to compare with"),
            Verdict::Identical { predictions } => {
                write!(f, "{predictions} of {predictions} recorded predictions reproduced byte for byte")
            }
            Verdict::Differ { same, recorded, produced } => {
                write!(f, "{same} of {recorded} recorded predictions reproduced ({produced} produced)")
            }
            Verdict::Damaged { same, recorded, produced } => write!(
                f,
                "the recording is damaged: {produced} predictions over its readable part, {same} equal to the \
                 {recorded} recorded predictions that could be read; not a reproduction"
            ),
        }
    }
}
