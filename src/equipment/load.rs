//! Loading a club by name or file: what the CLI, the daemon's configuration and the tests all call.

use std::io::Read;
use std::path::Path;

use sha2::{Digest, Sha256};

use super::{ClubFile, EquipmentError, LoadedClub};

/// The largest club file read (bytes): a club is a few hundred bytes; this keeps `club = "/dev/zero"` finite.
pub const MAX_CLUB_FILE_BYTES: u64 = 1 << 20;

/// A club from a preset name (`driver`, `iron7`, `sw`, ...) or a path to a TOML club file, with the file's model
/// sections.
pub fn load_club(spec: &str) -> Result<LoadedClub, EquipmentError> {
    load_club_source(spec).map(|(club, _)| club)
}

/// A club and the bytes it was read from: a club file's text, a preset's embedded file, or for the seed's two
/// code presets their name (see [`super::presets::Preset::bytes`]).
pub fn load_club_source(spec: &str) -> Result<(LoadedClub, Vec<u8>), EquipmentError> {
    if spec.ends_with(".toml") || Path::new(spec).exists() {
        let read_err = |source| EquipmentError::Read { path: spec.to_string(), source };
        let file = open_club_file(spec)?;
        let mut text = String::new();
        file.take(MAX_CLUB_FILE_BYTES + 1).read_to_string(&mut text).map_err(read_err)?;
        if text.len() as u64 > MAX_CLUB_FILE_BYTES {
            return Err(EquipmentError::TooLarge { path: spec.to_string(), max_bytes: MAX_CLUB_FILE_BYTES });
        }
        Ok((ClubFile::parse(&text)?, text.into_bytes()))
    } else {
        let preset = super::presets::find(spec).ok_or_else(|| EquipmentError::UnknownPreset(spec.to_string()))?;
        Ok((preset.load()?, preset.bytes().to_vec()))
    }
}

/// A club file opened for reading: a regular file only, no larger than [`MAX_CLUB_FILE_BYTES`]. A FIFO, a
/// device, a socket or a directory (`/proc/self/fd/1` when standard output is a pipe) is refused before it is
/// opened, and the file is opened without blocking and looked at again once open (the path may have been
/// replaced in between), so opening a club file never waits for a writer.
fn open_club_file(spec: &str) -> Result<std::fs::File, EquipmentError> {
    let read_err = |source| EquipmentError::Read { path: spec.to_string(), source };
    check_regular(spec, &std::fs::metadata(spec).map_err(read_err)?)?;
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(spec).map_err(read_err)?;
    check_regular(spec, &file.metadata().map_err(read_err)?)?;
    Ok(file)
}

/// Refuses what is not a regular file, or one larger than [`MAX_CLUB_FILE_BYTES`].
fn check_regular(spec: &str, meta: &std::fs::Metadata) -> Result<(), EquipmentError> {
    if !meta.is_file() {
        return Err(EquipmentError::NotRegularFile { path: spec.to_string(), kind: file_kind(meta) });
    }
    if meta.len() > MAX_CLUB_FILE_BYTES {
        return Err(EquipmentError::TooLarge { path: spec.to_string(), max_bytes: MAX_CLUB_FILE_BYTES });
    }
    Ok(())
}

/// What a path that is not a regular file is, in words.
fn file_kind(meta: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if meta.is_dir() {
        "a directory"
    } else {
        "not a regular file"
    }
}

/// The SHA-256 of a club's bytes, lower-case hex (`sha256sum FILE` prints the same).
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes).iter().map(|b| format!("{b:02x}")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A preset's hash is its file's: FIPS 180-4's example "abc" checks the digest itself.
    #[test]
    fn a_preset_hashes_as_its_file() {
        assert_eq!(sha256_hex(b"abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
        let (club, bytes) = load_club_source("sw").unwrap();
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/clubs/presets/sw.toml");
        let (from_file, file_bytes) = load_club_source(path).unwrap();
        assert_eq!((club, sha256_hex(&bytes)), (from_file, sha256_hex(&file_bytes)));
        assert!(load_club_source("putter").unwrap_err().to_string().contains("putter"));
    }

    /// A FIFO (which would block the reader until a writer came) and a directory are refused at once, naming
    /// what they are.
    #[cfg(unix)]
    #[test]
    fn a_fifo_or_a_directory_is_refused_without_blocking() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("club.toml");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            let e = load_club_source(fifo.to_str().unwrap()).unwrap_err();
            assert!(matches!(e, EquipmentError::NotRegularFile { kind: "a FIFO", .. }), "{e}");
            assert!(e.to_string().contains("is a FIFO"), "{e}");
        }
        let e = load_club_source(dir.path().to_str().unwrap()).unwrap_err();
        assert!(matches!(e, EquipmentError::NotRegularFile { kind: "a directory", .. }), "{e}");
        if std::path::Path::new("/dev/zero").exists() {
            let e = load_club_source("/dev/zero").unwrap_err();
            assert!(matches!(e, EquipmentError::NotRegularFile { kind: "a device", .. }), "{e}");
        }
    }
}
