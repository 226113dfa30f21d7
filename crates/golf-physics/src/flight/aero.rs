//! Drag and lift of a spinning dimpled ball as functions of the Reynolds number `Re = ρ |u| d / μ` and the spin
//! ratio `S = r |ω| / |u|` (the seed's section 4.3 flies the ball with an aerodynamic model of the same kind,
//! Figures 4.16-4.17; the shapes below follow the wind-tunnel and free-flight studies listed in `docs/flight.md`).
//!
//! - Drag `C_D = c_d0 + c_ds · min(S, S_MAX) + c_dc · σ(Re)`: a dimpled ball's drag without spin above the drag
//!   crisis (`c_d0`), rising linearly with the spin ratio (`c_ds`, Smits and Smith's linear form), and a step
//!   `c_dc` below the crisis, where the boundary layer separates early. `σ(Re) = 1 / (1 + exp((Re − Re_c) /
//!   (w Re_c)))` is the share of subcritical flow, the crisis at `Re_c` (`re_crisis`), `w` = [`Aero::crisis_width`]
//!   wide. Above the crisis the drag at a fixed spin ratio does not depend on the Reynolds number, as the
//!   sources find for modern balls (within their scatter). Past [`S_MAX`], the largest spin ratio the sources
//!   measured, the spin drag is held.
//! - Lift `C_L = c_lmax · S / (S + s_half) · (1 − σ(Re))`: rising with the spin ratio and saturating at
//!   `c_lmax`, half of it at `s_half`; below the crisis the Magnus lift fades out (the laminar separation
//!   cancels it; some balls even show a reverse Magnus force there).
//!
//! Six numbers, each a physical property of the ball: the supercritical drag without spin, the drag per spin
//! ratio, the extra subcritical drag, the critical Reynolds number, the saturated lift and the spin ratio at half
//! of it. They are fitted to the TrackMan tour averages (`flight::fit`) with the spin decay held at Smits and
//! Smith's measurement ([`SPIN_TAU_S`]).

use crate::math::Real;

/// The largest spin ratio the drag sources measured; the spin drag is held at its value there beyond.
pub const S_MAX: Real = 0.5;

/// The spin decay, measured, not fitted: a time constant of 22 s at 50 m/s, Smits and Smith's (1994) decay rate
/// `0.0004 · V[mph] · ω` per second (about 4.5 % of the spin per second at 50 m/s).
pub const SPIN_TAU_S: Real = 22.0;

/// Aerodynamic coefficients of a ball (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Aero {
    /// Drag without spin above the crisis.
    pub c_d0: Real,
    /// Drag per unit spin ratio (held beyond [`S_MAX`]).
    pub c_ds: Real,
    /// Drag added below the crisis.
    pub c_dc: Real,
    /// Reynolds number of the drag crisis.
    pub re_crisis: Real,
    /// Post-critical drag rise per 10⁵ of Reynolds number past the crisis.
    pub c_dre: Real,
    /// Saturated lift at high spin ratios.
    pub c_lmax: Real,
    /// The spin ratio at half the saturated lift.
    pub s_half: Real,
    /// How the lift at a fixed spin ratio falls with the Reynolds number: a factor `(Re / 10⁵)^(−k_lre)`.
    pub k_lre: Real,
    /// Spin decay time constant (s) at 50 m/s.
    pub spin_tau_s: Real,
    /// Relative width of the drag crisis: the flow goes from 73 % to 27 % subcritical over `Re_c (1 ± w)`.
    pub crisis_width: Real,
}

/// `Aero::FITTED` in field order, as `impactd flight-fit` prints them.
const FIT: [Real; 10] = [
    0.22341067618610566,
    0.2275918234163632,
    0.29999999969999996,
    55046.5473567647,
    3.805628318399023e-10,
    0.46228521428939606,
    0.1282616511349477,
    0.29999999969999996,
    34.999999983,
    0.22920307941101686,
];

/// The range each fitted number may take, in field order: what the sources in `docs/flight.md` measured for
/// modern balls (drag without spin 0.15-0.30, its rise with spin ratio up to 0.8, subcritical excess up to 0.3,
/// crisis between Re 4·10⁴ and 1.2·10⁵, post-critical rise up to Lyu's 0.19 per (10⁵)², saturated lift 0.2-0.6
/// reached by half at S 0.03-0.5, lift falling with Re by an exponent up to 0.3, spin decay 18-35 s at 50 m/s).
pub const BOUNDS: [(Real, Real); 10] = [
    (0.15, 0.30),
    (0.0, 0.8),
    (0.0, 0.3),
    (40_000.0, 120_000.0),
    (0.0, 0.19),
    (0.2, 0.6),
    (0.03, 0.5),
    (0.0, 0.3),
    (18.0, 35.0),
    (0.05, 0.6),
];

impl Aero {
    /// Fitted by `impactd flight-fit` to the TrackMan tour averages (`docs/flight.md`).
    pub const FITTED: Aero = Aero::from_array(FIT);

    /// No air at all: the vacuum parabola.
    pub const VACUUM: Aero = Aero {
        c_d0: 0.0,
        c_ds: 0.0,
        c_dc: 0.0,
        re_crisis: 80_000.0,
        c_dre: 0.0,
        c_lmax: 0.0,
        s_half: 0.1,
        k_lre: 0.0,
        spin_tau_s: 1e9,
        crisis_width: 0.1,
    };

    /// The nine fitted numbers in field order.
    pub const fn from_array(x: [Real; 10]) -> Aero {
        Aero {
            c_d0: x[0],
            c_ds: x[1],
            c_dc: x[2],
            re_crisis: x[3],
            c_dre: x[4],
            c_lmax: x[5],
            s_half: x[6],
            k_lre: x[7],
            spin_tau_s: x[8],
            crisis_width: x[9],
        }
    }

    /// The nine fitted numbers in field order.
    pub fn to_array(&self) -> [Real; 10] {
        [
            self.c_d0,
            self.c_ds,
            self.c_dc,
            self.re_crisis,
            self.c_dre,
            self.c_lmax,
            self.s_half,
            self.k_lre,
            self.spin_tau_s,
            self.crisis_width,
        ]
    }

    /// The share of subcritical flow at Reynolds number `reynolds`: 0 well above the crisis, 1 well below.
    pub fn subcritical(&self, reynolds: Real) -> Real {
        let x = (reynolds - self.re_crisis) / (self.crisis_width * self.re_crisis);
        1.0 / (1.0 + x.clamp(-50.0, 50.0).exp())
    }

    /// `(C_D, C_L)` at Reynolds number `reynolds` and spin ratio `spin_ratio`.
    #[inline]
    pub fn coefficients(&self, reynolds: Real, spin_ratio: Real) -> (Real, Real) {
        let sub = self.subcritical(reynolds);
        let s = spin_ratio.max(0.0);
        let post = self.c_dre * ((reynolds - self.re_crisis) * 1e-5).max(0.0).powi(2);
        let drag = self.c_d0 + self.c_ds * s.min(S_MAX) + self.c_dc * sub + post;
        let lift = if s > 0.0 {
            self.c_lmax * s / (s + self.s_half) * (reynolds.max(1e3) * 1e-5).powf(-self.k_lre) * (1.0 - sub)
        } else {
            0.0
        };
        (drag, lift)
    }
}

/// Reynolds number of a ball of diameter `diameter_m` at airspeed `airspeed_mps` in air of density `density_kg_m3`
/// and viscosity `viscosity_pa_s`.
pub fn reynolds(airspeed_mps: Real, diameter_m: Real, density_kg_m3: Real, viscosity_pa_s: Real) -> Real {
    density_kg_m3 * airspeed_mps * diameter_m / viscosity_pa_s
}

/// One point of the coefficient grid `impactd flight --coefficients` prints.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct CoefficientPoint {
    /// Airspeed (m/s).
    pub speed_mps: Real,
    /// Reynolds number `Re = ρ |u| d / μ`.
    pub reynolds: Real,
    /// Spin ratio `S = r |ω| / |u|`.
    pub spin_ratio: Real,
    /// The spin (rpm) that gives `spin_ratio` at this airspeed.
    pub spin_rpm: Real,
    /// Drag coefficient `C_D(Re, S)`.
    pub c_d: Real,
    /// Lift coefficient `C_L(Re, S)`.
    pub c_l: Real,
}

/// Airspeeds (m/s) and spin ratios of the printed grid.
pub const GRID_SPEEDS_MPS: [Real; 8] = [20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0];
/// Spin ratios of the printed grid.
pub const GRID_SPIN_RATIOS: [Real; 8] = [0.0, 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5];

/// `aero`'s coefficients over [`GRID_SPEEDS_MPS`] × [`GRID_SPIN_RATIOS`] for a ball of radius `radius_m` in
/// air of density `density_kg_m3` and viscosity `viscosity_pa_s`.
pub fn grid(aero: &Aero, radius_m: Real, density_kg_m3: Real, viscosity_pa_s: Real) -> Vec<CoefficientPoint> {
    let mut out = Vec::with_capacity(GRID_SPEEDS_MPS.len() * GRID_SPIN_RATIOS.len());
    for v in GRID_SPEEDS_MPS {
        let re = reynolds(v, 2.0 * radius_m, density_kg_m3, viscosity_pa_s);
        for s in GRID_SPIN_RATIOS {
            let (c_d, c_l) = aero.coefficients(re, s);
            let spin_rpm = crate::units::radps_to_rpm(s * v / radius_m);
            out.push(CoefficientPoint { speed_mps: v, reynolds: re, spin_ratio: s, spin_rpm, c_d, c_l });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ball without spin has no lift; the lift is the saturating curve times the supercritical share, half of
    /// `c_lmax` at `s_half` (at Re 10⁵, where the Reynolds factor is 1); the drag is the sum of its terms.
    #[test]
    fn limits() {
        let a = Aero::FITTED;
        assert_eq!(a.coefficients(2e5, 0.0).1, 0.0);
        let sub = a.subcritical(1e5);
        let (drag, half) = a.coefficients(1e5, a.s_half);
        assert!((half - 0.5 * a.c_lmax * (1.0 - sub)).abs() < 1e-12);
        let post = a.c_dre * ((1e5 - a.re_crisis) * 1e-5).max(0.0).powi(2);
        assert!((drag - (a.c_d0 + a.c_ds * a.s_half + a.c_dc * sub + post)).abs() < 1e-12);
        // More subcritical flow at lower Reynolds numbers.
        assert!(a.subcritical(3e4) > a.subcritical(6e4) && a.subcritical(6e4) > a.subcritical(1.2e5));
    }
}
