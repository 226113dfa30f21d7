//! Native motion-capture inputs: socket clients of OptiTrack's NatNet ([`natnet`]), Qualisys' QTM real-time
//! protocol ([`qtm`]) and Vicon's DataStream ([`vicon`]) on the pure codecs of [`crate::mocap`], shared by
//! `impactd bridge` and the daemon's `[rig.input]`. Every protocol implements [`protocol::Protocol`] and has one
//! entry in [`PROTOCOLS`]; the configuration, the running client and its counts, and the bridge are the same
//! for all.

pub mod config;
pub mod counters;
pub mod handle;
pub mod natnet;
pub mod protocol;
pub mod publish;
pub mod qtm;
pub mod registry;
pub mod shared;
pub mod vicon;

pub use config::MocapInputConfig;
pub use handle::{InputHandle, StatusSource};
pub use protocol::{Protocol, Route, Source};
pub use publish::{run_bridge, run_bridge_fitted, run_bridge_routes, run_bridge_with_balls};
pub use registry::PROTOCOLS;
pub use shared::Deliver;
