//! Display and wire units. The code works in SI; these conversions are used only where a field name says
//! `_mph`, `_rpm`, `_deg`, `_mm` or `_yd`.

use crate::math::Real;

/// Metres per second in one mile per hour (exact: 1609.344 m / 3600 s).
pub const MPS_PER_MPH: Real = 1609.344 / 3600.0;
/// Radians per second in one revolution per minute.
pub const RADPS_PER_RPM: Real = 2.0 * std::f64::consts::PI / 60.0;
/// Metres in one yard (exact).
pub const M_PER_YD: Real = 0.9144;

#[inline]
/// Miles per hour to metres per second.
pub fn mph_to_mps(mph: Real) -> Real {
    mph * MPS_PER_MPH
}
#[inline]
/// Metres per second to miles per hour.
pub fn mps_to_mph(mps: Real) -> Real {
    mps / MPS_PER_MPH
}
#[inline]
/// Revolutions per minute to radians per second.
pub fn rpm_to_radps(rpm: Real) -> Real {
    rpm * RADPS_PER_RPM
}
#[inline]
/// Radians per second to revolutions per minute.
pub fn radps_to_rpm(radps: Real) -> Real {
    radps / RADPS_PER_RPM
}
#[inline]
/// Degrees to radians.
pub fn deg_to_rad(deg: Real) -> Real {
    deg.to_radians()
}
#[inline]
/// Radians to degrees.
pub fn rad_to_deg(rad: Real) -> Real {
    rad.to_degrees()
}
#[inline]
/// Millimetres to metres.
pub fn mm_to_m(mm: Real) -> Real {
    mm * 1e-3
}
#[inline]
/// Metres to millimetres.
pub fn m_to_mm(m: Real) -> Real {
    m * 1e3
}
#[inline]
/// Metres to yards.
pub fn m_to_yd(m: Real) -> Real {
    m / M_PER_YD
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips() {
        assert!((mps_to_mph(mph_to_mps(113.0)) - 113.0).abs() < 1e-12);
        // 100 mph = 44.704 m/s exactly.
        assert!((mph_to_mps(100.0) - 44.704).abs() < 1e-12);
        // 60 rpm = 2 pi rad/s.
        assert!((rpm_to_radps(60.0) - 2.0 * std::f64::consts::PI).abs() < 1e-12);
    }
}
