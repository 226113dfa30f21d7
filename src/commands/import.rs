//! `impactd import CAPTURE.c3d --markers SET.toml --rig RIG -o samples.jsonl`: a C3D capture's marker
//! trajectories as clubhead samples (JSONL, one per frame), the marker set fitted to each frame.

use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::Args;
use impactd::daemon::recording::c3d::{self, CaptureSamples, ImportCounts};
use impactd::kinematics::{MarkerFitter, MarkerSet};

#[derive(Debug, Args)]
pub struct ImportArgs {
    /// A C3D capture.
    pub file: PathBuf,
    /// The marker set of the tracked body (TOML `[markers]`, metres in the body frame).
    #[arg(long)]
    pub markers: PathBuf,
    /// The rig the samples belong to.
    #[arg(long)]
    pub rig: String,
    /// The JSONL file of samples to write (`-`: standard output).
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    #[command(flatten)]
    pub fit: FitArgs,
}

/// The marker fit's flags, shared by `import` and `replay`.
#[derive(Debug, Clone, Args)]
pub struct FitArgs {
    /// A marker further than this from its fitted place is dropped as a swap or a ghost (mm).
    #[arg(long, default_value_t = 3.0)]
    pub reject_mm: f64,
}

impl FitArgs {
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
    let fitter = args.fit.fitter(&args.markers)?;
    let reader = c3d::open(&args.file).with_context(|| format!("{}", args.file.display()))?;
    for w in &reader.info.warnings {
        eprintln!("{}: warning: {w}", args.file.display());
    }
    let mut samples =
        CaptureSamples::new(reader, fitter, &args.rig).with_context(|| format!("{}", args.file.display()))?;
    let sink: Box<dyn Write> = if args.output.as_os_str() == "-" {
        Box::new(std::io::stdout().lock())
    } else {
        Box::new(std::fs::File::create(&args.output).with_context(|| format!("creating {}", args.output.display()))?)
    };
    let mut out = BufWriter::with_capacity(1 << 16, sink);
    while let Some(s) = samples.next_sample().with_context(|| format!("{}", args.file.display()))? {
        serde_json::to_writer(&mut out, &s)?;
        out.write_all(b"\n")?;
    }
    out.flush().with_context(|| format!("writing {}", args.output.display()))?;
    eprintln!("{}", describe(&samples.counts));
    Ok(ExitCode::SUCCESS)
}

/// One line on what an import saw.
pub fn describe(c: &ImportCounts) -> String {
    format!(
        "{} frames: {} occluded (fewer than 3 markers), {} with markers that disagree, {} markers rejected by their \
         residual",
        c.frames, c.occluded, c.inconsistent, c.rejected_markers
    )
}
