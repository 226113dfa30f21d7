//! A static trial read for calibration: every marker over the frames asked for, averaged, each marker used
//! checked still over them.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use impactd::daemon::recording::c3d::static_trial::marker_frames;
use impactd::kinematics::calibrate::{static_markers, StaticMarker};
use impactd::math::Vector3;

use super::Trial;

pub struct StaticTrial {
    path: PathBuf,
    first: u64,
    asked: u64,
    limit_m: f64,
    labels: Vec<String>,
    frames: Vec<Vec<Option<Vector3>>>,
    /// The markers checked so far (for the report).
    pub checked: std::cell::RefCell<Vec<StaticMarker>>,
}

impl StaticTrial {
    pub fn load(t: &Trial) -> Result<Self> {
        Self::load_at(&t.capture, t.frame, t.frames, t.static_mm)
    }

    pub fn load_at(path: &Path, first: u64, count: u64, static_mm: f64) -> Result<Self> {
        if count == 0 {
            bail!("--frames must be at least 1");
        }
        if !(static_mm.is_finite() && static_mm > 0.0) {
            bail!("--static-mm must be a positive number of millimetres");
        }
        let (labels, frames) = marker_frames(path, first, count).with_context(|| format!("{}", path.display()))?;
        Ok(StaticTrial {
            path: path.to_path_buf(),
            first,
            asked: count,
            limit_m: static_mm * 1e-3,
            labels,
            frames,
            checked: Default::default(),
        })
    }

    fn index(&self, label: &str) -> Result<usize> {
        match self.labels.iter().position(|l| l == label.trim()) {
            Some(i) => Ok(i),
            None => bail!("{}: no marker `{label}` (it has {})", self.path.display(), self.labels.join(", ")),
        }
    }

    /// The mean positions of `labels` (lab, m), each checked still over the frames.
    pub fn means(&self, labels: &[String]) -> Result<Vec<Vector3>> {
        let indices: Vec<usize> = labels.iter().map(|l| self.index(l)).collect::<Result<_>>()?;
        let tracks: Vec<Vec<Option<Vector3>>> = indices.iter().map(|&i| self.frames[i].clone()).collect();
        let names: Vec<String> = indices.iter().map(|&i| self.labels[i].clone()).collect();
        let checked = static_markers(&names, &tracks, self.first, self.limit_m)
            .with_context(|| format!("{}", self.path.display()))?;
        let means = checked.iter().map(|m| m.mean_m).collect();
        self.checked.borrow_mut().extend(checked);
        Ok(means)
    }

    /// The markers not in `except`, each the mean over its valid frames (unchecked: they only say where things
    /// stand); markers never valid are left out.
    pub fn others(&self, except: &[String]) -> Vec<(String, Vector3)> {
        self.labels
            .iter()
            .zip(&self.frames)
            .filter(|(l, _)| !except.iter().any(|e| e.trim() == l.as_str()))
            .filter_map(|(l, track)| {
                let seen: Vec<Vector3> = track.iter().flatten().copied().collect();
                (!seen.is_empty()).then(|| (l.clone(), seen.iter().sum::<Vector3>() / seen.len() as f64))
            })
            .collect()
    }

    /// One line on what was averaged and how still it was.
    pub fn report(&self, what: &str) -> String {
        let checked = self.checked.borrow();
        let frames = self.frames.first().map_or(0, Vec::len);
        let short = if (frames as u64) < self.asked {
            format!(" (the capture ends there: {} frames were asked for)", self.asked)
        } else {
            String::new()
        };
        let line = match checked.iter().max_by(|a, b| a.moved_m.total_cmp(&b.moved_m)) {
            _ if frames == 1 => format!(
                "{what}: one frame ({}): nothing to average and no motion to check (--frames 50 averages the noise \
                 and checks the trial is still)",
                self.first
            ),
            Some(worst) => format!(
                "{what}: {frames} frames from {} averaged; the most any marker used moved from its mean: {:.2} mm \
                 (`{}`, limit {:.1} mm)",
                self.first,
                worst.moved_m * 1e3,
                worst.label,
                self.limit_m * 1e3
            ),
            None => format!("{what}: {frames} frames from {} averaged", self.first),
        };
        line + &short
    }
}
