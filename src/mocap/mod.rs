//! Motion-capture systems' real-time protocols as pure byte codecs (no sockets, no IO): OptiTrack NatNet
//! ([`natnet`]), Qualisys QTM ([`qtm`]) and Vicon DataStream ([`vicon`]), and the step from one of their frames
//! to a clubhead sample on the wire ([`track`]). The socket clients that use them are in `daemon::bridges`;
//! keeping the codecs pure lets them be fuzzed and benchmarked alone.

pub mod bytes;
pub mod natnet;
pub mod qtm;
pub mod track;
pub mod vicon;
