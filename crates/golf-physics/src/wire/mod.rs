//! The JSON forms of the physics' inputs and outputs: serde types with units in their field names. A delivery
//! and its predicted launch (`impactd predict`), a launch to fly, the impact and launch messages the pipeline
//! emits, and what they carry (the club file, the shot's labels, the ball used). The daemon's bus adds its own
//! messages (status, bridges, comparisons) and their key expressions on top of these.
//!
//! This module holds the JSON forms only; it depends on no transport.

mod ball;
mod club;
mod delivery;
mod flight;
mod impact_timing;
mod labels;
mod messages;
pub mod model_name;

pub use ball::{BallSampleMsg, BallSource, BallUsed};
pub use club::{parse_club_put, ClubChange, ClubPutError, ClubRef, ClubSource, MAX_CLUB_PUT_BYTES};
pub use delivery::{DeliveryInput, Handedness, OutOfBounds, PredictOutput};
pub use flight::{FlightInput, FlightInputError, MAX_BALL_SPIN_RPM};
pub use impact_timing::{ImpactInstant, ImpactTimingMsg};
pub use labels::{LabelsError, ShotLabels, MAX_LABEL_BYTES, MAX_TAGS};
pub use messages::{ClubheadSampleMsg, ImpactMessage, ImpactStateMsg, LaunchPrediction, QuaternionMsg};
