//! Iron and wedge spin against TrackMan's validation sessions (research/wedge-spin.md,
//! research/scripts/spin-decomposition.py).
//!
//! A ball at rest struck at one point gains angular momentum about its centre only from the impulse, `I w = r_b x P`
//! (seed eq. 3.5 with `w_i = 0`): with the contact on the face normal through its centre, `|w| = m R |v_t| / I`,
//! `v_t` the ball's velocity across the normal (Table 3.1's ball: 45.9 g, 21.3 mm, 83.36 g cm2). Each model's spin
//! error then splits into TrackMan's relation (its spin is 1.136 times that closed form at its own launch,
//! research/tests/tour_iron_spin.rs), the model's launch and ball speed through the closed form, and a rest the closed
//! form does not hold for. These tests pin what the decomposition found: no rest for the rolling and slip models (the
//! contact normal is TrackMan's, lie and face angle and an off-centre strike included), the adjusted model's rest
//! is Table 3.3's ball-CG shift, and the slip model's obliquity law (Cross's grip, impact/impulse/oblique.rs) is
//! eq. 3.11 at the strike's obliquity and brings the validation wedges' spin within 600 rpm.

#![allow(clippy::unwrap_used)]

use std::process::Command;

use impactd::equipment::load_club;
use impactd::impact::registry::{build_one, BuildOptions};
use impactd::impact::tour::centred_delivery;
use impactd::impact::Equipment;
use impactd::math::Vector3;
use serde_json::Value;

const M_BALL: f64 = 0.0459;
const R_BALL: f64 = 0.0213;
const I_BALL: f64 = 83.36e-7;

fn unit(elevation_deg: f64, azimuth_deg: f64) -> Vector3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    Vector3::new(e.cos() * a.cos(), e.sin(), e.cos() * a.sin())
}

/// `impactd predict --club PRESET --model MODEL` on one delivery line: (ball velocity, ball spin), world.
fn predict(preset: &str, model: &str, line: &str) -> (Vector3, Vector3) {
    let dir = std::env::temp_dir().join(format!("impactd-wedge-spin-{}-{preset}-{model}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("in.jsonl");
    std::fs::write(&input, format!("{line}\n")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(["predict", "--club", preset, "--model", model, "-i", input.to_str().unwrap()])
        .output()
        .unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let q: Value = serde_json::from_slice(&out.stdout).unwrap();
    let v = |k: &str| {
        let a: Vec<f64> = q[k].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        Vector3::new(a[0], a[1], a[2])
    };
    (v("ball_velocity_mps"), v("ball_spin_radps"))
}

/// The rolling and slip models' spin is the closed form about TrackMan's own face normal (dynamic loft, face
/// angle) to 1e-6, with a dynamic lie, face angle, club path and an off-centre strike, and the spin lies in the
/// face plane: the 3D geometry of the lie and face puts the contact normal where TrackMan's numbers say. (The
/// decomposition's rest of 3-5 rpm for these models is Table 3.1's 83.36 g cm2 against `0.4 m R^2`, 83.30.)
#[test]
fn the_contact_normal_is_trackmans() {
    let deliveries = [
        (r#""dynamic_loft_deg":33.0,"face_angle_deg":-1.5,"club_path_deg":2.0,"dynamic_lie_deg":58.0"#, 33.0, -1.5),
        (r#""dynamic_loft_deg":24.0,"face_angle_deg":2.5,"club_path_deg":-3.0,"dynamic_lie_deg":66.0"#, 24.0, 2.5),
        (r#""dynamic_loft_deg":38.0,"face_angle_deg":0.5,"club_path_deg":0.0"#, 38.0, 0.5),
    ];
    for preset in ["pw", "iron8"] {
        for model in ["standard", "slip"] {
            for (fields, loft, face) in deliveries {
                for (h, v) in [(0.0, 0.0), (9.0, 6.0), (-12.0, -4.0)] {
                    let strike = format!(r#""impact_h_mm":{h},"impact_v_mm":{v}"#);
                    let line = format!(r#"{{"club_speed_mph":80,"attack_angle_deg":-5.0,{fields},{strike}}}"#);
                    let (vel, w) = predict(preset, model, &line);
                    let n = unit(loft, face);
                    let v_t = vel - n * vel.dot(&n);
                    let closed = M_BALL * R_BALL * v_t.norm() / I_BALL;
                    let what = format!("{preset} {model} {line}");
                    assert!((w.norm() / closed - 1.0).abs() < 1e-6, "{what}: {:.3} against {closed:.3}", w.norm());
                    assert!(w.dot(&n).abs() < 1e-6 * w.norm(), "{what}: spin off the face plane");
                }
            }
        }
    }
}

/// The adjusted model's rest (-390 to -640 rpm on every validation iron and wedge) is its ball-CG shift, Table 3.3
/// (7-iron: (-0.395, -0.182, -0.071) mm in the impact frame, "down and toward the heel ... closer to the
/// clubface"): `I w = r_b x m v` with `r_b = -(R n + F Δ)` holds to 1e-9 of the spin, and the normal impulse's arm
/// below the contact, `m Δ_y (v . n) / I`, takes 400 rpm (380-420) of backspin from a pitching wedge at 75 mph
/// (the seed found the shift improved its mocap-measured spins; TrackMan's relation puts these shots the other
/// way).
#[test]
fn the_adjusted_models_rest_is_its_ball_cg_shift() {
    let delta = Vector3::new(-0.395e-3, -0.182e-3, -0.071e-3);
    let loft: f64 = 33.0;
    let line = format!(r#"{{"club_speed_mph":75,"attack_angle_deg":-5.0,"dynamic_loft_deg":{loft}}}"#);
    let (v, w) = predict("pw", "adjusted", &line);
    // No lie, face or path: the impact frame is the face's, x' = n, y' up the face, z' toward the toe.
    let (l, z) = (loft.to_radians(), Vector3::new(0.0, 0.0, 1.0));
    let (n, y) = (Vector3::new(l.cos(), l.sin(), 0.0), Vector3::new(-l.sin(), l.cos(), 0.0));
    let r_b = -(n * R_BALL + n * delta.x + y * delta.y + z * delta.z);
    let expected = r_b.cross(&(v * M_BALL)) / I_BALL;
    assert!((w - expected).norm() < 1e-9 * w.norm(), "{w:?} against {expected:?}");
    let arm_rpm = M_BALL * delta.y * v.dot(&n) / I_BALL * 60.0 / std::f64::consts::TAU;
    assert!((-420.0..=-380.0).contains(&arm_rpm), "{arm_rpm:.0} rpm");
}

/// Eq. 3.11 at the strike's obliquity: on the `pw` preset (Table 3.4 up to 32.8 deg, Cross's 0.25 from 40 deg),
/// the contact's tangential velocity up the face after the impact is `-e(θ)` times before, with `θ` the spin loft
/// of a centred strike without head rotation, and `e` Table 3.4's 0.0183 below the rise, the mean of 0.0183 and
/// 0.25 halfway, 0.25 beyond.
#[test]
fn the_obliquity_law_is_eq_3_11_at_the_strikes_obliquity() {
    let club = load_club("pw").unwrap();
    let eq = Equipment::new(club.club.clone());
    let slip = build_one("slip", &club, &BuildOptions { cor: 0.83, ..Default::default() }).unwrap();
    for (spin_loft, e) in [(25.0, 0.0183), (30.0, 0.0183), (36.4, 0.5 * (0.0183 + 0.25)), (45.0, 0.25)] {
        let d = centred_delivery(75.0, -5.0, spin_loft - 5.0);
        let state = d.to_state(&eq).unwrap();
        let g = state.contact(&eq.club).unwrap();
        let l = slip.predict(&state, &eq).unwrap();
        let (n, y) = (g.world_from_impact.column(0).into_owned(), g.world_from_impact.column(1).into_owned());
        let r_b = -n * R_BALL;
        let after = (l.club_velocity_mps + l.club_angular_velocity_radps.cross(&g.r_club_m))
            - (l.ball_velocity_mps + l.ball_spin_radps.cross(&r_b));
        let before = g.contact_velocity_mps;
        let theta = (before.dot(&n) / before.norm()).acos().to_degrees();
        assert!((theta - spin_loft).abs() < 1e-9, "obliquity {theta} against the spin loft {spin_loft}");
        let e_y = -after.dot(&y) / before.dot(&y);
        assert!((e_y - e).abs() < 1e-9, "spin loft {spin_loft}: e_y {e_y:.6} against {e:.6}");
    }
}

/// The grip never creates energy: on every iron and wedge preset carrying the law, over spin lofts from the
/// irons' to a lob wedge's and strikes off the centre, the slip model's collision loses kinetic energy (head and
/// ball, translation and rotation), whatever part of the rise each strike sits on, with the full normal
/// restitution (the solver's energy guard, which lowers it, never fires).
#[test]
fn the_grip_never_creates_energy() {
    use impactd::impact::impulse::{solve, ImpulseModel, ImpulseTuning, ImpulseVariant};
    for preset in ["iron8", "iron9", "pw", "gw", "sw", "lw"] {
        let club = load_club(preset).unwrap();
        let eq = Equipment::new(club.club.clone());
        let tuning = ImpulseTuning::from_sections(&club.club, &club.sections).unwrap();
        assert!(tuning.slip_oblique.is_some(), "{preset} carries the law");
        let model = ImpulseModel::new(ImpulseVariant::Slip).with_tuning(tuning);
        for spin_loft in [20.0, 30.0, 34.0, 38.0, 42.0, 50.0, 60.0] {
            for (h, v) in [(0.0, 0.0), (10.0, 5.0), (-10.0, -6.0)] {
                let mut d = centred_delivery(80.0, -6.0, spin_loft - 6.0);
                (d.impact_h_m, d.impact_v_m) = (h * 1e-3, v * 1e-3);
                let p = model.problem(&d.to_state(&eq).unwrap(), &eq).unwrap();
                let s = solve(&p).unwrap();
                let ic = p.club_inertia_inv.try_inverse().unwrap();
                let ib = p.ball_inertia_inv.try_inverse().unwrap();
                // (club velocity, club angular velocity, ball velocity, ball angular velocity) before and after.
                let zero = Vector3::zeros();
                let states = [
                    [p.club_velocity_mps, p.club_angular_velocity_radps, zero, zero],
                    [
                        s.club_velocity_mps,
                        s.club_angular_velocity_radps,
                        s.ball_velocity_mps,
                        s.ball_angular_velocity_radps,
                    ],
                ];
                let energy = |[vc, wc, vb, wb]: [Vector3; 4]| {
                    0.5 * (p.club_mass_kg * vc.norm_squared()
                        + wc.dot(&(ic * wc))
                        + p.ball_mass_kg * vb.norm_squared()
                        + wb.dot(&(ib * wb)))
                };
                let (before, after) = (energy(states[0]), energy(states[1]));
                assert!(after < before, "{preset} at {spin_loft} deg, ({h}, {v}) mm: {before} J -> {after} J");
                // The solver lowers the normal restitution when an impulse would create energy; the loss above
                // must come from the law itself, so the normal closing velocity must reverse by the full COR.
                let n = p.world_from_impact.column(0).into_owned();
                let closing = |[vc, wc, vb, wb]: [Vector3; 4]| {
                    ((vc + wc.cross(&p.r_club_m)) - (vb + wb.cross(&p.r_ball_m))).dot(&n)
                };
                let (u0, u1) = (closing(states[0]), closing(states[1]));
                let e = -u1 / u0;
                assert!((e - p.restitution.x).abs() < 1e-9, "{preset} at {spin_loft} deg: normal restitution {e}");
            }
        }
    }
}

/// (mae, bias) of `field` for the slip model on the club labelled `club` of a validation report session.
fn slip_stat(file: &str, club: &str, field: &str) -> (f64, f64) {
    let path = format!("{}/tests/data/trackman/{file}", env!("CARGO_MANIFEST_DIR"));
    let out = Command::new(env!("CARGO_BIN_EXE_impactd"))
        .args(["compare", "--by-club", "--located", "--json", "--models", "slip", &path])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    let c = r["clubs"].as_array().unwrap().iter().find(|c| c["label"] == club).unwrap();
    let e = &c["models"][0][field];
    (e["mae"].as_f64().unwrap(), e["bias"].as_f64().unwrap())
}

/// The validation sessions' wedges and 9-iron with the presets' obliquity law (research/wedge-spin.md): the slip
/// model's pitching-wedge spin MAE 502 and 439 rpm (1,002 and 1,379 with Table 3.4's constants), the 9-iron's
/// 316 (477), launch within 0.75 deg (the issue's targets: 600 rpm, 1 deg). The held-out sessions are not read.
#[test]
fn the_validation_wedges_spin_within_600_rpm() {
    for (file, club, spin_max, launch_max) in [
        ("report-2025-03-13-pw-driver-5w-7i.json", "Pitching Wedge", 550.0, 0.85),
        ("report-2025-07-11-driver-4i-5h-pw.json", "Pitching Wedge", 480.0, 0.8),
        ("report-2025-10-30-5w-driver-6i-9i.json", "9 Iron", 350.0, 0.75),
    ] {
        let (spin, _) = slip_stat(file, club, "spin_rpm");
        let (launch, _) = slip_stat(file, club, "launch_angle_deg");
        assert!(spin <= spin_max, "{file} {club}: spin MAE {spin:.0} rpm");
        assert!(launch <= launch_max, "{file} {club}: launch MAE {launch:.2} deg");
    }
}
