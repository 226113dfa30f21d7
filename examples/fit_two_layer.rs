#![allow(clippy::unwrap_used)]
//! Identifies the two-layer model's seven parameters (Table 3.5) from 550 synthetic 7-iron shots, the size of
//! the seed's driver set, and prints the report as JSON: the speed figure of docs/identify.md (not run in CI).
//!
//!     cargo run --release --no-default-features --example fit_two_layer [SHOTS] [POPULATION] [GENERATIONS]

use impactd::equipment::{ClubSpec, LoadedClub, ModelSections};
use impactd::impact::Equipment;
use impactd::offline::identify::dataset::resolve;
use impactd::offline::identify::fit::{run, FitOptions};
use impactd::offline::identify::synth::{generate, DeliveryRanges, LmNoise, SynthSpec};
use impactd::offline::identify::{FitModel, ParamSpace};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arg = |i: usize, default: usize| std::env::args().nth(i).and_then(|a| a.parse().ok()).unwrap_or(default);
    let (shots, population, generations) = (arg(1, 550), arg(2, 21), arg(3, 40));
    let space = ParamSpace::new(FitModel::parse("continuous")?, &[])?;
    let club = LoadedClub { club: ClubSpec::iron7(), sections: ModelSections::default() };
    // The truth: Table 3.5's 7-iron moved by 10-40 % per parameter.
    let truth = [8.5e9, 7.0e-3, 0.42, 45.0, 9.0e-3, 2.2e-3, 0.65];
    let spec = SynthSpec {
        club: space.club_with(&club, &truth),
        model: "continuous".into(),
        shots,
        noise: LmNoise::default(),
        ranges: DeliveryRanges::IRON7,
        seed: 17,
    };
    let shots = resolve(&generate(&spec)?, &Equipment::new(club.club.clone()))?;
    let options = FitOptions {
        folds: 0,
        population: Some(population),
        generations,
        local_evaluations: 300,
        seed: 1,
        ..FitOptions::default()
    };
    let mut last = std::time::Instant::now();
    let (report, _) = run(&space, &club, &Default::default(), &shots, &options, &mut |phase, p| {
        if last.elapsed().as_secs_f64() > 10.0 {
            eprintln!(
                "{phase} {} {}/{} best {:.5} ({} evaluations)",
                p.stage, p.step, p.steps, p.best_cost, p.evaluations
            );
            last = std::time::Instant::now();
        }
    })?;
    println!("{}", serde_json::json!({ "truth": truth, "report": report }));
    Ok(())
}
