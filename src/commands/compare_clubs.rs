//! `impactd compare --by-club`: each club of TrackMan exports on its own preset (TrackMan's `Club` column), every
//! model's ball speed, launch angle, spin and spin axis as MAE and bias (`identify::by_club`), spin only on shots
//! whose spin TrackMan measured; `--located` keeps only shots with an impact location. TrackMan's dynamic loft
//! and face angle are the face's at the contact point (its definitions); on a wood's curved face they are turned
//! into the face centre's (`offline::identify::trackman_reading`).

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use impactd::equipment::BallSpec;
use impactd::impact::registry::{self, BuildOptions};
use impactd::impact::Equipment;
use impactd::offline::identify::by_club::{club_model_stats, preset_for_club_name, ClubModelStats};
use impactd::offline::identify::cost::predict_all;
use impactd::offline::identify::dataset::resolve;
use impactd::offline::identify::trackman_reading::{at_face_centre, through_spin_relation};
use impactd::offline::identify::DatasetLine;
use impactd::session::trackman_csv::{read_labelled, RowLabels};

/// One club's shots and each model's accuracy on them.
#[derive(Debug, serde::Serialize)]
pub struct ClubReport {
    /// The name in the export's `Club` column.
    pub label: String,
    /// The preset it ran on.
    pub club: String,
    pub shots: usize,
    /// Shots with measured spin.
    pub spin_shots: usize,
    pub models: Vec<ClubModelStats>,
}

/// What `--by-club` reads and reports.
#[derive(Debug, serde::Serialize)]
pub struct ByClub {
    pub files: Vec<PathBuf>,
    /// TrackMan's loft and face read through its spin relation (`--spin-relation`).
    pub spin_relation: bool,
    /// Rows with club and ball data left out: without an impact location (with `--located`).
    pub unlocated_left_out: usize,
    pub clubs: Vec<ClubReport>,
}

/// Every labelled row of the files (TrackMan exports only).
fn read_rows(files: &[PathBuf]) -> Result<Vec<(DatasetLine, RowLabels)>> {
    let mut rows = Vec::new();
    for path in files {
        let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        if !impactd::session::trackman_csv::is_trackman_csv(&text) {
            bail!("{}: --by-club reads TrackMan CSV exports only", path.display());
        }
        let (r, skipped) = read_labelled(&text).with_context(|| path.display().to_string())?;
        if skipped > 0 {
            eprintln!("{}: {skipped} rows without club or ball data skipped", path.display());
        }
        rows.extend(r);
    }
    Ok(rows)
}

/// The report: clubs in the order they first appear; `soil` for the ground model (`none`: on a tee).
/// `spin_relation`: TrackMan's loft and face read through its spin relation (`trackman_reading`).
pub fn by_club(
    files: &[PathBuf],
    models: &str,
    located: bool,
    soil: Option<&str>,
    spin_relation: bool,
) -> Result<ByClub> {
    // `both` and the other groups expand here as everywhere (impact::registry::resolve); `--soil` is the turf of
    // the ground model, so a group takes its turf members with it, and models without the ground ignore it.
    let names_ground = |m: &str| m == "ground" || registry::GROUPS.iter().any(|g| g.name == m);
    let on_turf = soil.is_some() && models.split(',').map(str::trim).any(names_ground);
    let models = registry::resolve(models, on_turf).context("--models")?;
    let models = models.as_str();
    let mut rows = read_rows(files)?;
    let before = rows.len();
    if located {
        rows.retain(|(_, l)| l.impact_located);
    }
    let mut labels: Vec<String> = Vec::new();
    for (_, l) in &rows {
        let name = l.club.clone().unwrap_or_default();
        if !labels.contains(&name) {
            labels.push(name);
        }
    }
    let ball = BallSpec::SEED;
    let mut clubs = Vec::new();
    for label in labels {
        let Some(preset) = preset_for_club_name(&label) else {
            bail!("club `{label}`: no preset for that name (TrackMan's club names: Driver, 3 Wood, Hybrid, 4-9 Iron, Pitching/Gap/Sand/Lob Wedge)");
        };
        let group: Vec<&(DatasetLine, RowLabels)> =
            rows.iter().filter(|(_, l)| l.club.as_deref().unwrap_or_default() == label).collect();
        let spin_measured: Vec<bool> = group.iter().map(|(_, l)| l.spin_measured).collect();
        let club = super::args::load_club(preset)?;
        let equipment = Equipment { club: club.club.clone(), ball };
        let lines = group
            .iter()
            .enumerate()
            .map(|(i, (d, _))| {
                let trackman =
                    if spin_relation { through_spin_relation(&d.delivery, &d.measured) } else { d.delivery.clone() };
                let delivery = at_face_centre(&trackman, &equipment)
                    .with_context(|| format!("club `{label}`, shot {}: TrackMan's loft and face", i + 1))?;
                Ok(DatasetLine { delivery, measured: d.measured.clone() })
            })
            .collect::<Result<Vec<_>>>()?;
        let shots = resolve(&lines, &equipment).with_context(|| format!("club `{label}`"))?;
        let measured: Vec<[f64; 5]> = shots.iter().map(|s| s.measured).collect();
        let mut stats = Vec::new();
        for name in models.split(',') {
            let mut loaded = club.clone();
            if name == "ground" {
                super::args::set_soil(&mut loaded, soil, name)?;
            }
            let model = registry::build_one(name, &loaded, &BuildOptions { ball, ..Default::default() })
                .with_context(|| format!("model `{name}` on club `{label}`"))?;
            let predicted = predict_all(model.as_ref(), &equipment, &shots);
            stats.push(club_model_stats(name, &predicted, &measured, &spin_measured));
        }
        clubs.push(ClubReport {
            label,
            club: preset.to_string(),
            shots: shots.len(),
            spin_shots: spin_measured.iter().filter(|m| **m).count(),
            models: stats,
        });
    }
    Ok(ByClub { files: files.to_vec(), spin_relation, unlocated_left_out: before - rows.len(), clubs })
}

/// The table: per club, a line per model (ball speed in mph, launch and axis in deg, spin in rpm).
pub fn render(r: &ByClub) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    if r.unlocated_left_out > 0 {
        let _ = writeln!(s, "{} shots without an impact location left out", r.unlocated_left_out);
    }
    for c in &r.clubs {
        let _ = writeln!(
            s,
            "{} ({}): {} shots, {} with measured spin (MAE / bias, predicted - measured)",
            c.label, c.club, c.shots, c.spin_shots
        );
        let _ = writeln!(
            s,
            "{:<12} {:>17} {:>15} {:>17} {:>15}",
            "model", "ball speed (mph)", "launch (deg)", "spin (rpm)", "spin axis (deg)"
        );
        for m in &c.models {
            let pair = |e: &impactd::offline::identify::by_club::ErrorStats, d: usize| {
                format!("{:.d$} / {:+.d$}", e.mae, e.bias)
            };
            let _ = writeln!(
                s,
                "{:<12} {:>17} {:>15} {:>17} {:>15}{}",
                m.model,
                pair(&m.ball_speed_mph, 2),
                pair(&m.launch_angle_deg, 2),
                pair(&m.spin_rpm, 0),
                pair(&m.spin_axis_deg, 2),
                if m.failed > 0 { format!("  ({} failed)", m.failed) } else { String::new() }
            );
        }
    }
    s
}
