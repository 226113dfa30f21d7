//! The `impactd` command line (clap). `main` only parses and calls [`run`].

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::equipment::ClubSpec;
use crate::impact::{DeliveryMetrics, Equipment, ImpactError, ImpactModel, ImpulseModel, ImpulseVariant};
use crate::wire::{DeliveryInput, PredictOutput};

/// Predicts golf ball launch conditions from motion-capture samples of the clubhead.
#[derive(Debug, Parser)]
#[command(name = "impactd", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

impl Cli {
    /// Whether this is `impactd demo` (which prints its own lines instead of logging).
    pub fn is_demo(&self) -> bool {
        #[cfg(feature = "daemon")]
        if matches!(self.command, Command::Demo(_)) {
            return true;
        }
        false
    }
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// JSONL deliveries in (stdin or --input), JSONL launch conditions out.
    Predict(PredictArgs),
    /// Times each model in-process on a fixed spread of deliveries.
    Bench(BenchArgs),
    /// Evaluations against synthetic truth.
    #[command(subcommand)]
    Eval(EvalCommand),
    /// JSONL launches in (the fields `impactd predict` writes), JSONL trajectories out.
    Flight(FlightArgs),
    /// Refit the flight model's coefficients to the TrackMan tour averages and show the fit.
    FlightFit {
        /// Nelder-Mead iterations per restart, from `flight::fit::START`, before the minimax stage (0: show the
        /// errors of `Aero::FITTED`).
        #[arg(long, default_value_t = 3000)]
        iterations: usize,
    },
    /// A heatmap over the clubface (SVG) of a launch or flight number, for a delivery given by flags.
    Map(MapArgs),
    /// Pictures (SVG).
    #[command(subcommand)]
    Plot(PlotCommand),
    /// Write the JSON Schemas of every message type.
    Schemas {
        /// Directory to write `<Type>.json` into.
        #[arg(short = 'o', long = "output", default_value = "schemas")]
        output: PathBuf,
    },
    /// The daemon: clubhead samples in on zenoh, predictions out, everything recorded.
    #[cfg(feature = "daemon")]
    Run(crate::cli_daemon::RunArgs),
    /// The daemon and a simulated rig in one process: zero setup.
    #[cfg(feature = "daemon")]
    Demo(crate::cli_daemon::DemoArgs),
    /// A synthetic rig publishing clubhead samples at real rate, with the truth of each shot.
    #[cfg(feature = "daemon")]
    Sim(crate::cli_daemon::SimArgs),
    /// The pipeline over a recording (MCAP) or a JSONL file of samples.
    #[cfg(feature = "daemon")]
    Replay(crate::cli_daemon::ReplayArgs),
    /// Channels, counts, duration and shots of a recording.
    #[cfg(feature = "daemon")]
    Info { file: PathBuf },
    /// Salvage a recording cut off by a crash (exit 0: nothing lost, 3: data lost).
    #[cfg(feature = "daemon")]
    Recover(crate::cli_daemon::RecoverArgs),
}

#[derive(Debug, Subcommand)]
pub enum PlotCommand {
    /// The continuous model's normal and tangential force and the ball's spin through one impact.
    Forces(ForcesArgs),
    /// Side and top views of one or more shots: JSONL launches in (stdin or --input).
    Trajectory(TrajectoryArgs),
}

/// Where and in what air the ball flies.
#[derive(Debug, Clone, Args)]
pub struct ConditionArgs {
    #[arg(long, default_value_t = 22.5, allow_hyphen_values = true)]
    pub temp_c: f64,
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub altitude_m: f64,
    /// Relative humidity, 0-1.
    #[arg(long, default_value_t = 0.5)]
    pub humidity: f64,
    /// Station pressure (hPa); default: the standard atmosphere at the altitude.
    #[arg(long)]
    pub pressure_hpa: Option<f64>,
    #[arg(long, default_value_t = 0.0)]
    pub wind_mps: f64,
    /// The direction the wind blows toward (deg from the target line, right +): 0 tailwind, 180 headwind.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub wind_dir_deg: f64,
}

impl ConditionArgs {
    pub fn conditions(&self) -> Result<crate::flight::Conditions> {
        let c = crate::flight::Conditions {
            temperature_c: self.temp_c,
            pressure_hpa: self.pressure_hpa,
            humidity: self.humidity,
            altitude_m: self.altitude_m,
            wind_mps: self.wind_mps,
            wind_dir_deg: self.wind_dir_deg,
        };
        c.validate().map_err(|e| anyhow::anyhow!("conditions: {e}"))?;
        Ok(c)
    }
}

#[derive(Debug, Args)]
pub struct FlightArgs {
    #[command(flatten)]
    pub conditions: ConditionArgs,
    /// Also output the path, sampled every this many seconds.
    #[arg(long)]
    pub points_s: Option<f64>,
    #[arg(long, short)]
    pub input: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct TrajectoryArgs {
    #[command(flatten)]
    pub conditions: ConditionArgs,
    #[arg(long, short)]
    pub input: Option<PathBuf>,
    #[arg(short = 'o', long = "output", default_value = "trajectory.svg")]
    pub output: PathBuf,
}

/// What `impactd map` colours the face by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MapMetric {
    BallSpeed,
    Launch,
    Backspin,
    Sidespin,
    Carry,
    Offline,
}

#[derive(Debug, Args)]
pub struct MapArgs {
    #[arg(long, default_value = "driver")]
    pub club: String,
    #[arg(long, value_enum, default_value = "adjusted")]
    pub model: ModelName,
    #[arg(long, value_enum, default_value = "ball-speed")]
    pub metric: MapMetric,
    #[command(flatten)]
    pub delivery: DeliveryArgs,
    /// Grid cells along each face axis.
    #[arg(long, default_value_t = 21)]
    pub cells: usize,
    #[arg(short = 'o', long = "output", default_value = "map.svg")]
    pub output: PathBuf,
}

#[derive(Debug, Args)]
pub struct ForcesArgs {
    #[arg(long, default_value = "driver")]
    pub club: String,
    #[command(flatten)]
    pub delivery: DeliveryArgs,
    /// Output SVG file.
    #[arg(short = 'o', long = "output", default_value = "forces.svg")]
    pub output: PathBuf,
}

#[derive(Debug, Subcommand)]
pub enum EvalCommand {
    /// Synthetic swings through every impact-state estimator: errors of the delivery and of the launch.
    Extrapolation(ExtrapolationArgs),
}

#[derive(Debug, Args)]
pub struct ExtrapolationArgs {
    /// Club preset or club file.
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// Capture rate (Hz).
    #[arg(long, default_value_t = 720.0)]
    pub rate: f64,
    /// Number of swings.
    #[arg(long, default_value_t = 1000)]
    pub shots: usize,
    /// Gaussian position noise per axis (mm).
    #[arg(long, default_value_t = 0.2)]
    pub noise_mm: f64,
    /// Gaussian orientation noise per axis (deg).
    #[arg(long, default_value_t = 0.1)]
    pub noise_deg: f64,
    /// Gaussian timestamp jitter (us).
    #[arg(long, default_value_t = 0.0)]
    pub jitter_us: f64,
    /// Probability that a frame is dropped.
    #[arg(long, default_value_t = 0.0)]
    pub drop: f64,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Estimators to compare (comma-separated).
    #[arg(long, value_delimiter = ',', default_value = "linear2,poly,arc")]
    pub estimators: Vec<String>,
    /// Shape of the swings' path before impact: an arc (the `arc` estimator's own model) or a double pendulum
    /// (arm and club, the wrist uncocking).
    #[arg(long, value_enum, default_value_t = PathArg::Arc)]
    pub path: PathArg,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
}

/// `--path` of `impactd eval extrapolation`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PathArg {
    Arc,
    DoublePendulum,
}

/// Impact models selectable on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ModelName {
    Standard,
    Adjusted,
    Slip,
    Continuous,
}

/// A model chosen on the command line.
pub enum Model {
    Impulse(ImpulseModel),
    Continuous(crate::impact::ContinuousModel),
}

impl Model {
    pub fn new(name: ModelName, cor: f64) -> Self {
        match name {
            ModelName::Standard => Model::Impulse(ImpulseModel::new(ImpulseVariant::Standard).with_cor(cor)),
            ModelName::Adjusted => Model::Impulse(ImpulseModel::new(ImpulseVariant::Adjusted).with_cor(cor)),
            ModelName::Slip => Model::Impulse(ImpulseModel::new(ImpulseVariant::Slip).with_cor(cor)),
            ModelName::Continuous => Model::Continuous(crate::impact::ContinuousModel::default()),
        }
    }

    pub fn as_dyn(&self) -> &dyn ImpactModel {
        match self {
            Model::Impulse(m) => m,
            Model::Continuous(m) => m,
        }
    }
}

/// A delivery given with flags (TrackMan names; unset numbers are 0, the loft the club's).
#[derive(Debug, Clone, Args)]
pub struct DeliveryArgs {
    #[arg(long, default_value_t = 100.0)]
    pub club_speed_mph: f64,
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub attack_angle_deg: f64,
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub club_path_deg: f64,
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub face_angle_deg: f64,
    #[arg(long, allow_hyphen_values = true)]
    pub dynamic_loft_deg: Option<f64>,
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub impact_h_mm: f64,
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
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
        }
    }
}

#[derive(Debug, Args)]
pub struct PredictArgs {
    /// Club preset (driver, iron7) or a path to a club .toml file.
    #[arg(long, default_value = "driver")]
    pub club: String,
    /// Impact model.
    #[arg(long, value_enum, default_value = "adjusted")]
    pub model: ModelName,
    /// Coefficient of restitution along the face normal (seed eq. 3.6).
    #[arg(long, default_value_t = crate::impact::impulse::DEFAULT_COR)]
    pub cor: f64,
    /// Read deliveries from this file instead of stdin.
    #[arg(long, short)]
    pub input: Option<PathBuf>,
    /// With the continuous model: add the normal and tangential force and the ball's spin over time.
    #[arg(long)]
    pub trace: bool,
}

#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Print JSON (`{"stages": [{"name", "ns_per_op"}]}`) instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Only stages whose name contains this.
    #[arg(long)]
    pub filter: Option<String>,
}

/// Loads a club preset by name or a club file by path.
pub fn load_club(spec: &str) -> Result<ClubSpec> {
    let path = Path::new(spec);
    if spec.ends_with(".toml") || path.exists() {
        let text = std::fs::read_to_string(path).with_context(|| format!("reading club file {spec}"))?;
        ClubSpec::from_toml_str(&text).with_context(|| format!("club file {spec}"))
    } else {
        Ok(ClubSpec::preset(spec)?)
    }
}

fn open_input(path: Option<&Path>) -> Result<Box<dyn BufRead>> {
    Ok(match path {
        Some(p) => {
            Box::new(BufReader::new(std::fs::File::open(p).with_context(|| format!("opening input {}", p.display()))?))
        }
        None => Box::new(BufReader::new(std::io::stdin())),
    })
}

/// The field a prediction error is about, so the message can name it.
fn describe(err: &ImpactError, input: &DeliveryInput) -> String {
    match err {
        ImpactError::SpeedOutOfRange { speed_mps } => {
            format!("field `club_speed_mph`: {:.1} mph ({speed_mps:.1} m/s) is outside 1-100 m/s", input.club_speed_mph)
        }
        ImpactError::OffFace { .. } | ImpactError::Face(_) => {
            format!("fields `impact_h_mm`/`impact_v_mm`: {err}")
        }
        ImpactError::NotFinite { field } => format!("field `{field}`: must be a finite number"),
        ImpactError::NotApproaching => {
            format!("fields `club_path_deg`/`face_angle_deg`/`dynamic_loft_deg`: {err}")
        }
        other => other.to_string(),
    }
}

/// A `predict --trace` answer: the launch, then the contact's course.
#[derive(serde::Serialize)]
struct TracedOutput {
    #[serde(flatten)]
    output: PredictOutput,
    contact_time_us: f64,
    peak_normal_force_n: f64,
    trace: Vec<crate::impact::continuous::TracePoint>,
}

#[derive(serde::Serialize)]
#[serde(untagged)]
enum Answer {
    Plain(PredictOutput),
    Traced(TracedOutput),
}

fn predict(args: &PredictArgs) -> Result<ExitCode> {
    if !(0.0..=1.0).contains(&args.cor) {
        bail!("--cor must be within 0 and 1, got {}", args.cor);
    }
    let club = load_club(&args.club)?;
    let equipment = Equipment::new(club.clone());
    if args.trace && args.model != ModelName::Continuous {
        bail!("--trace needs --model continuous");
    }
    let model = Model::new(args.model, args.cor);
    let input = open_input(args.input.as_deref())?;
    let stdout = std::io::stdout().lock();
    let stderr = std::io::stderr().lock();
    let tally = crate::jsonl::process("impactd predict", input, stdout, stderr, |d: DeliveryInput| {
        d.check_finite().map_err(|e| describe(&e, &d))?;
        let delivery = d.to_delivery(club.loft_deg());
        let state = delivery.to_state(&equipment).map_err(|e| describe(&e, &d))?;
        let metrics = DeliveryMetrics::from_state(&state, &club);
        let hand = d.handedness.unwrap_or_default();
        match (&model, args.trace) {
            (Model::Continuous(m), true) => {
                let r = m.simulate(&state, &equipment, 10).map_err(|e| describe(&e, &d))?;
                Ok(Answer::Traced(TracedOutput {
                    output: PredictOutput::new(&r.launch, &metrics, hand, &equipment),
                    contact_time_us: r.contact_time_s * 1e6,
                    peak_normal_force_n: r.peak_normal_force_n,
                    trace: r.trace,
                }))
            }
            _ => {
                let launch = model.as_dyn().predict(&state, &equipment).map_err(|e| describe(&e, &d))?;
                Ok(Answer::Plain(PredictOutput::new(&launch, &metrics, hand, &equipment)))
            }
        }
    })?;
    Ok(if tally.rejected > 0 { ExitCode::from(1) } else { ExitCode::SUCCESS })
}

fn bench(args: &BenchArgs) -> Result<ExitCode> {
    let mut stages = crate::stages::all_stages();
    if let Some(f) = &args.filter {
        stages.retain(|s| s.name.contains(f.as_str()));
    }
    let mut results = Vec::new();
    let mut err = std::io::stderr().lock();
    for stage in &mut stages {
        if !args.json {
            let _ = write!(err, "timing {} ...\r", stage.name);
        }
        let ns = crate::stages::time_stage(stage, 15, 40);
        results.push(serde_json::json!({ "name": stage.name, "ns_per_op": ns }));
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::json!({ "stages": results }))?;
    } else {
        writeln!(out, "{:<36} {:>14}", "stage", "median/op")?;
        for r in &results {
            let ns = r["ns_per_op"].as_f64().unwrap_or(f64::NAN);
            let shown = if ns < 1e3 {
                format!("{ns:.0} ns")
            } else if ns < 1e6 {
                format!("{:.2} us", ns / 1e3)
            } else {
                format!("{:.2} ms", ns / 1e6)
            };
            writeln!(out, "{:<36} {:>14}", r["name"].as_str().unwrap_or(""), shown)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn eval_extrapolation(args: &ExtrapolationArgs) -> Result<ExitCode> {
    if !(args.rate >= 60.0 && args.rate <= 10_000.0) {
        bail!("--rate must be within 60 and 10000 Hz, got {}", args.rate);
    }
    if args.noise_mm < 0.0 || args.noise_deg < 0.0 || args.jitter_us < 0.0 || !(0.0..1.0).contains(&args.drop) {
        bail!("noise, jitter and drop probability must not be negative (drop below 1)");
    }
    let estimators = args
        .estimators
        .iter()
        .map(|n| {
            crate::kinematics::EstimatorSpec::by_name(n).with_context(|| {
                format!("unknown estimator '{n}' (known: {})", crate::kinematics::EstimatorSpec::NAMES.join(", "))
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let config = crate::eval::EvalConfig {
        club: load_club(&args.club)?,
        rate_hz: args.rate,
        shots: args.shots,
        noise_mm: args.noise_mm,
        noise_deg: args.noise_deg,
        jitter_us: args.jitter_us,
        drop_probability: args.drop,
        seed: args.seed,
        estimators,
        path: match args.path {
            PathArg::Arc => crate::swing::SwingPath::Arc,
            PathArg::DoublePendulum => crate::swing::SwingPath::DoublePendulum,
        },
    };
    let mut err = std::io::stderr().lock();
    let step = (args.shots / 20).max(1);
    let report = crate::eval::run(&config, |done| {
        if done % step == 0 || done == args.shots {
            let _ = write!(err, "\r{done}/{} swings", args.shots);
            if done == args.shots {
                let _ = writeln!(err);
            }
        }
    });
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string(&report)?)?;
        return Ok(ExitCode::SUCCESS);
    }
    writeln!(
        out,
        "{} at {} Hz, {} swings on {} paths, noise {} mm / {} deg, seed {}",
        report.club,
        report.rate_hz,
        report.shots,
        report.path.name(),
        report.noise_mm,
        report.noise_deg,
        report.seed
    )?;
    write!(out, "{:<22}", "error (est - truth)")?;
    for e in &report.estimators {
        write!(out, " {:>21}", format!("{} rms / max", e.name))?;
    }
    writeln!(out)?;
    for (k, key) in report.estimators[0].errors.entries().iter().map(|(k, _)| *k).enumerate() {
        write!(out, "{key:<22}")?;
        for e in &report.estimators {
            let s = e.errors.entries()[k].1;
            write!(out, " {:>10} / {:>8}", format!("{:.4}", s.rms), format!("{:.3}", s.max))?;
        }
        writeln!(out)?;
    }
    for e in &report.estimators {
        if !e.refused.is_empty() {
            writeln!(out, "{}: {} estimated, refused {:?}", e.name, e.shots, e.refused)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn plot_forces(args: &ForcesArgs) -> Result<ExitCode> {
    let club = load_club(&args.club)?;
    let equipment = Equipment::new(club.clone());
    let input = args.delivery.input();
    input.check_finite().map_err(|e| anyhow::anyhow!(describe(&e, &input)))?;
    let state =
        input.to_delivery(club.loft_deg()).to_state(&equipment).map_err(|e| anyhow::anyhow!(describe(&e, &input)))?;
    let r = crate::impact::ContinuousModel::default().simulate(&state, &equipment, 2)?;
    let m = crate::impact::LaunchMetrics::from_ball(&r.launch.ball_velocity_mps, &r.launch.ball_spin_radps);
    let chart = crate::plot::LineChart {
        title: format!(
            "{} at {:.0} mph: contact {:.0} us, peak {:.1} kN; ball {:.1} mph, {:.0} rpm",
            club.name,
            input.club_speed_mph,
            r.contact_time_s * 1e6,
            r.peak_normal_force_n / 1e3,
            m.ball_speed_mph,
            m.total_spin_rpm
        ),
        x_label: "time from first contact (us)".into(),
        y_label: "force on the ball (N)".into(),
        y2_label: Some("ball spin (rpm)".into()),
        series: vec![
            crate::plot::Series {
                name: "normal force".into(),
                points: r.trace.iter().map(|p| (p.t_us, p.normal_force_n)).collect(),
                color: crate::plot::PALETTE[0],
                right_axis: false,
            },
            crate::plot::Series {
                name: "tangential force (+ along the face's slip)".into(),
                points: r.trace.iter().map(|p| (p.t_us, p.tangential_force_n)).collect(),
                color: crate::plot::PALETTE[1],
                right_axis: false,
            },
            crate::plot::Series {
                name: "ball spin (right axis)".into(),
                points: r.trace.iter().map(|p| (p.t_us, p.ball_spin_rpm)).collect(),
                color: crate::plot::PALETTE[2],
                right_axis: true,
            },
            crate::plot::Series {
                name: "cover spin (right axis)".into(),
                points: r.trace.iter().map(|p| (p.t_us, p.cover_spin_rpm)).collect(),
                color: crate::plot::PALETTE[3],
                right_axis: true,
            },
        ],
        equal_axes: false,
    };
    std::fs::write(&args.output, chart.svg(900.0, 520.0))
        .with_context(|| format!("writing {}", args.output.display()))?;
    eprintln!("wrote {}", args.output.display());
    Ok(ExitCode::SUCCESS)
}

fn flight(args: &FlightArgs) -> Result<ExitCode> {
    let flight = crate::flight::Flight { conditions: args.conditions.conditions()?, ..Default::default() };
    let every = args.points_s.unwrap_or(0.0);
    if every < 0.0 || !every.is_finite() {
        bail!("--points-s must be positive");
    }
    let input = open_input(args.input.as_deref())?;
    let tally = crate::jsonl::process(
        "impactd flight",
        input,
        std::io::stdout().lock(),
        std::io::stderr().lock(),
        |l: crate::wire::FlightInput| Ok(flight.fly(&l.to_launch()?, every)),
    )?;
    Ok(if tally.rejected > 0 { ExitCode::from(1) } else { ExitCode::SUCCESS })
}

fn flight_fit(iterations: usize) -> Result<ExitCode> {
    use crate::flight::fit;
    let rows = fit::parse_table(fit::TRACKMAN_CSV).map_err(|e| anyhow::anyhow!("TrackMan table: {e}"))?;
    let current = crate::flight::Aero::FITTED;
    let (aero, cost, worst) = if iterations == 0 {
        (current, fit::cost(&current, &rows), fit::worst(&current, &rows))
    } else {
        eprintln!("fitting from fit::START ({iterations} Nelder-Mead iterations per restart, then minimax)...");
        let f = fit::fit(&rows, &fit::START, iterations, |step| match step {
            fit::Step::Run(run, cost) => eprintln!("Nelder-Mead run {run}: cost {cost:.4}"),
            fit::Step::Minimax(i, worst) => eprintln!("minimax {i}: largest scaled error {worst:.6}"),
        });
        (f.aero, f.cost, f.worst)
    };
    println!(
        "{} (largest error {:.4} of its target, cost {cost:.4}): {aero:?}",
        if iterations == 0 { "current" } else { "fitted" },
        worst
    );
    println!("{:<8} {:>15} {:>13} {:>14}  within", "club", "carry yd", "apex yd", "land deg");
    let mut within = 0;
    for r in &rows {
        let (c, a, l) = fit::predict(&aero, r);
        let (dc, da, dl) = (c - r.carry_yd, a - r.max_height_yd, l - r.land_angle_deg);
        let ok = dc.abs() <= 3.0 && da.abs() <= 2.0 && dl.abs() <= 2.0;
        within += usize::from(ok);
        println!(
            "{:<8} {:>6.1} ({:+6.2}) {:>5.1} ({:+5.2}) {:>5.1} ({:+5.2})  {}",
            r.club,
            c,
            dc,
            a,
            da,
            l,
            dl,
            if ok { "yes" } else { "no" }
        );
    }
    println!("{within} of {} clubs within carry 3 yd, apex 2 yd and land angle 2 deg", rows.len());
    Ok(ExitCode::SUCCESS)
}

fn plot_trajectory(args: &TrajectoryArgs) -> Result<ExitCode> {
    let flight = crate::flight::Flight { conditions: args.conditions.conditions()?, ..Default::default() };
    let input = open_input(args.input.as_deref())?;
    let mut side = Vec::new();
    let mut top = Vec::new();
    for (i, line) in input.lines().enumerate() {
        let line = line?;
        if line.trim().is_empty() {
            continue;
        }
        let l: crate::wire::FlightInput =
            crate::jsonl::parse_line(&line).map_err(|e| anyhow::anyhow!("line {}: {e}", i + 1))?;
        let t = flight.fly(&l.to_launch().map_err(|e| anyhow::anyhow!("line {}: {e}", i + 1))?, 0.05);
        let color = crate::plot::PALETTE[side.len() % crate::plot::PALETTE.len()];
        let name = format!(
            "shot {}: carry {:.0} yd, apex {:.0} yd, {:+.0} yd",
            side.len() + 1,
            t.carry_yd,
            t.apex_yd,
            t.offline_yd
        );
        let yd = crate::units::m_to_yd;
        side.push(crate::plot::Series {
            name: name.clone(),
            points: t.points.iter().map(|p| (yd(p[1]), yd(p[2]))).collect(),
            color,
            right_axis: false,
        });
        top.push(crate::plot::Series {
            name,
            points: t.points.iter().map(|p| (yd(p[1]), yd(p[3]))).collect(),
            color,
            right_axis: false,
        });
    }
    if side.is_empty() {
        bail!("no launches read");
    }
    let side = crate::plot::LineChart {
        title: "side view".into(),
        x_label: "downrange (yd)".into(),
        y_label: "height (yd)".into(),
        y2_label: None,
        series: side,
        equal_axes: false,
    };
    let top = crate::plot::LineChart {
        title: "top view (right +)".into(),
        x_label: "downrange (yd)".into(),
        y_label: "offline (yd)".into(),
        y2_label: None,
        series: top,
        equal_axes: false,
    };
    let (w, h) = (900.0, 380.0);
    let svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{}"><g>{}</g><g transform="translate(0,{h})">{}</g></svg>"#,
        2.0 * h,
        side.svg(w, h),
        top.svg(w, h)
    );
    std::fs::write(&args.output, svg).with_context(|| format!("writing {}", args.output.display()))?;
    eprintln!("wrote {}", args.output.display());
    Ok(ExitCode::SUCCESS)
}

fn map(args: &MapArgs) -> Result<ExitCode> {
    if !(3..=101).contains(&args.cells) {
        bail!("--cells must be within 3 and 101");
    }
    let club = load_club(&args.club)?;
    let equipment = Equipment::new(club.clone());
    let model = Model::new(args.model, crate::impact::impulse::DEFAULT_COR);
    let flight = crate::flight::Flight::default();
    let n = args.cells;
    // The grid spans the face's outline; cells off the face stay blank.
    let (h0, h1, v0, v1) = club.face_outline.bounds_mm();
    let xs: Vec<f64> = (0..n).map(|i| h0 + (h1 - h0) * i as f64 / (n - 1) as f64).collect();
    let ys: Vec<f64> = (0..n).map(|j| v0 + (v1 - v0) * j as f64 / (n - 1) as f64).collect();
    let mut values = vec![vec![f64::NAN; n]; n];
    for (j, v) in ys.iter().enumerate() {
        for (i, h) in xs.iter().enumerate() {
            let mut input = args.delivery.input();
            input.impact_h_mm = *h;
            input.impact_v_mm = *v;
            let Ok(state) = input.to_delivery(club.loft_deg()).to_state(&equipment) else { continue };
            let Ok(launch) = model.as_dyn().predict(&state, &equipment) else { continue };
            let m = crate::impact::LaunchMetrics::from_ball(&launch.ball_velocity_mps, &launch.ball_spin_radps);
            values[j][i] = match args.metric {
                MapMetric::BallSpeed => m.ball_speed_mph,
                MapMetric::Launch => m.launch_angle_deg,
                MapMetric::Backspin => m.backspin_rpm,
                MapMetric::Sidespin => m.sidespin_rpm,
                MapMetric::Carry | MapMetric::Offline => {
                    let t = flight.fly(
                        &crate::flight::LaunchState {
                            velocity_mps: launch.ball_velocity_mps,
                            spin_radps: launch.ball_spin_radps,
                        },
                        0.0,
                    );
                    if args.metric == MapMetric::Carry {
                        t.carry_yd
                    } else {
                        t.offline_yd
                    }
                }
            };
        }
    }
    let label = match args.metric {
        MapMetric::BallSpeed => "ball speed (mph)",
        MapMetric::Launch => "launch angle (deg)",
        MapMetric::Backspin => "backspin (rpm)",
        MapMetric::Sidespin => "sidespin (rpm, + fade)",
        MapMetric::Carry => "carry (yd)",
        MapMetric::Offline => "offline (yd, right +)",
    };
    if values.iter().flatten().all(|v| !v.is_finite()) {
        bail!("no impact location on the face gives a prediction for this delivery (check the club speed and angles)");
    }
    // The CG seen along the face normal: its offset from the face centre in the face's (h, v) coordinates.
    let cg_mm = [-club.face.center_m.z * 1e3, -club.face.center_m.dot(&club.face.u0()) * 1e3];
    let heat = crate::plot::Heatmap {
        title: format!("{} {}: {} at {:.0} mph", club.name, model.as_dyn().name(), label, args.delivery.club_speed_mph),
        x_label: "impact location toward the toe (mm)".into(),
        y_label: "impact location up the face (mm)".into(),
        value_label: label.into(),
        xs,
        ys,
        values,
        outline: club.face_outline.vertices_mm.clone(),
        markers: vec![("face centre".into(), [0.0, 0.0]), ("CG".into(), cg_mm)],
    };
    std::fs::write(&args.output, heat.svg(760.0, 520.0))
        .with_context(|| format!("writing {}", args.output.display()))?;
    eprintln!("wrote {}", args.output.display());
    Ok(ExitCode::SUCCESS)
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Predict(args) => predict(&args),
        Command::Bench(args) => bench(&args),
        Command::Eval(EvalCommand::Extrapolation(args)) => eval_extrapolation(&args),
        Command::Plot(PlotCommand::Forces(args)) => plot_forces(&args),
        Command::Plot(PlotCommand::Trajectory(args)) => plot_trajectory(&args),
        Command::Flight(args) => flight(&args),
        Command::FlightFit { iterations } => flight_fit(iterations),
        Command::Map(args) => map(&args),
        Command::Schemas { output } => {
            std::fs::create_dir_all(&output).with_context(|| format!("creating {}", output.display()))?;
            for (name, schema) in crate::wire::schemas() {
                let path = output.join(format!("{name}.json"));
                std::fs::write(&path, schema).with_context(|| format!("writing {}", path.display()))?;
            }
            Ok(ExitCode::SUCCESS)
        }
        #[cfg(feature = "daemon")]
        Command::Run(args) => crate::cli_daemon::run(&args),
        #[cfg(feature = "daemon")]
        Command::Demo(args) => crate::cli_daemon::demo_cmd(&args),
        #[cfg(feature = "daemon")]
        Command::Sim(args) => crate::cli_daemon::sim(&args),
        #[cfg(feature = "daemon")]
        Command::Replay(args) => crate::cli_daemon::replay_cmd(&args),
        #[cfg(feature = "daemon")]
        Command::Info { file } => crate::cli_daemon::info(&file),
        #[cfg(feature = "daemon")]
        Command::Recover(args) => crate::cli_daemon::recover(&args),
    }
}
