//! The NatNet and QTM decoders over arbitrary bytes and over mutations of valid packets (proptest; cargo-fuzz
//! would need a nightly toolchain): never a panic, and bounded allocation: a decoded list never holds more
//! items than the packet's bytes could encode, whatever its count fields say. Valid packets round-trip.

#![allow(clippy::unwrap_used)]

use impactd::mocap::natnet::markers::LabeledMarker;
use impactd::mocap::natnet::{self, Frame, RigidBody, Version, RIGID_BODY_BYTES};
use impactd::mocap::qtm::{self, Body6d, Frame6d};
use impactd::mocap::{natnet::encode as natnet_encode, qtm::encode as qtm_encode};
use proptest::prelude::*;

const VERSIONS: [Version; 5] =
    [Version::V3_0, Version::V3_1, Version::V4_0, Version::V4_1, Version { major: 4, minor: 2 }];

fn natnet_frame(n: usize, seed: u32) -> Frame {
    let rigid_bodies = (0..n)
        .map(|i| RigidBody {
            id: i as i32 + 1,
            position_m: [seed as f32 * 1e-6, i as f32, -0.5],
            orientation_xyzw: [0.0, 0.0, 0.6, 0.8],
            mean_error_m: 1e-4,
            tracking_valid: i % 3 != 0,
        })
        .collect();
    Frame {
        frame_number: seed as i32,
        rigid_bodies,
        // Labelled markers of an asset (id 9), every params bit pattern of the low three bits.
        labeled_markers: (0..=n)
            .map(|i| LabeledMarker {
                id: LabeledMarker::pack_id(9, i as i32 + 1),
                position_m: [i as f32 * 0.01, seed as f32 * 1e-6, 0.25],
                size_m: 0.014,
                params: (i % 8) as i16,
                residual_m: 1e-4,
            })
            .collect(),
        timestamp_s: f64::from(seed) / 360.0,
        mid_exposure_ticks: u64::from(seed) * 27_778,
        data_received_ticks: u64::from(seed) * 27_778 + 10_000,
        transmit_ticks: u64::from(seed) * 27_778 + 20_000,
        models_changed: seed.is_multiple_of(2),
    }
}

fn qtm_frame(n: usize, seed: u32) -> Frame6d {
    let bodies = (0..n)
        .map(|i| Body6d {
            position_mm: [i as f32, seed as f32, f32::NAN],
            rotation: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
            residual_mm: seed.is_multiple_of(2).then_some(0.3),
        })
        .collect();
    Frame6d {
        timestamp_us: i64::from(seed) * 2778,
        frame_number: seed,
        bodies,
        drop_rate_2d: 3,
        out_of_sync_rate_2d: 1,
        // Every third seed carries labelled 3D markers too.
        markers_mm: (0..if seed.is_multiple_of(3) { n + 1 } else { 0 })
            .map(|i| [i as f32, -(seed as f32), 7.5])
            .collect(),
    }
}

/// Decodes a datagram as every version; checks the bounds.
fn natnet_bounded(bytes: &[u8]) {
    let mut frame = Frame::default();
    for v in VERSIONS {
        let _ = natnet::decode(bytes, v, &mut frame);
        assert!(frame.rigid_bodies.len() * RIGID_BODY_BYTES <= bytes.len());
        assert!(frame.rigid_bodies.capacity() <= 2 * (bytes.len() / RIGID_BODY_BYTES) + 4);
        if let Ok((_, payload)) = natnet::split(bytes) {
            if let Ok(m) = natnet::decode_model_def(payload, v) {
                // A rigid body description is at least a NUL, id, parent, offset and marker count: 25 bytes.
                assert!(m.rigid_bodies.len() * 25 <= payload.len());
            }
        }
    }
}

fn qtm_bounded(bytes: &[u8]) {
    let mut frame = Frame6d::default();
    let _ = qtm::decode_data(bytes, &mut frame);
    assert!(frame.bodies.len() * 48 <= bytes.len());
    assert!(frame.bodies.capacity() <= 2 * (bytes.len() / 48) + 4);
    if bytes.len() >= 8 {
        let _ = qtm::header(bytes[..8].try_into().unwrap());
    }
    let _ = qtm::body_names(&String::from_utf8_lossy(bytes));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn natnet_arbitrary_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..1500)) {
        natnet_bounded(&bytes);
    }

    #[test]
    fn natnet_mutated_frames(
        n in 0usize..12,
        seed in any::<u32>(),
        v in 0usize..5,
        edits in proptest::collection::vec((any::<usize>(), any::<u8>()), 0..8),
        cut in any::<usize>(),
    ) {
        let version = VERSIONS[v];
        let frame = natnet_frame(n, seed);
        let mut bytes = natnet_encode::frame(version, &frame, "club", &[[0.1, 0.2, 0.3]]).unwrap();
        let mut decoded = Frame::default();
        prop_assert_eq!(natnet::decode(&bytes, version, &mut decoded), Ok(natnet::Message::Frame));
        prop_assert_eq!(&decoded, &frame);
        for (i, b) in edits {
            let len = bytes.len();
            bytes[i % len] = b;
        }
        let keep = cut % (bytes.len() + 1);
        natnet_bounded(&bytes[..keep]);
        natnet_bounded(&bytes);
    }

    #[test]
    fn natnet_mutated_models(n in 0usize..6, v in 0usize..5, edits in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..6)) {
        let names: Vec<String> = (0..n).map(|i| format!("body{i}")).collect();
        let bodies: Vec<(i32, &str)> = names.iter().enumerate().map(|(i, s)| (i as i32, s.as_str())).collect();
        let mut bytes = natnet_encode::model_def(VERSIONS[v], &bodies).unwrap();
        let (_, payload) = natnet::split(&bytes).unwrap();
        let m = natnet::decode_model_def(payload, VERSIONS[v]).unwrap();
        prop_assert_eq!(m.rigid_bodies.iter().map(|b| b.name.clone()).collect::<Vec<_>>(), names);
        prop_assert!(m.complete, "force plate, device and camera walked in every version");
        for (i, b) in edits {
            let len = bytes.len();
            bytes[i % len] = b;
        }
        natnet_bounded(&bytes);
    }

    #[test]
    fn qtm_arbitrary_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..1500)) {
        qtm_bounded(&bytes);
    }

    #[test]
    fn qtm_mutated_packets(
        n in 0usize..12,
        seed in any::<u32>(),
        edits in proptest::collection::vec((any::<usize>(), any::<u8>()), 0..8),
        cut in any::<usize>(),
    ) {
        let frame = qtm_frame(n, seed);
        let packet = qtm_encode::data(&frame);
        let (size, kind) = qtm::header(packet[..8].try_into().unwrap()).unwrap();
        prop_assert_eq!((size, kind), (packet.len(), qtm::PACKET_DATA));
        let mut bytes = packet[8..].to_vec();
        let mut decoded = Frame6d::default();
        qtm::decode_data(&bytes, &mut decoded).unwrap();
        prop_assert_eq!(format!("{decoded:?}"), format!("{frame:?}"));
        for (i, b) in edits {
            let len = bytes.len();
            bytes[i % len] = b;
        }
        let keep = cut % (bytes.len() + 1);
        qtm_bounded(&bytes[..keep]);
        qtm_bounded(&bytes);
    }

    #[test]
    fn qtm_parameters_round_trip(names in proptest::collection::vec("[ -~]{0,12}", 0..6)) {
        let refs: Vec<&str> = names.iter().map(String::as_str).collect();
        prop_assert_eq!(qtm::body_names(&qtm_encode::parameters_6d(&refs)), names);
    }
}

/// A count field of 2^31 - 1 rigid bodies in a 60-byte datagram allocates nothing for them.
#[test]
fn a_huge_count_allocates_nothing() {
    let mut p = Vec::new();
    p.extend_from_slice(&7u16.to_le_bytes());
    let mut payload = vec![0u8; 4 + 4 + 4]; // frame number, no marker sets, no legacy markers
    payload.extend_from_slice(&i32::MAX.to_le_bytes());
    payload.extend_from_slice(&[0u8; 40]);
    p.extend_from_slice(&(payload.len() as u16).to_le_bytes());
    p.extend_from_slice(&payload);
    let mut frame = Frame::default();
    let err = natnet::decode(&p, Version::V3_1, &mut frame).unwrap_err();
    assert_eq!(err.reason(), "truncated");
    assert!(frame.rigid_bodies.capacity() <= 4);
}
