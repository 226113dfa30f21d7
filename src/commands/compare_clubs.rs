//! `impactd compare --by-club`: each club of TrackMan exports on its own preset (TrackMan's `Club` column), every
//! model's ball speed, launch angle, spin and spin axis as MAE and bias (`identify::by_club`), spin only on shots
//! whose spin TrackMan measured; `--located` keeps only shots with an impact location. TrackMan's dynamic loft
//! and face angle are the face's at the contact point (its definitions); on a wood's curved face they are turned
//! into the face centre's (`offline::identify::trackman_reading`).

use std::collections::BTreeMap;
use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use impactd::equipment::BallSpec;
use impactd::impact::registry::{self, BuildOptions};
use impactd::impact::{Equipment, ImpactError};
use impactd::offline::identify::by_club::{club_model_stats, preset_for_club_name, ClubModelStats, SpinMeasured};
use impactd::offline::identify::cost::predict_all;
use impactd::offline::identify::trackman_reading::{at_face_centre, through_spin_relation};
use impactd::offline::identify::DatasetLine;
use impactd::session::measured;
use impactd::session::trackman_csv::{RowLabels, SkippedRows};

/// One club's shots and each model's accuracy on them.
#[derive(Debug, serde::Serialize)]
pub struct ClubReport {
    /// The name in the export's `Club` column (a report's API name in the CSV's spelling: `7Iron` is `7 Iron`).
    pub label: String,
    /// The preset it ran on.
    pub club: String,
    pub shots: usize,
    /// Shots with measured spin.
    pub spin_shots: usize,
    /// Shots no model was run on, by reason: a delivery the club refuses (an impact location off its face, a lie
    /// its face cannot have, ...).
    pub refused: BTreeMap<String, usize>,
    pub models: Vec<ClubModelStats>,
}

/// Shots of a club with no preset, left out.
#[derive(Debug, serde::Serialize)]
pub struct NoPreset {
    pub label: String,
    pub shots: usize,
}

/// What `--by-club` reads and reports.
#[derive(Debug, serde::Serialize)]
pub struct ByClub {
    pub files: Vec<PathBuf>,
    /// TrackMan's loft and face read through its spin relation (`--spin-relation`).
    pub spin_relation: bool,
    /// Rows (strokes) of the files left out before any club: no club or ball speed, incomplete club data.
    pub skipped_rows: SkippedRows,
    /// Shots of clubs with no preset, left out (before `--located`).
    pub no_preset: Vec<NoPreset>,
    /// Rows with club and ball data left out: without an impact location (with `--located`).
    pub unlocated_left_out: usize,
    pub clubs: Vec<ClubReport>,
}

/// Every labelled row of the files (any launch monitor's export `session::measured` reads) and the rows skipped.
fn read_rows(files: &[PathBuf]) -> Result<(Vec<(DatasetLine, RowLabels)>, SkippedRows)> {
    let mut rows = Vec::new();
    let mut skipped = SkippedRows::default();
    for path in files {
        let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        let Some(format) = measured::format_of(&text) else {
            bail!(
                "{}: --by-club reads launch monitors' exports only (TrackMan CSV or report JSON, Foresight FSX CSV, \
                 Uneekor shot CSV)",
                path.display()
            );
        };
        let (r, s) = measured::read_labelled(format, &text)
            .with_context(|| format!("{} ({})", path.display(), format.describe()))?;
        if s.total() > 0 {
            eprintln!("{}: {}", path.display(), s.describe());
        }
        skipped.without_club_or_ball += s.without_club_or_ball;
        skipped.incomplete_club_data += s.incomplete_club_data;
        rows.extend(r);
    }
    Ok((rows, skipped))
}

/// The reason a delivery is refused, as the output counts it.
pub fn refusal(e: &ImpactError) -> String {
    match e {
        ImpactError::OffFace { .. } => "impact location off the face".into(),
        ImpactError::LieUnreachable { .. } => "dynamic lie the face cannot have".into(),
        ImpactError::NotFinite { field } => format!("`{field}` not finite"),
        ImpactError::SpeedOutOfRange { .. } => "club speed outside 1-100 m/s".into(),
        ImpactError::NotApproaching => "club not moving toward the ball".into(),
        ImpactError::NotConverged { model, .. } => format!("{model} not converged"),
        other => other.to_string(),
    }
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
    let on_turf = soil.is_some() && models.split(',').map(str::trim).any(registry::takes_soil);
    let models = registry::resolve(models, on_turf).context("--models")?;
    let models = models.as_str();
    let (mut rows, skipped_rows) = read_rows(files)?;
    let label_of = |l: &RowLabels| l.club.clone().unwrap_or_default();
    let mut no_preset: Vec<NoPreset> = Vec::new();
    for (_, l) in &rows {
        let label = label_of(l);
        if preset_for_club_name(&label).is_some() {
            continue;
        }
        match no_preset.iter_mut().find(|n| n.label == label) {
            Some(n) => n.shots += 1,
            None => no_preset.push(NoPreset { label, shots: 1 }),
        }
    }
    rows.retain(|(_, l)| preset_for_club_name(&label_of(l)).is_some());
    let before = rows.len();
    if located {
        rows.retain(|(_, l)| l.impact_located);
    }
    let mut labels: Vec<String> = Vec::new();
    for (_, l) in &rows {
        let name = label_of(l);
        if !labels.contains(&name) {
            labels.push(name);
        }
    }
    let ball = BallSpec::SEED;
    let mut clubs = Vec::new();
    for label in labels {
        let Some(preset) = preset_for_club_name(&label) else { continue };
        let club = super::args::load_club(preset)?;
        let equipment = Equipment { club: club.club.clone(), ball };
        let (mut shots, mut spin_measured, mut refused) = (Vec::new(), Vec::new(), BTreeMap::new());
        for (d, l) in rows.iter().filter(|(_, l)| label_of(l) == label) {
            let trackman =
                if spin_relation { through_spin_relation(&d.delivery, &d.measured) } else { d.delivery.clone() };
            let shot = at_face_centre(&trackman, &equipment)
                .and_then(|delivery| DatasetLine { delivery, measured: d.measured.clone() }.to_shot(&equipment));
            match shot {
                Ok(s) => {
                    shots.push(s);
                    spin_measured.push(SpinMeasured { spin: l.spin_measured, axis: l.axis_measured });
                }
                Err(e) => *refused.entry(refusal(&e)).or_insert(0) += 1,
            }
        }
        let measured: Vec<[f64; 5]> = shots.iter().map(|s| s.measured).collect();
        let mut stats = Vec::new();
        for name in models.split(',') {
            let mut loaded = club.clone();
            if registry::takes_soil(name) {
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
            spin_shots: spin_measured.iter().filter(|m| m.spin).count(),
            refused,
            models: stats,
        });
    }
    Ok(ByClub {
        files: files.to_vec(),
        spin_relation,
        skipped_rows,
        no_preset,
        unlocated_left_out: before - rows.len(),
        clubs,
    })
}

/// The table: per club, a line per model (ball speed in mph, launch and axis in deg, spin in rpm).
pub fn render(r: &ByClub) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    if r.skipped_rows.total() > 0 {
        let _ = writeln!(s, "{}", r.skipped_rows.describe());
    }
    for n in &r.no_preset {
        let _ = writeln!(s, "club `{}`: no preset for that name, its {} shots left out", n.label, n.shots);
    }
    if r.unlocated_left_out > 0 {
        let _ = writeln!(s, "{} shots without an impact location left out", r.unlocated_left_out);
    }
    for c in &r.clubs {
        let _ = writeln!(
            s,
            "{} ({}): {} shots, {} with measured spin (MAE / bias, predicted - measured)",
            c.label, c.club, c.shots, c.spin_shots
        );
        for (reason, n) in &c.refused {
            let _ = writeln!(s, "  {n} shots refused ({reason}), left out");
        }
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
