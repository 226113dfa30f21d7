//! `impactd.toml`: the rigs a daemon serves. Unknown or invalid fields stop start-up with an error naming the
//! field.
//!
//! ```toml
//! status_period_s = 1.0
//!
//! [[rig]]
//! name = "bay1"                 # key expressions mocap/bay1/clubhead, golf/bay1/launch, ...
//! club = "driver"               # preset (driver, iron7) or a path to a club .toml
//! model = "adjusted"            # standard | adjusted | slip | continuous | both
//! cor = 0.83
//! estimator = "arc"             # linear2 | poly | arc | arc@60 | poly@44:5:39:3 | poly:24:4:24:3
//! ball_position_m = [0.0, 0.0, 0.0]   # world frame
//! flight = true                 # add carry, apex, landing and offline to each prediction
//! [rig.world_from_lab]          # default identity
//! rotation_xyzw = [0.0, 0.0, 0.0, 1.0]
//! translation_m = [0.0, 0.0, 0.0]
//! [rig.club_from_body]          # the tracked body's pose in the club frame; default identity
//! rotation_xyzw = [0.0, 0.0, 0.0, 1.0]
//! translation_m = [0.0, 0.0, 0.0]
//! [rig.launch_monitor]          # measured launches on lm/<rig>/launch, compared on golf/<rig>/comparison
//! pair_window_s = [0.05, 5.0]   # a measurement pairs with the shot it follows by this delay (s)
//! ```

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::DaemonError;
use crate::kinematics::{Calibration, EstimatorSpec};
use crate::math::{Isometry3, Translation3Ext, Vector3};
use crate::pipeline::{ModelChoice, RigSetup};

/// The whole file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DaemonConfig {
    #[serde(default = "default_status_period")]
    pub status_period_s: f64,
    #[serde(rename = "rig")]
    pub rigs: Vec<RigConfig>,
}

fn default_status_period() -> f64 {
    1.0
}

/// One `[[rig]]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigConfig {
    pub name: String,
    #[serde(default = "default_club")]
    pub club: String,
    #[serde(default = "default_model")]
    pub model: String,
    #[serde(default = "default_cor")]
    pub cor: f64,
    #[serde(default = "default_estimator")]
    pub estimator: String,
    #[serde(default)]
    pub ball_position_m: [f64; 3],
    #[serde(default)]
    pub world_from_lab: Option<PoseConfig>,
    #[serde(default)]
    pub club_from_body: Option<PoseConfig>,
    /// Add the ball flight (carry, apex, landing, offline; calm air at sea level) to each prediction.
    #[serde(default = "default_true")]
    pub flight: bool,
    /// `[rig.launch_monitor]`: pairing measured launches with predictions.
    #[serde(default)]
    pub launch_monitor: LaunchMonitorConfig,
}

/// `[rig.launch_monitor]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LaunchMonitorConfig {
    /// The delays (s) from a predicted impact to a measurement that pair them: `[min, max]`.
    #[serde(default = "default_pair_window")]
    pub pair_window_s: [f64; 2],
}

fn default_pair_window() -> [f64; 2] {
    let w = crate::identify::pairing::PairWindow::default();
    [w.min_s, w.max_s]
}

impl Default for LaunchMonitorConfig {
    fn default() -> Self {
        LaunchMonitorConfig { pair_window_s: default_pair_window() }
    }
}

impl LaunchMonitorConfig {
    /// The pairing window.
    pub fn window(&self) -> crate::identify::pairing::PairWindow {
        crate::identify::pairing::PairWindow { min_s: self.pair_window_s[0], max_s: self.pair_window_s[1] }
    }
}

fn default_true() -> bool {
    true
}

fn default_club() -> String {
    "driver".into()
}
fn default_model() -> String {
    "adjusted".into()
}
fn default_cor() -> f64 {
    crate::impact::impulse::DEFAULT_COR
}
fn default_estimator() -> String {
    "arc".into()
}

/// A rigid transform: rotation quaternion `[x, y, z, w]` and translation (m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoseConfig {
    #[serde(default = "identity_xyzw")]
    pub rotation_xyzw: [f64; 4],
    #[serde(default)]
    pub translation_m: [f64; 3],
}

fn identity_xyzw() -> [f64; 4] {
    [0.0, 0.0, 0.0, 1.0]
}

fn invalid(field: String, reason: impl Into<String>) -> DaemonError {
    DaemonError::Config { field, reason: reason.into() }
}

impl PoseConfig {
    fn to_isometry(self, field: String) -> Result<Isometry3, DaemonError> {
        if self.rotation_xyzw.iter().chain(self.translation_m.iter()).any(|v| !v.is_finite()) {
            return Err(invalid(field, "must be finite numbers"));
        }
        let q = crate::kinematics::sample::unit_quaternion(&self.rotation_xyzw, 1e-3)
            .ok_or_else(|| invalid(format!("{field}.rotation_xyzw"), "must be a unit quaternion [x, y, z, w]"))?;
        Ok(Isometry3::from_parts(Vector3::from(self.translation_m).into_translation(), q))
    }
}

impl Default for DaemonConfig {
    /// One rig, `rig1`, with a driver and the defaults.
    fn default() -> Self {
        DaemonConfig {
            status_period_s: 1.0,
            rigs: vec![RigConfig {
                name: "rig1".into(),
                club: default_club(),
                model: default_model(),
                cor: default_cor(),
                estimator: default_estimator(),
                ball_position_m: [0.0; 3],
                world_from_lab: None,
                club_from_body: None,
                flight: true,
                launch_monitor: LaunchMonitorConfig::default(),
            }],
        }
    }
}

impl DaemonConfig {
    /// Reads and validates a file.
    pub fn load(path: &Path) -> Result<(Self, Vec<RigSetup>), DaemonError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| DaemonError::Io { what: format!("reading {}", path.display()), source: e })?;
        Self::parse(&text)
    }

    /// Parses and validates TOML text.
    pub fn parse(text: &str) -> Result<(Self, Vec<RigSetup>), DaemonError> {
        let config: DaemonConfig =
            toml::from_str(text).map_err(|e| DaemonError::ConfigSyntax(e.message().to_string()))?;
        let rigs = config.setups()?;
        Ok((config, rigs))
    }

    /// The pipelines' setups, validating every field.
    pub fn setups(&self) -> Result<Vec<RigSetup>, DaemonError> {
        if !(self.status_period_s > 0.0 && self.status_period_s <= 60.0) {
            return Err(invalid("status_period_s".into(), "must be within 0 and 60 s"));
        }
        if self.rigs.is_empty() {
            return Err(invalid("rig".into(), "at least one [[rig]] is needed"));
        }
        let mut names = std::collections::BTreeSet::new();
        self.rigs
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let f = |name: &str| format!("rig[{i}].{name}");
                if !crate::wire::keys::valid_rig_name(&r.name) {
                    return Err(invalid(f("name"), format!("`{}` must be letters, digits, _ or -", r.name)));
                }
                if !names.insert(r.name.clone()) {
                    return Err(invalid(f("name"), format!("`{}` appears twice", r.name)));
                }
                let club = crate::cli::load_club(&r.club).map_err(|e| invalid(f("club"), format!("{e:#}")))?;
                if !(0.0..=1.0).contains(&r.cor) {
                    return Err(invalid(f("cor"), "must be within 0 and 1"));
                }
                let model = ModelChoice::parse(&r.model, r.cor)
                    .ok_or_else(|| invalid(f("model"), format!("`{}` is not {}", r.model, ModelChoice::NAMES)))?;
                let estimator = EstimatorSpec::by_name(&r.estimator).ok_or_else(|| {
                    invalid(
                        f("estimator"),
                        format!("`{}` is not arc, arc@MS, poly, poly@..., poly:... or linear2", r.estimator),
                    )
                })?;
                let [lo, hi] = r.launch_monitor.pair_window_s;
                if !(lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo < hi && hi <= 600.0) {
                    return Err(invalid(
                        f("launch_monitor.pair_window_s"),
                        "must be [min, max] with 0 <= min < max <= 600 s",
                    ));
                }
                if r.ball_position_m.iter().any(|v| !v.is_finite() || v.abs() > 50.0) {
                    return Err(invalid(f("ball_position_m"), "must be finite and within 50 m"));
                }
                let calibration = Calibration {
                    world_from_lab: r
                        .world_from_lab
                        .map(|p| p.to_isometry(f("world_from_lab")))
                        .transpose()?
                        .unwrap_or_default(),
                    club_from_body: r
                        .club_from_body
                        .map(|p| p.to_isometry(f("club_from_body")))
                        .transpose()?
                        .unwrap_or_default(),
                };
                let mut setup = RigSetup::new(&r.name, club);
                setup.model = model;
                if !r.flight {
                    setup.flight = None;
                }
                setup.estimator = estimator;
                setup.calibration = calibration;
                setup.detector.ball_position_m = Vector3::from(r.ball_position_m);
                Ok(setup)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_field() {
        let err = |t: &str| DaemonConfig::parse(t).unwrap_err().to_string();
        assert!(err("[[rig]]\nname = \"a\"\ncolour = 1").contains("colour"));
        assert!(err("[[rig]]\nname = \"a\"\nmodel = \"fast\"").contains("rig[0].model"));
        assert!(err("[[rig]]\nname = \"a\"\nclub = \"putter\"").contains("rig[0].club"));
        assert!(err("[[rig]]\nname = \"a b\"").contains("rig[0].name"));
        assert!(err("[[rig]]\nname = \"a\"\n[[rig]]\nname = \"a\"").contains("rig[1].name"));
        assert!(err("[[rig]]\nname = \"a\"\n[rig.world_from_lab]\nrotation_xyzw = [0.0, 0.0, 0.0, 3.0]")
            .contains("rig[0].world_from_lab.rotation_xyzw"));
        assert!(err("[[rig]]\nname = \"a\"\nestimator = \"magic\"").contains("rig[0].estimator"));
        assert!(err("status_period_s = 0.0\n[[rig]]\nname = \"a\"").contains("status_period_s"));
        assert!(err("[[rig]]\nname = \"a\"\n[rig.launch_monitor]\npair_window_s = [5.0, 1.0]")
            .contains("rig[0].launch_monitor.pair_window_s"));
        let (c, r) = DaemonConfig::parse("[[rig]]\nname = \"bay1\"\nclub = \"iron7\"\nmodel = \"slip\"").unwrap();
        assert_eq!(c.rigs[0].estimator, "arc");
        assert_eq!(r[0].club.name, "iron7");
    }
}
