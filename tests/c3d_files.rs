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
