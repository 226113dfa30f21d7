//! `impactd calibrate body|club|lab`: from a static trial (a C3D capture), the marker set of a body, the tracked
//! body in the club frame (`[rig.club_from_body]`) and the lab in the world (`[rig.world_from_lab]`). Each
//! writes the section it determines (to -o FILE, or standard output) and reports what it measured on stderr.
//! Marker positions are averaged over `--frames` frames from `--frame` (0-based).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::{Args, Subcommand};
use impactd::daemon::recording::c3d::static_trial::mean_positions;
use impactd::daemon::DaemonConfig;
use impactd::equipment::{load_club, ClubSpec};
use impactd::kinematics::calibrate::{self, BallAt, FaceMarkers, LabMarkers};
use impactd::math::{Isometry3, Vector3};

#[derive(Debug, Subcommand)]
pub enum CalibrateCommand {
    /// A marker set: origin at the markers' centroid, axes the lab's.
    Body(BodyArgs),
    /// `club_from_body` from the club at address (soled square behind the ball, or face markers).
    Club(ClubArgs),
    /// `world_from_lab` from two markers on the target line and markers on the floor.
    Lab(LabArgs),
}

#[derive(Debug, Args)]
pub struct Trial {
    /// The static trial (C3D).
    pub capture: PathBuf,
    /// The first frame to use (0-based index).
    #[arg(long, default_value_t = 0)]
    pub frame: u64,
    /// Average the markers over this many frames from --frame.
    #[arg(long, default_value_t = 1)]
    pub frames: u64,
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

#[derive(Debug, Args)]
pub struct ClubArgs {
    #[command(flatten)]
    pub trial: Trial,
    /// The marker set of the tracked body on the club.
    #[arg(long)]
    pub markers: PathBuf,
    /// The club (preset or club file); default: the rig's.
    #[arg(long)]
    pub club: Option<String>,
    /// The configuration with the rig's `world_from_lab` and `ball_position_m` (default: identity, origin).
    #[arg(short = 'c', long = "config")]
    pub config: Option<PathBuf>,
    /// The rig of the configuration (default: its first).
    #[arg(long)]
    pub rig: Option<String>,
    /// Face markers: heel end, toe end (along a score line), then at least one more on the face. Without them
    /// the club is taken as soled square behind the ball at its specified lie, the face centre against it.
    #[arg(long, value_delimiter = ',')]
    pub face: Vec<String>,
    /// A marker on the face centre (else the face markers' centroid).
    #[arg(long)]
    pub face_centre: Option<String>,
    /// Radius of the markers (mm): their centres sit this far off the surface they are stuck on.
    #[arg(long, default_value_t = 0.0)]
    pub marker_radius_mm: f64,
}

#[derive(Debug, Args)]
pub struct LabArgs {
    #[command(flatten)]
    pub trial: Trial,
    /// Two markers on the target line: the rear one, then the one toward the target.
    #[arg(long, value_delimiter = ',', required = true)]
    pub target_line: Vec<String>,
    /// Markers on the floor (at least 3, not on one line; may repeat the target-line markers).
    #[arg(long, value_delimiter = ',', required = true)]
    pub floor: Vec<String>,
    /// A marker whose centre is the ball's (a taped ball); else the ball rests on the floor at the rear marker.
    #[arg(long)]
    pub ball: Option<String>,
    /// The lab's up axis: x, y, z, -x, -y or -z (which side of the floor is up).
    #[arg(long, default_value = "z")]
    pub lab_up: String,
    /// Radius of the floor markers (mm): their centres sit this far above the floor.
    #[arg(long, default_value_t = 0.0)]
    pub marker_radius_mm: f64,
}

pub fn run(command: &CalibrateCommand) -> Result<ExitCode> {
    match command {
        CalibrateCommand::Body(a) => body(a),
        CalibrateCommand::Club(a) => club(a),
        CalibrateCommand::Lab(a) => lab(a),
    }
}

fn positions(trial: &Trial, labels: &[String]) -> Result<Vec<Vector3>> {
    if trial.frames == 0 {
        bail!("--frames must be at least 1");
    }
    mean_positions(&trial.capture, labels, trial.frame, trial.frames)
        .with_context(|| format!("{}", trial.capture.display()))
}

fn write(trial: &Trial, text: &str) -> Result<ExitCode> {
    match &trial.output {
        Some(path) => std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))?,
        None => print!("{text}"),
    }
    Ok(ExitCode::SUCCESS)
}

fn body(a: &BodyArgs) -> Result<ExitCode> {
    let p = positions(&a.trial, &a.labels)?;
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

fn lab(a: &LabArgs) -> Result<ExitCode> {
    let [rear, front] = a.target_line.as_slice() else { bail!("--target-line takes two markers: REAR,FRONT") };
    let mut labels = vec![rear.clone(), front.clone()];
    labels.extend(a.floor.iter().cloned());
    labels.extend(a.ball.iter().cloned());
    let p = positions(&a.trial, &labels)?;
    let lab_up = match a.lab_up.as_str() {
        "x" => Vector3::x(),
        "y" => Vector3::y(),
        "z" => Vector3::z(),
        "-x" => -Vector3::x(),
        "-y" => -Vector3::y(),
        "-z" => -Vector3::z(),
        other => bail!("--lab-up {other}: one of x, y, z, -x, -y, -z"),
    };
    let floor_m = p[2..2 + a.floor.len()].to_vec();
    let markers = LabMarkers {
        rear_m: p[0],
        front_m: p[1],
        floor_m,
        lab_up,
        ball: if a.ball.is_some() { BallAt::Marker(p[p.len() - 1]) } else { BallAt::RearMarker },
        marker_radius_m: radius_m(a.marker_radius_mm)?,
        ball_radius_m: impactd::equipment::BallSpec::default().radius_m,
    };
    let world_from_lab = calibrate::world_from_lab(&markers)?;
    let rest = world_from_lab * impactd::math::Point3::from(p[0]);
    eprintln!(
        "world_from_lab: the lab's origin at ({:.1}, {:.1}, {:.1}) mm in the world; the rear marker at ({:.1}, \
         {:.1}, {:.1}) mm",
        world_from_lab.translation.x * 1e3,
        world_from_lab.translation.y * 1e3,
        world_from_lab.translation.z * 1e3,
        rest.x * 1e3,
        rest.y * 1e3,
        rest.z * 1e3
    );
    write(&a.trial, &section("world_from_lab", &world_from_lab))
}

fn club(a: &ClubArgs) -> Result<ExitCode> {
    let fit = super::import::FitArgs { reject_mm: 3.0, ball_marker: None, ball_offset_mm: Vec::new() };
    let fitter = fit.fitter(&a.markers)?;
    let set = &fitter.set;
    let mut labels = set.labels.clone();
    labels.extend(a.face.iter().cloned());
    labels.extend(a.face_centre.iter().cloned());
    let p = positions(&a.trial, &labels)?;
    let body: Vec<Option<Vector3>> = p[..set.len()].iter().map(|v| Some(*v)).collect();
    let fit = fitter.fit(&body).context("fitting the marker set to the static trial")?;
    let (world_from_lab, ball_position_m, rig_club) = rig(a.config.as_deref(), a.rig.as_deref())?;
    let club_name = a.club.clone().or(rig_club).unwrap_or_else(|| "driver".into());
    let club: ClubSpec = load_club(&club_name).with_context(|| format!("--club {club_name}"))?.club;
    let ball_radius_m = impactd::impact::Equipment::new(club.clone()).ball.radius_m;
    let result = if a.face.is_empty() {
        if a.face_centre.is_some() {
            bail!("--face-centre needs --face (the face markers give the face's plane)");
        }
        calibrate::club_soled_square(&fit.lab_from_body, &world_from_lab, &club, &ball_position_m, ball_radius_m)
    } else {
        if a.face.len() < 3 {
            bail!("--face takes at least 3 markers: HEEL,TOE,OTHER[,...]");
        }
        let f = &p[set.len()..];
        let face = FaceMarkers {
            heel_m: f[0],
            toe_m: f[1],
            others_m: f[2..a.face.len()].to_vec(),
            centre_m: a.face_centre.as_ref().map(|_| f[f.len() - 1]),
            marker_radius_m: radius_m(a.marker_radius_mm)?,
        };
        calibrate::club_from_face(&fit.lab_from_body, &world_from_lab, &face, &club)?
    };
    let c = result.face_centre_body_m * 1e3;
    let n = result.face_normal_body;
    eprintln!("face centre in the body frame: ({:.1}, {:.1}, {:.1}) mm", c.x, c.y, c.z);
    eprintln!("face normal in the body frame: ({:.4}, {:.4}, {:.4})", n.x, n.y, n.z);
    eprintln!(
        "at address: loft {:.2} deg ({:+.2} deg against the club's {:.2}), lie {:+.2} deg against the club's \
         (toe up +), face angle {:+.2} deg; marker fit residual {:.3} mm",
        result.loft_deg,
        result.loft_residual_deg,
        club.loft_deg(),
        result.lie_residual_deg,
        result.face_angle_deg,
        fit.residual_m * 1e3
    );
    write(&a.trial, &section("club_from_body", &result.club_from_body))
}

/// A rig's `world_from_lab`, ball position and club from a configuration file.
fn rig(config: Option<&Path>, name: Option<&str>) -> Result<(Isometry3, Vector3, Option<String>)> {
    let Some(path) = config else {
        if name.is_some() {
            bail!("--rig needs -c (the configuration that has the rig)");
        }
        return Ok((Isometry3::identity(), Vector3::zeros(), None));
    };
    let (config, setups) = DaemonConfig::load(path)?;
    let i = match name {
        Some(n) => config
            .rigs
            .iter()
            .position(|r| r.name == n)
            .with_context(|| format!("no rig `{n}` in {}", path.display()))?,
        None => 0,
    };
    let (Some(rig), Some(setup)) = (config.rigs.get(i), setups.get(i)) else { bail!("{} has no rig", path.display()) };
    Ok((setup.calibration.world_from_lab, setup.detector.ball_position_m, Some(rig.club.clone())))
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
