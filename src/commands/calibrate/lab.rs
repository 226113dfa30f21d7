//! `calibrate lab`: `world_from_lab` from the floor (the up axis, on the side the other markers stand), the
//! target line or a stated target axis, and the ball (a marker, a static ball trial, a stated position, or at the
//! rear target-line marker).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;
use impactd::kinematics::calibrate::{self, nearest_axis, BallAt, LabMarkers, Target, UpFrom};
use impactd::math::Vector3;

use super::trial::StaticTrial;
use super::{radius_m, section, three, write, Trial};

#[derive(Debug, Args)]
pub struct LabArgs {
    #[command(flatten)]
    pub trial: Trial,
    /// Two markers on the target line: the rear one, then the one toward the target.
    #[arg(long, value_delimiter = ',', required_unless_present = "target", conflicts_with = "target")]
    pub target_line: Vec<String>,
    /// The lab axis toward the target, for a capture with no target-line markers: +x, -x, +y, -y, +z or -z
    /// (laid into the floor).
    #[arg(long, allow_hyphen_values = true)]
    pub target: Option<String>,
    /// Markers on the floor (at least 3, spread at least 50 mm (RMS) across their best line; may repeat the
    /// target-line markers).
    #[arg(long, value_delimiter = ',', required = true)]
    pub floor: Vec<String>,
    /// A marker whose centre is the ball's (a taped ball), in this trial or in --ball-trial.
    #[arg(long)]
    pub ball: Option<String>,
    /// A static ball trial: the --ball marker averaged there (over the same --frame/--frames) sets the origin.
    #[arg(long, requires = "ball")]
    pub ball_trial: Option<PathBuf>,
    /// The ball's centre in the lab's coordinates, in millimetres: X,Y,Z.
    #[arg(long, value_name = "X,Y,Z", value_delimiter = ',', allow_hyphen_values = true, conflicts_with = "ball")]
    pub ball_at: Vec<f64>,
    /// The lab's up axis: x, y, z, -x, -y or -z. A check: the floor's normal on the side the other markers stand
    /// is the up axis, and a stated one that disagrees is an error; needed only when no marker stands off the floor.
    #[arg(long, allow_hyphen_values = true)]
    pub lab_up: Option<String>,
    /// Radius of the floor markers (mm): their centres sit this far above the floor.
    #[arg(long, default_value_t = 0.0)]
    pub marker_radius_mm: f64,
}

fn axis(flag: &str, name: &str) -> Result<Vector3> {
    Ok(match name.trim_start_matches('+') {
        "x" => Vector3::x(),
        "y" => Vector3::y(),
        "z" => Vector3::z(),
        "-x" => -Vector3::x(),
        "-y" => -Vector3::y(),
        "-z" => -Vector3::z(),
        _ => bail!("{flag} {name}: one of x, y, z, -x, -y, -z (+x etc. too)"),
    })
}

pub fn lab(a: &LabArgs) -> Result<ExitCode> {
    let t = StaticTrial::load(&a.trial)?;
    let (target, target_text) = match (a.target_line.as_slice(), &a.target) {
        ([rear, front], None) => {
            let p = t.means(&[rear.clone(), front.clone()])?;
            (Target::Line { rear_m: p[0], front_m: p[1] }, format!("along the target-line markers {rear} -> {front}"))
        }
        ([], Some(name)) => (Target::Axis(axis("--target", name)?), format!("the lab's {name} laid into the floor")),
        _ => bail!("--target-line takes two markers: REAR,FRONT (or --target AXIS without target-line markers)"),
    };
    let floor_p = t.means(&a.floor)?;
    let floor: Vec<(String, Vector3)> = a.floor.iter().cloned().zip(floor_p).collect();
    let ball_trial = match &a.ball_trial {
        Some(path) => Some(StaticTrial::load_at(path, a.trial.frame, a.trial.frames, a.trial.static_mm)?),
        None => None,
    };
    let (ball, ball_text) = match (&a.ball, &ball_trial, a.ball_at.as_slice()) {
        (Some(label), Some(bt), _) => (
            BallAt::Centre(bt.means(std::slice::from_ref(label))?[0]),
            format!(
                "the marker {label} of the static ball trial {}",
                a.ball_trial.as_ref().map_or(String::new(), |p| p.display().to_string())
            ),
        ),
        (Some(label), None, _) => {
            (BallAt::Centre(t.means(std::slice::from_ref(label))?[0]), format!("the marker {label}"))
        }
        (None, _, []) => (
            BallAt::RearMarker,
            "assumed on the floor at the rear target-line marker (no --ball marker, ball trial or --ball-at)"
                .to_string(),
        ),
        (None, _, v) => (BallAt::Centre(three("--ball-at", v)? * 1e-3), "stated (--ball-at, lab mm)".to_string()),
    };
    let mut used: Vec<String> = a.target_line.iter().chain(&a.floor).cloned().collect();
    used.extend(a.ball.iter().cloned());
    let markers = LabMarkers {
        target,
        floor,
        others: t.others(&used),
        lab_up: a.lab_up.as_deref().map(|n| axis("--lab-up", n)).transpose()?,
        ball,
        marker_radius_m: radius_m(a.marker_radius_mm)?,
        ball_radius_m: impactd::equipment::BallSpec::default().radius_m,
    };
    let lab = calibrate::world_from_lab(&markers)?;
    eprintln!("{}", t.report("static trial"));
    if let Some(bt) = &ball_trial {
        eprintln!("{}", bt.report("ball trial"));
    }
    let (nearest, tilt_deg) = nearest_axis(&lab.up_lab);
    let up_from = match &lab.up_from {
        UpFrom::Markers { count, highest } => format!(
            "the side {count} markers off the floor stand on (`{}` {:.0} mm from it){}",
            highest.0,
            highest.1 * 1e3,
            if a.lab_up.is_some() { ", as --lab-up states" } else { "" }
        ),
        UpFrom::Stated => "the stated --lab-up (no marker stands off the floor to check it)".to_string(),
    };
    let u = lab.up_lab;
    eprintln!(
        "floor: {} markers, {:.0} mm (RMS) across their best line (at least {:.0}), at most {:.2} mm off their plane; \
         up ({:.4}, {:.4}, {:.4}) in the lab, {tilt_deg:.2} deg from the lab's {nearest}, from {up_from}",
        markers.floor.len(),
        lab.floor_spread_m * 1e3,
        calibrate::lab::MIN_FLOOR_SPREAD_M * 1e3,
        lab.floor_off_max_m * 1e3,
        u.x,
        u.y,
        u.z
    );
    eprintln!("target: {target_text}");
    eprintln!("ball: {ball_text}; its centre {:.1} mm above the floor", lab.ball_height_m * 1e3);
    let w = lab.world_from_lab;
    eprintln!(
        "world_from_lab: the lab's origin at ({:.1}, {:.1}, {:.1}) mm in the world",
        w.translation.x * 1e3,
        w.translation.y * 1e3,
        w.translation.z * 1e3
    );
    write(&a.trial, &section("world_from_lab", &w))
}
