//! Published measurements of golf-ball drag and lift that the model is checked against (tests, `docs/flight.md`
//! and its figures): Bearman and Harvey's wind tunnel (1976), Lyu et al.'s free flight of production balls
//! (2018), and the coefficients of Nathan's golf trajectory model as libgolf publishes them.

/// Bearman and Harvey (1976), wind tunnel, as tabulated over airspeed and spin rate in NTNU's TKT4140 course
/// material (`experdata/dragdata.m`, `liftdata.m`): airspeeds (m/s), and for 2000, 3000, 4000, 5000 and 6000 rpm
/// the drag and the lift at each airspeed.
pub const BH_SPEEDS_MPS: [crate::math::Real; 10] = [13.7, 21.6, 29.9, 38.4, 46.9, 55.2, 63.1, 71.9, 80.2, 88.1];
/// The spin rates of Bearman and Harvey's rows (rpm).
pub const BH_RPM: [crate::math::Real; 5] = [2000.0, 3000.0, 4000.0, 5000.0, 6000.0];
// Measured values; 0.318 is a drag coefficient, not 1/π.
/// Drag coefficients, a row per spin rate of [`BH_RPM`], a column per airspeed of [`BH_SPEEDS_MPS`].
#[allow(clippy::approx_constant)]
pub const BH_CD: [[crate::math::Real; 10]; 5] = [
    [0.363, 0.288, 0.275, 0.255, 0.247, 0.247, 0.247, 0.247, 0.247, 0.247],
    [0.420, 0.365, 0.318, 0.279, 0.268, 0.259, 0.256, 0.255, 0.2538, 0.2538],
    [0.428, 0.400, 0.347, 0.309, 0.284, 0.271, 0.267, 0.263, 0.2605, 0.2605],
    [0.481, 0.430, 0.374, 0.335, 0.306, 0.287, 0.275, 0.271, 0.2673, 0.2673],
    [0.515, 0.441, 0.386, 0.352, 0.329, 0.306, 0.288, 0.279, 0.274, 0.274],
];
/// Lift coefficients, laid out as [`BH_CD`].
pub const BH_CL: [[crate::math::Real; 10]; 5] = [
    [0.100, 0.185, 0.245, 0.200, 0.173, 0.153, 0.142, 0.136, 0.128, 0.128],
    [0.359, 0.335, 0.304, 0.246, 0.208, 0.184, 0.167, 0.1584, 0.1485, 0.1468],
    [0.400, 0.364, 0.335, 0.286, 0.2387, 0.215, 0.197, 0.1807, 0.169, 0.1582],
    [0.413, 0.391, 0.350, 0.312, 0.2693, 0.241, 0.226, 0.2031, 0.1895, 0.1791],
    [0.465, 0.423, 0.372, 0.339, 0.300, 0.266, 0.250, 0.2254, 0.210, 0.200],
];

/// Bilinear interpolation in Bearman and Harvey's table, airspeed and spin rate held inside it.
pub fn bearman_harvey(
    table: &[[crate::math::Real; 10]; 5],
    speed_mps: crate::math::Real,
    rpm: crate::math::Real,
) -> crate::math::Real {
    let locate = |xs: &[crate::math::Real], x: crate::math::Real| {
        let x = x.clamp(xs[0], xs[xs.len() - 1]);
        let i = xs.windows(2).position(|w| x <= w[1]).unwrap_or(xs.len() - 2);
        (i, (x - xs[i]) / (xs[i + 1] - xs[i]))
    };
    let (i, u) = locate(&BH_SPEEDS_MPS, speed_mps);
    let (j, w) = locate(&BH_RPM, rpm);
    let at = |j: usize| table[j][i] * (1.0 - u) + table[j][i + 1] * u;
    at(j) * (1.0 - w) + at(j + 1) * w
}

/// Lyu, Kensrud, Smith and Wang (2018), "Aerodynamics of golf balls in still air", Proceedings 2(6) 238: 13
/// production balls in free flight, 18-91 m/s, 1500-4500 rpm; the average fits
/// `C_D = 1.29e-10 Re² − 2.59e-5 Re + 1.50` below 32 m/s and `1.91e-11 Re² − 5.40e-6 Re + 0.56` above
/// (`Re = V d / ν`, d = 43 mm, ν = 1.48e-5 m²/s), and `C_L = 1.99 S − 3.25 S²` over their spin ratios.
pub fn lyu(speed_mps: crate::math::Real, spin_ratio: crate::math::Real) -> (crate::math::Real, crate::math::Real) {
    let re = speed_mps * 0.043 / 1.48e-5;
    let drag = if speed_mps <= 32.0 {
        1.29e-10 * re * re - 2.59e-5 * re + 1.50
    } else {
        1.91e-11 * re * re - 5.40e-6 * re + 0.56
    };
    // The spin ratios they measured at this airspeed.
    let s_at = |rpm: crate::math::Real| 0.0215 * crate::units::rpm_to_radps(rpm) / speed_mps;
    let s = spin_ratio.clamp(s_at(1500.0), s_at(4500.0));
    (drag, 1.99 * s - 3.25 * s * s)
}

/// Nathan's golf trajectory model (A. M. Nathan, "TrajectoryCalculatorGolf") with the coefficients the open-source
/// library libgolf publishes for it (`gdifiore/libgolf`, `docs/aerodynamic_model.md`): `(C_D, C_L)` at Reynolds
/// number `reynolds` and spin ratio `spin_ratio`. With `x = Re / 10⁵`: drag `0.5` below x 0.5, falling linearly to
/// `0.2` at x 1, plus `0.18 S`; lift above x 0.7 the saturating `c_max · 16 S / (1 + 16 S)`, `c_max` 0.268 up to
/// S 0.35 rising linearly to 0.32 at S 0.5. Below x 0.7 libgolf interpolates Bearman-based lift bins; here the
/// same saturating curve fades linearly to nothing at x 0.3 instead. Its spin decays with the time constant
/// `r / (2·10⁻⁵ v)` (21 s at 50 m/s).
pub fn nathan(reynolds: crate::math::Real, spin_ratio: crate::math::Real) -> (crate::math::Real, crate::math::Real) {
    let x = reynolds * 1e-5;
    let s = spin_ratio.max(0.0);
    let drag = 0.5 - 0.3 * ((x - 0.5) / 0.5).clamp(0.0, 1.0) + 0.18 * s;
    let c_max = 0.268 + 0.052 * ((s - 0.35) / 0.15).clamp(0.0, 1.0);
    let lift = c_max * 16.0 * s / (1.0 + 16.0 * s) * ((x - 0.3) / 0.4).clamp(0.0, 1.0);
    (drag, lift)
}
