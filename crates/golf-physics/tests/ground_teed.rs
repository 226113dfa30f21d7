//! One ball for every continuous model: with no ground under the ball the `ground` model (seed chapter 4) is the
//! `continuous` model (seed section 3.2.1, Table 3.5 in its default one-cycle reading) with a flexible shaft on
//! the head, and nothing else. The seed builds chapter 4 that way ("the two-layer ball volumetric contact model is
//! used as it was the most accurate of the iron models", section 4.1) and its chapter 3 neglects the shaft "due to
//! the short duration of the impact": so with the shaft made negligible (a thousandth of its mass, a
//! twenty-thousandth of its stiffness) the two must agree within 0.5 mph and 2 % of spin, and what is left between
//! them with the seed's shaft (Tables 4.1-4.2) is the shaft's own effect, measured here.

#![allow(clippy::unwrap_used)]

use crate::load_club;
use golf_physics::equipment::shaft::ShaftSpec;
use golf_physics::equipment::soil::SoilSpec;
use golf_physics::impact::continuous::iron_ground::{GroundModel, Strike};
use golf_physics::impact::registry::{build_one, BuildOptions};
use golf_physics::impact::{Delivery, Equipment, ImpactModel, LaunchMetrics};
use golf_physics::math::{Real, Vector3};
use golf_physics::units::mph_to_mps;

/// The delivery: the seed's 7-iron at 85 mph, 4.3 deg down, 26 deg of dynamic loft (its section 4.3
/// swing), struck `v_mm` up the face and `h_mm` toward the toe.
fn delivery(h_mm: Real, v_mm: Real) -> Delivery {
    Delivery {
        club_speed_mps: mph_to_mps(85.0),
        attack_angle_rad: (-4.3f64).to_radians(),
        club_path_rad: 0.0,
        face_angle_rad: 0.0,
        dynamic_loft_rad: 26f64.to_radians(),
        impact_h_m: h_mm * 1e-3,
        impact_v_m: v_mm * 1e-3,
        club_angular_velocity_radps: Vector3::zeros(),
    }
}

fn metrics(model: &dyn ImpactModel, eq: &Equipment, h_mm: Real, v_mm: Real) -> LaunchMetrics {
    let l = model.predict(&delivery(h_mm, v_mm).to_state(eq).unwrap(), eq).unwrap();
    LaunchMetrics::from_ball(&l.ball_velocity_mps, &l.ball_spin_radps)
}

/// The teed ground model with the seed's shaft scaled: `mass` and `stiffness` multiply Tables 4.1-4.2's.
fn teed(eq: &Equipment, mass: Real, stiffness: Real) -> golf_physics::impact::continuous::iron_ground::PreparedGround {
    let mut m = GroundModel::new(SoilSpec::firm());
    m.with_ground = false;
    let seed = ShaftSpec::iron7();
    m.shaft = ShaftSpec { mass_kg: seed.mass_kg * mass, youngs_modulus_pa: seed.youngs_modulus_pa * stiffness, ..seed };
    m.prepare(eq).unwrap()
}

#[test]
fn teed_ground_model_is_the_continuous_model_plus_the_shaft() {
    let club = load_club("iron7").unwrap();
    let eq = Equipment::new(club.club.clone());
    let continuous = build_one("continuous", &club, &BuildOptions::default()).unwrap();
    // The registry's ground model, default ball, `--soil none`.
    let mut teed_club = club.clone();
    teed_club.sections.insert(
        "soil",
        golf_physics::impact::continuous::iron_ground::sections::soil_arg_section_with("none", &|_| {
            Err(std::io::ErrorKind::NotFound.into())
        })
        .unwrap(),
    );
    let seed_shaft = build_one("ground", &teed_club, &BuildOptions::default()).unwrap();
    let no_shaft = teed(&eq, 1e-3, 5e-5);
    for (h, v) in [(0.0, -8.0), (0.0, 0.0), (0.0, 5.0), (10.0, -4.0)] {
        let c = metrics(continuous.as_ref(), &eq, h, v);
        let g0 = metrics(&no_shaft, &eq, h, v);
        let g = metrics(seed_shaft.as_ref(), &eq, h, v);
        println!(
            "({h}, {v}) mm: continuous {:.2} mph {:.0} rpm; teed ground, negligible shaft {:.2} mph {:.0} rpm; \
             seed's shaft {:.2} mph {:.0} rpm (the shaft: {:+.2} mph, {:+.1} %)",
            c.ball_speed_mph,
            c.total_spin_rpm,
            g0.ball_speed_mph,
            g0.total_spin_rpm,
            g.ball_speed_mph,
            g.total_spin_rpm,
            g.ball_speed_mph - g0.ball_speed_mph,
            100.0 * (g.total_spin_rpm / g0.total_spin_rpm - 1.0)
        );
        assert!((g0.ball_speed_mph - c.ball_speed_mph).abs() < 0.5, "ball speed: {g0:?} vs {c:?}");
        assert!((g0.total_spin_rpm / c.total_spin_rpm - 1.0).abs() < 0.02, "spin: {g0:?} vs {c:?}");
        // The seed's shaft only adds to the head's effective mass (its tip moves with the hosel): never slower,
        // and its effect grows away from the CG (measured +0.4 mph at 8 mm below the centre, +3.0 at the
        // centre, +6.2 at 5 mm above; research/models-notes.md).
        assert!(g.ball_speed_mph > g0.ball_speed_mph - 0.1, "{g:?} vs {g0:?}");
    }
}

/// A thin strike (the sole reaches the turf after the ball has left) is the teed strike: the ground never acts
/// while the ball is on the face.
#[test]
fn thin_strike_is_the_teed_strike() {
    let club = load_club("iron7").unwrap();
    let eq = Equipment::new(club.club.clone());
    let on_turf = GroundModel::new(SoilSpec::firm()).prepare(&eq).unwrap();
    let mut m = GroundModel::new(SoilSpec::firm());
    m.with_ground = false;
    let off_tee = m.prepare(&eq).unwrap();
    let state = delivery(0.0, -8.0).to_state(&eq).unwrap();
    let (a, b) = (on_turf.simulate(&state, 0).unwrap(), off_tee.simulate(&state, 0).unwrap());
    assert_eq!((a.strike, b.strike), (Strike::Thin, Strike::Teed));
    assert!(b.ground_contact_before_ball_ms.is_none() && b.divot_depth_mm == 0.0);
    let la = LaunchMetrics::from_ball(&a.launch.ball_velocity_mps, &a.launch.ball_spin_radps);
    let lb = LaunchMetrics::from_ball(&b.launch.ball_velocity_mps, &b.launch.ball_spin_radps);
    println!(
        "thin {:.3} mph {:.0} rpm; teed {:.3} mph {:.0} rpm",
        la.ball_speed_mph, la.total_spin_rpm, lb.ball_speed_mph, lb.total_spin_rpm
    );
    assert!((la.ball_speed_mph - lb.ball_speed_mph).abs() < 0.05);
    assert!((la.total_spin_rpm / lb.total_spin_rpm - 1.0).abs() < 0.005);
}

/// Both models read Table 3.5 the same way by default, and `[continuous] reading = "table"` switches both.
#[test]
fn both_models_take_the_same_reading_of_table_3_5() {
    let mut club = load_club("iron7").unwrap();
    let eq = Equipment::new(club.club.clone());
    let mut table = toml::Table::new();
    table.insert("reading".into(), toml::Value::String("table".into()));
    club.sections.insert("continuous", table);
    let continuous = build_one("continuous", &club, &BuildOptions::default()).unwrap();
    club.sections.insert(
        "soil",
        golf_physics::impact::continuous::iron_ground::sections::soil_arg_section_with("none", &|_| {
            Err(std::io::ErrorKind::NotFound.into())
        })
        .unwrap(),
    );
    let ground = build_one("ground", &club, &BuildOptions::default()).unwrap();
    let (c, g) = (metrics(continuous.as_ref(), &eq, 0.0, -8.0), metrics(ground.as_ref(), &eq, 0.0, -8.0));
    println!(
        "table reading: continuous {:.2} mph {:.0} rpm; ground {:.2} mph {:.0} rpm",
        c.ball_speed_mph, c.total_spin_rpm, g.ball_speed_mph, g.total_spin_rpm
    );
    // The printed table loses 4-5 mph against the one-cycle reading at this strike (the issue: 120.1 against
    // 115.7 mph); the two models stay within the seed shaft's effect of each other.
    assert!(c.ball_speed_mph < 117.0 && g.ball_speed_mph < 117.0, "{c:?} {g:?}");
    assert!((g.ball_speed_mph - c.ball_speed_mph).abs() < 1.0);
}
