//! `impactd plot ground`: the ground model's fat and good strike of one swing (seed Figures 4.10 and 4.15).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;
use impactd::impact::continuous::iron_ground::GROUND_REPORT;
use impactd::impact::{Equipment, ModelRun, RunOptions};
use impactd::wire::DeliveryInput;

use super::args::{load_club, one_model, set_soil, write_output};

/// The seed's swing over the face (section 4.3) by default: 90 mph, 4.3° down, 25° dynamic loft, turning at
/// 27 rad/s about the normal of a 60° swing plane.
#[derive(Debug, Args)]
pub struct GroundPlotArgs {
    /// An iron preset or club .toml file.
    #[arg(long, default_value = "iron7")]
    pub club: String,
    /// soft, medium or firm (Table 4.3), a soil .toml file, or none (the same strike off a tee).
    #[arg(long, default_value = "firm")]
    pub soil: String,
    /// Club speed of both strikes (mph).
    #[arg(long, default_value_t = 90.0)]
    pub club_speed_mph: f64,
    /// Attack angle of both strikes (deg; negative is down).
    #[arg(long, default_value_t = -4.3, allow_hyphen_values = true)]
    pub attack_angle_deg: f64,
    /// Dynamic loft of both strikes (deg).
    #[arg(long, default_value_t = 25.0, allow_hyphen_values = true)]
    pub dynamic_loft_deg: f64,
    /// The club's turning rate about the swing plane's normal (rad/s).
    #[arg(long, default_value_t = 27.0, allow_hyphen_values = true)]
    pub turn_radps: f64,
    /// Impact location up the face of the fat strike (mm; the ball rests on the ground, so higher is fatter).
    #[arg(long, default_value_t = 15.0, allow_hyphen_values = true)]
    pub fat_v_mm: f64,
    /// Impact location up the face of the good strike (mm).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub good_v_mm: f64,
    /// The SVG file to write.
    #[arg(short = 'o', long = "output", default_value = "ground.svg")]
    pub output: PathBuf,
}

pub fn run(args: &GroundPlotArgs) -> Result<ExitCode> {
    let mut loaded = load_club(&args.club)?;
    set_soil(&mut loaded, Some(&args.soil), "ground")?;
    let model = one_model("ground", &loaded, impactd::impact::impulse::DEFAULT_COR)?;
    let club = loaded.club.clone();
    let equipment = Equipment::new(club.clone());
    let plane = 60f64.to_radians();
    let strike = |v_mm: f64| -> Result<ModelRun> {
        let input = DeliveryInput {
            club_speed_mph: args.club_speed_mph,
            attack_angle_deg: args.attack_angle_deg,
            club_path_deg: 0.0,
            face_angle_deg: 0.0,
            dynamic_loft_deg: Some(args.dynamic_loft_deg),
            impact_h_mm: 0.0,
            impact_v_mm: v_mm,
            club_angular_velocity_radps: Some([0.0, args.turn_radps * plane.cos(), args.turn_radps * plane.sin()]),
            handedness: None,
            dynamic_lie_deg: None,
        };
        let state = impactd::predict::state_of(&input, &club, &equipment)?;
        Ok(model.run(&state, &equipment, &RunOptions::traced(2))?)
    };
    let kind =
        |r: &ModelRun| r.report.as_ref().filter(|g| g.key == GROUND_REPORT).and_then(|g| g.fields.text("strike"));
    let fat = strike(args.fat_v_mm)?;
    if kind(&fat) != Some("fat") {
        bail!(
            "--fat-v-mm {}: that strike is {}, not fat (strike higher on the face)",
            args.fat_v_mm,
            kind(&fat).unwrap_or("not a ground strike")
        );
    }
    let good = strike(args.good_v_mm)?;
    if kind(&good) == Some("fat") {
        bail!("--good-v-mm {}: that strike is fat too (strike lower on the face)", args.good_v_mm);
    }
    let title = format!("{} at {:.0} mph on {} soil", club.name, args.club_speed_mph, args.soil);
    let svg = impactd::offline::plot::ground_svg(&title, &[("fat", &fat), ("good", &good)])?;
    write_output(&args.output, &svg)?;
    Ok(ExitCode::SUCCESS)
}
