//! The codec's rules: a frame round-trips, `Contents`' carry-over, what is refused before any allocation, the
//! SDK's numbering and clock, and the step to a sample (row-major matrix, occlusion, fitted markers).

use super::encode::{self, FrameOut};
use super::enums::*;
use super::items::{MarkerDef, SEGMENT_POSE_BYTES};
use super::sample::{resolve_markers, resolve_segment, segment_sample, RouteIds, Unresolved};
use super::*;
use crate::mocap::bytes::Writer;

fn statics() -> StaticObjects {
    StaticObjects {
        frame_period_ticks: Some(187_500),
        up_axis: Some(UpAxis::Z),
        subjects: vec![SubjectDef {
            subject_id: 3,
            name: "club".into(),
            segments: vec![SegmentDef { segment_id: 1, parent_id: 0, bounds: [0.0; 6], name: "head".into() }],
            markers: ["a", "b", "c"]
                .iter()
                .enumerate()
                .map(|(i, n)| MarkerDef { marker_id: i as u32 + 1, name: n.to_string() })
                .collect(),
            attachments: vec![(1, 1), (2, 1), (3, 1)],
        }],
    }
}

/// Rz(90 deg), row-major: rows (0, -1, 0), (1, 0, 0), (0, 0, 1).
const RZ90: [f64; 9] = [0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];

fn dynamics(id: u32, posed: bool) -> DynamicObjects {
    DynamicObjects {
        frame_id: Some(id),
        timecode: Some(Timecode { hours: 1, subframes_per_frame: 1, ..Timecode::default() }),
        latency: vec![LatencySample { name: "Data Collection".into(), latency_s: 0.002 }],
        segments: if posed {
            vec![SegmentPose { subject_id: 3, segment_id: 1, translation_mm: [1000.0, -250.0, 30.0], rotation: RZ90 }]
        } else {
            Vec::new()
        },
        markers: (1..=3)
            .map(|m| LabeledRecon {
                subject_id: 3,
                marker_id: m,
                position_mm: [f64::from(m) * 10.0, 0.0, 5.0],
                ..LabeledRecon::default()
            })
            .collect(),
    }
}

fn packet(s: &StaticObjects, resend: bool, d: &DynamicObjects, unchanged: &[u32]) -> Vec<u8> {
    encode::frame(&FrameOut {
        statics: s,
        resend_statics: resend,
        dynamics: d,
        unchanged_dynamics: unchanged,
        wanted: &enums::CLIENT_WANTS,
    })
}

#[test]
fn a_frame_round_trips_and_carries_over_what_contents_lists_unchanged() {
    let mut dec = Decoder::new();
    let s = statics();
    let sum = dec.decode(&packet(&s, true, &dynamics(10, true), &[])).unwrap();
    assert!(sum.statics && sum.frame && !sum.object_enums);
    assert_eq!(dec.frame.statics, s);
    assert_eq!(dec.frame.dynamics, dynamics(10, true));
    // Statics unchanged, markers unchanged, the segment not sent: occluded; the markers of frame 10 kept.
    let mut next = dynamics(11, false);
    next.markers.clear();
    let sum = dec.decode(&packet(&s, false, &next, &[LABELED_RECONS])).unwrap();
    assert!(sum.frame && !sum.statics, "the static objects were not resent");
    assert_eq!(dec.frame.statics, s);
    assert_eq!(dec.frame.dynamics.frame_id, Some(11));
    assert!(dec.frame.dynamics.segments.is_empty());
    assert_eq!(dec.frame.dynamics.markers, dynamics(10, true).markers);
    // A packet without a dynamic object (a ping's answer) keeps the frame.
    let sum = dec.decode(&encode::pings(&[5, 6])).unwrap();
    assert_eq!((sum.frame, sum.pings, dec.pings.as_slice()), (false, 2, &[5u64, 6][..]));
    assert_eq!(dec.frame.dynamics.frame_id, Some(11));
    // Markers neither sent nor unchanged: none.
    dec.decode(&packet(&s, false, &next, &[])).unwrap();
    assert!(dec.frame.dynamics.markers.is_empty());
}

#[test]
fn the_sdk_numbering_the_clock_and_the_rate() {
    let mut dec = Decoder::new();
    dec.decode(&packet(&statics(), true, &dynamics(719, true), &[])).unwrap();
    assert_eq!(dec.frame.sdk_frame_number(), Some(720));
    assert_eq!(dec.frame.rate_hz(), Some(720.0));
    // 719 frames of 187,500 ticks at 135 MHz: 998.611... ms.
    assert_eq!(dec.frame.t_ns(), Some(998_611_111));
    assert_eq!(dec.frame.latency_total_s(), Some(0.002));
}

#[test]
fn a_bad_packet_is_refused_and_changes_nothing() {
    let mut dec = Decoder::new();
    let good = packet(&statics(), true, &dynamics(10, true), &[]);
    dec.decode(&good).unwrap();
    let before = dec.frame.clone();
    let mut tag = good.clone();
    tag[0] = 0;
    assert!(matches!(dec.decode(&tag), Err(ViconError::BadTag(_))));
    assert!(matches!(dec.decode(&good[..good.len() - 1]), Err(ViconError::SizeMismatch { .. })));
    let mut big = good.clone();
    big[4..8].copy_from_slice(&(8u32 << 20).to_le_bytes());
    assert!(matches!(framing::header(big[..8].try_into().unwrap()), Err(ViconError::Oversized(_))));
    // A GlobalSegments claiming a billion segments: refused from its count, nothing reserved.
    let mut p = framing::PacketWriter::new();
    p.item(FRAME_INFO, |b| b.put_u32(11));
    p.item(GLOBAL_SEGMENTS, |b| {
        b.put_u32(3);
        b.put_u32(1_000_000_000);
    });
    let e = dec.decode(&p.finish()).unwrap_err();
    assert!(matches!(e, ViconError::BadCount { min: SEGMENT_POSE_BYTES, left: 0, .. }), "{e:?}");
    assert_eq!(e.reason(), "malformed");
    // An item overrunning the packet.
    let mut p = good.clone();
    p[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(matches!(dec.decode(&p), Err(ViconError::ItemOverrun { .. })));
    assert_eq!(dec.frame, before);
}

#[test]
fn a_segment_sample_is_metres_and_the_row_major_matrix_as_a_quaternion() {
    let mut dec = Decoder::new();
    dec.decode(&packet(&statics(), true, &dynamics(99, true), &[])).unwrap();
    let ids = resolve_segment(&dec.frame, "club", None).unwrap();
    assert_eq!(ids, RouteIds::Segment { subject_id: 3, segment_id: 1 });
    let (s, bad) = segment_sample(&dec.frame, 3, 1).unwrap();
    assert!(bad.is_none() && !s.occluded);
    assert_eq!((s.frame, s.position_m), (100, [1.0, -0.25, 0.03]));
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let q = s.orientation_xyzw;
    assert!(q[0].abs() < 1e-12 && q[1].abs() < 1e-12 && (q[2] - h).abs() < 1e-12 && (q[3] - h).abs() < 1e-12, "{q:?}");
    dec.decode(&packet(&statics(), false, &dynamics(100, false), &[])).unwrap();
    let (s, bad) = segment_sample(&dec.frame, 3, 1).unwrap();
    assert!(s.occluded && bad.is_none() && s.position_m == [0.0; 3] && s.frame == 101);
    assert_eq!(resolve_segment(&dec.frame, "club", Some("shaft")).unwrap_err().reason(), "segment_not_in_model");
    assert!(matches!(resolve_segment(&dec.frame, "iron", None), Err(Unresolved::NoSubject(_))));
}

#[test]
fn a_marker_set_resolves_by_name_among_the_subjects_markers() {
    let mut dec = Decoder::new();
    dec.decode(&packet(&statics(), true, &dynamics(1, true), &[])).unwrap();
    let set = crate::kinematics::MarkerSet::new([
        ("c".to_string(), crate::math::Vector3::new(0.03, 0.0, 0.0)),
        ("a".to_string(), crate::math::Vector3::new(0.01, 0.0, 0.0)),
        ("b".to_string(), crate::math::Vector3::new(0.02, 0.0, 0.01)),
    ])
    .unwrap();
    let fitter = crate::kinematics::MarkerFitter::new(set);
    assert_eq!(
        resolve_markers(&dec.frame, "club", &fitter).unwrap(),
        RouteIds::Markers { subject_id: 3, marker_ids: vec![3, 1, 2] }
    );
}
