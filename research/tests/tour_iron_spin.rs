//! Irons against the tour: TrackMan's PGA Tour 7-iron (90 mph, attack -4.3 deg; launch 16.3 deg, 120 mph,
//! 7,097 rpm: tests/data/trackman-pga-tour-averages.csv) at the dynamic loft that reproduces its launch.
//!
//! The bound: a ball at rest struck at one point gains angular momentum about its centre only from the friction
//! impulse, `I w = m R |v_t|`, so a homogeneous ball (`I = 0.4 m R^2`, Table 3.1's 83.36 g cm2) leaves with
//! `w R = 2.5 |v_t|`, whatever the friction law: at a launch angle `LA` off a face at dynamic loft `DL`,
//! `spin = 2.5 v sin(DL - LA) / R`. 7,097 rpm at 120 mph needs `DL - LA = 6.8 deg`; rolling at separation
//! (the standard and adjusted models, seed 3.1) leaves the ball about 5 deg below the face normal, so about
//! 5,100 rpm: 28 % short. Only tangential restitution (Cross's e_t > 0, the ball "gripping" the face) leaves the
//! ball further below the normal: the slip model with e_y = 0.20, the top of the range the seed cites (-0.2 to 0.2,
//! Cross and Dewhurst; 0.2-0.3 for premium balls at 50 deg incidence), and a restitution of 0.78 (a face without
//! spring-like effect: about 0.77 at driver speeds, higher at an iron's lower normal speed) reach both targets.

#![allow(clippy::unwrap_used)]

use impactd::equipment::load_club;
use impactd::impact::registry::{build_one, BuildOptions};
use impactd::impact::tour::{centred_delivery, dynamic_loft_for_launch, TOUR_IRON7};
use impactd::impact::{Equipment, LaunchMetrics};

/// (dynamic loft, launch metrics) of `model` on the seed's 7-iron with `extra` (fields, then sections) added, at
/// the tour launch (an extra `[slip]` section in place of the preset's).
fn at_tour_launch(model: &str, extra: &str, cor: f64) -> (f64, LaunchMetrics) {
    let dir = std::env::temp_dir().join(format!("impactd-tour-iron-{}-{model}-{cor}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("iron7.toml");
    let preset = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/clubs/presets/iron7.toml")).unwrap();
    // The extra fields go before the preset's sections; an extra `[slip]` replaces the preset's.
    let (fields, sections) = extra.find('[').map_or((extra, ""), |i| extra.split_at(i));
    let (top, slip) = preset.split_at(preset.find("\n[slip]").unwrap_or(preset.len()));
    let slip = if sections.contains("[slip]") { "" } else { slip };
    std::fs::write(&path, format!("{top}\n{fields}{slip}\n{sections}")).unwrap();
    let club = load_club(path.to_str().unwrap()).unwrap();
    let eq = Equipment::new(club.club.clone());
    let m = build_one(model, &club, &BuildOptions { cor, ..Default::default() }).unwrap();
    let loft = dynamic_loft_for_launch(m.as_ref(), &eq, &TOUR_IRON7).unwrap();
    let d = centred_delivery(TOUR_IRON7.club_speed_mph, TOUR_IRON7.attack_angle_deg, loft);
    let l = m.predict(&d.to_state(&eq).unwrap(), &eq).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    (loft, LaunchMetrics::from_ball(&l.ball_velocity_mps, &l.ball_spin_radps))
}

/// `spin = 2.5 v sin(DL - LA) / R` holds for the impulse model with its ball's CG on the normal (standard,
/// seed 3.1) at the tour launch (to 1 %), and rolling falls 28 % short of TrackMan's 7,097 rpm while 6 % too
/// fast.
#[test]
fn rolling_is_bounded_by_the_balls_angular_momentum() {
    let (loft, m) = at_tour_launch("standard", "", 0.83);
    let r = 0.0213;
    let v = m.ball_speed_mph * 0.44704;
    let closed = 2.5 * v * (loft - m.launch_angle_deg).to_radians().sin() / r * 60.0 / std::f64::consts::TAU;
    assert!(
        (m.total_spin_rpm / closed - 1.0).abs() < 0.01,
        "model {:.0} rpm, closed form {closed:.0}",
        m.total_spin_rpm
    );
    assert!((m.launch_angle_deg - 16.3).abs() < 0.02);
    assert!(m.total_spin_rpm < 0.75 * 7097.0, "{:.0} rpm", m.total_spin_rpm);
    assert!(m.ball_speed_mph > 1.05 * 120.0, "{:.1} mph", m.ball_speed_mph);
    // The loft TrackMan's spin needs at this launch and speed: 6.8 deg above the launch.
    let need = (7097.0 * std::f64::consts::TAU / 60.0 * r / (2.5 * 120.0 * 0.44704)).asin().to_degrees();
    assert!((need - 6.8).abs() < 0.1, "{need:.2}");
}

/// With e_y = 0.20 and e = 0.78, both inside published ranges, and the shaft's share about the heel-toe axis the
/// other iron presets carry (594 g cm2 for this head, research/scripts/shaft-share.py), the slip model (seed 3.1.2)
/// launches the tour 7-iron at 16.3 deg within 10 % of its spin and 3 % of its ball speed; with the seed's
/// Table 3.4 values (e_y = 0.018, e = 0.83) it does not. (On the head alone, without the share: 6,360 rpm,
/// 10.4 % short; research/real-shots.md.)
#[test]
fn tangential_restitution_in_its_published_range_reaches_the_tour() {
    let share = "shaft_heel_toe_inertia_g_cm2 = 594.0\n";
    let (_, seed) = at_tour_launch("slip", share, 0.83);
    assert!(seed.total_spin_rpm < 0.8 * 7097.0, "{:.0}", seed.total_spin_rpm);
    let (loft, m) = at_tour_launch("slip", &format!("{share}[slip]\ne_y = 0.20\ne_z = 0.0\n"), 0.78);
    println!("dynamic loft {loft:.2} deg: {:.1} mph, {:.0} rpm", m.ball_speed_mph, m.total_spin_rpm);
    assert!((m.total_spin_rpm / 7097.0 - 1.0).abs() <= 0.10, "{:.0} rpm", m.total_spin_rpm);
    assert!((m.ball_speed_mph / 120.0 - 1.0).abs() <= 0.03, "{:.1} mph", m.ball_speed_mph);
}

/// The same bound on real shots, with TrackMan's own numbers: on every shot whose spin TrackMan measured (every
/// session of tests/data/trackman/ with a dynamic loft: three players, nine sessions, driver to wedge), its spin is
/// 1.136 (within 0.002) times `2.5 v sin(a) / R`, `a` the angle between the face normal (dynamic loft, face angle)
/// and the ball's direction (launch angle and direction). A constant ratio on every shot says TrackMan's dynamic
/// loft and face angle are computed from its ball data with a fixed relation, `w R = 2.84 |v_t|` (a ball of
/// `I = 0.352 m R^2`, or its own impact model), not measured apart from them: a model with Table 3.1's
/// `I = 0.4 m R^2` given TrackMan's loft and launch spins 12 % less whatever its friction law (research/real-shots.md).
#[test]
fn trackmans_dynamic_loft_and_spin_keep_a_fixed_ratio() {
    let mut ratios = Vec::new();
    // The validation sessions and the held-out ones (TrackMan's relation, not a model's: no model is fitted here).
    let mut files: Vec<(String, String)> = ["tests/data/trackman", "research/data/trackman"]
        .iter()
        .flat_map(|d| {
            let dir = format!("{}/{d}", env!("CARGO_MANIFEST_DIR"));
            std::fs::read_dir(&dir)
                .unwrap()
                .map(move |e| (e.unwrap().file_name().to_string_lossy().into_owned(), dir.clone()))
        })
        .filter(|(f, _)| f.ends_with(".csv") && !f.contains(".converted") || f.ends_with(".json"))
        .collect();
    files.sort();
    for (file, dir) in &files {
        let text = std::fs::read_to_string(format!("{dir}/{file}")).unwrap();
        let (rows, _) = if file.ends_with(".json") {
            impactd::session::trackman_report::read_labelled(&text).unwrap()
        } else {
            impactd::session::trackman_csv::read_labelled(&text).unwrap()
        };
        for (line, labels) in rows.iter().filter(|(_, l)| l.spin_measured) {
            let (m, d) = (&line.measured, &line.delivery);
            let dir = |elevation: f64, azimuth: f64| {
                let (e, a) = (elevation.to_radians(), azimuth.to_radians());
                [e.cos() * a.cos(), e.sin(), e.cos() * a.sin()]
            };
            let Some(loft) = d.dynamic_loft_deg else { continue };
            let n = dir(loft, d.face_angle_deg);
            let b = dir(m.launch_angle_deg, m.launch_direction_deg);
            let angle = (n[0] * b[0] + n[1] * b[1] + n[2] * b[2]).clamp(-1.0, 1.0).acos();
            let spin = m.backspin_rpm.hypot(m.sidespin_rpm);
            let bound = 2.5 * m.ball_speed_mph * 0.44704 * angle.sin() / 0.0213 * 60.0 / std::f64::consts::TAU;
            ratios.push((labels.club.clone().unwrap(), spin / bound));
        }
    }
    // 32 shots of the two CSV sessions and the third player's report sessions' measured spins with complete club
    // data (every club TrackMan names, with a preset or not).
    assert!(ratios.len() > 300, "{} shots", ratios.len());
    for (club, r) in &ratios {
        assert!((r - 1.136).abs() <= 0.002, "{club}: measured spin {r:.4} x the bound");
    }
}
