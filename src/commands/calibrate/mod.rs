//! `impactd calibrate body|club|lab`: from a static trial (a C3D capture), the marker set of a body, the tracked
//! body in the club frame (`[rig.club_from_body]`) and the lab in the world (`[rig.world_from_lab]`). Each
//! writes the section it determines (to -o FILE, or standard output) and reports what it measured on stderr.
//! Marker positions are averaged over `--frames` frames from `--frame` (0-based), each marker checked still
//! over them (`--static-mm`).

mod club;
mod lab;
mod trial;

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::{Args, Subcommand};
use impactd::kinematics::calibrate;
use impactd::math::{Isometry3, Vector3};

pub use club::ClubArgs;
pub use lab::LabArgs;

#[derive(Debug, Subcommand)]
pub enum CalibrateCommand {
    /// A marker set: origin at the markers' centroid, axes the lab's.
    Body(BodyArgs),
    /// `club_from_body` from the club at address: the face located by face markers, a pointer trial or the
    /// marker set's `[face]`, else assumed soled square behind the ball (and said so); --shaft measures lean and lie.
    Club(ClubArgs),
    /// `world_from_lab` from markers on the floor (the up axis) and the target line or --target (the target).
    Lab(LabArgs),
}

#[derive(Debug, Args)]
pub struct Trial {
    /// The static trial (C3D or TRC).
    pub capture: PathBuf,
    /// The first frame to use (0-based index).
    #[arg(long, default_value_t = 0)]
    pub frame: u64,
    /// Average the markers over this many frames from --frame.
    #[arg(long, default_value_t = 1)]
    pub frames: u64,
    /// A marker moving more than this (mm) from its mean over the frames averaged makes the trial not static:
    /// refused, with the marker and how far it moved.
    #[arg(long, default_value_t = calibrate::DEFAULT_STATIC_LIMIT_M * 1e3)]
    pub static_mm: f64,
    /// Where to write the section (default: standard output).
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct BodyArgs {
    #[command(flatten)]
    pub trial: Trial,
    /// The body's markers (comma-separated, at least 3).
    #[arg(long, value_delimiter = ',', required = true)]
    pub labels: Vec<String>,
}

pub fn run(command: &CalibrateCommand) -> Result<ExitCode> {
    match command {
        CalibrateCommand::Body(a) => body(a),
        CalibrateCommand::Club(a) => club::club(a),
        CalibrateCommand::Lab(a) => lab::lab(a),
    }
}

fn write(trial: &Trial, text: &str) -> Result<ExitCode> {
    match &trial.output {
        Some(path) => std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))?,
        None => print!("{text}"),
    }
    Ok(ExitCode::SUCCESS)
}

fn body(a: &BodyArgs) -> Result<ExitCode> {
    let t = trial::StaticTrial::load(&a.trial)?;
    let p = t.means(&a.labels)?;
    let markers: Vec<(String, Vector3)> = a.labels.iter().cloned().zip(p).collect();
    let set = calibrate::body_set(&markers)?;
    eprintln!("marker set of {} markers, origin at their centroid, lab axes", set.len());
    write(&a.trial, &set.to_toml())
}

fn radius_m(mm: f64) -> Result<f64> {
    if !(mm.is_finite() && (0.0..=50.0).contains(&mm)) {
        bail!("--marker-radius-mm must be 0-50 mm");
    }
    Ok(mm * 1e-3)
}

/// Three comma-separated numbers, finite.
fn three(flag: &str, v: &[f64]) -> Result<Vector3> {
    match v {
        [x, y, z] if [x, y, z].iter().all(|v| v.is_finite()) => Ok(Vector3::new(*x, *y, *z)),
        _ => bail!("{flag} takes three finite numbers X,Y,Z"),
    }
}

/// The TOML section `[rig.NAME]` of a pose.
fn section(name: &str, pose: &Isometry3) -> String {
    let q = pose.rotation;
    let t = pose.translation.vector;
    format!(
        "[rig.{name}]\nrotation_xyzw = [{:.9}, {:.9}, {:.9}, {:.9}]\ntranslation_m = [{:.7}, {:.7}, {:.7}]\n",
        q.i, q.j, q.k, q.w, t.x, t.y, t.z
    )
}
