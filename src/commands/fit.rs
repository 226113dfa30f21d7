//! `impactd fit --model M --club C FILE... [--params LIST] [--seed K] [--folds K] -o fitted.toml`: identifies a
//! model's parameters by minimising eq. 3.13 over measured shots (differential evolution within the parameters'
//! bounds, then Nelder-Mead; parallel over shots; deterministic for a seed), reports k-fold cross-validated
//! errors before and after, and writes the club file with the fitted section, which `predict --club` and `run`
//! accept. A progress bar with the best cost on a terminal, plain lines otherwise. `--objective likelihood`
//! minimises the launch monitor's noise likelihood instead (weighted least squares with `--noise`, or with the
//! noise estimated from the residuals; identify::objective), which reaches the Cramér-Rao bound where eq. 3.13
//! scatters more (docs/identify.md).

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use clap::Args;
use impactd::equipment::BallSpec;
use impactd::impact::Equipment;
use impactd::offline::identify::club_toml::to_toml;
use impactd::offline::identify::dataset::resolve;
use impactd::offline::identify::fit::{run as fit_run, FitOptions, FitReport, LocalMethod};
use impactd::offline::identify::{FitModel, Objective, ParamSpace, FIELDS};

#[derive(Debug, Args)]
pub struct FitArgs {
    /// The model whose parameters to identify: one with identifiable parameters (`impactd models` names them).
    #[arg(long)]
    pub model: String,
    /// Club preset or club file: the starting parameters (its section, else the seed's).
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// JSONL datasets, TrackMan CSV exports, TrackMan report JSON or MCAP recordings with measured shots.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// The parameters to fit, comma-separated (default: all of the model's).
    #[arg(long, value_delimiter = ',')]
    pub params: Vec<String>,
    /// Seed of the search and of the folds (same seed, same result).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Cross-validation folds (0: none).
    #[arg(long, default_value_t = 5, value_parser = super::checked::count_or_zero_usize)]
    pub folds: usize,
    /// Differential evolution population (default: 10 per parameter, at least 20).
    #[arg(long, value_parser = super::checked::count_usize)]
    pub population: Option<usize>,
    /// Generations of the global search.
    #[arg(long, default_value_t = 100, value_parser = super::checked::count_or_zero_usize)]
    pub generations: usize,
    /// Passes over the shots of the local search after the global one, at most (it stops sooner when the cost
    /// no longer falls).
    #[arg(long, default_value_t = 400, value_parser = super::checked::count_or_zero_usize)]
    pub local_evaluations: usize,
    /// The local search: Levenberg-Marquardt on the residuals (default for a model resolved in time) or
    /// Nelder-Mead (default otherwise).
    #[arg(long, value_enum)]
    pub local: Option<LocalArg>,
    /// Run the global search in every cross-validation fold too (default only for a model without a coarse
    /// step; a model resolved in time starts each fold's local search from the fit on all shots).
    #[arg(long)]
    pub fold_global: bool,
    /// Shots the global search evaluates (a seeded subsample; default all, 150 for a model resolved in time).
    #[arg(long, value_parser = super::checked::count_usize)]
    pub global_shots: Option<usize>,
    /// Integrate the global search at the exact step too (default: 4 x coarser for a model resolved in time).
    #[arg(long)]
    pub exact_global: bool,
    /// Stop the global search when its best cost gains under 0.1 % in this many generations (0: never).
    #[arg(long, default_value_t = 10, value_parser = super::checked::count_or_zero_usize)]
    pub stall_generations: usize,
    /// What to minimise: eq. 3.13's least-absolute criterion (the seed's), or the likelihood of the launch
    /// monitor's noise (normal, independent per field).
    #[arg(long, value_enum, default_value_t = ObjectiveArg::LeastAbsolute)]
    pub objective: ObjectiveArg,
    /// With --objective likelihood: the noise's standard deviation per field, ball speed (mph), launch (deg),
    /// direction (deg), backspin (rpm), sidespin (rpm), e.g. synth's default 0.5,0.2,0.3,150,150; without it
    /// the noise is estimated from the residuals (the profile likelihood).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub noise: Option<Vec<f64>>,
    /// Where to write the fitted club file.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Replace the -o file if it exists.
    #[arg(long, requires = "output")]
    pub overwrite: bool,
    /// The report as one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// `--local`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum LocalArg {
    /// Nelder-Mead's simplex (derivative-free).
    NelderMead,
    /// Levenberg-Marquardt steps on the reweighted residuals (finite-difference Jacobian).
    #[value(name = "levenberg-marquardt", alias = "lm")]
    LevenbergMarquardt,
}

/// `--objective`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ObjectiveArg {
    /// Eq. 3.13: mean absolute errors over the measured means (the seed's).
    #[value(name = "least-absolute", alias = "eq-3.13")]
    LeastAbsolute,
    /// The launch monitor's noise likelihood (weighted least squares).
    Likelihood,
}

fn objective(args: &FitArgs) -> Result<Objective> {
    let noise = match &args.noise {
        Some(v) if v.len() == 5 => Some([v[0], v[1], v[2], v[3], v[4]]),
        Some(v) => bail!("--noise: expected 5 standard deviations, got {}", v.len()),
        None => None,
    };
    match args.objective {
        ObjectiveArg::LeastAbsolute if noise.is_some() => bail!("--noise needs --objective likelihood"),
        ObjectiveArg::LeastAbsolute => Ok(Objective::LeastAbsolute),
        ObjectiveArg::Likelihood => Ok(Objective::likelihood(noise)?),
    }
}

pub fn run(args: &FitArgs) -> Result<ExitCode> {
    if let Some(path) = args.output.as_ref().filter(|p| !args.overwrite && p.exists()) {
        anyhow::bail!("{} exists; choose a new name or pass --overwrite", path.display());
    }
    let objective = objective(args)?;
    let model = FitModel::parse(&args.model)?;
    let space = ParamSpace::new(model, &args.params)?;
    let loaded = super::compare::load_files(&args.files)?;
    if loaded.lines.is_empty() {
        bail!("no measured shots in the files");
    }
    let club = super::args::load_club(&args.club)?;
    let ball = BallSpec::SEED;
    let shots = resolve(&loaded.lines, &Equipment { club: club.club.clone(), ball })?;
    let options = FitOptions {
        seed: args.seed,
        folds: args.folds,
        population: args.population,
        generations: args.generations,
        local_evaluations: args.local_evaluations,
        local: args.local.map(|l| match l {
            LocalArg::NelderMead => LocalMethod::NelderMead,
            LocalArg::LevenbergMarquardt => LocalMethod::LevenbergMarquardt,
        }),
        fold_global: args.fold_global.then_some(true),
        global_shots: args.global_shots,
        coarse_global: !args.exact_global,
        stall_generations: args.stall_generations,
        objective,
    };
    let bar = std::io::stderr().is_terminal().then(|| {
        let b = indicatif::ProgressBar::new_spinner();
        b.enable_steady_tick(Duration::from_millis(200));
        b
    });
    let mut last_line = Instant::now();
    let started = Instant::now();
    let (report, fitted) = fit_run(&space, &club, &ball, &shots, &options, &mut |phase, p| {
        let line = format!(
            "{phase}: {} {}/{} best cost {:.5} ({} evaluations, {:.0} s)",
            p.stage,
            p.step,
            p.steps,
            p.best_cost,
            p.evaluations,
            started.elapsed().as_secs_f64()
        );
        match &bar {
            Some(b) => b.set_message(line),
            None if last_line.elapsed() >= Duration::from_secs(5) => {
                eprintln!("{line}");
                last_line = Instant::now();
            }
            None => {}
        }
    })?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    // Regression: `fit --model maw` ended at its bounds and said nothing.
    for warning in at_bounds(&report) {
        eprintln!("impactd fit: warning: {warning}");
    }
    if let Some(path) = &args.output {
        let comment = format!(
            "{} parameters fitted by `impactd fit` (objective {}; eq. 3.13 over {} shots: {:.5} -> {:.5}, seed {})",
            report.model, report.objective, report.shots, report.cost_before, report.cost, report.seed
        );
        let text = to_toml(&fitted, &comment)?;
        let mut file = impactd::output_file::create_output(path, args.overwrite)?;
        file.write_all(text.as_bytes())
            .and_then(|()| file.sync_all())
            .with_context(|| format!("writing {}", path.display()))?;
        eprintln!("wrote {}", path.display());
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", render(&report));
    }
    Ok(ExitCode::SUCCESS)
}

/// The parameters that ended on (within 0.1 % of the span of) a bound: the data would have moved them further,
/// so the fit is the bound's, not the data's.
fn at_bounds(r: &FitReport) -> Vec<String> {
    r.params
        .iter()
        .filter_map(|p| {
            let tolerance = 1e-3 * (p.hi - p.lo).abs();
            let side = if (p.fitted - p.lo).abs() <= tolerance {
                "lower"
            } else if (p.hi - p.fitted).abs() <= tolerance {
                "upper"
            } else {
                return None;
            };
            Some(format!(
                "{} ended at its {side} bound ({:.5} {}, bounds [{:.4}, {:.4}]): the fit is the bound's, not the data's; \
                 widen the bounds or question the model",
                p.name, p.fitted, p.unit, p.lo, p.hi
            ))
        })
        .collect()
}

fn render(r: &FitReport) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} on {} ({} shots, seed {}, objective {} {:.5}): eq. 3.13 {:.5} -> {:.5} ({} evaluations, {} impacts, \
         {:.1} s; cross-validation {} impacts, {:.1} s)",
        r.model,
        r.club,
        r.shots,
        r.seed,
        r.objective,
        r.objective_value,
        r.cost_before,
        r.cost,
        r.evaluations,
        r.simulations,
        r.fit_seconds,
        r.cv_simulations,
        r.cv_seconds
    );
    let _ = writeln!(
        s,
        "{:<18} {:>12} {:>12} {:>12} {:>12} {:>12} {:>24}",
        "parameter", "start", "fitted", "CRB", "CRB alone", "eq. 3.13 SD", "bounds"
    );
    let or_flat = |v: Option<f64>| v.map_or("flat".to_string(), |v| format!("{v:.5}"));
    for p in &r.params {
        let bounds = format!("[{:.4}, {:.4}]", p.lo, p.hi);
        let (joint, alone, scatter) = (or_flat(p.std_error), or_flat(p.std_error_alone), or_flat(p.scatter));
        let _ = writeln!(
            s,
            "{:<18} {:>12.5} {:>12.5} {joint:>12} {alone:>12} {scatter:>12} {bounds:>24} {}",
            p.name, p.start, p.fitted, p.unit
        );
    }
    if let Some(cv) = &r.cv {
        let _ = writeln!(s, "{}-fold cross-validated MAE (held-out shots): before -> after", cv.folds);
        for (i, (_, label)) in FIELDS.iter().enumerate() {
            let _ = writeln!(s, "  {label:<16} {:>9.3} -> {:>9.3}", cv.before[i].mae, cv.after[i].mae);
        }
        let _ = writeln!(s, "  {:<16} {:>9.5} -> {:>9.5}", "eq. 3.13", cv.cost_before, cv.cost_after);
    }
    s
}
