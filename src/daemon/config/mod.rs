//! `impactd.toml`: the rigs a daemon serves. Unknown or invalid fields stop start-up with an error naming the
//! field.
//!
//! ```toml
//! status_period_s = 1.0
//! units = "imperial"            # or "metric": the lines logged per shot (messages keep both)
//!
//! [[rig]]
//! name = "bay1"                 # key expressions mocap/bay1/clubhead, golf/bay1/launch, ...
//! club = "driver"               # a preset (driver, wood3, hybrid, iron4-iron9, pw, gw, sw, lw) or a club .toml
//! model = "slip"                # a model of the registry (`impactd models`), or a comma-separated list
//! soil = "firm"                 # with model = "ground" (an iron): soft | medium | firm | a soil .toml |
//!                               # none (the ball on a tee);
//!                               # with model = "both" it stands for "slip,ground"
//! cor = 0.83
//! estimator = "arc"             # linear2 | poly | arc | arc@60 | poly@44:5:39:3 | poly:24:4:24:3
//! ball_position_m = [0.0, 0.0, 0.0]   # world frame
//! flight = true                 # add carry, apex, landing and offline to each prediction
//! [rig.conditions]              # the air and turf it flies in (default: sea level, calm, 22.5 C, 50 %)
//! temperature_c = 22.5          # also altitude_m, humidity_pct, pressure_hpa, wind_mps, wind_dir_deg, firmness
//! [rig.world_from_lab]          # default identity
//! rotation_xyzw = [0.0, 0.0, 0.0, 1.0]
//! translation_m = [0.0, 0.0, 0.0]
//! [rig.club_from_body]          # the tracked body's pose in the club frame; default identity
//! rotation_xyzw = [0.0, 0.0, 0.0, 1.0]
//! translation_m = [0.0, 0.0, 0.0]
//! [rig.clubs]                  # tracked bodies and their clubs: another body in view switches the club
//! driver_body = "driver"        # body name = a preset or a club .toml (a put on golf/<rig>/club also switches)
//! seven = { club = "iron7", club_from_body = { translation_m = [0.0, 0.02, 0.0] } }
//! [rig.labels]                 # the labels of the shots until a put on golf/<rig>/session replaces them
//! player = "ann"
//! tags = ["fitting"]
//! [rig.simulator]               # send each shot to a golf simulator over Open Connect v1 (GSPro, OpenGolfSim)
//! open_connect = "127.0.0.1:921"
//! max_shot_age_s = 5.0          # a shot older than this when the connection comes back is dropped, not sent
//! # or, instead of open_connect, OpenGolfSim's developer API: opengolfsim = "127.0.0.1:3111"
//! # (opengolfsim_unit = "metric" (m/s, default) or "imperial" (mph))
//! [rig.input]                   # read the rig's body straight from Motive, QTM or Vicon
//! protocol = "natnet"           # natnet | qtm | vicon
//! server = "192.168.1.20"       # HOST or HOST:PORT
//! body = "driver"               # Vicon: subject = "driver"
//! unicast = true
//! [rig.launch_monitor]          # take measured shots from launch monitor connectors, as a simulator would
//! open_connect_listen = "127.0.0.1:921"
//! pair_window_s = [0.05, 5.0]   # a measurement pairs with the prediction it follows by this delay (s)
//!
//! [web]                         # the bay screen (`--web` overrides); a page per rig at http://ADDR/
//! listen = "127.0.0.1:8080"
//! hosts = ["bay1.local"]        # names it answers as besides the listen address and localhost (--web-host)
//! token = "..."                 # its controls' token (beyond loopback one is made at start when unset)
//!
//! [clubs]                       # where a put on golf/<rig>/club may name club files (presets always);
//! dirs = ["/srv/clubs"]         # default: this file's directory and ./clubs; relative to this file; [] for
//!                               # presets only
//! ```
//!
//! Its parts, a file each: a rig's club with its soil and models ([`club`]), the directories a put may name club
//! files in ([`club_dirs`]), a rig's air and turf ([`flight`]), the poses and body clubs ([`pose`]) and the bay
//! screen ([`web`]).

pub mod club;
pub mod club_dirs;
pub mod flight;
pub mod pose;
pub mod web;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

pub use club_dirs::ClubsConfig;
pub use web::WebConfig;

use crate::daemon::bridges::open_connect::{LaunchMonitorConfig, SimulatorConfig};
use crate::daemon::inputs::MocapInputConfig;
use crate::daemon::DaemonError;
use crate::kinematics::{Calibration, EstimatorSpec};
use crate::math::Vector3;
use crate::pipeline::RigSetup;
pub use flight::ConditionsConfig;
pub use pose::{BodyClub, MountedClub, PoseConfig};

/// The whole file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DaemonConfig {
    #[serde(default = "default_status_period")]
    pub status_period_s: f64,
    /// The units of the lines logged per shot: `imperial` (mph, yd) or `metric` (m/s, m); the messages keep both.
    #[serde(default)]
    pub units: crate::session::Units,
    #[serde(rename = "rig")]
    pub rigs: Vec<RigConfig>,
    /// The bay screen (`[web] listen = "127.0.0.1:8080"`), served when given (or with `--web`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub web: Option<WebConfig>,
    /// `[clubs]`: the directories a put on `golf/<rig>/club` may name club files in.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clubs: Option<ClubsConfig>,
    /// The directory of the file this configuration was loaded from (absolute), which relative club directories
    /// are taken from; `None` for a configuration not read from a file.
    #[serde(skip)]
    pub config_dir: Option<PathBuf>,
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
    /// The turf under the ball for the ground model (a preset, a soil file, or `none`: the ball on a tee).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub soil: Option<String>,
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
    /// The air and turf of that flight (and of the bay screen's flight lines).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub conditions: Option<ConditionsConfig>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub simulator: Option<SimulatorConfig>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub launch_monitor: Option<LaunchMonitorConfig>,
    /// The rig's samples straight from a NatNet or QTM server (besides `mocap/<rig>/clubhead`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub input: Option<MocapInputConfig>,
    /// The labels of the rig's shots until a put on `golf/<rig>/session` replaces them.
    #[serde(default, skip_serializing_if = "crate::wire::ShotLabels::is_empty")]
    pub labels: crate::wire::ShotLabels,
    /// Tracked bodies (rigid bodies, 6DOF bodies, marker sets) and the club each holds: a sample naming another
    /// body (`body`, or a `[rig.input]` body) switches the rig's club.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub clubs: BTreeMap<String, BodyClub>,
}

fn default_true() -> bool {
    true
}

fn default_club() -> String {
    "driver".into()
}
fn default_model() -> String {
    crate::impact::registry::DEFAULT_MODEL.into()
}
fn default_cor() -> f64 {
    crate::impact::impulse::DEFAULT_COR
}
fn default_estimator() -> String {
    "arc".into()
}

fn invalid(field: String, reason: impl Into<String>) -> DaemonError {
    DaemonError::Config { field, reason: reason.into() }
}

impl Default for DaemonConfig {
    /// One rig, `rig1`, with a driver and the defaults.
    fn default() -> Self {
        DaemonConfig {
            status_period_s: 1.0,
            units: crate::session::Units::Imperial,
            web: None,
            clubs: None,
            config_dir: None,
            rigs: vec![RigConfig {
                name: "rig1".into(),
                club: default_club(),
                model: default_model(),
                cor: default_cor(),
                soil: None,
                estimator: default_estimator(),
                ball_position_m: [0.0; 3],
                world_from_lab: None,
                club_from_body: None,
                flight: true,
                conditions: None,
                simulator: None,
                launch_monitor: None,
                input: None,
                labels: Default::default(),
                clubs: BTreeMap::new(),
            }],
        }
    }
}

/// The largest configuration file (impactd's or zenoh's) read.
pub const MAX_CONFIG_BYTES: u64 = crate::capped::MAX_INPUT_FILE_BYTES;

impl DaemonConfig {
    /// Reads and validates a file.
    pub fn load(path: &Path) -> Result<(Self, Vec<RigSetup>), DaemonError> {
        let text = crate::capped::read_to_string(path, MAX_CONFIG_BYTES)
            .map_err(|e| DaemonError::Io { what: format!("reading {}", path.display()), source: e })?;
        let (mut config, setups) = Self::parse(&text)?;
        let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
        config.config_dir = Some(std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf()));
        Ok((config, setups))
    }

    /// Parses and validates TOML text.
    pub fn parse(text: &str) -> Result<(Self, Vec<RigSetup>), DaemonError> {
        let config: DaemonConfig = toml::from_str(text)
            .map_err(|e| DaemonError::ConfigSyntax { origin: "config".into(), source: Box::new(e) })?;
        let rigs = config.setups()?;
        Ok((config, rigs))
    }

    /// Sends every rig that has no simulator of its own to the Open Connect simulator at `address`
    /// (`--open-connect ADDR`).
    pub fn set_default_open_connect(&mut self, address: &str) {
        for r in &mut self.rigs {
            let sim = r.simulator.get_or_insert_with(SimulatorConfig::default);
            if sim.open_connect.is_none() {
                sim.open_connect = Some(address.to_string());
            }
        }
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
                if !(0.0..=1.0).contains(&r.cor) {
                    return Err(invalid(f("cor"), "must be within 0 and 1"));
                }
                let club = r
                    .prepare_club(&r.club, &f("club"))
                    .map_err(|source| DaemonError::RigClub { field: f(source.part()), source })?;
                let estimator = EstimatorSpec::by_name(&r.estimator).ok_or_else(|| {
                    invalid(
                        f("estimator"),
                        format!("`{}` is not arc, arc@MS, poly, poly@..., poly:... or linear2", r.estimator),
                    )
                })?;
                if let Some(Err((field, reason))) = r.simulator.as_ref().map(SimulatorConfig::check) {
                    return Err(invalid(f(&format!("simulator.{field}")), reason));
                }
                if let Some(Err((field, reason))) = r.launch_monitor.as_ref().map(LaunchMonitorConfig::check) {
                    return Err(invalid(f(&format!("launch_monitor.{field}")), reason));
                }
                if let Some(Err((field, reason))) = r.input.as_ref().map(MocapInputConfig::source) {
                    return Err(invalid(f(&format!("input.{field}")), reason));
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
                let mut setup = RigSetup::new(&r.name, club.club);
                setup.models = club.models;
                setup.club_ref = club.club_ref;
                for (body, entry) in &r.clubs {
                    let field = f(&format!("clubs.{body}"));
                    let mut switch = r
                        .prepare_club(entry.club(), &field)
                        .map_err(|source| DaemonError::RigClub { field: field.clone(), source })?;
                    let club_from_body = match entry {
                        BodyClub::Mounted(MountedClub { club_from_body: Some(p), .. }) => {
                            p.to_isometry(format!("{field}.club_from_body"))?
                        }
                        _ => calibration.club_from_body,
                    };
                    switch.calibration = Some(Calibration { club_from_body, ..calibration });
                    setup.bodies.insert(body.clone(), switch);
                }
                setup.flight = match (&r.conditions, r.flight) {
                    (_, false) => None,
                    (Some(c), true) => {
                        Some(c.flight().map_err(|source| DaemonError::Conditions { field: f("conditions"), source })?)
                    }
                    (None, true) => setup.flight,
                };
                setup.estimator = estimator;
                setup.calibration = calibration;
                setup.detector.ball_position_m = Vector3::from(r.ball_position_m);
                r.labels.check().map_err(|source| DaemonError::Labels { field: f("labels"), source })?;
                setup.labels = r.labels.clone();
                Ok(setup)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bay_screen_is_served_where_web_listen_says_loopback_by_default() {
        let rig = "[[rig]]\nname = \"bay1\"\n";
        assert_eq!(DaemonConfig::parse(rig).unwrap().0.web, None);
        let (c, _) = DaemonConfig::parse(&format!("{rig}[web]\nlisten = \"127.0.0.1:9090\"\n")).unwrap();
        assert_eq!(c.web.unwrap().listen, "127.0.0.1:9090");
        let (c, _) = DaemonConfig::parse(&format!("{rig}[web]\n")).unwrap();
        assert_eq!(c.web.unwrap().listen, "127.0.0.1:8080");
        let (c, _) =
            DaemonConfig::parse(&format!("{rig}[web]\nhosts = [\"bay1.local\"]\ntoken = \"0123456789abcdef\"\n"))
                .unwrap();
        let web = c.web.clone().unwrap();
        assert_eq!((web.hosts, web.token.as_deref()), (vec!["bay1.local".to_string()], Some("0123456789abcdef")));
        // The token is never written out (a recording keeps the configuration).
        let written = toml::to_string(&c).unwrap();
        assert!(written.contains("bay1.local") && !written.contains("0123456789abcdef"), "{written}");
        let e = DaemonConfig::parse(&format!("{rig}[web]\nlisten_on = \"x\"\n")).unwrap_err().to_string();
        assert!(e.contains("listen_on"), "{e}");
    }

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
        assert!(err("[[rig]]\nname = \"a\"\n[rig.simulator]\nopen_connect = \"gspro\"")
            .contains("rig[0].simulator.open_connect"));
        assert!(err("[[rig]]\nname = \"a\"\n[rig.simulator]\nmax_shot_age_s = -1.0")
            .contains("rig[0].simulator.max_shot_age_s"));
        assert!(err("[[rig]]\nname = \"a\"\n[rig.input]\nnatnet = \"h\"\nqtm = \"h\"\nbody = \"c\"")
            .contains("rig[0].input.natnet"));
        assert!(err("[[rig]]\nname = \"a\"\n[rig.input]\nqtm = \"h\"\nbody = \"\"").contains("rig[0].input.body"));
        assert!(err(
            "[[rig]]\nname = \"a\"\n[rig.input]\nnatnet = \"h\"\nbody = \"c\"\nmulticast_group = \"10.0.0.1\""
        )
        .contains("rig[0].input.multicast_group"));
        assert!(err("[[rig]]\nname = \"a\"\n[rig.launch_monitor]\nopen_connect_listen = \"localhost\"")
            .contains("rig[0].launch_monitor.open_connect_listen"));
        let (mut c, _) = DaemonConfig::parse(
            "[[rig]]\nname = \"a\"\n[rig.simulator]\nopen_connect = \"10.0.0.2:921\"\n[[rig]]\nname = \"b\"",
        )
        .unwrap();
        c.set_default_open_connect("127.0.0.1:921");
        let sims: Vec<_> = c.rigs.iter().map(|r| r.simulator.as_ref().unwrap().open_connect.clone().unwrap()).collect();
        assert_eq!(sims, ["10.0.0.2:921", "127.0.0.1:921"]);
        assert_eq!(c.rigs[1].simulator.as_ref().unwrap().max_shot_age_s, 5.0);
        let (c, r) = DaemonConfig::parse("[[rig]]\nname = \"bay1\"\nclub = \"iron7\"\nmodel = \"slip\"").unwrap();
        assert_eq!(c.rigs[0].estimator, "arc");
        assert_eq!(r[0].club.name, "iron7");
    }

    /// `[rig.clubs]`: each body's club is loaded and built at start, with its hash and the body's own
    /// `club_from_body`; a bad club or pose is refused naming the body.
    #[test]
    fn bodies_map_to_clubs() {
        let rig = |clubs: &str| format!("[[rig]]\nname = \"bay1\"\n[rig.clubs]\n{clubs}");
        let text =
            rig("seven = \"iron7\"\nwedge = { club = \"sw\", club_from_body = { translation_m = [0.0, 0.01, 0.0] } }");
        let (_, r) = DaemonConfig::parse(&text).unwrap();
        let seven = &r[0].bodies["seven"];
        assert_eq!(seven.club.name, "iron7");
        let sha = crate::equipment::sha256_hex(crate::equipment::presets::find("iron7").unwrap().bytes());
        assert_eq!(seven.club_ref.as_ref().map(|c| c.sha256.clone()), Some(sha));
        let wedge = r[0].bodies["wedge"].calibration.unwrap();
        assert_eq!(wedge.club_from_body.translation.vector.y, 0.01);
        assert_eq!(r[0].club_ref.as_ref().map(|c| c.file.as_str()), Some("driver"));
        let err = |t: &str| DaemonConfig::parse(t).unwrap_err().to_string();
        assert!(err(&rig("seven = \"putter\"")).contains("rig[0].clubs.seven"));
        let bad_pose = rig("w = { club = \"sw\", club_from_body = { rotation_xyzw = [0.0, 0.0, 0.0, 2.0] } }");
        assert!(err(&bad_pose).contains("rig[0].clubs.w.club_from_body"), "{}", err(&bad_pose));
    }

    /// `soil` gives the ground model its turf; with `both` it means the impulse model, then the ground model;
    /// without a ground model, or an unknown soil, it is refused naming the field.
    #[test]
    fn soil_selects_the_turf_of_the_ground_model() {
        let rig = |extra: &str| format!("[[rig]]\nname = \"bay1\"\nclub = \"iron7\"\n{extra}");
        let (_, r) = DaemonConfig::parse(&rig("model = \"both\"\nsoil = \"soft\"")).unwrap();
        let names: Vec<&str> = r[0].models.iter().map(|m| m.name()).collect();
        assert_eq!(names, ["slip", "ground"]);
        let (_, r) = DaemonConfig::parse(&rig("model = \"ground\"\nsoil = \"firm\"")).unwrap();
        assert_eq!(r[0].models.len(), 1);
        // `none`: the ground model with no ground, the ball on a tee.
        let (_, r) = DaemonConfig::parse(&rig("model = \"ground\"\nsoil = \"none\"")).unwrap();
        assert_eq!(r[0].models[0].name(), "ground");
        let (_, r) = DaemonConfig::parse(&rig("model = \"both\"")).unwrap();
        assert_eq!(r[0].models[1].name(), "continuous");
        let err = |t: &str| DaemonConfig::parse(t).unwrap_err().to_string();
        assert!(err(&rig("model = \"ground\"\nsoil = \"mud\"")).contains("rig[0].soil"));
        assert!(err(&rig("model = \"adjusted\"\nsoil = \"firm\"")).contains("rig[0].soil"));
    }

    #[test]
    fn conditions_fly_the_rigs_ball_and_a_bad_one_names_its_field() {
        let rig = |extra: &str| format!("[[rig]]\nname = \"bay1\"\n{extra}");
        let (_, r) = DaemonConfig::parse(&rig("[rig.conditions]\naltitude_m = 1600.0")).unwrap();
        assert_eq!(r[0].flight.map(|f| f.conditions.altitude_m), Some(1600.0));
        let (_, r) = DaemonConfig::parse(&rig("flight = false\n[rig.conditions]\naltitude_m = 1600.0")).unwrap();
        assert!(r[0].flight.is_none());
        let err = DaemonConfig::parse(&rig("[rig.conditions]\nwind_mps = -1.0")).unwrap_err().to_string();
        assert!(err.contains("rig[0].conditions") && err.contains("wind_mps"), "{err}");
    }
}
