//! Bad C3D files: truncated, a wrong parameter section, an unknown processor, NaN coordinates and -1
//! residuals, labels with trailing spaces; each gives a clear error or a warning, never a panic. And arbitrary
//! or mutated bytes into the reader (proptest): no panic, and memory bounded by the format's own limits (one
//! frame buffer of at most (4 x 65535 + 65535) x 4 bytes, a parameter section of at most 1024 blocks).

#![allow(clippy::unwrap_used)]

use std::io::Cursor;
use std::path::{Path, PathBuf};

use impactd::daemon::recording::c3d::{C3dError, C3dReader, Frame};
use proptest::prelude::*;

fn kept(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/c3d").join(name)
}

/// A reader over bytes and every frame it gave.
type ReadAll<'a> = (C3dReader<Cursor<&'a [u8]>>, Vec<Frame>);

fn read_all(bytes: &[u8]) -> Result<ReadAll<'_>, C3dError> {
    let mut reader = C3dReader::new(Cursor::new(bytes))?;
    let mut frames = Vec::new();
    let mut f = Frame::default();
    while reader.next_frame(&mut f)? {
        frames.push(f.clone());
    }
    Ok((reader, frames))
}

#[test]
fn a_truncated_file_keeps_its_whole_frames_and_says_so() {
    let bytes = std::fs::read(kept("pc_real.c3d")).unwrap();
    let (whole, all) = read_all(&bytes).unwrap();
    let frame_bytes = whole.info.frame_bytes;
    let cut = &bytes[..bytes.len() - 10 * frame_bytes - 7];
    let (reader, frames) = read_all(cut).unwrap();
    // pc_real's data section ends on a block boundary past its last frame, so what is cut is whole frames
    // plus padding: the frames left read as before, and the header's count is flagged.
    assert!(frames.len() < all.len() && frames.len() >= all.len() - 11);
    assert_eq!(frames[..], all[..frames.len()]);
    assert!(reader.info.warnings.iter().any(|w| w.starts_with("truncated:")), "{:?}", reader.info.warnings);
    // Cut inside the header or the parameters: an error that says what could not be read.
    let e = read_all(&bytes[..300]).err().unwrap().to_string();
    assert!(e.contains("less than a 512-byte header"), "{e}");
    // Regression: an empty file (BTK's test set has one) was said to have a second byte of 0x00.
    for n in [0, 1] {
        let e = read_all(&bytes[..n]).err().unwrap().to_string();
        assert!(e.contains(&format!("it has {n} bytes, less than a 512-byte header")), "{e}");
    }
    let e = read_all(&bytes[..514]).err().unwrap().to_string();
    assert!(e.contains("the parameter section"), "{e}");
}

#[test]
fn a_wrong_parameter_section_is_a_clear_error_or_a_warning() {
    let bytes = std::fs::read(kept("pc_int.c3d")).unwrap();
    // The processor byte names no processor.
    let mut bad = bytes.clone();
    bad[512 + 3] = 99;
    let e = read_all(&bad).err().unwrap().to_string();
    assert!(e.contains("processor type byte 99"), "{e}");
    // Not a C3D file at all.
    let e = read_all(b"\x89MCAP0\r\n and more bytes of something else entirely").err().unwrap().to_string();
    assert!(e.contains("not a C3D file"), "{e}");
    // A parameter's data runs off the section: that one is skipped with a warning, the rest is read.
    let mut bad = bytes.clone();
    let at = bytes.windows(6).position(|w| w == b"LABELS").unwrap();
    bad[at + 6 + 2 + 2] = 255; // its first dimension
    bad[at + 6 + 2 + 3] = 255; // its second
    let (reader, frames) = read_all(&bad).unwrap();
    assert_eq!(frames.len(), 89);
    assert!(reader.info.warnings.iter().any(|w| w.contains("LABELS")), "{:?}", reader.info.warnings);
}

#[test]
fn validity_is_the_residual_word_and_nan_is_never_a_position() {
    let bytes = std::fs::read(kept("pc_real.c3d")).unwrap();
    let (reader, frames) = read_all(&bytes).unwrap();
    let data = reader.info.data_start_byte as usize;
    // The first frame with two valid points a, b: a's residual word set to -1 with its coordinates kept: invalid;
    // b's x set to NaN with its residual kept: invalid too.
    let (k, f) = frames.iter().enumerate().find(|(_, f)| f.points_m.iter().flatten().count() >= 2).unwrap();
    let valid: Vec<usize> = (0..f.points_m.len()).filter(|i| f.points_m[*i].is_some()).take(2).collect();
    let at = |i: usize| data + k * reader.info.frame_bytes + 16 * i;
    let mut bad = bytes.clone();
    bad[at(valid[0]) + 12..at(valid[0]) + 16].copy_from_slice(&(-1.0f32).to_le_bytes());
    bad[at(valid[1])..at(valid[1]) + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    let (_, after) = read_all(&bad).unwrap();
    assert_eq!(after[k].points_m[valid[0]], None);
    assert_eq!(after[k].points_m[valid[1]], None);
    assert_eq!(after[k].residual_m[valid[0]], -1.0);
    assert_eq!(after[k].points_m.iter().flatten().count(), f.points_m.iter().flatten().count() - 2);
    // Integer data: a -1 residual word likewise.
    let bytes = std::fs::read(kept("pc_int.c3d")).unwrap();
    let (reader, frames) = read_all(&bytes).unwrap();
    let (k, f) = frames.iter().enumerate().find(|(_, f)| f.points_m.iter().flatten().count() >= 1).unwrap();
    let i = f.points_m.iter().position(Option::is_some).unwrap();
    let at = reader.info.data_start_byte as usize + k * reader.info.frame_bytes + 8 * i;
    let mut bad = bytes.clone();
    bad[at + 6..at + 8].copy_from_slice(&(-1i16).to_le_bytes());
    assert_eq!(read_all(&bad).unwrap().1[k].points_m[i], None);
}

#[test]
fn labels_lose_their_trailing_spaces() {
    let bytes = std::fs::read(kept("pc_real.c3d")).unwrap();
    let (reader, _) = read_all(&bytes).unwrap();
    // The file pads its 4-character labels to the parameter's row width.
    assert!(reader.info.labels.iter().all(|l| !l.ends_with(' ') && !l.is_empty()));
    assert_eq!(reader.info.labels[0], "RFT1");
}

fn exercise(bytes: &[u8]) {
    if let Ok(mut reader) = C3dReader::new(Cursor::new(bytes)) {
        // Bounded allocation: the frame buffer is the format's frame size, never a claimed frame count.
        assert!(reader.info.frame_bytes <= (4 * 65535 + 65535) * 4);
        let mut f = Frame::default();
        let mut n = 0u64;
        while let Ok(true) = reader.next_frame(&mut f) {
            n += 1;
        }
        assert!(n <= reader.info.frames);
        assert!(reader.info.frames * reader.info.frame_bytes as u64 <= bytes.len() as u64);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..4096)) {
        exercise(&bytes);
    }

    #[test]
    fn mutated_sample_files_never_panic(
        which in 0usize..4,
        edits in proptest::collection::vec((0usize..2048, any::<u8>()), 1..16),
        cut in 0usize..50_000,
    ) {
        let name = ["pc_int.c3d", "sgi_real.c3d", "dec_int.c3d", "basketball.c3d"][which];
        let mut bytes = std::fs::read(kept(name)).unwrap();
        // The header and the parameter section (the first 2 KiB) are where a mutation changes the layout.
        for (at, value) in edits {
            if at < bytes.len() {
                bytes[at] = value;
            }
        }
        bytes.truncate(bytes.len().saturating_sub(cut));
        exercise(&bytes);
    }
}
