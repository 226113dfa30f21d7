//! From motion-capture frames to the impact state: samples and calibration, a per-rig track that rejects bad
//! frames with a reason, impact detection, and estimators that extrapolate the pre-impact frames to the first
//! contact between the face and the ball.

pub mod arc;
pub mod ball_tracker;
pub mod calibrate;
pub mod club_data;
pub mod contact_step;
pub mod detect;
pub mod estimate;
pub mod fit;
pub mod frame_gap;
pub mod guards;
pub mod marker_fit;
pub mod marker_set;
pub mod miss_watch;
pub mod normal_factor;
pub mod path_speed;
pub mod sample;
pub mod so3;
mod spec;
pub mod track;
pub mod uncertainty;

pub use detect::{Detection, DetectorConfig, GivenImpact, ImpactDetector};
pub use estimate::{EstimateError, EstimatorSpec, ImpactEstimate, Quality, Scene};
pub use marker_fit::{BodyFit, FitFailure, MarkerFitter};
pub use marker_set::{MarkerSet, MarkerSetError, StatedFace, StatedShaft};
pub use sample::{Calibration, ClubPose, ClubheadSample};
pub use track::{Reject, Track, TrackLimits};
