pub mod equipment;
pub mod face;
pub mod impact;
pub mod math;
pub mod units;
pub mod wire;
pub mod rng;
