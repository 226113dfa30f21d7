#![allow(clippy::unwrap_used)]
//! Identification recovers known parameters from synthetic launch-monitor data (issue 17's numbers): 500 driver
//! shots made with parameters the fit does not know, plus the noise of `LmNoise::default()` (0.5 mph, 0.2 deg
//! launch, 0.3 deg direction, 150 rpm per spin component).

use impactd::equipment::{ClubSpec, LoadedClub, ModelSections};
use impactd::impact::Equipment;
use impactd::offline::identify::cost::normal_mae;
use impactd::offline::identify::dataset::resolve;
use impactd::offline::identify::fit::{run, FitOptions, FitReport};
use impactd::offline::identify::synth::{generate, DeliveryRanges, LmNoise, SynthSpec};
use impactd::offline::identify::{FitModel, ParamSpace};

fn fit(model: &str, truth: &[f64], seed: u64) -> FitReport {
    let space = ParamSpace::new(FitModel::parse(model).unwrap(), &[]).unwrap();
    let club = LoadedClub { club: ClubSpec::driver(), sections: ModelSections::default() };
    let spec = SynthSpec {
        club: space.club_with(&club, truth),
        model: model.to_string(),
        shots: 500,
        noise: LmNoise::default(),
        ranges: DeliveryRanges::DRIVER,
        seed,
    };
    let lines = generate(&spec).unwrap();
    let shots = resolve(&lines, &Equipment::new(club.club.clone())).unwrap();
    // The fit starts from the preset (Table 3.3 / 3.4), not from the truth.
    assert_ne!(space.get(&club), truth);
    let (report, fitted) =
        run(&space, &club, &Default::default(), &shots, &FitOptions::default(), &mut |_, _| {}).unwrap();
    assert_eq!(space.get(&fitted).len(), truth.len());
    report
}

/// Each held-out MAE within 10 % of the noise's own: `σ √(2/π)` per field.
fn assert_held_out_mae_is_the_noise(report: &FitReport) {
    let cv = report.cv.as_ref().unwrap();
    for (stats, sigma) in cv.after.iter().zip(LmNoise::default().as_array()) {
        let ratio = stats.mae / normal_mae(sigma);
        assert!(
            (ratio - 1.0).abs() <= 0.10,
            "{}: held-out MAE {:.4} is {ratio:.3} x the noise's",
            stats.field,
            stats.mae
        );
    }
    assert!(cv.cost_after < cv.cost_before, "{cv:?}");
}

/// The shift along the face normal (x') moves the ball's centre along the line of the normal impulse: it only
/// lengthens the lever arm of the small tangential impulse, by Δx / R ≈ 0.3 % of the spin for 0.075 mm (about
/// 7 rpm of 2000), under the 150 rpm noise's reach with 500 shots; it trades against Δm. Over seeds 11-14 the
/// fitted Δx misses by 0.08, 0.41, 0.33 and 0.02 mm and Δm by 0.19, 0.52, 0.29 and 0.11 g, while Δy and Δz
/// stay within 0.03 mm (research/identify-results.md). Without noise every parameter comes back to 1e-3 (the optimiser
/// is not the limit).
#[test]
fn adjusted_recovers_delta_mass_within_half_a_gram_and_the_tangential_ball_cg_shift_within_50_um() {
    // Δm = 7.3 g and Δ = (0.31, -0.42, 0.17) mm, inside the 1-12 g and 0.5 mm per axis.
    let truth = [7.3e-3, 0.31e-3, -0.42e-3, 0.17e-3];
    let report = fit("adjusted", &truth, 11);
    let p = &report.params;
    assert!((p[0].fitted - 7.3).abs() < 0.5, "delta mass {:.3} g", p[0].fitted);
    for (i, want_mm) in [(2, -0.42), (3, 0.17)] {
        assert!((p[i].fitted - want_mm).abs() < 0.05, "{} {:.4} mm", p[i].name, p[i].fitted);
    }
    // Along the normal: only within the range of 0.5 mm (see above). The fit reports the Cramér-Rao
    // bound of x' (about 0.1 mm; research/tests/identifiability.rs) and the larger scatter of eq. 3.13's own estimate;
    // the error is within three of the latter.
    assert!((p[1].fitted - 0.31).abs() < 0.5, "{} {:.4} mm", p[1].name, p[1].fitted);
    let crb_mm = p[1].std_error.unwrap();
    assert!((0.05..0.2).contains(&crb_mm), "x' CRB {crb_mm:.4} mm");
    let sd_mm = p[1].scatter.unwrap();
    assert!(sd_mm > crb_mm && (p[1].fitted - 0.31).abs() <= 3.0 * sd_mm, "x' {:.4} mm, SD {sd_mm:.4} mm", p[1].fitted);
    assert_held_out_mae_is_the_noise(&report);
}

#[test]
fn slip_recovers_e_y_and_e_z_within_0_01() {
    let truth = [0.045, -0.03];
    let report = fit("slip", &truth, 12);
    assert!((report.params[0].fitted - 0.045).abs() < 0.01, "{:?}", report.params);
    assert!((report.params[1].fitted + 0.03).abs() < 0.01, "{:?}", report.params);
    assert_held_out_mae_is_the_noise(&report);
}

#[test]
fn the_fit_repeats_for_a_seed() {
    let a = fit("slip", &[0.02, 0.01], 5);
    let b = fit("slip", &[0.02, 0.01], 5);
    assert_eq!(a.params, b.params);
    assert_eq!(a.cost.to_bits(), b.cost.to_bits());
}
