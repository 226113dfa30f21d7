//! Argument groups shared by several commands: the flight conditions, a delivery given by flags, the impact
//! model's name and zenoh's usual flags ([`ZenohFlags`]: `--zenoh-config`, `-m/--mode`, `-e/--connect`,
//! `-l/--listen`, `--no-multicast-scouting`).

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::Args;

#[cfg(feature = "daemon")]
use impactd::daemon::bus::{Mode, ZenohArgs};

#[cfg(feature = "daemon")]
use super::error::CliError;
use std::sync::Arc;

use impactd::equipment::LoadedClub;
use impactd::impact::registry::{self, BuildOptions};
use impactd::impact::ImpactModel;
use impactd::wire::DeliveryInput;

/// Where and in what air the ball flies.
#[derive(Debug, Clone, Args)]
pub struct ConditionArgs {
    /// Air temperature (deg C).
    #[arg(long, default_value_t = 22.5)]
    pub temp_c: f64,
    /// Altitude above sea level (m); sets the default pressure.
    #[arg(long, default_value_t = 0.0)]
    pub altitude_m: f64,
    /// Relative humidity in percent, 0-100, as weather services give it.
    #[arg(long, default_value_t = 50.0)]
    pub humidity: f64,
    /// Station pressure (hPa); default: the standard atmosphere at the altitude.
    #[arg(long)]
    pub pressure_hpa: Option<f64>,
    /// Wind speed (m/s).
    #[arg(long, default_value_t = 0.0)]
    pub wind_mps: f64,
    /// The direction the wind blows toward (deg from the target line, right +): 0 tailwind, 180 headwind.
    #[arg(long, default_value_t = 0.0)]
    pub wind_dir_deg: f64,
}

impl ConditionArgs {
    pub fn conditions(&self) -> Result<impactd::flight::Conditions> {
        if !(0.0..=100.0).contains(&self.humidity) {
            bail!("--humidity is relative humidity in percent, 0-100, got {}", self.humidity);
        }
        let c = impactd::flight::Conditions {
            temperature_c: self.temp_c,
            pressure_hpa: self.pressure_hpa,
            humidity: self.humidity / 100.0,
            altitude_m: self.altitude_m,
            wind_mps: self.wind_mps,
            wind_dir_deg: self.wind_dir_deg,
        };
        c.validate().context("conditions")?;
        Ok(c)
    }

    /// The flight model in these conditions, bouncing and rolling on turf of the given firmness.
    pub fn flight(&self, firmness: f64) -> Result<impactd::flight::Flight> {
        let turf = impactd::flight::Turf { firmness };
        turf.validate().context("--firmness")?;
        Ok(impactd::flight::Flight { conditions: self.conditions()?, turf, ..Default::default() })
    }
}

/// A model name from the registry (`impact::registry`): one model, a group (`both`) or a comma-separated list.
pub fn model_name(name: &str) -> std::result::Result<String, String> {
    registry::resolve(name, false).map(|_| name.to_string()).map_err(|e| e.to_string())
}

/// The single model a command runs, from the registry, with the club file's parameters.
pub fn one_model(name: &str, club: &LoadedClub, cor: f64) -> Result<Arc<dyn ImpactModel>> {
    let options = BuildOptions { cor, ..BuildOptions::default() };
    Ok(registry::build_one(name, club, &options)?)
}

/// `--soil`: the turf of the ground model (a preset, a soil file, or `none` for a teed ball), as the club's
/// `[soil]` section.
pub fn set_soil(club: &mut LoadedClub, soil: Option<&str>, model: &str) -> Result<()> {
    let Some(soil) = soil else { return Ok(()) };
    registry::resolve(model, true).context("--soil")?;
    let section = impactd::impact::continuous::iron_ground::sections::soil_arg_section(soil).context("--soil")?;
    club.sections.insert("soil", section);
    Ok(())
}

/// Whether a model is resolved in time (has a trace of forces).
pub fn resolved_in_time(name: &str) -> bool {
    registry::entry(name).is_some_and(|e| e.resolved_in_time)
}

/// A delivery given with flags (TrackMan names; unset numbers are 0, the loft the club's).
#[derive(Debug, Clone, Args)]
pub struct DeliveryArgs {
    /// Club speed at impact (mph, the face centre's speed; 2.3-223 mph = 1-100 m/s).
    #[arg(long, default_value_t = 100.0)]
    pub club_speed_mph: f64,
    /// Attack angle (deg, up +).
    #[arg(long, default_value_t = 0.0)]
    pub attack_angle_deg: f64,
    /// Club path (deg, right of the target +).
    #[arg(long, default_value_t = 0.0)]
    pub club_path_deg: f64,
    /// Face angle (deg, open/right +).
    #[arg(long, default_value_t = 0.0)]
    pub face_angle_deg: f64,
    /// Dynamic loft (deg); default: the loft tour players deliver with the club (`impactd models --presets`).
    #[arg(long)]
    pub dynamic_loft_deg: Option<f64>,
    /// Impact location from the face centre toward the toe (mm, toe +).
    #[arg(long, default_value_t = 0.0)]
    pub impact_h_mm: f64,
    /// Impact location from the face centre up the face (mm, up +).
    #[arg(long, default_value_t = 0.0)]
    pub impact_v_mm: f64,
}

impl DeliveryArgs {
    pub fn input(&self) -> DeliveryInput {
        DeliveryInput {
            club_speed_mph: self.club_speed_mph,
            attack_angle_deg: self.attack_angle_deg,
            club_path_deg: self.club_path_deg,
            face_angle_deg: self.face_angle_deg,
            dynamic_loft_deg: self.dynamic_loft_deg,
            impact_h_mm: self.impact_h_mm,
            impact_v_mm: self.impact_v_mm,
            club_angular_velocity_radps: None,
            handedness: None,
            dynamic_lie_deg: None,
        }
    }
}

/// A club preset by name or a club file by path.
pub fn load_club(spec: &str) -> Result<LoadedClub> {
    Ok(impactd::equipment::load_club(spec)?)
}

/// The file at `path`, else stdin, by lines.
pub fn open_input(path: Option<&Path>) -> Result<Box<dyn BufRead>> {
    Ok(match path {
        Some(p) => {
            Box::new(BufReader::new(std::fs::File::open(p).with_context(|| format!("opening input {}", p.display()))?))
        }
        None => Box::new(BufReader::new(std::io::stdin())),
    })
}

/// The exit code of bad input: a line a command cannot read or answer (not JSON, not the message it reads, a
/// field out of range), for every command that reads lines (`predict`, `flight`, `replay`, `compare`, `fit`).
pub const BAD_INPUT_EXIT: u8 = 2;

/// Exit 2 when any line was rejected (the others were answered).
pub fn exit_code(tally: impactd::jsonl::Tally) -> ExitCode {
    if tally.rejected > 0 {
        ExitCode::from(BAD_INPUT_EXIT)
    } else {
        ExitCode::SUCCESS
    }
}

/// Writes `text` to `path` (making its directory when it is not there) and says so on stderr.
pub fn write_output(path: &Path, text: &str) -> Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty() && !d.exists()) {
        std::fs::create_dir_all(dir).with_context(|| format!("making {}", dir.display()))?;
    }
    std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// zenoh's usual command-line flags.
#[cfg(feature = "daemon")]
#[derive(Debug, Clone, Default, Args)]
pub struct ZenohFlags {
    /// A zenoh configuration file (JSON5).
    #[arg(long = "zenoh-config", value_name = "FILE")]
    pub zenoh_config: Option<std::path::PathBuf>,
    /// peer or client.
    #[arg(short = 'm', long = "mode")]
    pub mode: Option<String>,
    /// Endpoints to connect to (e.g. tcp/192.168.1.10:7447); repeatable.
    #[arg(short = 'e', long = "connect")]
    pub connect: Vec<String>,
    /// Endpoints to listen on (e.g. tcp/0.0.0.0:7447); repeatable.
    #[arg(short = 'l', long = "listen")]
    pub listen: Vec<String>,
    /// Disable multicast scouting (the default unless a zenoh configuration file or --multicast-scouting says
    /// otherwise).
    #[arg(long = "no-multicast-scouting", conflicts_with = "multicast_scouting")]
    pub no_multicast_scouting: bool,
    /// Enable multicast scouting: peers on the network find each other (and this process) by themselves.
    #[arg(long = "multicast-scouting")]
    pub multicast_scouting: bool,
}

#[cfg(feature = "daemon")]
impl ZenohFlags {
    /// The flags checked: what the daemon's bus opens a session from.
    pub fn args(&self) -> Result<ZenohArgs, CliError> {
        let mode = match &self.mode {
            Some(name) => Some(Mode::from_name(name).ok_or_else(|| CliError::BadMode(name.clone()))?),
            None => None,
        };
        Ok(ZenohArgs {
            zenoh_config: self.zenoh_config.clone(),
            mode,
            connect: self.connect.clone(),
            listen: self.listen.clone(),
            no_multicast_scouting: self.no_multicast_scouting,
            multicast_scouting: self.multicast_scouting,
        })
    }
}
