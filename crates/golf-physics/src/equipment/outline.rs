//! The clubface's outline: where on the face an impact can be, as a polygon of impact locations `(h, v)` (mm;
//! h toward the toe, v up the face, about the face centre; ARCHITECTURE.md section 2).
//!
//! Presets:
//! - The driver: an ellipse 104 mm heel to toe and 58 mm high about the face centre (a 460 cm³ head's face,
//!   the rules' limit on the head's size makes faces of 100-110 by 55-60 mm), as 24 vertices.
//! - The 7-iron: the scoring area of a cavity-back 7-iron with the face centre 19 mm above the leading edge: the
//!   leading edge from the heel (-33, -17) to the toe (30, -19), a rounded toe up to 27 mm, and the top line
//!   falling to 14 mm at the heel where the hosel begins. An impact 25 mm below the centre is under the
//!   leading edge, i.e. in the ground.
//! - A club file without `face_outline_mm` gets the rectangle of its `face_half_width_m` and
//!   `face_half_height_m` when those are given, else the preset outline of its face shape.

use crate::math::Real;

/// A closed polygon of impact locations (mm), counter-clockwise or clockwise.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceOutline {
    /// The polygon's corners, `[h, v]` (mm).
    pub vertices_mm: Vec<[Real; 2]>,
}

impl FaceOutline {
    /// The preset driver's ellipse (104 x 58 mm).
    pub fn driver() -> Self {
        let n = 24;
        let vertices_mm = (0..n)
            .map(|k| {
                let a = 2.0 * std::f64::consts::PI * k as Real / n as Real;
                [52.0 * a.cos(), 29.0 * a.sin()]
            })
            .collect();
        FaceOutline { vertices_mm }
    }

    /// The preset 7-iron's scoring area.
    pub fn iron7() -> Self {
        FaceOutline {
            vertices_mm: vec![
                [-33.0, -17.0],
                [30.0, -19.0],
                [36.0, -14.0],
                [38.0, 0.0],
                [36.0, 14.0],
                [30.0, 23.0],
                [20.0, 27.0],
                [-33.0, 14.0],
            ],
        }
    }

    /// A rectangle of the given half-width and half-height (m).
    pub fn rectangle(half_width_m: Real, half_height_m: Real) -> Self {
        let (w, h) = (half_width_m * 1e3, half_height_m * 1e3);
        FaceOutline { vertices_mm: vec![[-w, -h], [w, -h], [w, h], [-w, h]] }
    }

    /// Whether the impact location `(h, v)` (m) is inside (even-odd rule; the boundary counts as inside up to
    /// rounding).
    pub fn contains(&self, h_m: Real, v_m: Real) -> bool {
        let (x, y) = (h_m * 1e3, v_m * 1e3);
        let n = self.vertices_mm.len();
        let mut inside = false;
        for i in 0..n {
            let [xi, yi] = self.vertices_mm[i];
            let [xj, yj] = self.vertices_mm[(i + n - 1) % n];
            if (yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi {
                inside = !inside;
            }
        }
        inside
    }

    /// The smallest box holding the outline: (h min, h max, v min, v max), mm.
    pub fn bounds_mm(&self) -> (Real, Real, Real, Real) {
        self.vertices_mm
            .iter()
            .fold((Real::INFINITY, Real::NEG_INFINITY, Real::INFINITY, Real::NEG_INFINITY), |(a, b, c, d), [h, v]| {
                (a.min(*h), b.max(*h), c.min(*v), d.max(*v))
            })
    }

    /// Checks that the outline is a polygon of finite vertices around the face centre.
    pub fn validate(&self) -> Result<(), &'static str> {
        if self.vertices_mm.len() < 3 {
            return Err("needs at least 3 vertices");
        }
        if self.vertices_mm.iter().flatten().any(|x| !x.is_finite()) {
            return Err("has a vertex that is not a finite number");
        }
        if !self.contains(0.0, 0.0) {
            return Err("must enclose the face centre (0, 0)");
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The points the issue found mapped and predicted on the 7-iron: 25 mm below the centre and the map's
    /// corner (-38, +25) mm are off its face; the centre and a 15 mm toe or heel strike are on it.
    #[test]
    fn the_iron_outline_excludes_the_ground_and_the_hosel() {
        let o = FaceOutline::iron7();
        assert!(o.validate().is_ok());
        assert!(!o.contains(0.0, -0.025));
        assert!(!o.contains(-0.038, 0.025));
        for (h, v) in [(0.0, 0.0), (0.015, 0.0), (-0.015, 0.0), (0.0, 0.010), (0.0, -0.012)] {
            assert!(o.contains(h, v), "{h} {v}");
        }
    }

    #[test]
    fn the_driver_outline_is_its_ellipse() {
        let o = FaceOutline::driver();
        assert!(o.validate().is_ok());
        assert!(o.contains(0.045, 0.0) && !o.contains(0.053, 0.0));
        assert!(o.contains(0.0, 0.027) && !o.contains(0.0, 0.030));
        // (40, 20) mm: (40/52)² + (20/29)² = 1.07, outside the ellipse and its inscribed polygon.
        assert!(!o.contains(0.040, 0.020));
        let r = FaceOutline::rectangle(0.01, 0.005);
        assert!(r.contains(0.0099, -0.0049) && !r.contains(0.0101, 0.0));
        assert!(FaceOutline { vertices_mm: vec![[1.0, 1.0], [2.0, 1.0], [2.0, 2.0]] }.validate().is_err());
    }
}
