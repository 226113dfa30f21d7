//! The flexible shaft (seed section 4.1, eq. 4.1-4.2, Tables 4.1-4.2): the model's bending stiffness against the
//! geometry's, the assembled club's first frequency, and convergence of its dynamics.

#![allow(clippy::unwrap_used)]

use golf_physics::equipment::shaft::ShaftSpec;
use golf_physics::equipment::sole::SoleSpec;
use golf_physics::equipment::ClubSpec;
use golf_physics::impact::continuous::shaft::modal::{ModalClub, ModalState, ModalVec};
use golf_physics::impact::continuous::shaft::{three_point_ei, FlexibleClub, HeadOnShaft, ShaftMesh};
use golf_physics::math::{Real, Vector3};

fn club(elements: usize, clamp_m: Real) -> FlexibleClub {
    FlexibleClub::new(
        &ShaftSpec::iron7(),
        &HeadOnShaft::of(&ClubSpec::iron7()),
        &SoleSpec::IRON7,
        ShaftMesh { elements, clamp_m },
    )
    .unwrap()
}

/// Eq. 4.1 along the shaft: the model's three-point deflection over a 5 in (127 mm) span, the span of a shaft
/// EI meter, gives the EI of Table 4.2's geometry at mid-span within 2 % (it averages EI over the span, so the
/// difference is largest where the taper is steepest).
#[test]
fn three_point_bending_matches_the_geometrys_ei() {
    let shaft = ShaftSpec::iron7();
    let span = 0.127;
    let mut worst: Real = 0.0;
    let mut x = 0.5 * span;
    while x <= shaft.length_m() - 0.5 * span + 1e-9 {
        let ei_model = three_point_ei(&shaft, x, span, 16).unwrap();
        let ei_geom = shaft.ei_n_m2(x);
        let rel = (ei_model / ei_geom - 1.0).abs();
        println!("x = {x:.3} m: EI model {ei_model:.2} N m², geometry {ei_geom:.2} N m², {:.3} %", 100.0 * rel);
        worst = worst.max(rel);
        x += 0.025;
    }
    println!("largest difference {:.3} %", 100.0 * worst);
    assert!(worst < 0.02, "{worst}");
}

/// A uniform tube: the model's three-point EI is the closed form's to rounding (eq. 4.1 is exact for a
/// uniform beam, and cubic Hermite elements are exact under point loads).
#[test]
fn three_point_bending_uniform_tube_is_exact() {
    let mut shaft = ShaftSpec::iron7();
    for s in &mut shaft.stations {
        s.outer_radius_m = 6e-3;
        s.wall_m = 0.45e-3;
    }
    let ei = three_point_ei(&shaft, 0.5, 0.2, 4).unwrap();
    assert!((ei / shaft.ei_n_m2(0.5) - 1.0).abs() < 1e-10, "{ei}");
}

/// The assembled club (Table 4.2 shaft, 264 g head with Table 3.1 inertia), butt clamped: its first bending
/// frequency. Club fitters measure 4.5-5.5 Hz (270-330 cpm) for a stiff steel 7-iron, on a meter that clamps
/// the butt's 5 in (127 mm).
#[test]
fn first_bending_frequency() {
    let butt = club(24, 0.0).first_frequency_hz().unwrap();
    let fitter = club(24, 0.127).first_frequency_hz().unwrap();
    println!(
        "first frequency: butt end clamped {butt:.3} Hz ({:.0} cpm); 5 in clamp {fitter:.3} Hz ({:.0} cpm)",
        butt * 60.0,
        fitter * 60.0
    );
    assert!((4.5..=5.5).contains(&fitter), "{fitter}");
    assert!(butt < fitter);
}

/// The frequencies converge under mesh refinement: the first five within 0.1 % from 12 to 48 elements.
#[test]
fn frequencies_converge_with_the_mesh() {
    let fine = club(48, 0.0).modes().unwrap().0;
    let coarse = club(12, 0.0).modes().unwrap().0;
    for i in 0..5 {
        let rel = (coarse[i] / fine[i] - 1.0).abs();
        println!(
            "mode {i}: {:.3} Hz (48 el) vs {:.3} Hz (12 el)",
            fine[i] / std::f64::consts::TAU,
            coarse[i] / std::f64::consts::TAU
        );
        assert!(rel < 1e-3, "mode {i}: {rel}");
    }
}

/// Runs a 0.4 ms, 500 N half-sine push on the head's CG along the face normal (a ball-sized impulse) and 5 ms
/// after, returning the head's CG displacement and rotation (club frame).
fn push(elements: usize, max_hz: Real, step_s: Real) -> (Vector3, Vector3) {
    let modal = ModalClub::new(&club(elements, 0.0), max_hz, 0.0).unwrap();
    let loft = 30.5f64.to_radians();
    let dir = -Vector3::new(loft.cos(), loft.sin(), 0.0);
    let torque = Vector3::zeros();
    let force =
        |t: Real| if t < 4e-4 { 500.0 * (std::f64::consts::PI * t / 4e-4).sin() * dir } else { Vector3::zeros() };
    let mut s = ModalState::default();
    let n = (5.4e-3 / step_s).round() as usize;
    let add = |s: &ModalState, v: &ModalVec, a: &ModalVec, h: Real| ModalState {
        eta: s.eta + v * h,
        eta_dot: s.eta_dot + a * h,
    };
    for i in 0..n {
        let t = i as Real * step_s;
        let a1 = modal.acceleration(&s, &force(t), &torque);
        let s2 = add(&s, &s.eta_dot, &a1, 0.5 * step_s);
        let a2 = modal.acceleration(&s2, &force(t + 0.5 * step_s), &torque);
        let s3 = add(&s, &s2.eta_dot, &a2, 0.5 * step_s);
        let a3 = modal.acceleration(&s3, &force(t + 0.5 * step_s), &torque);
        let s4 = add(&s, &s3.eta_dot, &a3, step_s);
        let a4 = modal.acceleration(&s4, &force(t + step_s), &torque);
        s = ModalState {
            eta: s.eta + (s.eta_dot + 2.0 * s2.eta_dot + 2.0 * s3.eta_dot + s4.eta_dot) * (step_s / 6.0),
            eta_dot: s.eta_dot + (a1 + 2.0 * a2 + 2.0 * a3 + a4) * (step_s / 6.0),
        };
    }
    let o = modal.head_offset(&s);
    (o.cg_m, o.rotation_rad)
}

/// The head's response to a push converges under mesh refinement, mode cut-off and step halving (< 0.5 %);
/// eight elements with every mode kept (48, the highest at 1.5e5 rad/s) are within 0.43 % of 48 elements.
#[test]
fn head_response_converges() {
    let reference = push(48, 5000.0, 1e-6);
    let rel = |a: &(Vector3, Vector3)| {
        ((a.0 - reference.0).norm() / reference.0.norm()).max((a.1 - reference.1).norm() / reference.1.norm())
    };
    println!("reference: CG {:?} mm, rotation {:?} deg", reference.0 * 1e3, reference.1.map(|r| r.to_degrees()));
    for (elements, max_hz, step) in
        [(8, 1e9, 1e-7), (12, 5000.0, 1e-6), (24, 5000.0, 1e-6), (48, 2000.0, 1e-6), (48, 5000.0, 2e-6)]
    {
        let r = rel(&push(elements, max_hz, step));
        println!("{elements} elements, modes to {max_hz} Hz, step {step}: {:.4} %", 100.0 * r);
        assert!(r < 0.005, "{elements} {max_hz} {step}: {r}");
    }
}

/// Momentum bookkeeping: the elastic club's momentum changes by the push's impulse plus the impulse of the grip's
/// reaction (both integrated with the step's own weights). With every mode kept the balance is exact to
/// rounding; dropping modes above 5 kHz leaves a small residue.
#[test]
fn momentum_balances_the_push_and_the_grip() {
    for (elements, max_hz, tol) in [(8, 1e9, 1e-9), (24, 5000.0, 1e-2)] {
        let modal = ModalClub::new(&club(elements, 0.0), max_hz, 0.0).unwrap();
        let f = Vector3::new(-400.0, -150.0, 60.0);
        let torque = Vector3::new(0.5, -1.0, 2.0);
        let h: Real = if max_hz > 1e8 { 2e-8 } else { 1e-6 };
        let mut s = ModalState::default();
        let mut grip_impulse = Vector3::zeros();
        let n = (2e-4 / h).round() as usize;
        for _ in 0..n {
            let add = |s: &ModalState, v: &ModalVec, a: &ModalVec, h: Real| ModalState {
                eta: s.eta + v * h,
                eta_dot: s.eta_dot + a * h,
            };
            let a1 = modal.acceleration(&s, &f, &torque);
            let s2 = add(&s, &s.eta_dot, &a1, 0.5 * h);
            let a2 = modal.acceleration(&s2, &f, &torque);
            let s3 = add(&s, &s2.eta_dot, &a2, 0.5 * h);
            let a3 = modal.acceleration(&s3, &f, &torque);
            let s4 = add(&s, &s3.eta_dot, &a3, h);
            let a4 = modal.acceleration(&s4, &f, &torque);
            // The clamp's reaction is the force the grip applies to the shaft.
            let g = |s: &ModalState, a: &ModalVec| modal.grip_force(s, a);
            grip_impulse += (g(&s, &a1) + 2.0 * g(&s2, &a2) + 2.0 * g(&s3, &a3) + g(&s4, &a4)) * (h / 6.0);
            s = ModalState {
                eta: s.eta + (s.eta_dot + 2.0 * s2.eta_dot + 2.0 * s3.eta_dot + s4.eta_dot) * (h / 6.0),
                eta_dot: s.eta_dot + (a1 + 2.0 * a2 + 2.0 * a3 + a4) * (h / 6.0),
            };
        }
        let p = modal.momentum(&s);
        let want = f * 2e-4 + grip_impulse;
        let rel = (p - want).norm() / (f * 2e-4).norm();
        println!("{elements} elements, {} modes: momentum {p:?}, impulses {want:?}, residue {rel:.3e}", modal.n_modes);
        assert!(rel < tol, "{rel}");
    }
}

/// Eq. 4.2 on the assembled club: a torque T about the shaft's axis at the tip twists it by
/// θ = T ∫₀ᴸ dx / GJ(x), and a tip force F bends it by δ = F ∫₀ᴸ (L − x)² / EI(x) dx (unit-load method);
/// 24 elements give both within 0.1 % (the elements' stiffness averages GJ and EI over each element where the
/// closed form averages their inverses: a second-order difference that vanishes as the mesh refines).
#[test]
fn static_twist_and_tip_deflection_match_closed_forms() {
    use golf_physics::math::Real;
    let shaft = ShaftSpec::iron7();
    let c = club(24, 0.0);
    let n = c.dofs();
    let tip = c.tip_dof();
    let l = shaft.length_m();
    let steps = 200_000;
    let h = l / steps as Real;
    let (mut twist, mut bend) = (0.0, 0.0);
    for i in 0..steps {
        let x = (i as Real + 0.5) * h;
        twist += h / shaft.gj_n_m2(x);
        bend += h * (l - x).powi(2) / shaft.ei_n_m2(x);
    }
    let mut f = golf_physics::math::DVector::zeros(n);
    f[tip + 3] = 1.0; // torque about the shaft axis, N m
    let u = c.static_displacement(&f).unwrap();
    assert!((u[tip + 3] / twist - 1.0).abs() < 1e-3, "{} vs {twist}", u[tip + 3]);
    let mut f = golf_physics::math::DVector::zeros(n);
    f[tip + 1] = 1.0; // lateral force, N
    let u = c.static_displacement(&f).unwrap();
    assert!((u[tip + 1] / bend - 1.0).abs() < 1e-3, "{} vs {bend}", u[tip + 1]);
    println!(
        "tip twist {:.4} rad/(N m) (GJ_eff {:.1} N m² over the length), tip compliance {:.4} m/N",
        twist,
        l / twist,
        bend
    );
}
