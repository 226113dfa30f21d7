//! `impactd models`: the model registry, as the README and docs/club-files.md show it (generated from here by
//! scripts/registry-docs.sh, and checked against it by tests/cli/registry_docs.rs).

use std::process::ExitCode;

use anyhow::Result;
use clap::Args;
use impactd::impact::registry;

#[derive(Debug, Args)]
pub struct ModelsArgs {
    /// The club-file sections each model reads, with their fields, instead of the models.
    #[arg(long, conflicts_with = "presets")]
    pub sections: bool,
    /// The club presets as a table (name, loft, lie, mass, CG, inertia, the models that refuse it, SHA-256).
    #[arg(long, conflicts_with = "sections")]
    pub presets: bool,
    /// The model names alone, one a line (for scripts).
    #[arg(long, conflicts_with_all = ["sections", "presets"])]
    pub names: bool,
}

pub fn run(args: &ModelsArgs) -> Result<ExitCode> {
    let text = if args.names {
        registry::MODELS.iter().map(|m| format!("{}\n", m.name)).collect()
    } else if args.sections {
        registry::sections_markdown()
    } else if args.presets {
        presets_markdown()?
    } else {
        registry::models_markdown()
    };
    print!("{text}");
    Ok(ExitCode::SUCCESS)
}

/// The presets as docs/club-files.md tables them: each preset's physical numbers, the CG as its depth behind the
/// face plane and its height below the face centre along the face, the dynamic loft `predict` delivers when a line
/// gives none (`impact::delivered_loft`), and the models that refuse it with why.
fn presets_markdown() -> Result<String> {
    use impactd::equipment::presets::PRESETS;
    use impactd::impact::registry::{build_one, BuildOptions, MODELS};
    use impactd::impact::{Delivery, Equipment};
    let mut out = String::from(
        "| preset | aliases | loft ° | delivered loft ° | lie ° | head g | CG behind face mm | CG below centre mm | I_xx, I_yy, I_zz g cm² | shaft's I_zz share g cm² | shaft g | refused by | sha256 |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for p in PRESETS {
        let club = p.load()?;
        let c = &club.club;
        let (l, v) = (c.face.loft_rad, c.face.center_m);
        // The head's own inertia; the shaft's share about the heel-toe axis in its own column.
        let i = c.head_inertia_kg_m2() * 1e7;
        let eq = Equipment::new(c.clone());
        let delivery = Delivery {
            club_speed_mps: 40.0,
            attack_angle_rad: 0.0,
            club_path_rad: 0.0,
            face_angle_rad: 0.0,
            dynamic_loft_rad: l,
            impact_h_m: 0.0,
            impact_v_m: 0.0,
            club_angular_velocity_radps: impactd::math::Vector3::zeros(),
        };
        let refused: Vec<String> = MODELS
            .iter()
            .filter_map(|m| {
                let state = delivery.to_state(&eq).ok()?;
                let run = build_one(m.name, &club, &BuildOptions::default()).and_then(|b| b.predict(&state, &eq));
                run.err().map(|e| format!("`{}` ({e})", m.name))
            })
            .collect();
        out.push_str(&format!(
            "| `{}` | {} | {:.1} | {:.1} | {:.1} | {:.0} | {:.2} | {:.2} | {:.0}, {:.0}, {:.0} | {:.0} | {:.0} | {} | `{}` |\n",
            p.name,
            p.aliases.join(", "),
            c.loft_deg(),
            impactd::impact::delivered_loft::delivered_loft_deg(c.loft_deg()),
            c.lie_deg,
            c.mass_kg * 1e3,
            (v.x * l.cos() + v.y * l.sin()) * 1e3,
            (-v.x * l.sin() + v.y * l.cos()) * 1e3,
            i[(0, 0)],
            i[(1, 1)],
            i[(2, 2)],
            c.shaft_heel_toe_inertia_kg_m2 * 1e7,
            c.shaft_mass_kg * 1e3,
            if refused.is_empty() { "none".to_string() } else { refused.join("; ") },
            impactd::equipment::sha256_hex(p.bytes()).get(..16).unwrap_or_default(),
        ));
    }
    Ok(out)
}
