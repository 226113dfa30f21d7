//! A new model is its own file: a toy model written here, behind `ImpactModel` alone, is predicted, reported and
//! traced by `predict` and drawn by the force chart with nothing outside this file knowing its type; and built by
//! name from a registry entry as `impactd::impact::registry::MODELS` holds one (in the crate, that entry is the one more
//! line a new model takes). A continuous model is the same plus its parts: every one of them (two-layer, Maw,
//! Arakawa, the iron on the turf) runs on the shared `Assembly` (ARCHITECTURE.md, "Adding things").
//!
//! The toy is the point-mass limit of the impulse models (ARCHITECTURE.md section 6): a head of mass M meeting a
//! ball of mass m head-on with restitution e sends it off at `v (1 + e) M / (M + m)`; its "trace" is a
//! half-sine force pulse of duration T carrying that impulse.

#![allow(clippy::unwrap_used)]

use impactd::equipment::{ClubSpec, LoadedClub};
use impactd::impact::registry::{build_from, BuildOptions, ModelEntry};
use impactd::impact::report::Value;
use impactd::impact::{
    Course, Equipment, Fields, ImpactError, ImpactModel, ImpactState, Launch, ModelRun, Report, RunOptions, Trace,
};
use impactd::math::Vector3;
use impactd::predict::{run, Predictor};

#[derive(Debug)]
struct PointMass {
    cor: f64,
    contact_s: f64,
}

impl ImpactModel for PointMass {
    fn name(&self) -> &'static str {
        "toy/point_mass"
    }

    fn run(&self, state: &ImpactState, eq: &Equipment, o: &RunOptions) -> Result<ModelRun, ImpactError> {
        let (big_m, m) = (eq.club.mass_kg, eq.ball.mass_kg);
        let v = state.cg_velocity_mps;
        let ball_velocity_mps = v * (1.0 + self.cor) * big_m / (big_m + m);
        let impulse_n_s = ball_velocity_mps * m;
        let launch = Launch {
            ball_velocity_mps,
            ball_spin_radps: Vector3::zeros(),
            club_velocity_mps: v - impulse_n_s / big_m,
            club_angular_velocity_radps: state.angular_velocity_radps,
            impulse_n_s,
        };
        // The pulse whose integral is the impulse: F(t) = F_max sin(pi t / T), F_max = pi J / (2 T).
        let peak_n = std::f64::consts::PI * impulse_n_s.norm() / (2.0 * self.contact_s);
        let course = (o.trace_every > 0).then(|| Course {
            summary: Fields(vec![("contact_time_us", (self.contact_s * 1e6).into())]),
            trace: Trace(
                (0..=20)
                    .map(|i| {
                        let t = self.contact_s * i as f64 / 20.0;
                        Fields(vec![
                            ("t_us", (t * 1e6).into()),
                            ("normal_force_n", (peak_n * (std::f64::consts::PI * t / self.contact_s).sin()).into()),
                        ])
                    })
                    .collect(),
            ),
        });
        let report = Report {
            key: "toy",
            fields: Fields(vec![("peak_force_n", peak_n.into()), ("kind", Value::Text("point mass"))]),
        };
        Ok(ModelRun { launch, report: Some(report), course })
    }
}

#[test]
fn a_model_in_one_file_is_predicted_reported_traced_and_drawn() {
    let toy = PointMass { cor: 0.8, contact_s: 450e-6 };
    let input = "{\"club_speed_mph\":100,\"dynamic_loft_deg\":10.5}\n";
    let (mut out, mut err) = (Vec::new(), Vec::new());
    run(&ClubSpec::driver(), Predictor::Traced(&toy), input.as_bytes(), &mut out, &mut err).unwrap();
    let line: serde_json::Value = serde_json::from_slice(&out).unwrap();
    // The closed form: without rotation the CG moves with the face centre, 100 mph; the seed's driver head and ball
    // (Table 3.1: M = 204 g; m = 45.9 g), e = 0.8.
    let (big_m, m) = (ClubSpec::driver().mass_kg, impactd::equipment::BallSpec::SEED.mass_kg);
    assert_eq!((big_m, m), (0.204, 0.0459));
    let expected_mph = 100.0 * 1.8 * big_m / (big_m + m);
    let got = line["ball_speed_mph"].as_f64().unwrap();
    assert!((got / expected_mph - 1.0).abs() < 1e-9, "{got} mph, closed form {expected_mph} mph");
    // Its report under its key, its course's summary beside the launch, its trace: all by name.
    assert_eq!(line["toy"]["kind"], "point mass");
    assert!(line["toy"]["peak_force_n"].as_f64().unwrap() > 1e3);
    assert_eq!(line["contact_time_us"].as_f64().unwrap(), 450.0);
    assert_eq!(line["trace"].as_array().unwrap().len(), 21);

    // The force chart reads the same course by name.
    let eq = Equipment::new(ClubSpec::driver());
    let state = impactd::predict::state_of(&serde_json::from_str(input.trim()).unwrap(), &eq.club, &eq).unwrap();
    let r = toy.run(&state, &eq, &RunOptions::traced(1)).unwrap();
    let chart = impactd::offline::plot::forces_chart("driver", 100.0, &r).unwrap();
    assert_eq!(chart.series[0].points.len(), 21);
    assert!(chart.title.contains("contact 450 µs"), "{}", chart.title);
    // Without a trace asked, no course.
    assert!(toy.run(&state, &eq, &RunOptions::default()).unwrap().course.is_none());
}

/// The toy's registry entry, written as an entry of `MODELS` is.
const TOY: ModelEntry = ModelEntry {
    name: "toy/point_mass",
    summary: "a point-mass head meeting a point-mass ball head-on",
    sections: &[],
    resolved_in_time: true,
    fit: None,
    build: |_, _| Ok(std::sync::Arc::new(PointMass { cor: 0.8, contact_s: 450e-6 })),
};

#[test]
fn the_toy_is_built_by_name_from_its_registry_entry() {
    let club = LoadedClub { club: ClubSpec::driver(), sections: Default::default() };
    let models = build_from(&[TOY], "toy/point_mass", &club, &BuildOptions::default()).unwrap();
    assert_eq!(models.iter().map(|m| m.name()).collect::<Vec<_>>(), ["toy/point_mass"]);
    let input = "{\"club_speed_mph\":100,\"dynamic_loft_deg\":10.5}\n";
    let (mut out, mut err) = (Vec::new(), Vec::new());
    run(&club.club, Predictor::Traced(models[0].as_ref()), input.as_bytes(), &mut out, &mut err).unwrap();
    let line: serde_json::Value = serde_json::from_slice(&out).unwrap();
    assert_eq!(line["toy"]["kind"], "point mass");
    assert_eq!(line["contact_time_us"].as_f64().unwrap(), 450.0);
    // A name the registry does not hold is refused, naming what it holds.
    let e = build_from(&[TOY], "toy/other", &club, &BuildOptions::default()).err().unwrap().to_string();
    assert!(e.contains("toy/other") && e.contains("toy/point_mass"), "{e}");
}
