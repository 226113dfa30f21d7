//! Decoding one motion-capture frame of 10 rigid bodies: NatNet 4.1 and 3.1 (`NAT_FRAMEOFDATA` with a marker
//! set and labeled markers, as Motive sends it), a QTM 6D data packet and a Vicon DataStream frame of 10
//! subjects (one segment and four labelled markers each, the static objects listed unchanged, as a server sends
//! every frame after the first). Budget: 2 us each.
//! `cargo bench --bench mocap_decode`.

#![allow(clippy::unwrap_used)]

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use impactd::mocap::natnet::{self, Frame, RigidBody, Version};
use impactd::mocap::qtm::{self, Body6d, Frame6d};
use impactd::mocap::vicon::{self, encode::FrameOut};
use impactd::mocap::{natnet::encode as natnet_encode, qtm::encode as qtm_encode, track};

fn bodies_natnet() -> Frame {
    Frame {
        frame_number: 123_456,
        rigid_bodies: (0..10)
            .map(|i| RigidBody {
                id: i + 1,
                position_m: [0.1 * i as f32, 1.0, -0.3],
                orientation_xyzw: [0.0, 0.0, 0.6, 0.8],
                mean_error_m: 2e-4,
                tracking_valid: true,
            })
            .collect(),
        labeled_markers: Vec::new(),
        timestamp_s: 342.9,
        mid_exposure_ticks: 3_429_000_000,
        data_received_ticks: 3_429_020_000,
        transmit_ticks: 3_429_035_000,
        models_changed: false,
    }
}

fn bench(c: &mut Criterion) {
    let frame = bodies_natnet();
    let markers: Vec<[f32; 3]> = (0..30).map(|i| [i as f32 * 0.01, 1.0, 0.0]).collect();
    for version in [Version::V4_1, Version::V3_1] {
        let bytes = natnet_encode::frame(version, &frame, "club", &markers).unwrap();
        let mut out = Frame::default();
        c.bench_function(&format!("natnet {version} frame, 10 rigid bodies ({} bytes)", bytes.len()), |b| {
            b.iter(|| natnet::decode(black_box(&bytes), version, &mut out).unwrap())
        });
        c.bench_function(&format!("natnet {version} frame, 10 rigid bodies, decoded to samples"), |b| {
            b.iter(|| {
                natnet::decode(black_box(&bytes), version, &mut out).unwrap();
                out.rigid_bodies
                    .iter()
                    .map(|r| impactd::mocap::natnet::sample::natnet_sample(r, &out, Some(10_000_000)).0.t_ns)
                    .sum::<u64>()
            })
        });
    }
    let q = Frame6d {
        timestamp_us: 342_900_000,
        frame_number: 123_456,
        bodies: (0..10)
            .map(|i| Body6d {
                position_mm: [100.0 * i as f32, 1000.0, -300.0],
                rotation: [0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0],
                residual_mm: None,
            })
            .collect(),
        drop_rate_2d: 0,
        out_of_sync_rate_2d: 0,
        markers_mm: Vec::new(),
    };
    let packet = qtm_encode::data(&q);
    let body = &packet[qtm::HEADER_BYTES..];
    let mut out = Frame6d::default();
    c.bench_function(&format!("qtm 6D packet, 10 bodies ({} bytes)", packet.len()), |b| {
        b.iter(|| qtm::decode_data(black_box(body), &mut out).unwrap())
    });
    c.bench_function("qtm 6D packet, 10 bodies, decoded to samples", |b| {
        b.iter(|| {
            qtm::decode_data(black_box(body), &mut out).unwrap();
            out.bodies.iter().map(|r| track::qtm_sample(r, &out).0.t_ns).sum::<u64>()
        })
    });
    vicon_frames(c);
}

/// Ten subjects, as `tests/inputs/vicon_fuzz.rs` builds them.
fn vicon_scene() -> (vicon::StaticObjects, vicon::DynamicObjects) {
    use vicon::items::MarkerDef;
    let subjects = (1..=10)
        .map(|s| vicon::SubjectDef {
            subject_id: s,
            name: format!("club {s}"),
            segments: vec![vicon::SegmentDef { segment_id: 1, parent_id: 0, bounds: [0.0; 6], name: "head".into() }],
            markers: (1..=4).map(|m| MarkerDef { marker_id: m, name: format!("m{m}") }).collect(),
            attachments: (1..=4).map(|m| (m, 1)).collect(),
        })
        .collect();
    let statics = vicon::StaticObjects { frame_period_ticks: Some(187_500), up_axis: Some(vicon::UpAxis::Z), subjects };
    let dynamics = vicon::DynamicObjects {
        frame_id: Some(123_456),
        timecode: Some(vicon::Timecode { hours: 10, subframes_per_frame: 1, ..Default::default() }),
        latency: vec![
            vicon::LatencySample { name: "Data Collection".into(), latency_s: 0.0021 },
            vicon::LatencySample { name: "Core Processor".into(), latency_s: 0.0009 },
        ],
        segments: (1..=10)
            .map(|s| vicon::SegmentPose {
                subject_id: s,
                segment_id: 1,
                translation_mm: [100.0 * f64::from(s), 1000.0, -300.0],
                rotation: [0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0],
            })
            .collect(),
        markers: (0..40)
            .map(|k| vicon::LabeledRecon {
                subject_id: k / 4 + 1,
                marker_id: k % 4 + 1,
                radius_mm: 7.0,
                position_mm: [f64::from(k), 1000.0, 0.0],
                covariance: [0.0; 9],
                trajectory_id: k,
            })
            .collect(),
    };
    (statics, dynamics)
}

fn vicon_frames(c: &mut Criterion) {
    let (statics, dynamics) = vicon_scene();
    let out = |resend| FrameOut {
        statics: &statics,
        resend_statics: resend,
        dynamics: &dynamics,
        unchanged_dynamics: &[],
        wanted: &vicon::enums::CLIENT_WANTS,
    };
    let first = vicon::encode::frame(&out(true));
    let packet = vicon::encode::frame(&out(false));
    let mut decoder = vicon::Decoder::new();
    decoder.decode(&first).unwrap();
    c.bench_function(&format!("vicon frame, 10 subjects ({} bytes)", packet.len()), |b| {
        b.iter(|| decoder.decode(black_box(&packet)).unwrap())
    });
    c.bench_function("vicon frame, 10 subjects, decoded to samples", |b| {
        b.iter(|| {
            decoder.decode(black_box(&packet)).unwrap();
            (1..=10u32)
                .filter_map(|s| vicon::sample::segment_sample(&decoder.frame, s, 1))
                .map(|(s, _)| s.t_ns)
                .sum::<u64>()
        })
    });
    c.bench_function(&format!("vicon frame, 10 subjects, statics resent ({} bytes)", first.len()), |b| {
        b.iter(|| decoder.decode(black_box(&first)).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
