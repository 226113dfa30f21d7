//! The protocols impactd reads: one entry each (a new input is its folder plus its line here).

use super::natnet::protocol::NatNet;
use super::protocol::{protocol_in, Protocol};
use super::qtm::protocol::Qtm;
use super::vicon::protocol::Vicon;

/// Every protocol impactd reads.
pub static PROTOCOLS: &[&dyn Protocol] = &[&NatNet, &Qtm, &Vicon];

/// The protocol named `name`.
pub fn protocol(name: &str) -> Option<&'static dyn Protocol> {
    protocol_in(PROTOCOLS, name)
}

/// Every protocol's name, for messages.
pub fn names() -> String {
    PROTOCOLS.iter().map(|p| p.name()).collect::<Vec<_>>().join(", ")
}
