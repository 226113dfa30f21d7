//! C3D import and the marker fit (issue targets: import >= 1 M marker-frames/s with 4 markers per body; the
//! rigid fit <= 1 us per body-frame). The capture is written here as a minimal Intel float C3D file (header,
//! a POINT group, the frames) of 4 markers moving with 0.1 mm of noise, one marker in 20 occluded.

use std::io::Write;

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use impactd::daemon::recording::c3d::{self, CaptureSamples};
use impactd::kinematics::{MarkerFitter, MarkerSet};
use impactd::math::{Isometry3, Point3, Vector3};
use impactd::rng::Rng;

const FRAMES: usize = 20_000;
const MARKERS: [(&str, [f64; 3]); 4] = [
    ("CH1", [0.035, 0.0, 0.01]),
    ("CH2", [-0.035, 0.004, 0.012]),
    ("TOE", [0.0, 0.025, -0.03]),
    ("HEEL", [0.012, -0.022, 0.028]),
];

fn set() -> MarkerSet {
    MarkerSet::new(MARKERS.iter().map(|(l, p)| (l.to_string(), Vector3::from(*p)))).unwrap_or_else(|e| panic!("{e}"))
}

fn pose(i: usize) -> Isometry3 {
    let t = i as f64 * 1e-3;
    Isometry3::new(Vector3::new(t.sin(), 0.8 + 0.2 * t.cos(), 0.1 * t), Vector3::new(0.3 * t, 1.0 + t, -0.2))
}

/// Markers of frame `i` (lab, mm) and their residual words.
fn markers(i: usize, rng: &mut Rng) -> Vec<[f32; 4]> {
    let p = pose(i);
    MARKERS
        .iter()
        .map(|(_, b)| {
            let q = p * Point3::from(Vector3::from(*b));
            let n = Vector3::new(rng.normal(), rng.normal(), rng.normal()) * 1e-4;
            let r = if rng.chance(0.05) { -1.0 } else { 1.0 };
            [((q.x + n.x) * 1e3) as f32, ((q.y + n.y) * 1e3) as f32, ((q.z + n.z) * 1e3) as f32, r]
        })
        .collect()
}

fn c3d_bytes() -> Vec<u8> {
    let n = MARKERS.len();
    let mut header = vec![0u8; 512];
    header[0] = 2;
    header[1] = 0x50;
    let put16 = |h: &mut Vec<u8>, word: usize, v: u16| h[2 * (word - 1)..2 * word].copy_from_slice(&v.to_le_bytes());
    put16(&mut header, 2, n as u16);
    put16(&mut header, 4, 1);
    put16(&mut header, 5, FRAMES as u16);
    header[12..16].copy_from_slice(&(-0.1f32).to_le_bytes());
    put16(&mut header, 9, 3);
    header[20..24].copy_from_slice(&1000f32.to_le_bytes());
    let mut params = vec![1, 0x50, 1, 84];
    params.extend_from_slice(&[5, (-1i8) as u8]);
    params.extend_from_slice(b"POINT");
    params.extend_from_slice(&3u16.to_le_bytes());
    params.push(0);
    let labels: Vec<u8> = MARKERS.iter().flat_map(|(l, _)| format!("{l:<4}").into_bytes()).collect();
    let mut body = vec![0xff, 2, 4, n as u8];
    body.extend_from_slice(&labels);
    params.extend_from_slice(&[6, 1]);
    params.extend_from_slice(b"LABELS");
    params.extend_from_slice(&((2 + body.len() + 1) as u16).to_le_bytes());
    params.extend_from_slice(&body);
    params.push(0);
    params.extend_from_slice(&[5, 1]);
    params.extend_from_slice(b"UNITS");
    params.extend_from_slice(&0u16.to_le_bytes());
    params.extend_from_slice(&[0xff, 1, 2, b'm', b'm', 0]);
    params.resize(512, 0);
    let mut out = header;
    out.extend_from_slice(&params);
    let mut rng = Rng::new(1);
    for i in 0..FRAMES {
        for m in markers(i, &mut rng) {
            for v in m {
                out.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    out
}

fn import(c: &mut Criterion) {
    let path = std::env::temp_dir().join(format!("impactd-bench-{}.c3d", std::process::id()));
    let written = std::fs::File::create(&path).and_then(|mut f| f.write_all(&c3d_bytes()));
    written.unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut group = c.benchmark_group("c3d");
    group.throughput(Throughput::Elements((FRAMES * MARKERS.len()) as u64));
    // What `impactd import` does: read, fit each frame, write a JSON line per sample.
    group.bench_function("import 4 markers/body (marker-frames)", |b| {
        let mut jsonl = Vec::with_capacity(FRAMES * 220);
        b.iter(|| {
            jsonl.clear();
            let reader = c3d::open(&path).unwrap_or_else(|e| panic!("{e}"));
            let mut samples =
                CaptureSamples::new(reader, MarkerFitter::new(set()), "bay1").unwrap_or_else(|e| panic!("{e}"));
            while let Some(s) = samples.next_sample().unwrap_or_else(|e| panic!("{e}")) {
                serde_json::to_writer(&mut jsonl, &s).unwrap_or_else(|e| panic!("{e}"));
                jsonl.push(b'\n');
            }
            black_box(jsonl.len())
        })
    });
    group.finish();
    let _ = std::fs::remove_file(&path);

    let fitter = MarkerFitter::new(set());
    let mut rng = Rng::new(2);
    let frames: Vec<Vec<Option<Vector3>>> = (0..1000)
        .map(|i| {
            let p = pose(i);
            set()
                .body_m
                .iter()
                .map(|b| {
                    Some((p * Point3::from(*b)).coords + Vector3::new(rng.normal(), rng.normal(), rng.normal()) * 1e-4)
                })
                .collect()
        })
        .collect();
    let mut group = c.benchmark_group("marker fit");
    group.throughput(Throughput::Elements(frames.len() as u64));
    group.bench_function("4 markers (body-frames)", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for f in &frames {
                sum += fitter.fit(black_box(f)).map(|r| r.residual_m).unwrap_or(0.0);
            }
            sum
        })
    });
    // A frame with a ghost (one marker 2 cm off): the rejection fits each 3 of the 4 to find it.
    let ghosts: Vec<Vec<Option<Vector3>>> = frames
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let mut f = f.clone();
            f[i % 4] = f[i % 4].map(|p| p + Vector3::new(0.0, 0.02, 0.0));
            f
        })
        .collect();
    group.bench_function("4 markers, one a ghost (body-frames)", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for f in &ghosts {
                sum += fitter.fit(black_box(f)).map(|r| r.residual_m).unwrap_or(0.0);
            }
            sum
        })
    });
    group.finish();
}

criterion_group!(benches, import);
criterion_main!(benches);
