//! Physical laws the impulse-momentum family must obey (seed section 3.1), checked over a seeded spread of
//! deliveries on both preset clubs and all three variants.

#![allow(clippy::unwrap_used)]

use golf_physics::equipment::ClubSpec;
use golf_physics::impact::impulse::{solve, ContactProblem, ImpulseTuning};
use golf_physics::impact::{
    Delivery, DeliveryMetrics, Equipment, ImpactModel, ImpulseModel, ImpulseVariant, LaunchMetrics,
};
use golf_physics::math::{mirror_z, mirror_z_axial, mirror_z_tensor, Matrix3, Vector3};
use golf_physics::rng::Rng;
use golf_physics::wire::{DeliveryInput, Handedness, PredictOutput};

fn clubs() -> [ClubSpec; 2] {
    [ClubSpec::driver(), ClubSpec::iron7()]
}

fn random_delivery(rng: &mut Rng, club: &ClubSpec) -> Delivery {
    Delivery {
        club_speed_mps: rng.uniform(25.0, 55.0),
        attack_angle_rad: rng.uniform(-6.0, 5.0).to_radians(),
        club_path_rad: rng.uniform(-6.0, 6.0).to_radians(),
        face_angle_rad: rng.uniform(-5.0, 5.0).to_radians(),
        dynamic_loft_rad: (club.loft_deg() + rng.uniform(-5.0, 6.0)).to_radians(),
        impact_h_m: rng.uniform(-0.02, 0.02),
        impact_v_m: rng.uniform(-0.012, 0.012),
        club_angular_velocity_radps: Vector3::new(
            rng.uniform(-10.0, 10.0),
            rng.uniform(-40.0, 10.0),
            rng.uniform(-10.0, 10.0),
        ),
    }
}

/// Every (club, variant, delivery, problem) in the spread.
fn spread(n: usize) -> Vec<(Equipment, ImpulseModel, Delivery, ContactProblem)> {
    let mut rng = Rng::new(2024);
    let mut out = Vec::new();
    for club in clubs() {
        let eq = Equipment::new(club.clone());
        for variant in ImpulseVariant::ALL {
            let model = ImpulseModel::new(variant);
            for _ in 0..n {
                let d = random_delivery(&mut rng, &club);
                let state = d.to_state(&eq).unwrap();
                let p = model.problem(&state, &eq).unwrap();
                out.push((eq.clone(), model, d, p));
            }
        }
    }
    out
}

fn rel(a: Vector3, b: Vector3) -> f64 {
    (a - b).norm() / a.norm().max(b.norm()).max(1e-300)
}

/// Closed form: with no external impulse, eq. 3.2 + 3.4 conserve m_c v_c + m_b v_b, and eq. 3.3 + 3.5 conserve
/// the angular momentum about the (fixed) contact point: I_c w_c + m_c (−r_c) × v_c + I_b w_b + m_b (−r_b) × v_b.
#[test]
fn momentum_is_conserved() {
    for (_, _, _, p) in spread(200) {
        let s = solve(&p).unwrap();
        let lin0 = p.club_mass_kg * p.club_velocity_mps + p.ball_mass_kg * p.ball_velocity_mps;
        let lin1 = p.club_mass_kg * s.club_velocity_mps + p.ball_mass_kg * s.ball_velocity_mps;
        assert!(rel(lin0, lin1) < 1e-12, "linear {}", rel(lin0, lin1));
        let ic = p.club_inertia_inv.try_inverse().unwrap();
        let ib = p.ball_inertia_inv.try_inverse().unwrap();
        let ang = |vc: Vector3, wc: Vector3, vb: Vector3, wb: Vector3| {
            ic * wc - p.club_mass_kg * p.r_club_m.cross(&vc) + ib * wb - p.ball_mass_kg * p.r_ball_m.cross(&vb)
        };
        let a0 =
            ang(p.club_velocity_mps, p.club_angular_velocity_radps, p.ball_velocity_mps, p.ball_angular_velocity_radps);
        let a1 =
            ang(s.club_velocity_mps, s.club_angular_velocity_radps, s.ball_velocity_mps, s.ball_angular_velocity_radps);
        assert!(rel(a0, a1) < 1e-12, "angular {}", rel(a0, a1));
    }
}

/// Eq. 3.6 (COR along x′) and eq. 3.9–3.12 (rolling or tangential restitution along y′, z′) hold after impact.
#[test]
fn restitution_constraints_hold() {
    for (_, _, _, p) in spread(200) {
        let s = solve(&p).unwrap();
        let u0 = p.club_contact_velocity(&p.club_velocity_mps, &p.club_angular_velocity_radps)
            - p.ball_contact_velocity(&p.ball_velocity_mps, &p.ball_angular_velocity_radps);
        let u1 = p.club_contact_velocity(&s.club_velocity_mps, &s.club_angular_velocity_radps)
            - p.ball_contact_velocity(&s.ball_velocity_mps, &s.ball_angular_velocity_radps);
        for axis in 0..3 {
            let dir = p.world_from_impact.column(axis);
            let want = -p.restitution[axis] * u0.dot(&dir);
            assert!((u1.dot(&dir) - want).abs() < 1e-10 * u0.norm(), "axis {axis}");
        }
    }
}

/// Kinetic energy of both bodies before and after a solved collision (J).
fn energies(p: &ContactProblem, s: &golf_physics::impact::impulse::ContactSolution) -> (f64, f64) {
    (
        kinetic_energy(
            p,
            p.club_velocity_mps,
            p.club_angular_velocity_radps,
            p.ball_velocity_mps,
            p.ball_angular_velocity_radps,
        ),
        kinetic_energy(
            p,
            s.club_velocity_mps,
            s.club_angular_velocity_radps,
            s.ball_velocity_mps,
            s.ball_angular_velocity_radps,
        ),
    )
}

fn kinetic_energy(p: &ContactProblem, vc: Vector3, wc: Vector3, vb: Vector3, wb: Vector3) -> f64 {
    let ic = p.club_inertia_inv.try_inverse().unwrap();
    let ib = p.ball_inertia_inv.try_inverse().unwrap();
    0.5 * (p.club_mass_kg * vc.norm_squared()
        + wc.dot(&(ic * wc))
        + p.ball_mass_kg * vb.norm_squared()
        + wb.dot(&(ib * wb)))
}

/// Kinetic energy never increases for 0 <= e <= 1, with rolling (e_y = e_z = 0) or the seed's slip values. Below
/// e = 0.99 it strictly decreases. At e = 1 Newton's restitution (eq. 3.6) would create energy when the contact
/// couples normal and tangential motion; the solver then lowers the normal restitution to the largest value that
/// does not (energetic consistency), so the energy is conserved to rounding there.
#[test]
fn energy_never_increases() {
    let mut lowered = 0;
    for (_, _, _, p0) in spread(300) {
        for e in [0.0, 0.2, 0.4, 0.6, 0.7, 0.8, 0.83, 0.9, 0.95, 0.98, 0.99, 0.995, 1.0] {
            let mut p = p0;
            p.restitution.x = e;
            let s = solve(&p).unwrap();
            let (before, after) = energies(&p, &s);
            assert!(after <= before * (1.0 + 1e-12), "e = {e}: {before} -> {after}");
            if e <= 0.99 {
                assert!(after < before, "e = {e}");
            }
            // Eq. 3.6 holds exactly unless the solver had to lower the restitution.
            let u0 = p.club_contact_velocity(&p.club_velocity_mps, &p.club_angular_velocity_radps);
            let u1 = p.club_contact_velocity(&s.club_velocity_mps, &s.club_angular_velocity_radps)
                - p.ball_contact_velocity(&s.ball_velocity_mps, &s.ball_angular_velocity_radps);
            let n = p.world_from_impact.column(0);
            let e_eff = -u1.dot(&n) / u0.dot(&n);
            if (e_eff - e).abs() > 1e-9 {
                assert!(e_eff < e && e > 0.99, "restitution lowered at e = {e} to {e_eff}");
                assert!((after - before).abs() <= 1e-9 * before, "lowered to conserve energy");
                lowered += 1;
            }
        }
    }
    // The correction is real but rare: it engages for some deliveries only very near e = 1.
    assert!(lowered > 0 && lowered < 60, "{lowered}");
}

/// Closed form of the energy change of an impulsive contact: with relative contact velocity u before, u' =
/// -F E F^T u after and P = K^-1 (u - u'), the kinetic energy changes by -(1/2) P . (u + u').
#[test]
fn energy_change_matches_the_closed_form() {
    for (_, _, _, p0) in spread(100) {
        for e in [0.0, 0.5, 0.83, 1.0] {
            let mut p = p0;
            p.restitution.x = e;
            let s = solve(&p).unwrap();
            let (before, after) = energies(&p, &s);
            let u0 = p.club_contact_velocity(&p.club_velocity_mps, &p.club_angular_velocity_radps);
            let u1 = p.club_contact_velocity(&s.club_velocity_mps, &s.club_angular_velocity_radps)
                - p.ball_contact_velocity(&s.ball_velocity_mps, &s.ball_angular_velocity_radps);
            let closed = -0.5 * s.impulse_n_s.dot(&(u0 + u1));
            assert!(((after - before) - closed).abs() < 1e-9 * before, "e = {e}");
        }
    }
}

/// Penner's closed form (Penner 2003, "The physics of golf"): a point-mass head (contact at its CG, so r_c = 0),
/// rolling, centred on a flat face of loft L at speed v gives
/// v_n = (1 + e) M v cos L / (M + m),  v_t = v sin L / (1 + m/M + m R²/I_b)  and spin w = m R v_t / I_b
/// (Penner's 5 v_t / 2R for I_b = 2/5 m R²).
#[test]
fn penner_point_mass_limit() {
    let mut club = ClubSpec::iron7();
    club.face.center_m = Vector3::zeros();
    club.face.shape = golf_physics::face::FaceShape::Plane;
    for loft_deg in [10.0, 20.0, 30.5, 45.0] {
        club.face.loft_rad = f64::to_radians(loft_deg);
        let eq = Equipment::new(club.clone());
        let (m_head, ball) = (club.mass_kg, eq.ball);
        let v = 40.0;
        let e = 0.83;
        let d = Delivery {
            club_speed_mps: v,
            attack_angle_rad: 0.0,
            club_path_rad: 0.0,
            face_angle_rad: 0.0,
            dynamic_loft_rad: club.face.loft_rad,
            impact_h_m: 0.0,
            impact_v_m: 0.0,
            club_angular_velocity_radps: Vector3::zeros(),
        };
        let state = d.to_state(&eq).unwrap();
        let launch = ImpulseModel::new(ImpulseVariant::Standard).with_cor(e).predict(&state, &eq).unwrap();
        let l = club.face.loft_rad;
        let vn = (1.0 + e) * m_head * v * l.cos() / (m_head + ball.mass_kg);
        let vt =
            v * l.sin() / (1.0 + ball.mass_kg / m_head + ball.mass_kg * ball.radius_m.powi(2) / ball.inertia_kg_m2);
        let speed = vn.hypot(vt);
        let launch_angle = l - vt.atan2(vn); // the normal is at +L, the tangential part points down the face
        let spin = ball.mass_kg * ball.radius_m * vt / ball.inertia_kg_m2; // = 5 v_t / 2R for a uniform sphere
        let got = &launch;
        assert!((got.ball_velocity_mps.norm() - speed).abs() < 1e-9 * speed);
        let got_angle = got.ball_velocity_mps.y.atan2(got.ball_velocity_mps.x);
        assert!((got_angle - launch_angle).abs() < 1e-9);
        assert!((got.ball_spin_radps.z - spin).abs() < 1e-9 * spin, "{} vs {spin}", got.ball_spin_radps.z);
        assert!(got.ball_spin_radps.xy().norm() < 1e-9 * spin);
    }
}

fn launch_of(club: &ClubSpec, variant: ImpulseVariant, input: &DeliveryInput) -> PredictOutput {
    let eq = Equipment::new(club.clone());
    let d = input.to_delivery(club.loft_deg());
    let state = d.to_state(&eq).unwrap();
    let launch = ImpulseModel::new(variant).predict(&state, &eq).unwrap();
    PredictOutput::new(&launch, &DeliveryMetrics::from_state(&state, club), input.handedness.unwrap_or_default(), &eq)
}

fn driver_at(h_mm: f64) -> DeliveryInput {
    DeliveryInput { club_speed_mph: 110.0, dynamic_loft_deg: Some(13.0), impact_h_mm: h_mm, ..Default::default() }
}

/// Gear effect on the driver: a toe hit spins the ball toward a hook (lower sidespin) and a heel hit toward a
/// slice, while the bulge starts the toe hit right of the centre hit (and the heel hit left).
#[test]
fn driver_gear_effect_and_bulge() {
    let club = ClubSpec::driver();
    for variant in ImpulseVariant::ALL {
        let centre = launch_of(&club, variant, &driver_at(0.0));
        let toe = launch_of(&club, variant, &driver_at(20.0));
        let heel = launch_of(&club, variant, &driver_at(-20.0));
        assert!(
            toe.launch.sidespin_rpm < centre.launch.sidespin_rpm - 100.0,
            "{variant:?} toe {} centre {}",
            toe.launch.sidespin_rpm,
            centre.launch.sidespin_rpm
        );
        assert!(heel.launch.sidespin_rpm > centre.launch.sidespin_rpm + 100.0, "{variant:?} heel");
        assert!(toe.launch.launch_direction_deg > centre.launch.launch_direction_deg + 1.0, "{variant:?} bulge toe");
        assert!(heel.launch.launch_direction_deg < centre.launch.launch_direction_deg - 1.0, "{variant:?} bulge heel");
    }
}

/// An open face on a straight path starts the ball right with fade (positive) sidespin, on both clubs.
#[test]
fn open_face_starts_right_with_fade() {
    for club in clubs() {
        for variant in ImpulseVariant::ALL {
            let input = DeliveryInput { club_speed_mph: 95.0, face_angle_deg: 4.0, ..Default::default() };
            let out = launch_of(&club, variant, &input);
            assert!(out.launch.launch_direction_deg > 2.0, "{} {variant:?}", club.name);
            assert!(out.launch.sidespin_rpm > 300.0, "{} {variant:?} {}", club.name, out.launch.sidespin_rpm);
            assert!(out.launch.spin_axis_deg > 0.0);
        }
    }
}

/// A left-handed golfer's delivery with the same numbers as a right-hander's gives the mirror-image launch:
/// same speed, launch angle and backspin; direction, sidespin and spin axis change sign (the boundary mirror).
#[test]
fn left_handed_delivery_mirrors_the_launch() {
    let mut rng = Rng::new(99);
    for club in clubs() {
        for variant in ImpulseVariant::ALL {
            for _ in 0..50 {
                let right = DeliveryInput {
                    club_speed_mph: rng.uniform(70.0, 120.0),
                    attack_angle_deg: rng.uniform(-5.0, 4.0),
                    club_path_deg: rng.uniform(-5.0, 5.0),
                    face_angle_deg: rng.uniform(-4.0, 4.0),
                    dynamic_loft_deg: Some(club.loft_deg() + rng.uniform(-3.0, 4.0)),
                    impact_h_mm: rng.uniform(-15.0, 15.0),
                    impact_v_mm: rng.uniform(-8.0, 8.0),
                    club_angular_velocity_radps: Some([
                        rng.uniform(-5.0, 5.0),
                        rng.uniform(-30.0, 5.0),
                        rng.uniform(-5.0, 5.0),
                    ]),
                    handedness: None,
                    dynamic_lie_deg: None,
                };
                // The left-hander's world is the mirror: z -> -z; path and face angles change sign, the angular
                // velocity mirrors as an axial vector.
                let w = right.club_angular_velocity_radps.unwrap();
                let left = DeliveryInput {
                    club_path_deg: -right.club_path_deg,
                    face_angle_deg: -right.face_angle_deg,
                    club_angular_velocity_radps: Some([-w[0], -w[1], w[2]]),
                    handedness: Some(Handedness::Left),
                    ..right.clone()
                };
                let (r, l) = (launch_of(&club, variant, &right).launch, launch_of(&club, variant, &left).launch);
                let close = |a: f64, b: f64| (a - b).abs() < 1e-9 * (1.0 + a.abs());
                assert!(close(r.ball_speed_mps, l.ball_speed_mps));
                assert!(close(r.launch_angle_deg, l.launch_angle_deg));
                assert!(close(r.backspin_rpm, l.backspin_rpm));
                assert!(close(r.launch_direction_deg, -l.launch_direction_deg));
                assert!(close(r.sidespin_rpm, -l.sidespin_rpm));
                assert!(close(r.spin_axis_deg, -l.spin_axis_deg));
            }
        }
    }
}

/// The solver itself is mirror-symmetric: reflecting every input through z -> -z (positions, velocities and the
/// frame as polar vectors, angular velocities as axial vectors, inertia as M I M) reflects every output. This
/// holds for any club, including the presets' asymmetric inertia.
#[test]
fn solver_is_mirror_symmetric() {
    for (_, _, _, p) in spread(50) {
        let m = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -1.0));
        let q = ContactProblem {
            club_inertia_inv: mirror_z_tensor(&p.club_inertia_inv),
            ball_inertia_inv: mirror_z_tensor(&p.ball_inertia_inv),
            r_club_m: mirror_z(&p.r_club_m),
            r_ball_m: mirror_z(&p.r_ball_m),
            world_from_impact: m * p.world_from_impact,
            club_velocity_mps: mirror_z(&p.club_velocity_mps),
            club_angular_velocity_radps: mirror_z_axial(&p.club_angular_velocity_radps),
            ball_velocity_mps: mirror_z(&p.ball_velocity_mps),
            ball_angular_velocity_radps: mirror_z_axial(&p.ball_angular_velocity_radps),
            ..p
        };
        let (a, b) = (solve(&p).unwrap(), solve(&q).unwrap());
        assert!(rel(mirror_z(&a.ball_velocity_mps), b.ball_velocity_mps) < 1e-12);
        assert!(rel(mirror_z_axial(&a.ball_angular_velocity_radps), b.ball_angular_velocity_radps) < 1e-12);
        assert!(rel(mirror_z_axial(&a.club_angular_velocity_radps), b.club_angular_velocity_radps) < 1e-12);
        let (la, lb) = (
            LaunchMetrics::from_ball(&a.ball_velocity_mps, &a.ball_angular_velocity_radps),
            LaunchMetrics::from_ball(&b.ball_velocity_mps, &b.ball_angular_velocity_radps),
        );
        assert!((la.sidespin_rpm + lb.sidespin_rpm).abs() < 1e-6);
        assert!((la.launch_direction_deg + lb.launch_direction_deg).abs() < 1e-9);
    }
}

/// A club symmetric about its x-y plane (no toe offset, no z products of inertia) hit with a mirrored delivery
/// gives the mirrored launch inside the right-handed model itself: the physics, not the boundary, is symmetric.
#[test]
fn symmetric_club_mirrored_delivery() {
    let mut club = ClubSpec::driver();
    club.face.center_m.z = 0.0;
    for (i, j) in [(0, 2), (2, 0), (1, 2), (2, 1)] {
        club.inertia_kg_m2[(i, j)] = 0.0;
    }
    club.inertia_inv_kg_m2 = club.inertia_kg_m2.try_inverse().unwrap();
    let mut rng = Rng::new(5);
    for variant in [ImpulseVariant::Standard, ImpulseVariant::Adjusted] {
        let tuned = club.clone();
        let mut tuning = ImpulseTuning::seed_for(&club);
        tuning.adjusted_ball_cg_shift_m.z = 0.0; // a heel-ward shift is itself handed
        for _ in 0..50 {
            let d = random_delivery(&mut rng, &tuned);
            let w = d.club_angular_velocity_radps;
            let dm = Delivery {
                club_path_rad: -d.club_path_rad,
                face_angle_rad: -d.face_angle_rad,
                impact_h_m: -d.impact_h_m,
                club_angular_velocity_radps: Vector3::new(-w.x, -w.y, w.z),
                ..d
            };
            let eq = Equipment::new(tuned.clone());
            let model = ImpulseModel::new(variant).with_tuning(tuning);
            let a = model.predict(&d.to_state(&eq).unwrap(), &eq).unwrap();
            let b = model.predict(&dm.to_state(&eq).unwrap(), &eq).unwrap();
            assert!(rel(mirror_z(&a.ball_velocity_mps), b.ball_velocity_mps) < 1e-12);
            assert!(rel(mirror_z_axial(&a.ball_spin_radps), b.ball_spin_radps) < 1e-12);
        }
    }
}
