//! How sure a prediction is: one-sigma standard deviations of the delivery's numbers and of the launch's, from
//! the delivery's covariance (the estimator's, `kinematics::uncertainty`) carried through the impact model by
//! linearisation.
//!
//! The delivery is described by eleven parameters `d = (s, a, p, f, l, h, v, ω_x, ω_y, ω_z, λ)`: club speed,
//! attack angle, club path, face angle, dynamic loft, impact location, the head's angular velocity and dynamic
//! lie, which fix an [`ImpactState`] through [`Delivery::to_state_with_lie`]. The launch's
//! covariance is `J Σ_d Jᵀ`, with the Jacobian `J = ∂L/∂d` of the launch numbers `L` by forward differences over
//! the eleven parameters: twelve runs of the model (each recomputing only the part of the state its parameter
//! moves: `StateParts`), about 0.2 us each for the impulse-momentum models (seed eq.
//! 3.1-3.12). A continuous model's run costs 0.4 ms or more, so its launch's uncertainty uses the
//! impulse-momentum Jacobian (the `adjusted` model, or the rig's own impulse-momentum model): the two agree on
//! how the launch moves with the delivery to within a few per cent near a centred strike, far less than the
//! uncertainty itself is known.

use super::{
    ContactGeometry, Delivery, Equipment, ImpactError, ImpactModel, ImpactState, LaunchMetrics, StatePart, StateParts,
};
use crate::math::{Real, SMatrix, SVector, Vector3};

/// The delivery's parameters (see the module docs).
pub const DELIVERY_PARAMETERS: usize = 11;

/// The covariance of a delivery's parameters (SI: m/s, rad, m, rad/s), in the order of the module docs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeliveryCovariance {
    /// The covariance matrix (SI units squared, symmetric).
    pub cov: SMatrix<DELIVERY_PARAMETERS, DELIVERY_PARAMETERS>,
}

pub use super::sigmas::{DeliveryUncertainty, LaunchUncertainty};

impl DeliveryCovariance {
    /// The standard deviations of the delivery's numbers.
    pub fn sigmas(&self) -> DeliveryUncertainty {
        let c = &self.cov;
        let sd = |i: usize| c[(i, i)].max(0.0).sqrt();
        let deg = |i: usize| sd(i).to_degrees();
        // Face to path is face minus path: their covariance counts.
        let f2p = (c[(3, 3)] + c[(2, 2)] - 2.0 * c[(2, 3)]).max(0.0).sqrt().to_degrees();
        DeliveryUncertainty {
            club_speed_mph: crate::units::mps_to_mph(sd(0)),
            attack_angle_deg: deg(1),
            club_path_deg: deg(2),
            face_angle_deg: deg(3),
            dynamic_loft_deg: deg(4),
            face_to_path_deg: f2p,
            impact_h_mm: sd(5) * 1e3,
            impact_v_mm: sd(6) * 1e3,
        }
    }
}

/// The parameter vector of a delivery and its dynamic lie.
fn parameters(d: &Delivery, lie_rad: Real) -> SVector<DELIVERY_PARAMETERS> {
    let w = d.club_angular_velocity_radps;
    SVector::<DELIVERY_PARAMETERS>::from_column_slice(&[
        d.club_speed_mps,
        d.attack_angle_rad,
        d.club_path_rad,
        d.face_angle_rad,
        d.dynamic_loft_rad,
        d.impact_h_m,
        d.impact_v_m,
        w.x,
        w.y,
        w.z,
        lie_rad,
    ])
}

fn delivery_of(x: &SVector<DELIVERY_PARAMETERS>) -> (Delivery, Real) {
    (
        Delivery {
            club_speed_mps: x[0],
            attack_angle_rad: x[1],
            club_path_rad: x[2],
            face_angle_rad: x[3],
            dynamic_loft_rad: x[4],
            impact_h_m: x[5],
            impact_v_m: x[6],
            club_angular_velocity_radps: Vector3::new(x[7], x[8], x[9]),
        },
        x[10],
    )
}

/// The launch numbers the uncertainty reports, in [`LaunchUncertainty`]'s order.
fn launch_numbers(m: &LaunchMetrics) -> SVector<5> {
    SVector::<5>::new(m.ball_speed_mph, m.launch_angle_deg, m.launch_direction_deg, m.total_spin_rpm, m.spin_axis_deg)
}

/// Forward-difference steps: small against the parameters' uncertainty (0.01-0.1 of a sigma at 720 Hz), large
/// against rounding.
const STEPS: [Real; DELIVERY_PARAMETERS] = [1e-3, 1e-5, 1e-5, 1e-5, 1e-5, 1e-6, 1e-6, 1e-3, 1e-3, 1e-3, 1e-5];

/// How a model's launch numbers move with the delivery's parameters, around one delivery.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaunchJacobian {
    j: SMatrix<5, DELIVERY_PARAMETERS>,
}

impl LaunchJacobian {
    /// Linearises `model` around `delivery` at `dynamic_lie_rad` (twelve runs).
    pub fn of(
        model: &dyn ImpactModel,
        equipment: &Equipment,
        delivery: &Delivery,
        dynamic_lie_rad: Real,
    ) -> Result<LaunchJacobian, ImpactError> {
        let x0 = parameters(delivery, dynamic_lie_rad);
        // Each step moves one part of the state (`StateParts`): the others, and the contact's geometry where
        // neither the orientation nor the impact location moved, are the base run's. The same numbers as
        // twelve full runs, for a third less.
        let parts0 = StateParts::of(delivery, equipment, Some(dynamic_lie_rad))?;
        let state0 = parts0.assemble(delivery, equipment);
        let geometry0 = state0.contact(&equipment.club)?;
        let launch = |state: &ImpactState, geometry: &ContactGeometry| -> Result<SVector<5>, ImpactError> {
            let l = model.predict_at(state, geometry, equipment)?;
            Ok(launch_numbers(&LaunchMetrics::from_ball(&l.ball_velocity_mps, &l.ball_spin_radps)))
        };
        let run = |x: &SVector<DELIVERY_PARAMETERS>, part: StatePart| -> Result<SVector<5>, ImpactError> {
            let (d, lie) = delivery_of(x);
            let state = parts0.with(part, &d, equipment, Some(lie))?.assemble(&d, equipment);
            match part {
                StatePart::None | StatePart::Direction => launch(&state, &geometry0.moving_with(&state)),
                StatePart::Orientation | StatePart::Contact => launch(&state, &state.contact(&equipment.club)?),
            }
        };
        let y0 = launch(&state0, &geometry0)?;
        let mut j = SMatrix::<5, DELIVERY_PARAMETERS>::zeros();
        for (k, step) in STEPS.iter().enumerate() {
            let part = match k {
                1 | 2 => StatePart::Direction,
                3 | 4 | 10 => StatePart::Orientation,
                5 | 6 => StatePart::Contact,
                _ => StatePart::None,
            };
            let mut x = x0;
            x[k] += step;
            // A step off the face's edge is taken the other way.
            let (y, h) = match run(&x, part) {
                Ok(y) => (y, *step),
                Err(_) => {
                    x[k] = x0[k] - step;
                    (run(&x, part)?, -step)
                }
            };
            let mut dy = y - y0;
            // Angles that wrap (a launch straight back, a spin axis past 180 deg) stay on one branch.
            for i in [2, 4] {
                dy[i] = (dy[i] + 180.0).rem_euclid(360.0) - 180.0;
            }
            j.set_column(k, &(dy / h));
        }
        Ok(LaunchJacobian { j })
    }

    /// The launch's standard deviations for the delivery's covariance.
    pub fn uncertainty(&self, delivery: &DeliveryCovariance) -> LaunchUncertainty {
        let c = self.j * delivery.cov * self.j.transpose();
        let sd = |i: usize| c[(i, i)].max(0.0).sqrt();
        LaunchUncertainty {
            ball_speed_mph: sd(0),
            launch_angle_deg: sd(1),
            launch_direction_deg: sd(2),
            total_spin_rpm: sd(3),
            spin_axis_deg: sd(4),
        }
    }
}

/// The model whose Jacobian a launch of `model` takes: `model` itself when it linearises itself (the
/// impulse-momentum models), else the first of the rig's `models` that does, else the `adjusted` model with the
/// seed's parameters for the club.
pub fn linearised<'a>(
    model: &'a std::sync::Arc<dyn ImpactModel>,
    models: &'a [std::sync::Arc<dyn ImpactModel>],
) -> std::sync::Arc<dyn ImpactModel> {
    if model.linearises_itself() {
        return std::sync::Arc::clone(model);
    }
    models
        .iter()
        .find(|m| m.linearises_itself())
        .map(std::sync::Arc::clone)
        .unwrap_or_else(|| std::sync::Arc::new(super::ImpulseModel::new(super::ImpulseVariant::Adjusted)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::ClubSpec;
    use crate::impact::{ImpulseModel, ImpulseVariant};

    /// The Jacobian's runs recompute only the part of the state their parameter moves (`StateParts`): the same
    /// numbers, bit for bit, as twelve full runs of `to_state_with_lie` and `predict`.
    #[test]
    fn the_jacobian_is_the_full_runs_bit_for_bit() {
        for (club, h, v) in [(ClubSpec::driver(), 0.012, -0.004), (ClubSpec::iron7(), -0.008, 0.003)] {
            let eq = Equipment::new(club);
            for model in [ImpulseVariant::Adjusted, ImpulseVariant::Slip].map(ImpulseModel::new) {
                let d = Delivery {
                    club_speed_mps: 40.0,
                    attack_angle_rad: (-3f64).to_radians(),
                    club_path_rad: 2f64.to_radians(),
                    face_angle_rad: (-1f64).to_radians(),
                    dynamic_loft_rad: 20f64.to_radians(),
                    impact_h_m: h,
                    impact_v_m: v,
                    club_angular_velocity_radps: Vector3::new(3.0, -25.0, 12.0),
                };
                let lie = 60f64.to_radians();
                let full = |x: &SVector<DELIVERY_PARAMETERS>| {
                    let (d, lie) = delivery_of(x);
                    let l = model.predict(&d.to_state_with_lie(&eq, Some(lie)).unwrap(), &eq).unwrap();
                    launch_numbers(&LaunchMetrics::from_ball(&l.ball_velocity_mps, &l.ball_spin_radps))
                };
                let x0 = parameters(&d, lie);
                let y0 = full(&x0);
                let jac = LaunchJacobian::of(&model, &eq, &d, lie).unwrap();
                for (k, step) in STEPS.iter().enumerate() {
                    let mut x = x0;
                    x[k] += step;
                    let mut dy = full(&x) - y0;
                    for i in [2, 4] {
                        dy[i] = (dy[i] + 180.0).rem_euclid(360.0) - 180.0;
                    }
                    assert_eq!(jac.j.column(k), dy / *step, "{} column {k}", model.name());
                }
            }
        }
    }

    /// The Jacobian's ball-speed row against a central difference of the model, and a one-parameter covariance
    /// giving that parameter's sigma times its derivative.
    #[test]
    fn the_jacobian_matches_the_model() {
        let eq = Equipment::new(ClubSpec::driver());
        let model = ImpulseModel::new(ImpulseVariant::Adjusted);
        let d = Delivery {
            club_speed_mps: 45.0,
            attack_angle_rad: 2f64.to_radians(),
            club_path_rad: 1f64.to_radians(),
            face_angle_rad: 0.5f64.to_radians(),
            dynamic_loft_rad: 13f64.to_radians(),
            impact_h_m: 0.005,
            impact_v_m: 0.003,
            club_angular_velocity_radps: Vector3::new(2.0, -30.0, 10.0),
        };
        let lie = 57f64.to_radians();
        let jac = LaunchJacobian::of(&model, &eq, &d, lie).unwrap();
        let speed = |s: Real| {
            let d = Delivery { club_speed_mps: s, ..d };
            let l = model.predict(&d.to_state_with_lie(&eq, Some(lie)).unwrap(), &eq).unwrap();
            LaunchMetrics::from_ball(&l.ball_velocity_mps, &l.ball_spin_radps).ball_speed_mph
        };
        let central = (speed(45.01) - speed(44.99)) / 0.02;
        assert!((jac.j[(0, 0)] - central).abs() < 1e-4 * central, "{} vs {central}", jac.j[(0, 0)]);
        let mut cov = SMatrix::<DELIVERY_PARAMETERS, DELIVERY_PARAMETERS>::zeros();
        cov[(0, 0)] = 0.04;
        let u = jac.uncertainty(&DeliveryCovariance { cov });
        assert!((u.ball_speed_mph - 0.2 * central).abs() < 1e-9);
        // Smash factor about 1.48: 0.2 m/s of club speed is about 0.66 mph of ball speed.
        assert!((0.6..0.72).contains(&u.ball_speed_mph), "{}", u.ball_speed_mph);
    }
}
