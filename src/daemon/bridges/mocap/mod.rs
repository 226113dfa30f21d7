//! Native motion-capture inputs: socket clients of OptiTrack's NatNet ([`natnet`]) and Qualisys' QTM
//! real-time protocol ([`qtm`]) on the pure codecs of [`crate::mocap`], shared by `impactd bridge` and the
//! daemon's `[rig.input]`.

pub mod input;
pub mod natnet;
pub mod publish;
pub mod qtm;
pub mod shared;

pub use input::{InputHandle, MocapInputConfig, Source, StatusSource};
pub use publish::{run_bridge, run_bridge_fitted, run_bridge_with_balls};
pub use shared::Deliver;
