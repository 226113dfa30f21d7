//! Time integration of ball flight (the impact models integrate in `impact::continuous`).
//!
//! A system gives the rate of its state ([`Ode::rate`]) and how a state moves along rates ([`Ode::advance`],
//! [`Ode::advance_rk4`]); [`rk4_step`] takes one classical fourth-order Runge-Kutta step. The caller owns the
//! loop, so it can stop at an event (first contact, separation, landing) and refine the last step; an adaptive
//! step can be added here behind the same trait.
//!
//! Each system writes its own `advance_rk4`, so each keeps its own floating-point order (replays stay
//! byte-identical across refactors).

use crate::math::Real;

/// An ordinary differential equation `ẋ = f(x)` over a state and its rate.
pub trait Ode {
    /// The state `x`.
    type State;
    /// The rate `ẋ` of a state.
    type Rate;
    /// `f(x)`.
    fn rate(&self, state: &Self::State) -> Self::Rate;
    /// `x + h r`.
    fn advance(state: &Self::State, rate: &Self::Rate, h: Real) -> Self::State;
    /// `x + h (k1 + 2 k2 + 2 k3 + k4) / 6`.
    fn advance_rk4(state: &Self::State, k: [&Self::Rate; 4], h: Real) -> Self::State;
}

/// One classical Runge-Kutta step of size `h` from `state`, whose rate `k1` the caller has already computed (it
/// usually needs it anyway: forces for a trace, the contact test).
#[inline]
pub fn rk4_step<S: Ode>(system: &S, state: &S::State, k1: &S::Rate, h: Real) -> S::State {
    let k2 = system.rate(&S::advance(state, k1, 0.5 * h));
    let k3 = system.rate(&S::advance(state, &k2, 0.5 * h));
    let k4 = system.rate(&S::advance(state, &k3, h));
    S::advance_rk4(state, [k1, &k2, &k3, &k4], h)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `ẋ = -x`: one RK4 step is the exponential's Taylor series to fourth order, `1 - h + h²/2 - h³/6 + h⁴/24`.
    struct Decay;
    impl Ode for Decay {
        type State = Real;
        type Rate = Real;
        fn rate(&self, x: &Real) -> Real {
            -x
        }
        fn advance(x: &Real, r: &Real, h: Real) -> Real {
            x + h * r
        }
        fn advance_rk4(x: &Real, k: [&Real; 4], h: Real) -> Real {
            x + h * (k[0] + 2.0 * k[1] + 2.0 * k[2] + k[3]) / 6.0
        }
    }

    #[test]
    fn one_step_is_the_fourth_order_taylor_series() {
        let h = 0.1;
        let x = rk4_step(&Decay, &1.0, &-1.0, h);
        let taylor = 1.0 - h + h * h / 2.0 - h.powi(3) / 6.0 + h.powi(4) / 24.0;
        assert!((x - taylor).abs() < 1e-15, "{x} vs {taylor}");
    }
}
