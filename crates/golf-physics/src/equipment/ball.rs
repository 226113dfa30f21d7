//! The golf ball (seed Table 3.1).

use crate::math::Real;

/// The golf ball (Table 3.1): a sphere with isotropic inertia about its centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallSpec {
    /// Mass (kg).
    pub mass_kg: Real,
    /// Radius (m).
    pub radius_m: Real,
    /// Moment of inertia about any axis through the centre (kg m^2).
    pub inertia_kg_m2: Real,
}

impl BallSpec {
    /// The seed's ball, Table 3.1: 45.9 g, 21.3 mm, 83.36 g cm^2.
    pub const SEED: BallSpec = BallSpec { mass_kg: 0.0459, radius_m: 0.0213, inertia_kg_m2: 83.36e-7 };
}

impl Default for BallSpec {
    fn default() -> Self {
        Self::SEED
    }
}
