//! What the Vicon tests stream: a club subject (one segment, four markers) and a ball subject at 720 Hz, frame
//! by frame with exact numbers, a swing's samples as frames, and the path to Vicon's own SDK client.

#![allow(clippy::unwrap_used)]
#![allow(dead_code)]

use std::path::PathBuf;

use impactd::kinematics::ClubheadSample;
use impactd::math::{Quaternion, UnitQuaternion};
use impactd::mocap::vicon::items::MarkerDef;
use impactd::mocap::vicon::{
    DynamicObjects, LabeledRecon, LatencySample, SegmentDef, SegmentPose, StaticObjects, SubjectDef, Timecode, UpAxis,
};

/// 720 Hz on the 135 MHz clock.
pub const PERIOD_TICKS: i64 = 187_500;
pub const CLUB: u32 = 1;
pub const BALL: u32 = 2;
pub const CLUB_MARKERS: [&str; 4] = ["toe", "heel", "crown", "hosel"];

fn segment(id: u32, parent: u32, name: &str) -> SegmentDef {
    SegmentDef { segment_id: id, parent_id: parent, bounds: [-60.0, -30.0, -25.0, 60.0, 30.0, 25.0], name: name.into() }
}

/// The club subject `name` (one segment named like it, four markers on it) and a ball.
pub fn statics_named(club: &str, up: UpAxis) -> StaticObjects {
    let markers =
        CLUB_MARKERS.iter().enumerate().map(|(i, n)| MarkerDef { marker_id: i as u32 + 1, name: n.to_string() });
    StaticObjects {
        frame_period_ticks: Some(PERIOD_TICKS),
        up_axis: Some(up),
        subjects: vec![
            SubjectDef {
                subject_id: CLUB,
                name: club.into(),
                segments: vec![segment(1, 0, club)],
                markers: markers.collect(),
                attachments: (1..=4).map(|m| (m, 1)).collect(),
            },
            SubjectDef {
                subject_id: BALL,
                name: "ball".into(),
                segments: vec![segment(1, 0, "ball")],
                markers: vec![MarkerDef { marker_id: 1, name: "ball".into() }],
                attachments: vec![(1, 1)],
            },
        ],
    }
}

pub fn statics() -> StaticObjects {
    statics_named("club", UpAxis::Z)
}

/// A rotation matrix (row-major) turning `a` rad about a tilted axis: exact doubles, not the identity.
pub fn rotation(a: f64) -> [f64; 9] {
    let axis = impactd::math::Vector3::new(0.3, -0.5, 0.81).normalize();
    let q = UnitQuaternion::from_axis_angle(&impactd::math::Unit::new_normalize(axis), a);
    let m = q.to_rotation_matrix();
    let mut out = [0.0; 9];
    for r in 0..3 {
        for c in 0..3 {
            out[3 * r + c] = m[(r, c)];
        }
    }
    out
}

/// The dynamic types frame `i` lists unchanged: every 11th frame's labelled markers are its predecessor's.
pub fn unchanged(i: u32) -> &'static [u32] {
    if i % 11 == 6 {
        &[impactd::mocap::vicon::enums::LABELED_RECONS]
    } else {
        &[]
    }
}

fn markers(i: u32) -> Vec<LabeledRecon> {
    let t = f64::from(i);
    let mut markers: Vec<LabeledRecon> = (1..=4u32)
        .filter(|&m| !(m == 3 && i % 5 == 1))
        .map(|m| LabeledRecon {
            subject_id: CLUB,
            marker_id: m,
            radius_mm: 7.0,
            position_mm: [-800.0 + 3.5 * t + f64::from(m) * 12.5, 100.0 + f64::from(m), 951.0 - f64::from(m) / 7.0],
            covariance: [0.0; 9],
            trajectory_id: 40 + m,
        })
        .collect();
    markers.push(LabeledRecon {
        subject_id: BALL,
        marker_id: 1,
        radius_mm: 21.335,
        position_mm: [0.0, 0.0, 21.335],
        covariance: [0.0; 9],
        trajectory_id: 7,
    });
    markers
}

/// Frame `i` of the scene: id 5000 + i; the club's segment occluded every 7th frame, its third marker every 5th
/// (but for the frames whose markers are unchanged, [`unchanged`]); the ball always seen.
pub fn frame(i: u32) -> DynamicObjects {
    let t = f64::from(i);
    let mut segments = Vec::new();
    if i % 7 != 3 {
        segments.push(SegmentPose {
            subject_id: CLUB,
            segment_id: 1,
            translation_mm: [-812.25 + 3.5 * t, 101.0625 - 0.1 * t, 950.5 + t / 3.0],
            rotation: rotation(0.01 * t + 0.2),
        });
    }
    segments.push(SegmentPose {
        subject_id: BALL,
        segment_id: 1,
        translation_mm: [0.0, 0.0, 21.335],
        rotation: rotation(0.0),
    });
    let markers = if unchanged(i).is_empty() { markers(i) } else { markers(i - 1) };
    DynamicObjects {
        frame_id: Some(5000 + i),
        timecode: Some(Timecode {
            hours: 10,
            minutes: 4,
            seconds: (i / 720 % 60) as u8,
            frames: (i / 24 % 30) as u8,
            subframe: (i % 24) as u16,
            subframes_per_frame: 24,
            standard: 1,
            user_bits: 0xBEEF,
            field: (i % 2) as u8,
        }),
        latency: vec![
            LatencySample { name: "Data Collection".into(), latency_s: 0.0021 + t * 1e-7 },
            LatencySample { name: "Core Processor".into(), latency_s: 0.00093 },
        ],
        segments,
        markers,
    }
}

/// A swing's sample as a frame of the club subject (root segment, mm, row-major rotation), the ball beside it:
/// the frame id is the sample's frame less one (the SDK numbers frames from the id plus one).
pub fn frame_of(s: &ClubheadSample) -> DynamicObjects {
    let [x, y, z, w] = s.orientation_xyzw;
    let m = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)).to_rotation_matrix();
    let mut rotation = [0.0; 9];
    for r in 0..3 {
        for c in 0..3 {
            rotation[3 * r + c] = m[(r, c)];
        }
    }
    let p = s.position_m * 1e3;
    let mut segments = vec![SegmentPose {
        subject_id: BALL,
        segment_id: 1,
        translation_mm: [0.0, 0.0, 21.335],
        rotation: rotation_identity(),
    }];
    if !s.occluded {
        segments.push(SegmentPose { subject_id: CLUB, segment_id: 1, translation_mm: [p.x, p.y, p.z], rotation });
    }
    DynamicObjects {
        frame_id: Some(s.frame as u32 - 1),
        timecode: None,
        // 2^-8 s: 3906.25 us exactly.
        latency: vec![LatencySample { name: "Data Collection".into(), latency_s: 0.00390625 }],
        segments,
        markers: Vec::new(),
    }
}

pub fn rotation_identity() -> [f64; 9] {
    [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
}

/// Vicon's own DataStream SDK client: `IMPACTD_VICON_SDK_CLIENT` (`scripts/test.sh` sets it), else what
/// `scripts/vicon-sdk-client.sh` prints (it builds the client the first time, a few minutes, then answers from
/// its cache under `target/vicon-sdk`). Without either the test fails and says why.
pub fn sdk_client() -> PathBuf {
    if let Some(p) = std::env::var_os("IMPACTD_VICON_SDK_CLIENT").map(PathBuf::from).filter(|p| p.exists()) {
        return p;
    }
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/vicon-sdk-client.sh");
    let out = std::process::Command::new("bash")
        .arg(&script)
        .stderr(std::process::Stdio::inherit())
        .output()
        .unwrap_or_else(|e| panic!("running {}: {e}", script.display()));
    let path = PathBuf::from(String::from_utf8_lossy(&out.stdout).trim());
    assert!(
        out.status.success() && path.exists(),
        "Vicon's DataStream SDK client could not be built ({}): see the messages above, or set \
         IMPACTD_VICON_SDK_CLIENT to a built client",
        out.status
    );
    path
}
