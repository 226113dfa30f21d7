//! The Vicon DataStream decoder over arbitrary bytes and over mutations of valid packets (proptest, as
//! tests/inputs/mocap_fuzz.rs does for NatNet and QTM): never a panic, and bounded allocation: no decoded list holds
//! more elements than the packet's bytes could encode, whatever its count fields say. Valid packets round-trip.

#![allow(clippy::unwrap_used)]

use impactd::mocap::vicon::encode::{self, FrameOut};
use impactd::mocap::vicon::enums::{CLIENT_WANTS, LABELED_RECONS};
use impactd::mocap::vicon::items::{MarkerDef, LABELED_RECON_BYTES, SEGMENT_POSE_BYTES};
use impactd::mocap::vicon::{
    Decoder, DynamicObjects, LabeledRecon, LatencySample, SegmentDef, SegmentPose, StaticObjects, SubjectDef, Timecode,
    UpAxis,
};
use proptest::prelude::*;

fn scene(n: usize, seed: u32) -> (StaticObjects, DynamicObjects) {
    let subjects = (0..n as u32)
        .map(|s| SubjectDef {
            subject_id: s + 1,
            name: format!("subject {s}"),
            segments: vec![SegmentDef { segment_id: 1, parent_id: 0, bounds: [seed as f32; 6], name: "root".into() }],
            markers: (1..=4).map(|m| MarkerDef { marker_id: m, name: format!("m{m}") }).collect(),
            attachments: (1..=4).map(|m| (m, 1)).collect(),
        })
        .collect();
    let statics = StaticObjects { frame_period_ticks: Some(187_500), up_axis: Some(UpAxis::Z), subjects };
    let dynamics = DynamicObjects {
        frame_id: Some(seed),
        timecode: Some(Timecode { frames: (seed % 30) as u8, subframes_per_frame: 1, ..Timecode::default() }),
        latency: vec![LatencySample { name: "Data Collection".into(), latency_s: f64::from(seed) * 1e-9 }],
        segments: (0..n as u32)
            .filter(|s| !(s + seed).is_multiple_of(4))
            .map(|s| SegmentPose {
                subject_id: s + 1,
                segment_id: 1,
                translation_mm: [f64::from(seed), f64::from(s), -1.5],
                rotation: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
            })
            .collect(),
        markers: (0..n as u32 * 4)
            .map(|k| LabeledRecon {
                subject_id: k / 4 + 1,
                marker_id: k % 4 + 1,
                radius_mm: 7.0,
                position_mm: [f64::from(k), f64::from(seed), 0.25],
                covariance: [0.0; 9],
                trajectory_id: k,
            })
            .collect(),
    };
    (statics, dynamics)
}

fn packet(s: &StaticObjects, d: &DynamicObjects, resend: bool, unchanged: &[u32]) -> Vec<u8> {
    encode::frame(&FrameOut {
        statics: s,
        resend_statics: resend,
        dynamics: d,
        unchanged_dynamics: unchanged,
        wanted: &CLIENT_WANTS,
    })
}

/// Decodes `bytes` with a fresh decoder; checks every list against the bytes.
fn bounded(bytes: &[u8]) {
    let mut dec = Decoder::new();
    let _ = dec.decode(bytes);
    let f = &dec.frame;
    assert!(f.dynamics.segments.len() * SEGMENT_POSE_BYTES <= bytes.len());
    assert!(f.dynamics.markers.len() * LABELED_RECON_BYTES <= bytes.len());
    assert!(f.dynamics.markers.capacity() <= 2 * (bytes.len() / LABELED_RECON_BYTES) + 4);
    assert!(f.dynamics.segments.capacity() <= 2 * (bytes.len() / SEGMENT_POSE_BYTES) + 4);
    assert!(f.dynamics.latency.len() * 12 <= bytes.len());
    // A subject is at least an id, a name's count and three counts: 20 bytes (plus its item header).
    assert!(f.statics.subjects.len() * 20 <= bytes.len());
    for s in &f.statics.subjects {
        assert!(s.segments.len() * 36 + s.markers.len() * 8 + s.attachments.len() * 8 <= bytes.len());
    }
    assert!(dec.object_enums.len() * 4 <= bytes.len());
    assert!(dec.pings.len() * 16 <= bytes.len());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn vicon_arbitrary_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..2000)) {
        bounded(&bytes);
    }

    /// Arbitrary bytes behind a valid header and item framing, so the item decoders see them.
    #[test]
    fn vicon_arbitrary_items(kind in prop_oneof![Just(1u32), Just(2), Just(5), Just(6), Just(9), Just(23), Just(26), Just(37), Just(42), Just(100_001), Just(100_004), any::<u32>()],
                             payload in proptest::collection::vec(any::<u8>(), 0..600)) {
        let mut p = impactd::mocap::vicon::framing::PacketWriter::new();
        p.item(kind, |b| b.extend_from_slice(&payload));
        bounded(&p.finish());
    }

    #[test]
    fn vicon_mutated_frames(
        n in 0usize..12,
        seed in any::<u32>(),
        resend in any::<bool>(),
        edits in proptest::collection::vec((any::<usize>(), any::<u8>()), 0..8),
        cut in any::<usize>(),
    ) {
        let (s, d) = scene(n, seed);
        let mut bytes = packet(&s, &d, true, &[]);
        let mut dec = Decoder::new();
        let sum = dec.decode(&bytes).unwrap();
        prop_assert!(sum.frame && sum.statics);
        prop_assert_eq!(&dec.frame.statics, &s);
        prop_assert_eq!(&dec.frame.dynamics, &d);
        // The next frame with the statics and markers unchanged: both carry over.
        let mut d2 = d.clone();
        d2.frame_id = Some(seed.wrapping_add(1));
        d2.markers.clear();
        dec.decode(&packet(&s, &d2, resend, &[LABELED_RECONS])).unwrap();
        prop_assert_eq!(&dec.frame.statics, &s);
        prop_assert_eq!(&dec.frame.dynamics.markers, &d.markers);
        for (i, b) in edits {
            let len = bytes.len();
            bytes[i % len] = b;
        }
        let keep = cut % (bytes.len() + 1);
        bounded(&bytes[..keep]);
        // A damaged packet after a good one: the good state survives a refusal.
        let before = dec.frame.clone();
        if dec.decode(&bytes[..keep]).is_err() {
            prop_assert_eq!(&dec.frame, &before);
        }
    }
}
