//! The clubhead (seed Table 3.1): mass, inertia, face geometry and the usable face.

use super::g_cm2_to_kg_m2;
use crate::face::{Face, FaceShape};
use crate::math::{Matrix3, Real, Vector3};

/// A clubhead, described in its club frame (origin at the CG; x forward, y up, z toward the toe at a square
/// address). Physical data only: a model's identified parameters live with the model.
#[derive(Debug, Clone, PartialEq)]
pub struct ClubSpec {
    /// Preset name or the `name` field of a club file.
    pub name: String,
    /// Mass of the head (kg).
    pub mass_kg: Real,
    /// Inertia tensor about the CG, club frame (kg m^2), as a model with a free head sees it: the head's own plus
    /// [`ClubSpec::shaft_heel_toe_inertia_kg_m2`] about the heel-toe (z) axis.
    pub inertia_kg_m2: Matrix3,
    /// Its inverse, kept beside it for the solvers.
    pub inertia_inv_kg_m2: Matrix3,
    /// What the shaft's tip adds about the heel-toe axis within a contact (kg m^2; 0 for the seed's heads). A head
    /// turned about that axis (a strike above or below the CG) swings the hosel, 40-60 mm above the CG, fore and
    /// aft, and the stiff tip of the shaft must go with it during the 0.4-0.5 ms of contact: the free head sees
    /// it as inertia. The ground model, which carries the shaft itself, takes it off again
    /// ([`ClubSpec::head_inertia_kg_m2`]).
    pub shaft_heel_toe_inertia_kg_m2: Real,
    /// Face centre, static loft and curvature.
    pub face: Face,
    /// Half the usable face width (toe-heel) and height (m): the box the impact detector searches.
    pub face_half_width_m: Real,
    /// Half the usable face height (m).
    pub face_half_height_m: Real,
    /// The face's outline: impact locations outside are rejected ([`FaceOutline`](super::FaceOutline)).
    pub face_outline: super::FaceOutline,
    /// Shaft mass (kg), for reference (the seed's section 3.1.4).
    pub shaft_mass_kg: Real,
    /// Static lie: the shaft's angle above the ground at a square address (deg); the shaft axis in the club
    /// frame is `(0, sin lie, -cos lie)`, from the head up toward the grip. The seed gives none: a curved face
    /// (driver) defaults to [`ClubSpec::DRIVER_LIE_DEG`], a flat one (iron) to [`ClubSpec::IRON_LIE_DEG`], which is
    /// also the ground model's sole lie unless its `[sole]` section says otherwise.
    pub lie_deg: Real,
}

impl ClubSpec {
    /// The seed's driver (Table 3.1).
    pub fn driver() -> Self {
        Self::build(
            "driver",
            0.204,
            [[2843.0, -733.0, 530.2], [-733.0, 5679.0, 0.5], [530.2, 0.5, 4085.0]],
            Vector3::new(0.0408, 0.0114, 0.001),
            9.8,
            FaceShape::Torus { bulge_radius_m: 0.305, roll_radius_m: 0.305 },
            (0.050, 0.030),
            0.060,
        )
    }

    /// The seed's 7-iron (Table 3.1).
    pub fn iron7() -> Self {
        Self::build(
            "iron7",
            0.264,
            [[2752.0, -51.0, -53.0], [-51.0, 2889.0, -429.0], [-53.0, -429.0, 576.6]],
            Vector3::new(0.00361, 0.00485, 0.00112),
            30.5,
            FaceShape::Plane,
            (0.038, 0.025),
            0.104,
        )
    }

    #[allow(clippy::too_many_arguments)]
    fn build(
        name: &str,
        mass_kg: Real,
        inertia_g_cm2: [[Real; 3]; 3],
        cg_to_face_center_m: Vector3,
        loft_deg: Real,
        shape: FaceShape,
        (face_half_width_m, face_half_height_m): (Real, Real),
        shaft_mass_kg: Real,
    ) -> Self {
        let inertia_kg_m2 = g_cm2_to_kg_m2(&inertia_g_cm2);
        ClubSpec {
            name: name.to_string(),
            mass_kg,
            inertia_inv_kg_m2: inertia_kg_m2.try_inverse().unwrap_or_else(Matrix3::zeros),
            inertia_kg_m2,
            shaft_heel_toe_inertia_kg_m2: 0.0,
            face: Face { center_m: cg_to_face_center_m, loft_rad: loft_deg.to_radians(), shape },
            face_half_width_m,
            face_half_height_m,
            face_outline: if shape.is_curved() { super::FaceOutline::driver() } else { super::FaceOutline::iron7() },
            shaft_mass_kg,
            lie_deg: Self::default_lie_deg(shape),
        }
    }

    /// The head's own inertia about its CG (club frame, kg m^2): [`ClubSpec::inertia_kg_m2`] without the shaft's
    /// share.
    pub fn head_inertia_kg_m2(&self) -> Matrix3 {
        let mut i = self.inertia_kg_m2;
        i[(2, 2)] -= self.shaft_heel_toe_inertia_kg_m2;
        i
    }

    /// A driver's static lie (deg): makers' spec sheets give 56-59°.
    pub const DRIVER_LIE_DEG: Real = 58.0;
    /// A 7-iron's static lie (deg): makers' spec sheets give 61.5-63° (the ground model's sole,
    /// `SoleSpec::IRON7`, uses the same value).
    pub const IRON_LIE_DEG: Real = 62.5;

    /// The static lie a club gets when nothing says otherwise: a driver's for a curved face, an iron's for a flat one.
    pub fn default_lie_deg(shape: FaceShape) -> Real {
        if shape.is_curved() {
            Self::DRIVER_LIE_DEG
        } else {
            Self::IRON_LIE_DEG
        }
    }

    /// The shaft axis from the head up toward the grip, club frame (a unit vector at the static lie).
    pub fn shaft_axis_up(&self) -> Vector3 {
        let lie = self.lie_deg.to_radians();
        Vector3::new(0.0, lie.sin(), -lie.cos())
    }

    /// Static loft in degrees.
    pub fn loft_deg(&self) -> Real {
        self.face.loft_rad.to_degrees()
    }

    /// Whether the face is curved (a wood: bulge and roll); the seed's driver parameters are the default for
    /// such a face, the 7-iron's for a flat one.
    pub fn is_wood(&self) -> bool {
        self.face.shape.is_curved()
    }

    /// Whether the impact location `(h, v)` (m) is on the face (inside its outline).
    pub fn on_face(&self, h_m: Real, v_m: Real) -> bool {
        self.face_outline.contains(h_m, v_m)
    }
}
