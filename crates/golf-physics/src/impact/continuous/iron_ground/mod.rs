//! The iron-plus-ground model (seed chapter 4): the continuous two-layer ball (section 3.2.1, eq. 3.14-3.15) on
//! a head carried by a flexible shaft (section 4.1, eq. 4.1-4.2) whose grip follows the swing's undisturbed
//! motion, with the ground's reaction on the sole (eq. 4.3-4.9) and face (eq. 4.10-4.13) for a ball resting on
//! the turf (section 4.3).
//!
//! It is an assembly of shared parts: the two-layer ball, the volumetric law, the head on its shaft
//! (`club::ShaftClub`, its modes by exponential time differencing) and the soil (`ground::SoilGround`), run on
//! the assembly's multi-rate stepping (`continuous::stepping`). What is its own here: where the ball and the
//! ground are ([`placement`]), how a strike steps and what it measures (`policy`, `measures`), the run and
//! its result (`run`), its report (`report`) and its club-file sections ([`sections`]).
//!
//! A run starts when the sole first touches the ground on the undisturbed swing (an event: nothing acts on the
//! club before it; at the ball's first contact when the ball comes first, a later touch ending a step), steps
//! at `ground_step_s` while only the ground acts and at `ball_step_s` from the ball's contact until it leaves
//! (the ground's forces are then evaluated once every `ground_hold_s` and held: they change over milliseconds,
//! the ball's over microseconds); the steps before the ball's contact shrink from the one to the other by
//! halves, each covering at most half the time the face needs to reach the ball, and it follows the ground
//! contact after the ball leaves to measure the divot. The ground's step follows the ground's forces, not the
//! stiffest shaft mode. Without ground (`with_ground = false`) it is the same flexible club on a teed-up ball,
//! the seed's reference in Figures 4.11-4.17.

mod measures;
pub mod placement;
mod policy;
mod reference_swing;
mod report;
mod run;
pub mod sections;

use crate::equipment::shaft::ShaftSpec;
use crate::equipment::soil::SoilSpec;
use crate::equipment::sole::SoleSpec;
use crate::equipment::EquipmentError;
use crate::impact::continuous::ground::{GroundForces, GroundPhase, SampledGround, SoilGround};
use crate::impact::continuous::shaft::exponential::ModalStepper;
use crate::impact::continuous::shaft::modal::ModalClub;
use crate::impact::continuous::shaft::{FlexibleClub, HeadOnShaft, ShaftError, ShaftMesh};
use crate::impact::continuous::stepping::StepLadder;
use crate::impact::continuous::TwoLayerParams;
use crate::impact::{Equipment, ImpactError, ImpactModel, ImpactState, Launch, ModelRun, RunOptions};
use crate::math::{Real, Vector3};

pub use placement::Strike;
pub use reference_swing::reference_swing;
pub use report::GROUND_REPORT;

/// The model's settings.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundModel {
    /// The soil under the ball (Table 4.3's presets or a soil file).
    pub soil: SoilSpec,
    /// The club's sole and shaft (typical 7-iron values and Tables 4.1-4.2 by default).
    pub sole: SoleSpec,
    /// See `sole`.
    pub shaft: ShaftSpec,
    /// The shaft's finite elements and the grip's clamp.
    pub mesh: ShaftMesh,
    /// Shaft modes above this are dropped (Hz); infinite keeps them all.
    pub max_mode_hz: Real,
    /// Ball parameters; `None` uses the club's in the continuous model's default reading of Table 3.5 (the
    /// one-cycle reading, `TwoLayerReading`), the same ball as `continuous`.
    pub params: Option<TwoLayerParams>,
    /// Steps during the ball's contact and while only the ground acts (s).
    pub ball_step_s: Real,
    /// See `ball_step_s`.
    pub ground_step_s: Real,
    /// During the ball's contact the ground's forces are evaluated once every `ground_hold_s` and held (s).
    pub ground_hold_s: Real,
    /// How long to follow the ground contact after the ball leaves (s).
    pub follow_s: Real,
    /// `false`: the same club on a teed ball, no ground (`[soil] preset = "none"`, `--soil none`).
    pub with_ground: bool,
}

impl GroundModel {
    /// The seed's 7-iron setup on `soil`: Table 4.1-4.2 shaft in 8 elements with every mode (within 0.43 % of
    /// 48 elements, crates/golf-physics/tests/shaft.rs), the typical 7-iron sole, 2 us steps in the ball's contact (halving moves
    /// ball speed < 2e-5 and spin < 6e-4, crates/golf-physics/tests/ground.rs), 120 us outside (against 7.5 us: launch within 4e-7
    /// in speed and 7e-6 in spin, divot length within 0.35 %, contact time and peak force within 0.15 %; classical
    /// Runge-Kutta on every mode needed < 18 us for the highest, 1.5e5 rad/s) and the ground held over 15 us in
    /// the ball's contact (against 3.75 us: spin within 2.5e-5).
    pub fn new(soil: SoilSpec) -> Self {
        GroundModel {
            soil,
            sole: SoleSpec::IRON7,
            shaft: ShaftSpec::iron7(),
            mesh: ShaftMesh { elements: 8, clamp_m: 0.0 },
            max_mode_hz: Real::INFINITY,
            params: None,
            ball_step_s: 2e-6,
            ground_step_s: 120e-6,
            ground_hold_s: 15e-6,
            follow_s: 15e-3,
            with_ground: true,
        }
    }

    /// Assembles the club once (its modes), for many shots.
    pub fn prepare(&self, equipment: &Equipment) -> Result<PreparedGround, ImpactError> {
        let club = &equipment.club;
        let model = self.clone();
        let flexible = FlexibleClub::new(&model.shaft, &HeadOnShaft::of(club), &model.sole, model.mesh)
            .map_err(shaft_error("mesh"))?;
        let modal = ModalClub::new(&flexible, model.max_mode_hz, 0.0).map_err(shaft_error("max_mode_hz"))?;
        let shaft_cg_m = flexible.tip_m + (flexible.butt_m - flexible.tip_m) * shaft_cg_fraction(&model.shaft);
        let steps = StepLadder::new(|h_s| ModalStepper::new(&modal, h_s), model.ball_step_s, model.ground_step_s);
        Ok(PreparedGround { model, equipment: equipment.clone(), modal, shaft_cg_m, steps })
    }
}

/// A flexible club the model's parameters cannot build is a bad parameter: the shaft's or the sole's field it
/// names, or `mesh_field` for the discretisation (the mesh, the modes kept); matrices that are not positive
/// definite are a numerical failure.
fn shaft_error(mesh_field: &'static str) -> impl Fn(ShaftError) -> ImpactError {
    move |e| match e {
        ShaftError::Equipment(EquipmentError::Invalid { field, reason }) => {
            ImpactError::InvalidParameter { field: field.into(), reason }
        }
        ShaftError::Equipment(e) => ImpactError::InvalidParameter { field: "shaft".into(), reason: e.to_string() },
        ShaftError::Mesh(reason) => ImpactError::InvalidParameter { field: mesh_field.into(), reason },
        ShaftError::NotPositiveDefinite => ImpactError::NotConverged { model: "ground", reason: e.to_string() },
    }
}

/// The shaft's CG from the tip toward the butt, as a fraction of its length.
fn shaft_cg_fraction(shaft: &ShaftSpec) -> Real {
    let n = 400;
    let l = shaft.length_m();
    let h = l / n as Real;
    let (mut m, mut mx) = (0.0, 0.0);
    for i in 0..n {
        let x = (i as Real + 0.5) * h;
        let dm = shaft.mass_per_length_kg_per_m(x) * h;
        m += dm;
        mx += dm * (l - x); // from the tip
    }
    mx / (m * l)
}

/// The model with its club assembled.
#[derive(Debug, Clone)]
pub struct PreparedGround {
    /// The settings.
    pub model: GroundModel,
    /// The club and ball it was assembled for.
    pub equipment: Equipment,
    /// The flexible club's modes (eq. 4.1-4.2).
    pub modal: ModalClub,
    /// The undeformed shaft's CG in the club frame (m).
    pub shaft_cg_m: Vector3,
    /// The run's step sizes and their modal steppers.
    steps: StepLadder<ModalStepper>,
}

/// One sample of a trace: the ground's forces on the head and its face angle and loft.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct GroundTracePoint {
    /// Time from the ball's first contact on the undisturbed swing (ms).
    pub t_ms: Real,
    /// The sole's force on the head, vertical (N, up +).
    pub sole_vertical_n: Real,
    /// The sole's force on the head, horizontal magnitude (N).
    pub sole_horizontal_n: Real,
    /// The face's earth pressure on the head, horizontal magnitude (N).
    pub face_horizontal_n: Real,
    /// The whole ground force, vertical (N, up +).
    pub ground_vertical_n: Real,
    /// The whole ground force, horizontal magnitude (N).
    pub ground_horizontal_n: Real,
    /// The ball's normal force on the face (N; 0 before and after contact).
    pub ball_normal_n: Real,
    /// Face angle (deg, open +).
    pub face_angle_deg: Real,
    /// Dynamic loft (deg).
    pub dynamic_loft_deg: Real,
    /// The contact phase.
    pub phase: GroundPhase,
}

/// What a run gives.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundResult {
    /// The ball and the club as the ball leaves.
    pub launch: Launch,
    /// Thin, good, fat or teed.
    pub strike: Strike,
    /// From the sole's first touch to the ball's first contact (ms; negative when the ball came first, `None`
    /// without ground contact).
    pub ground_contact_before_ball_ms: Option<Real>,
    /// At the ball's first contact, against the undisturbed swing: face-centre speed lost (mph), face angle
    /// (open +) and dynamic loft changes (deg).
    pub club_speed_loss_mph: Real,
    /// See `club_speed_loss_mph`.
    pub face_angle_change_deg: Real,
    /// See `club_speed_loss_mph`.
    pub dynamic_loft_change_deg: Real,
    /// Deepest sinkage of the sole (mm) and the head's horizontal travel with the leading edge below the
    /// surface (mm).
    pub divot_depth_mm: Real,
    /// See `divot_depth_mm`.
    pub divot_length_mm: Real,
    /// The largest ground force on the head (N).
    pub peak_ground_force_n: Real,
    /// Total time in contact with the ground (ms) and with the ball (us).
    pub ground_contact_ms: Real,
    /// See `ground_contact_ms`.
    pub ball_contact_us: Real,
    /// The club's linear momentum at the start and end, and the impulses of the ball, ground and grip on it
    /// (N s, world).
    pub club_momentum_start_n_s: Vector3,
    /// See `club_momentum_start_n_s`.
    pub club_momentum_end_n_s: Vector3,
    /// See `club_momentum_start_n_s`.
    pub ball_impulse_n_s: Vector3,
    /// The ground's impulse on the club before the ball's first contact (N s, world).
    pub ground_impulse_before_ball_n_s: Vector3,
    /// The ground's impulse on the club over the whole run (N s, world).
    pub ground_impulse_n_s: Vector3,
    /// The grip's impulse on the club over the whole run (N s, world).
    pub grip_impulse_n_s: Vector3,
    /// Steps taken.
    pub steps: usize,
    /// The run's course, when asked for.
    pub trace: Vec<GroundTracePoint>,
}

impl ImpactModel for PreparedGround {
    fn name(&self) -> &'static str {
        "ground"
    }

    /// The strike followed through the turf after the ball leaves (for the divot), with its `ground` report.
    fn run(&self, state: &ImpactState, _equipment: &Equipment, o: &RunOptions) -> Result<ModelRun, ImpactError> {
        self.simulate(state, o.trace_every).map(|r| r.into_run(o))
    }

    /// The launch alone stops when the ball leaves (the same launch as [`run`](ImpactModel::run), sooner).
    fn predict(&self, state: &ImpactState, _equipment: &Equipment) -> Result<Launch, ImpactError> {
        run::simulate(self, state, 0, 0.0, |ground| ground).map(|r| r.launch)
    }
}

impl PreparedGround {
    /// Runs one shot, following the ground contact after the ball leaves for up to `follow_s`, recording a
    /// trace point every `trace_every` ball steps of time, at every step where the steps are longer (0: none). [`ImpactModel::predict`] stops when the ball leaves.
    pub fn simulate(&self, state: &ImpactState, trace_every: usize) -> Result<GroundResult, ImpactError> {
        run::simulate(self, state, trace_every, self.model.follow_s, |ground| ground)
    }

    /// [`Self::simulate`] with the ground's forces computed by `with(ground)` instead of the soil under the ball
    /// (`ground`, already lowered out of reach without ground): for reading what a part of the ground's force
    /// does alone (research/ground-parts.md). The sole's first touch is still found on `ground`.
    pub fn simulate_with<G: SampledGround<Forces = GroundForces>>(
        &self,
        state: &ImpactState,
        trace_every: usize,
        with: impl FnOnce(SoilGround) -> G,
    ) -> Result<GroundResult, ImpactError> {
        run::simulate(self, state, trace_every, self.model.follow_s, with)
    }

    /// The ground under the ball of `state` (for the placement and strike).
    pub fn ground_for(&self, state: &ImpactState) -> Result<SoilGround, ImpactError> {
        let ball = &self.equipment.ball;
        let centre = placement::ball_centre_m(state, &self.equipment.club, ball)?;
        Ok(SoilGround::new(
            self.model.soil.clone(),
            self.model.sole,
            &self.equipment.club,
            placement::ground_y_m(&centre, ball),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::equipment::soil::SoilSpec;
    use crate::equipment::ClubSpec;

    /// The field an error names, if it is a bad parameter.
    fn invalid_field(model: &GroundModel) -> Option<String> {
        match model.prepare(&Equipment::new(ClubSpec::iron7())) {
            Err(ImpactError::InvalidParameter { field, .. }) => Some(field),
            Err(e) => panic!("not a bad parameter: {e:?}"),
            Ok(_) => None,
        }
    }

    /// A shaft, sole or mesh the model cannot build is `InvalidParameter` naming the field (it was reported as
    /// the model not converging); the seed's 7-iron setup builds.
    #[test]
    fn a_bad_shaft_parameter_is_an_invalid_parameter() {
        let good = GroundModel::new(SoilSpec::firm());
        assert_eq!(invalid_field(&good), None);
        let mut m = good.clone();
        m.shaft.mass_kg = -1.0;
        assert_eq!(invalid_field(&m).as_deref(), Some("shaft.mass_kg"));
        let mut m = good.clone();
        m.shaft.youngs_modulus_pa = Real::NAN;
        assert_eq!(invalid_field(&m).as_deref(), Some("shaft.youngs_modulus_pa"));
        let mut m = good.clone();
        m.sole.sole_width_m = 0.0;
        assert_eq!(invalid_field(&m).as_deref(), Some("sole.sole_width_m"));
        // Table 4.2's four stations need three elements at least.
        let mut m = good.clone();
        m.mesh.elements = 2;
        assert_eq!(invalid_field(&m).as_deref(), Some("mesh"));
        // The club's first mode is a few hertz: none is left below 0.5 Hz.
        let mut m = good;
        m.max_mode_hz = 0.5;
        assert_eq!(invalid_field(&m).as_deref(), Some("max_mode_hz"));
    }
}
