//! C3D files from c3d.org's sample sets (every vendor's): each opens and reads to its last frame, or fails with
//! an error that says what is wrong; none panics. `tests/data/c3d/` keeps a few small ones (see its README);
//! `IMPACTD_C3D_SAMPLES=DIR` adds every `.c3d` file under DIR (c3d.org's full sets, as c3dio's repository
//! ships them under tests/c3d_org_samples).

#![allow(clippy::unwrap_used)]

use std::path::{Path, PathBuf};

use impactd::daemon::recording::c3d::{self, Frame, Processor};

fn c3d_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    let mut entries: Vec<_> = entries.flatten().map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            c3d_files(&p, out);
        } else if p.extension().is_some_and(|e| e.eq_ignore_ascii_case("c3d")) {
            out.push(p);
        }
    }
}

fn kept() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/c3d")
}

/// Reads a whole file: (frames read, labels, warnings), or the error's text.
fn read_all(path: &Path) -> Result<(u64, usize, Vec<String>), String> {
    let mut reader = c3d::open(path).map_err(|e| format!("{e:#}"))?;
    let mut frame = Frame::default();
    let mut n = 0;
    while reader.next_frame(&mut frame).map_err(|e| format!("{e:#}"))? {
        assert_eq!(frame.points_m.len(), reader.info.labels.len());
        n += 1;
    }
    assert_eq!(n, reader.info.frames, "{}", path.display());
    Ok((n, reader.info.labels.len(), reader.info.warnings.clone()))
}

#[test]
fn every_sample_file_opens_or_fails_clearly() {
    let mut files = Vec::new();
    c3d_files(&kept(), &mut files);
    assert!(files.len() >= 5, "tests/data/c3d holds the kept samples");
    match std::env::var_os("IMPACTD_C3D_SAMPLES") {
        Some(dir) => {
            let before = files.len();
            c3d_files(Path::new(&dir), &mut files);
            assert!(files.len() > before, "IMPACTD_C3D_SAMPLES={dir:?} holds no .c3d file");
        }
        None => eprintln!("IMPACTD_C3D_SAMPLES is not set: only the {} kept samples are read", files.len()),
    }
    let (mut opened, mut failed) = (0, 0);
    for path in &files {
        match read_all(path) {
            Ok((frames, labels, warnings)) => {
                opened += 1;
                eprintln!("ok      {}: {frames} frames, {labels} points, warnings {warnings:?}", path.display());
            }
            Err(e) => {
                failed += 1;
                // A clear error names what is wrong, not just that something is.
                assert!(e.len() > 20, "{}: unclear error `{e}`", path.display());
                eprintln!("refused {}: {e}", path.display());
            }
        }
    }
    eprintln!("{opened} opened, {failed} refused, of {}", files.len());
    assert!(opened * 10 >= files.len() * 9, "{failed} of {} files refused", files.len());
}

/// c3d.org sample 2: the same capture (AMASS, Vicon 370; 36 markers, 89 frames) stored in all six variants, DEC,
/// Intel and SGI, integer and float: every variant gives the same markers, the integer ones within their
/// quantum (POINT:SCALE).
#[test]
fn dec_intel_and_sgi_integer_and_float_read_the_same() {
    let variants = ["dec_int", "dec_real", "pc_int", "pc_real", "sgi_int", "sgi_real"];
    let expected =
        [Processor::Dec, Processor::Dec, Processor::Intel, Processor::Intel, Processor::Mips, Processor::Mips];
    let mut all = Vec::new();
    for (name, processor) in variants.iter().zip(expected) {
        let mut reader = c3d::open(&kept().join(format!("{name}.c3d"))).unwrap();
        assert_eq!(reader.info.processor, processor, "{name}");
        assert_eq!((reader.info.frames, reader.info.labels.len(), reader.info.first_frame), (89, 36, 1), "{name}");
        assert_eq!(reader.info.float_data, name.ends_with("real"), "{name}");
        let mut frames = Vec::new();
        let mut frame = Frame::default();
        while reader.next_frame(&mut frame).unwrap() {
            frames.push(frame.clone());
        }
        all.push((name, reader.info.scale.abs() as f64 * reader.info.metres_per_unit, frames));
    }
    let (_, _, reference) = &all[3]; // pc_real
    let valid: usize = reference.iter().map(|f| f.points_m.iter().flatten().count()).sum();
    assert!(valid > 1000, "{valid} valid points");
    for (name, quantum_m, frames) in &all {
        for (f, r) in frames.iter().zip(reference) {
            for (p, q) in f.points_m.iter().zip(&r.points_m) {
                match (p, q) {
                    (Some(p), Some(q)) => assert!((p - q).amax() <= quantum_m.max(1e-6), "{name}: {p} vs {q}"),
                    (None, None) => {}
                    _ => panic!("{name} frame {}: validity differs", f.index),
                }
            }
        }
    }
}

/// What another reader's own tests assert about a file: the values in the file's units (mm here), as
/// Biomechanical-ToolKit's reader tests (`Testing/Python/C3DFileReaderTest.py` and `Testing/C++/
/// C3DFileReaderTest.h` in github.com/Biomechanical-ToolKit/BTKCore) give them.
struct Expected {
    /// File names (any case) this holds for.
    names: &'static [&'static str],
    rate_hz: f64,
    points: usize,
    frames: Option<u64>,
    first_frame: Option<u64>,
    analog_rate_hz: Option<f64>,
    analog_channels: Option<usize>,
    labels: &'static [(usize, &'static str)],
    /// (point, 0-based frame, axis, value in the file's units, tolerance).
    values: &'static [(usize, u64, usize, f64, f64)],
    /// (point, 0-based frame, residual in the file's units).
    residuals: &'static [(usize, u64, f64)],
    /// (point, 0-based frame) with a negative residual word: invalid (BTK gives such a point zero coordinates).
    invalid: &'static [(usize, u64)],
}

const EB015: &[&str] = &["Eb015pi.c3d", "Eb015si.c3d", "Eb015vi.c3d", "Eb015pr.c3d", "Eb015sr.c3d", "Eb015vr.c3d"];

/// BTK's numbers. Its `assertAlmostEqual(x, y, 3)` is a tolerance of 5e-4; sample 2's integer files (`pc_int`,
/// `sgi_int`) have a y of 523.5606 where the others have 523.8417, one quantum (POINT:SCALE 0.2812) below.
const EXPECTED: &[Expected] = &[
    Expected {
        names: EB015,
        rate_hz: 50.0,
        points: 26,
        frames: None,
        first_frame: None,
        analog_rate_hz: Some(200.0),
        analog_channels: Some(16),
        labels: &[(0, "RFT1")],
        values: &[
            (0, 8, 0, 250.4166, 5e-4),
            (17, 16, 0, 285.0, 5e-4),
            (17, 16, 1, 222.4166, 5e-4),
            (17, 16, 2, 564.4166, 5e-4),
        ],
        residuals: &[(0, 0, 1.3333), (14, 20, 1.91667)],
        invalid: &[],
    },
    Expected {
        names: &["dec_int.c3d", "dec_real.c3d", "pc_real.c3d", "sgi_real.c3d"],
        rate_hz: 50.0,
        points: 36,
        frames: Some(89),
        first_frame: None,
        analog_rate_hz: Some(200.0),
        analog_channels: Some(16),
        labels: &[(3, "RSK1")],
        values: &[(3, 16, 0, 384.0944, 5e-4), (3, 16, 1, 523.8417, 6e-4), (3, 16, 2, 311.2683, 5e-4)],
        residuals: &[],
        invalid: &[],
    },
    Expected {
        names: &["pc_int.c3d", "sgi_int.c3d"],
        rate_hz: 50.0,
        points: 36,
        frames: Some(89),
        first_frame: None,
        analog_rate_hz: Some(200.0),
        analog_channels: Some(16),
        labels: &[(3, "RSK1")],
        values: &[(3, 16, 0, 384.0944, 5e-4), (3, 16, 1, 523.5606, 5e-4), (3, 16, 2, 311.2683, 5e-4)],
        residuals: &[],
        invalid: &[],
    },
    Expected {
        names: &["Dance.c3d"],
        rate_hz: 65.05,
        points: 40,
        frames: Some(499),
        first_frame: None,
        analog_rate_hz: Some(65.05),
        analog_channels: Some(8),
        labels: &[],
        values: &[],
        residuals: &[],
        invalid: &[],
    },
    Expected {
        names: &["golfswing.c3d"],
        rate_hz: 107.53,
        points: 29,
        frames: Some(514),
        first_frame: None,
        analog_rate_hz: Some(107.53),
        analog_channels: Some(8),
        labels: &[],
        values: &[],
        residuals: &[],
        invalid: &[],
    },
    Expected {
        names: &["phasespace_sample.c3d"],
        rate_hz: 30.0,
        points: 40,
        frames: Some(701),
        first_frame: None,
        analog_rate_hz: None,
        analog_channels: Some(0),
        labels: &[],
        values: &[],
        residuals: &[],
        invalid: &[],
    },
    Expected {
        names: &["badParameterOffset.c3d"],
        rate_hz: 250.0,
        points: 41,
        frames: Some(111),
        first_frame: Some(1),
        analog_rate_hz: None,
        analog_channels: Some(0),
        labels: &[(0, "Point    1"), (40, "Point   41")],
        values: &[(0, 0, 0, 168.093002, 1e-5), (29, 10, 1, 731.903015, 1e-5)],
        residuals: &[],
        invalid: &[(40, 110)],
    },
    Expected {
        names: &["оно мне не вредит.c3d"],
        rate_hz: 250.0,
        points: 27,
        frames: None,
        first_frame: Some(91),
        analog_rate_hz: Some(1000.0),
        analog_channels: Some(6),
        labels: &[(0, "AbcdeFghijk:RASI"), (26, "AbcdeFghijk:LFIN")],
        values: &[],
        residuals: &[],
        invalid: &[],
    },
];

/// Every file named in [`EXPECTED`] that is here (the kept samples; with `IMPACTD_C3D_SAMPLES`, c3d.org's and
/// BTK's sets too) reads as BTK's tests say: rates, counts, first frame, labels, coordinates and residuals.
#[test]
fn files_read_as_btks_tests_assert() {
    let mut files = Vec::new();
    c3d_files(&kept(), &mut files);
    if let Some(dir) = std::env::var_os("IMPACTD_C3D_SAMPLES") {
        c3d_files(Path::new(&dir), &mut files);
    }
    let mut checked = 0;
    for path in &files {
        let name = path.file_name().unwrap().to_string_lossy().to_lowercase();
        let Some(want) = EXPECTED.iter().find(|e| e.names.iter().any(|n| n.to_lowercase() == name)) else { continue };
        let mut reader = c3d::open(path).unwrap();
        let info = reader.info.clone();
        let at = path.display();
        assert!((info.rate_hz - want.rate_hz).abs() < 5e-3, "{at}: rate {}", info.rate_hz);
        assert_eq!(info.labels.len(), want.points, "{at}");
        if let Some(frames) = want.frames {
            assert_eq!(info.frames, frames, "{at}");
        }
        if let Some(first) = want.first_frame {
            assert_eq!(info.first_frame, first, "{at}");
        }
        if let Some(rate) = want.analog_rate_hz {
            assert!((info.analog_rate_hz - rate).abs() < 5e-3, "{at}: analog rate {}", info.analog_rate_hz);
        }
        if let Some(n) = want.analog_channels {
            assert_eq!(info.analog_labels.len(), n, "{at}: analog channels {:?}", info.analog_labels);
        }
        for (i, label) in want.labels {
            assert_eq!(info.labels[*i], *label, "{at}");
        }
        let mut frame = Frame::default();
        while reader.next_frame(&mut frame).unwrap() {
            for &(point, index, axis, value, tol) in want.values.iter().filter(|v| v.1 == frame.index) {
                let p = frame.points_m[point].unwrap_or_else(|| panic!("{at}: point {point} frame {index} invalid"));
                let got = p[axis] / info.metres_per_unit;
                assert!((got - value).abs() <= tol, "{at}: point {point} frame {index} axis {axis}: {got} vs {value}");
            }
            for &(point, index) in want.invalid.iter().filter(|v| v.1 == frame.index) {
                assert!(frame.points_m[point].is_none() && frame.residual_m[point] < 0.0, "{at}: {point} {index}");
            }
            for &(point, index, value) in want.residuals.iter().filter(|v| v.1 == frame.index) {
                let got = f64::from(frame.residual_m[point]) / info.metres_per_unit;
                assert!((got - value).abs() < 5e-4, "{at}: residual of point {point} frame {index}: {got} vs {value}");
            }
        }
        checked += 1;
    }
    eprintln!("{checked} files checked against BTK's values");
    assert!(checked >= 6, "the kept sample 2 files at least");
}
