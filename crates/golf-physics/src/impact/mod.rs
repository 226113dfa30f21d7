//! Impact models: from the clubhead's state at first contact to the ball's launch.
//!
//! An [`ImpactState`] is the club at the instant it first touches a ball at rest (world frame, ARCHITECTURE.md
//! section 2). An [`ImpactModel`] turns it into a [`Launch`]: the ball's velocity and spin and the club's motion
//! after impact. [`Delivery`] is the TrackMan-style description users type and read; it converts to and from an
//! impact state. [`LaunchMetrics`] are the TrackMan launch numbers.

pub mod club_sections;
pub mod continuous;
pub mod delivered_loft;
mod delivery;
mod fit_model;
pub mod identifiable;
pub mod impulse;
mod launch;
pub mod registry;
pub mod report;
pub mod sanity;
pub mod sigmas;
pub mod tour;
pub mod uncertainty;

pub use continuous::ContinuousModel;
pub use delivery::{Delivery, DeliveryMetrics, StatePart, StateParts, SwingArc};
pub use fit_model::FitModelError;
pub use impulse::{ImpulseModel, ImpulseVariant};
pub use launch::LaunchMetrics;
pub use report::{Course, Fields, ModelRun, Report, RunOptions, Trace};
pub use sanity::LaunchWarning;

use crate::equipment::{BallSpec, ClubSpec, EquipmentError};
use crate::face::{impact_frame, FaceContact, FaceError};
use crate::math::{Isometry3, Matrix3, Real, Vector3};

/// Errors of the impact layer (not `Clone`: a part's error keeps its cause, an IO error among them).
#[derive(Debug, thiserror::Error)]
pub enum ImpactError {
    /// The impact location is outside the face's outline.
    #[error("impact location ({h_mm:.1} mm, {v_mm:.1} mm) is off the face")]
    OffFace {
        /// Toward the toe from the face centre (mm).
        h_mm: Real,
        /// Up the face from the face centre (mm).
        v_mm: Real,
    },
    /// The face's geometry refused the impact location.
    #[error(transparent)]
    Face(#[from] FaceError),
    /// A number of the state or delivery that is not finite.
    #[error("field `{field}` must be finite")]
    NotFinite {
        /// Its field.
        field: &'static str,
    },
    /// A club speed no swing gives.
    #[error("club speed {speed_mps:.2} m/s is outside 1-100 m/s")]
    SpeedOutOfRange {
        /// The speed (m/s).
        speed_mps: Real,
    },
    /// A dynamic lie the face's loft and angle cannot give.
    #[error("field `dynamic_lie_deg`: {lie_deg:.1} deg is no lie the face's loft and angle allow")]
    LieUnreachable {
        /// The lie asked for (deg).
        lie_deg: Real,
    },
    /// The contact point moves away from the ball: no collision.
    #[error("the club is not moving toward the ball at the contact point")]
    NotApproaching,
    /// The impulse-momentum solve's matrix is singular.
    #[error("the contact solve is singular")]
    Singular,
    /// A model's solve or stepping that did not finish.
    #[error("{model} did not converge: {reason}")]
    NotConverged {
        /// The model's name.
        model: &'static str,
        /// What it did not reach.
        reason: String,
    },
    /// A model parameter out of its range.
    #[error("model parameter `{field}` {reason}")]
    InvalidParameter {
        /// The parameter.
        field: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A part a model stands on (the soil, sole or shaft of its club-file sections) that the equipment refuses.
    #[error("model parameter `[{section}]` {source}")]
    Part {
        /// The club-file section.
        section: &'static str,
        /// Why the equipment refused it.
        #[source]
        source: EquipmentError,
    },
    /// A soil named for the turf model (`--soil`, a rig's `soil`) that is no preset and no soil file.
    #[error("model parameter `[soil]` {source}; or {} for the ball on a tee", continuous::iron_ground::sections::TEED)]
    Soil {
        /// Why it could not be read.
        #[source]
        source: EquipmentError,
    },
    /// A model name the registry does not have.
    #[error("unknown model '{name}' (expected {expected})")]
    UnknownModel {
        /// The name given.
        name: String,
        /// The registry's names.
        expected: String,
    },
    /// A club-file section no model reads.
    #[error("the club file's section [{section}] belongs to no model (known sections: {known})")]
    UnknownSection {
        /// The section's name.
        section: String,
        /// The sections the models read.
        known: String,
    },
}

/// The club and the ball a model needs (physical data only; a model carries its own parameters).
#[derive(Debug, Clone, PartialEq)]
pub struct Equipment {
    /// The clubhead.
    pub club: ClubSpec,
    /// The ball.
    pub ball: BallSpec,
}

impl Equipment {
    /// A club with the seed's ball.
    pub fn new(club: ClubSpec) -> Self {
        Equipment { club, ball: BallSpec::SEED }
    }
}

/// The clubhead at first contact with a ball at rest, in the world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactState {
    /// Pose of the club frame (origin at the CG) in the world.
    pub world_from_club: Isometry3,
    /// Velocity of the club's CG (m/s, world).
    pub cg_velocity_mps: Vector3,
    /// Angular velocity of the head (rad/s, world).
    pub angular_velocity_radps: Vector3,
    /// Impact location on the face: toward the toe (m).
    pub impact_h_m: Real,
    /// Impact location on the face: up the face (m).
    pub impact_v_m: Real,
}

/// The contact geometry and velocities shared by every model, computed once from a state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactGeometry {
    /// Rotation world_from_club.
    pub world_from_club: Matrix3,
    /// Club CG -> contact point (m, world).
    pub r_club_m: Vector3,
    /// The impact frame in the world: its columns are x' (normal toward the ball), y' (up the face) and z'
    /// (toe), so `v_world = world_from_impact * v_impact`.
    pub world_from_impact: Matrix3,
    /// Velocity of the club's material point at the contact (m/s, world), seed eq. 3.7.
    pub contact_velocity_mps: Vector3,
    /// Contact point and normal in the club frame.
    pub contact_club: FaceContact,
}

impl ImpactState {
    /// The contact geometry of this state on `club`.
    pub fn contact(&self, club: &ClubSpec) -> Result<ContactGeometry, ImpactError> {
        if !club.on_face(self.impact_h_m, self.impact_v_m) {
            return Err(ImpactError::OffFace { h_mm: self.impact_h_m * 1e3, v_mm: self.impact_v_m * 1e3 });
        }
        let contact_club = club.face.contact(self.impact_h_m, self.impact_v_m)?;
        let rot = *self.world_from_club.rotation.to_rotation_matrix().matrix();
        let r_club_m = rot * contact_club.point_m;
        let normal = rot * contact_club.normal;
        let toe = rot.column(2).into_owned();
        let world_from_impact = impact_frame(&normal, &toe);
        let contact_velocity_mps = self.cg_velocity_mps + self.angular_velocity_radps.cross(&r_club_m);
        Ok(ContactGeometry { world_from_club: rot, r_club_m, world_from_impact, contact_velocity_mps, contact_club })
    }
}

impl ContactGeometry {
    /// This geometry for `state`, a state of the same orientation and impact location moving otherwise: only the
    /// contact's velocity is recomputed (the same numbers as `state.contact(club)`).
    pub fn moving_with(&self, state: &ImpactState) -> ContactGeometry {
        let contact_velocity_mps = state.cg_velocity_mps + state.angular_velocity_radps.cross(&self.r_club_m);
        ContactGeometry { contact_velocity_mps, ..*self }
    }
}

/// What a model predicts: the ball's launch and the club just after impact (world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Launch {
    /// The ball's velocity after impact (m/s, world).
    pub ball_velocity_mps: Vector3,
    /// The ball's angular velocity after impact (rad/s, world).
    pub ball_spin_radps: Vector3,
    /// The head's CG velocity after impact (m/s, world).
    pub club_velocity_mps: Vector3,
    /// The head's angular velocity after impact (rad/s, world).
    pub club_angular_velocity_radps: Vector3,
    /// Impulse on the ball (N s, world).
    pub impulse_n_s: Vector3,
}

/// A model of the club-ball collision. Choosing a model is configuration: every model implements this, with one
/// method that runs it ([`run`](ImpactModel::run)); what it gives beyond the launch is read by name
/// ([`report`]), so nothing outside a model knows its type.
pub trait ImpactModel: Send + Sync + std::fmt::Debug {
    /// The name it publishes under: its name in the registry (`adjusted`), the one users type.
    fn name(&self) -> &'static str;
    /// Runs the collision from the state at first contact: the launch, the model's report and, when asked, the
    /// contact's course.
    fn run(&self, state: &ImpactState, equipment: &Equipment, options: &RunOptions) -> Result<ModelRun, ImpactError>;
    /// The launch alone (a run without a course).
    fn predict(&self, state: &ImpactState, equipment: &Equipment) -> Result<Launch, ImpactError> {
        Ok(self.run(state, equipment, &RunOptions::default())?.launch)
    }
    /// [`predict`](Self::predict) with the state's contact geometry at hand (`state.contact(&equipment.club)`):
    /// a model that reads it need not recompute it (the Jacobian's runs share it). The same launch.
    fn predict_at(
        &self,
        state: &ImpactState,
        contact: &ContactGeometry,
        equipment: &Equipment,
    ) -> Result<Launch, ImpactError> {
        let _ = contact;
        self.predict(state, equipment)
    }
    /// Whether a run is cheap enough (about a microsecond) for the launch's uncertainty to linearise this model
    /// itself (twelve runs, `uncertainty::LaunchJacobian`); the launches of the others take an impulse-momentum
    /// model's Jacobian.
    fn linearises_itself(&self) -> bool {
        false
    }
}
