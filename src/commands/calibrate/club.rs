//! `calibrate club`: `club_from_body` from the club at address, the face located by face markers, a pointer
//! trial or the marker set's `[face]` (else assumed soled square behind the ball, and reported so); shaft
//! markers (`--shaft`, or the marker set's `[shaft] markers`) give the address lean and lie, and the set's `[shaft]
//! grip` markers are checked for a club's length from the head's markers.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::Args;
use impactd::daemon::DaemonConfig;
use impactd::equipment::{load_club, ClubSpec};
use impactd::kinematics::calibrate::{
    self, pointer_tip, shaft_reading, ClubCalibration, FaceFrom, FaceMarkers, TipOffset, Touches,
};
use impactd::kinematics::{MarkerFitter, MarkerSet};
use impactd::math::{Isometry3, Point3, Vector3};

use super::trial::StaticTrial;
use super::{radius_m, section, write, Trial};

#[derive(Debug, Args)]
pub struct ClubArgs {
    #[command(flatten)]
    pub trial: Trial,
    /// The marker set of the tracked body on the club (its `[face]`, if stated, locates the face; its `[shaft]`
    /// names the shaft markers --shaft would and the grip markers checked for a club's length).
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
    /// Face markers: heel end, toe end (along a score line), then at least one more on the face.
    #[arg(long, value_delimiter = ',')]
    pub face: Vec<String>,
    /// A marker on the face centre (else the face markers' centroid).
    #[arg(long)]
    pub face_centre: Option<String>,
    /// Radius of the markers (mm): their centres sit this far off the surface they are stuck on.
    #[arg(long, default_value_t = 0.0)]
    pub marker_radius_mm: f64,
    /// Pointer trials (C3D or TRC) with the club's markers in view: three files, the tip on the face centre, then on the
    /// leading edge's heel end, then its toe end; or one file with --touch-frames.
    #[arg(long, value_delimiter = ',')]
    pub pointer: Vec<PathBuf>,
    /// The pointer's markers, the one nearest the tip first (at least 2).
    #[arg(long, value_delimiter = ',')]
    pub pointer_markers: Vec<String>,
    /// The pointer's tip (mm): one number, the distance beyond the first marker along the wand's axis (from its
    /// last marker through its first); or X,Y,Z in the wand's frame (origin the first marker, x toward the second,
    /// y toward the third in their plane, z = x cross y).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub tip_mm: Vec<f64>,
    /// With one pointer file: the first frame of each touch (centre, heel, toe), each averaged over --frames.
    #[arg(long, value_delimiter = ',')]
    pub touch_frames: Vec<u64>,
    /// Two markers on the shaft, on the same side of it (either order): the address shaft lean and lie (default:
    /// the marker set's `[shaft] markers`).
    #[arg(long, value_delimiter = ',')]
    pub shaft: Vec<String>,
}

pub fn club(a: &ClubArgs) -> Result<ExitCode> {
    let fit = super::super::import::FitArgs { reject_mm: 3.0, ball_marker: None, ball_offset_mm: Vec::new() };
    let fitter = fit.fitter(&a.markers)?;
    let text = std::fs::read_to_string(&a.markers).with_context(|| format!("reading {}", a.markers.display()))?;
    let stated = MarkerSet::face_from_toml(&text).with_context(|| format!("{}", a.markers.display()))?;
    let sources = [!a.face.is_empty(), !a.pointer.is_empty(), stated.is_some()];
    if sources.iter().filter(|s| **s).count() > 1 {
        bail!(
            "the face is located more than one way (--face markers, --pointer trials, the marker set's [face]): give \
             one"
        );
    }
    if a.face_centre.is_some() && a.face.is_empty() {
        bail!("--face-centre needs --face (the face markers give the face's plane)");
    }
    let t = StaticTrial::load(&a.trial)?;
    let (lab_from_body, residual_m) = body_pose(&t, &fitter)?;
    let (world_from_lab, ball_position_m, rig_club) = rig(a.config.as_deref(), a.rig.as_deref())?;
    let club_name = a.club.clone().or(rig_club).unwrap_or_else(|| "driver".into());
    let club: ClubSpec = load_club(&club_name).with_context(|| format!("--club {club_name}"))?.club;
    let ball_radius_m = impactd::impact::Equipment::new(club.clone()).ball.radius_m;
    let world_from_body = world_from_lab * lab_from_body;
    let stated_shaft = super::super::import::stated_shaft(&a.markers)?;
    check_grip(&t, &lab_from_body, &stated_shaft.grip)?;
    let (shaft_labels, flag) = match (a.shaft.as_slice(), stated_shaft.markers.as_slice()) {
        ([], []) => (Vec::new(), "--shaft"),
        ([], stated) => (stated.to_vec(), "the marker set's [shaft] markers"),
        (given, stated) => {
            if !stated.is_empty() && stated.iter().any(|s| !given.contains(s)) {
                eprintln!(
                    "--shaft {} given: the marker set's [shaft] markers {} are not used",
                    given.join(","),
                    stated.join(", ")
                );
            }
            (given.to_vec(), "--shaft")
        }
    };
    let shaft = match shaft_labels.as_slice() {
        [] => None,
        [lo, hi] => {
            let p = t.means(&[lo.clone(), hi.clone()]).with_context(|| format!("the shaft markers ({flag})"))?;
            let (lo_w, hi_w) = (world_from_lab * Point3::from(p[0]), world_from_lab * Point3::from(p[1]));
            Some(shaft_reading(&lo_w.coords, &hi_w.coords).context(flag)?)
        }
        _ => bail!("--shaft takes two markers on the shaft: A,B"),
    };
    let result = if let Some(face) = &stated {
        let shaft_body = shaft.map(|s| world_from_body.inverse_transform_vector(&s.up_world));
        calibrate::club_from_face_in_body(&face.centre_m, &face.normal, shaft_body.as_ref(), world_from_body, &club)?
    } else if !a.pointer.is_empty() {
        let touches = pointer_touches(a, &fitter)?;
        calibrate::club_from_touches(&touches, world_from_body, &club)?
    } else if !a.face.is_empty() {
        if a.face.len() < 3 {
            bail!("--face takes at least 3 markers: HEEL,TOE,OTHER[,...]");
        }
        let mut labels = a.face.clone();
        labels.extend(a.face_centre.iter().cloned());
        let f = t.means(&labels)?;
        let face = FaceMarkers {
            heel_m: f[0],
            toe_m: f[1],
            others_m: f[2..a.face.len()].to_vec(),
            centre_m: a.face_centre.as_ref().map(|_| f[f.len() - 1]),
            marker_radius_m: radius_m(a.marker_radius_mm)?,
        };
        calibrate::club_from_face(&lab_from_body, &world_from_lab, &face, &club)?
    } else {
        calibrate::club_soled_square(&lab_from_body, &world_from_lab, &club, &ball_position_m, ball_radius_m)
    };
    eprintln!("{}", t.report("static trial"));
    if a.config.is_none() {
        eprintln!(
            "no -c: the world is taken as the lab itself (identity world_from_lab, the ball at its origin): the \
             address angles below are in the lab's axes"
        );
    }
    if flag != "--shaft" {
        eprintln!("shaft markers {}: from the marker set's [shaft]", shaft_labels.join(", "));
    }
    report(&result, &club, &fitter, residual_m, shaft.as_ref().map(|s| (s, shaft_labels.as_slice())), a);
    write(&a.trial, &section("club_from_body", &result.club_from_body))
}

/// The grip markers the marker set names, each at a club's length from the head's markers in the static trial
/// (`guards::CLUB_LENGTH_M`): a refusal names the marker and its distance; within it, each is said.
fn check_grip(t: &StaticTrial, lab_from_body: &Isometry3, grip: &[String]) -> Result<()> {
    for g in grip {
        let p =
            t.means(std::slice::from_ref(g)).with_context(|| format!("the marker set's [shaft] grip marker {g}"))?;
        let d = (p[0] - lab_from_body.translation.vector).norm();
        if let Some(why) = impactd::kinematics::guards::club_length_refusal(g, d, "the static trial's mean") {
            bail!("{why} (the marker set's [shaft] grip)");
        }
        let (lo, hi) = impactd::kinematics::guards::CLUB_LENGTH_M;
        eprintln!("grip marker {g}: {d:.3} m from the head's markers, a club's length ({lo}-{hi} m)");
    }
    Ok(())
}

/// The body's pose in a static trial from its markers' means.
fn body_pose(t: &StaticTrial, fitter: &MarkerFitter) -> Result<(Isometry3, f64)> {
    let p = t.means(&fitter.set.labels)?;
    let body: Vec<Option<Vector3>> = p.iter().map(|v| Some(*v)).collect();
    let fit = fitter.fit(&body).context("fitting the marker set to the static trial")?;
    Ok((fit.lab_from_body, fit.residual_m))
}

/// The pointer's three touches in the body frame, each from its own still stretch of frames.
fn pointer_touches(a: &ClubArgs, fitter: &MarkerFitter) -> Result<Touches> {
    if a.pointer_markers.len() < 2 {
        bail!("--pointer needs --pointer-markers A,B[,C...] (the wand's markers, the one nearest the tip first)");
    }
    let tip = match a.tip_mm.as_slice() {
        [d] if d.is_finite() && d.abs() <= 1000.0 => TipOffset::Along(d * 1e-3),
        [x, y, z] if [x, y, z].iter().all(|v| v.is_finite() && v.abs() <= 1000.0) => {
            TipOffset::InFrame(Vector3::new(*x, *y, *z) * 1e-3)
        }
        _ => bail!("--pointer needs --tip-mm D (along the wand's axis) or --tip-mm X,Y,Z (in its frame), within 1 m"),
    };
    let stretches: Vec<(&Path, u64)> = match (a.pointer.as_slice(), a.touch_frames.as_slice()) {
        ([c, h, t], []) => vec![(c, a.trial.frame), (h, a.trial.frame), (t, a.trial.frame)],
        ([one], [c, h, t]) => vec![(one, *c), (one, *h), (one, *t)],
        _ => bail!(
            "--pointer takes three trials (CENTRE,HEEL,TOE), or one trial with --touch-frames C,H,T (the first frame \
             of each touch)"
        ),
    };
    let names = ["the face centre", "the leading edge's heel end", "the leading edge's toe end"];
    let mut tips = Vec::new();
    for ((path, first), name) in stretches.into_iter().zip(names) {
        let t = StaticTrial::load_at(path, first, a.trial.frames, a.trial.static_mm)
            .with_context(|| format!("the pointer on {name}"))?;
        let wand = t.means(&a.pointer_markers).with_context(|| format!("the pointer on {name}"))?;
        let (lab_from_body, _) = body_pose(&t, fitter).with_context(|| format!("the pointer on {name}"))?;
        let tip_lab = pointer_tip(&wand, &tip)?;
        eprintln!("{}", t.report(&format!("pointer on {name}")));
        tips.push(lab_from_body.inverse_transform_point(&Point3::from(tip_lab)).coords);
    }
    Ok(Touches { centre_m: tips[0], heel_m: tips[1], toe_m: tips[2] })
}

fn report(
    r: &ClubCalibration,
    club: &ClubSpec,
    fitter: &MarkerFitter,
    residual_m: f64,
    shaft: Option<(&calibrate::ShaftReading, &[String])>,
    a: &ClubArgs,
) {
    let how = match r.face {
        FaceFrom::Assumed => "ASSUMED, not measured: no --face markers, --pointer trials or [face] in the marker set, \
                              so the club is taken as soled square behind the ball at the club file's loft and lie, \
                              the face centre against the ball"
            .to_string(),
        FaceFrom::Markers => format!("measured by the face markers {}", a.face.join(", ")),
        FaceFrom::Pointer => "measured by the pointer's touches".to_string(),
        FaceFrom::MarkerSet { toe_measured: true } => {
            "stated by the marker set's [face], its turn about the normal from the shaft markers".to_string()
        }
        FaceFrom::MarkerSet { toe_measured: false } => "stated by the marker set's [face]; its turn about the normal \
                                                         ASSUMED (the toe level at address, the club file's lie): \
                                                         --shaft measures it"
            .to_string(),
    };
    eprintln!("face: {how}");
    let c = r.face_centre_body_m * 1e3;
    let n = r.face_normal_body;
    let centroid = fitter.set.body_m.iter().sum::<Vector3>() / fitter.set.len() as f64;
    eprintln!(
        "face centre in the body frame: ({:.1}, {:.1}, {:.1}) mm, {:.1} mm from the body's markers' centroid",
        c.x,
        c.y,
        c.z,
        (r.face_centre_body_m - centroid).norm() * 1e3
    );
    eprintln!("face normal in the body frame: ({:.4}, {:.4}, {:.4})", n.x, n.y, n.z);
    if r.face == FaceFrom::Assumed {
        eprintln!(
            "at address (assumed, not measured): loft {:.2} deg and lie {:.1} deg as the club file's, face angle 0; \
             marker fit residual {:.3} mm",
            club.loft_deg(),
            club.lie_deg,
            residual_m * 1e3
        );
    } else {
        eprintln!(
            "at address: loft {:.2} deg ({:+.2} deg against the club's {:.2}), lie {:+.2} deg against the club's \
             (toe up +), face angle {:+.2} deg; marker fit residual {:.3} mm",
            r.loft_deg,
            r.loft_deg - club.loft_deg(),
            club.loft_deg(),
            r.toe_up_deg,
            r.face_angle_deg,
            residual_m * 1e3
        );
    }
    if let Some((s, labels)) = shaft {
        eprintln!(
            "shaft at address ({}): lean {:+.2} deg (hands ahead +; the club frame's 0), lie {:.2} deg ({:+.2} deg \
             against the club's {:.1})",
            labels.join(", "),
            s.lean_deg,
            s.lie_deg,
            s.lie_deg - club.lie_deg,
            club.lie_deg
        );
        let off = s.lean_deg.abs().max((s.lie_deg - club.lie_deg).abs());
        if r.face == FaceFrom::Assumed && off > 1.0 {
            eprintln!(
                "the shaft is {off:.1} deg from the assumed square address: the assumed face is off by about as much; \
                 locate it (--face, --pointer or [face] in the marker set)"
            );
        }
    }
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
