//! `impactd import CAPTURE --markers SET.toml --rig RIG -o samples.jsonl`: a capture as clubhead samples (JSONL,
//! one per frame): a marker capture's (C3D, TRC) marker set fitted to each frame, a pose table's rows as they are
//! (`--columns`); with a ball (`--ball-marker`, a pose table's `ball=` columns), a ball sample before each frame's
//! sample.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::Args;
use impactd::captures::{CaptureOptions, ImportCounts};
use impactd::kinematics::{MarkerFitter, MarkerSet};

#[derive(Debug, Args)]
#[command(after_help = super::capture_check::QUALITY_HELP)]
pub struct ImportArgs {
    /// A capture: C3D, TRC (OpenSim's marker trajectories) or a pose table (CSV/TSV with --columns).
    pub file: PathBuf,
    /// The marker set of the tracked body (TOML `[markers]`, metres in the body frame): for C3D and TRC.
    #[arg(long)]
    pub markers: Option<PathBuf>,
    /// The club (preset or .toml file) whose face centre places a pose table with `origin=face-centre`.
    #[arg(long)]
    pub club: Option<String>,
    #[command(flatten)]
    pub capture: CaptureArgs,
    /// The rig the samples belong to.
    #[arg(long)]
    pub rig: String,
    /// The JSONL file of samples to write (`-`: standard output).
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    #[command(flatten)]
    pub fit: FitArgs,
    /// The rigs' configuration (the rig named by --rig: its club, calibration and ball): the samples are run
    /// through its pipeline as they are written, each swing that gives no prediction says why, and a capture
    /// whose swings give none exits 2. Without it the swings are not checked.
    #[arg(short = 'c', long = "config")]
    pub config: Option<PathBuf>,
    #[command(flatten)]
    pub impact: super::capture_check::ImpactArgs,
}

/// What a capture is and how to read it, shared by `import` and `replay`.
#[derive(Debug, Clone, Args)]
pub struct CaptureArgs {
    /// The capture's format (c3d, trc, pose-table); default: from the file's first bytes, else its extension.
    #[arg(long, value_name = "FORMAT")]
    pub format: Option<String>,
    /// A pose table's columns: a spec `time=Time:s; position=X,Y,Z:mm; quaternion-xyzw=QX,QY,QZ,QW` (also
    /// `quaternion-wxyz=`, `matrix=R11,...,R33`, `euler-ZYX=A,B,C:deg`; `ball=BX,BY,BZ`, `origin=face-centre`,
    /// `frame=`, `rate=HZ`), or a file holding one; default: the table's sidecar TABLE.columns (docs/captures.md).
    #[arg(long, value_name = "SPEC|FILE")]
    pub columns: Option<String>,
    /// Read the capture's lengths in this unit (mm, cm, dm, m, in, ft) instead of the one it states (or for a
    /// TRC that states none); reported as an override.
    #[arg(long, value_name = "UNIT")]
    pub units: Option<String>,
}

impl CaptureArgs {
    /// The capture's format, or an error when the file is none.
    pub fn format(&self, file: &Path) -> Result<Option<&'static impactd::captures::Format>> {
        if let Some(u) = &self.units {
            impactd::captures::units::metres_per(u)?;
        }
        Ok(impactd::captures::format_of(file, self.format.as_deref())?)
    }

    /// The options of reading `rig`'s samples from a capture.
    pub fn options(
        &self,
        rig: &str,
        markers: Option<&Path>,
        fit: &FitArgs,
        face_centre_club_m: Option<impactd::math::Vector3>,
    ) -> Result<CaptureOptions> {
        Ok(CaptureOptions {
            rig: rig.to_string(),
            fitter: markers.map(|m| fit.fitter(m)).transpose()?,
            ball_marker: fit.ball()?.map(|(label, offset)| (label.to_string(), offset)),
            columns: self.columns.clone(),
            units: self.units.clone(),
            face_centre_club_m,
        })
    }
}

/// The marker fit's flags, shared by `import` and `replay`.
#[derive(Debug, Clone, Args)]
pub struct FitArgs {
    /// A marker further than this from its fitted place is dropped as a swap or a ghost (mm).
    #[arg(long, default_value_t = 3.0)]
    pub reject_mm: f64,
    /// A marker on the ball: each frame's position (plus --ball-offset-mm) is the rig's tracked ball, which sets
    /// each shot's ball position (written as `mocap/<rig>/ball` lines before the frame's sample).
    #[arg(long, value_name = "LABEL")]
    pub ball_marker: Option<String>,
    /// From the ball marker to the ball's centre, in the capture's lab axes (mm): `0,0,-28` for a 14 mm marker
    /// on top of a ball in a Z-up lab.
    #[arg(long, value_name = "X,Y,Z", value_delimiter = ',', allow_hyphen_values = true, requires = "ball_marker")]
    pub ball_offset_mm: Vec<f64>,
}

impl FitArgs {
    /// The ball marker's label and its offset to the ball's centre (lab, m), when one is given.
    pub fn ball(&self) -> Result<Option<(&str, impactd::math::Vector3)>> {
        let Some(label) = &self.ball_marker else { return Ok(None) };
        let offset = match self.ball_offset_mm.as_slice() {
            [] => [0.0; 3],
            [x, y, z] if [x, y, z].iter().all(|v| v.is_finite() && v.abs() <= 200.0) => [*x, *y, *z],
            _ => bail!("--ball-offset-mm takes three finite numbers within 200 mm"),
        };
        Ok(Some((label.as_str(), impactd::math::Vector3::from(offset) * 1e-3)))
    }

    pub fn fitter(&self, markers: &std::path::Path) -> Result<MarkerFitter> {
        if !(self.reject_mm.is_finite() && self.reject_mm > 0.0) {
            bail!("--reject-mm must be a positive number of millimetres");
        }
        let text = std::fs::read_to_string(markers).with_context(|| format!("reading {}", markers.display()))?;
        let set = MarkerSet::from_toml(&text).with_context(|| format!("{}", markers.display()))?;
        Ok(MarkerFitter::new(set).with_reject_m(self.reject_mm * 1e-3))
    }
}

pub fn run(args: &ImportArgs) -> Result<ExitCode> {
    if !impactd::wire::keys::valid_rig_name(&args.rig) {
        bail!("--rig {}: a rig name is letters, digits, _ or -", args.rig);
    }
    let Some(format) = args.capture.format(&args.file)? else {
        bail!(
            "{} is not a capture: import reads {} (give --format for a file named otherwise)",
            args.file.display(),
            impactd::captures::format_names()
        );
    };
    let face_centre = match &args.club {
        Some(c) => Some(super::args::load_club(c)?.club.face.center_m),
        None => None,
    };
    let options = args.capture.options(&args.rig, args.markers.as_deref(), &args.fit, face_centre)?;
    let mut samples = (format.open)(&args.file, &options).with_context(|| format!("{}", args.file.display()))?;
    for w in samples.warnings() {
        eprintln!("{}: warning: {w}", args.file.display());
    }
    let sink: Box<dyn Write> = if args.output.as_os_str() == "-" {
        Box::new(std::io::stdout().lock())
    } else {
        Box::new(std::fs::File::create(&args.output).with_context(|| format!("creating {}", args.output.display()))?)
    };
    let mut check = check_pipeline(args)?;
    let mut tally = (0u64, 0u64, 0u64);
    let mut on_event = |e: impactd::pipeline::Event| {
        match &e {
            impactd::pipeline::Event::Launch(_) => tally.0 += 1,
            impactd::pipeline::Event::Failed { .. } => tally.1 += 1,
            impactd::pipeline::Event::Missed(_) => tally.2 += 1,
            _ => {}
        }
        for line in super::capture_check::describe(&e, &|_| Vec::new()) {
            eprintln!("{line}");
        }
    };
    let mut out = BufWriter::with_capacity(1 << 16, sink);
    while let Some(s) = samples.next_sample().with_context(|| format!("{}", args.file.display()))? {
        if let Some(ball) = samples.ball() {
            serde_json::to_writer(&mut out, &ball)?;
            out.write_all(b"\n")?;
            if let Some(p) = &mut check {
                let _ = p.on_ball((!ball.occluded).then_some(ball.position_m));
            }
        }
        serde_json::to_writer(&mut out, &s)?;
        out.write_all(b"\n")?;
        if let Some(p) = &mut check {
            p.on_sample_with(&s.to_sample(), &mut on_event);
        }
    }
    out.flush().with_context(|| format!("writing {}", args.output.display()))?;
    eprintln!("{}", describe(samples.counts(), format));
    let Some(mut p) = check else {
        eprintln!("swings not checked: import with -c CONFIG (or replay the samples) for their launches");
        return Ok(ExitCode::SUCCESS);
    };
    p.finish(&mut on_event);
    let (predictions, failed, missed) = tally;
    eprintln!("checked with rig {}: {predictions} predictions, {failed} failed, {missed} swings missed", args.rig);
    Ok(super::capture_check::nothing_predicted(predictions, failed, missed).unwrap_or(ExitCode::SUCCESS))
}

/// The pipeline of the rig named by --rig in the -c configuration, with the given impact instant.
fn check_pipeline(args: &ImportArgs) -> Result<Option<impactd::pipeline::Pipeline>> {
    let Some(path) = &args.config else {
        if args.impact.given()?.is_some() {
            bail!("--impact-frame and --impact-time check the capture's swings: they need -c CONFIG");
        }
        return Ok(None);
    };
    let (_, mut setups) = impactd::daemon::DaemonConfig::load(path)?;
    args.impact.apply(&mut setups)?;
    let names: Vec<String> = setups.iter().map(|s| s.name.clone()).collect();
    let Some(setup) = setups.into_iter().find(|s| s.name == args.rig) else {
        bail!("--rig {}: {} has no such rig (rigs: {})", args.rig, path.display(), names.join(", "));
    };
    Ok(Some(impactd::pipeline::Pipeline::new(setup)))
}

/// The `[shaft]` the marker set file at `markers` names (empty when it names none).
pub fn stated_shaft(markers: &Path) -> Result<impactd::kinematics::StatedShaft> {
    let text = std::fs::read_to_string(markers).with_context(|| format!("reading {}", markers.display()))?;
    MarkerSet::shaft_from_toml(&text).with_context(|| format!("{}", markers.display()))
}

/// One line on what an import saw.
pub fn describe(c: &ImportCounts, format: &impactd::captures::Format) -> String {
    if format.markers.is_none() {
        return format!("{} rows: {} occluded (empty position or orientation cells)", c.frames, c.occluded);
    }
    format!(
        "{} frames: {} occluded (fewer than 3 valid markers; {} of them after rejecting markers by their residual), {} \
         markers rejected by their residual",
        c.frames, c.occluded, c.occluded_by_rejection, c.rejected_markers
    )
}
