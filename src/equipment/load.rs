//! Loading a club by name or file: what the CLI, the daemon's configuration and the tests all call.

use std::io::Read;
use std::path::Path;

use super::{ClubFile, ClubSpec, EquipmentError, LoadedClub, ModelSections};

/// The largest club file read (bytes): a club is a few hundred bytes; this keeps `club = "/dev/zero"` finite.
pub const MAX_CLUB_FILE_BYTES: u64 = 1 << 20;

/// A club from a preset name (`driver`, `iron7`) or a path to a TOML club file, with the file's model sections.
pub fn load_club(spec: &str) -> Result<LoadedClub, EquipmentError> {
    if spec.ends_with(".toml") || Path::new(spec).exists() {
        let read_err = |source| EquipmentError::Read { path: spec.to_string(), source };
        let file = std::fs::File::open(spec).map_err(read_err)?;
        let mut text = String::new();
        file.take(MAX_CLUB_FILE_BYTES + 1).read_to_string(&mut text).map_err(read_err)?;
        if text.len() as u64 > MAX_CLUB_FILE_BYTES {
            return Err(EquipmentError::TooLarge { path: spec.to_string(), max_bytes: MAX_CLUB_FILE_BYTES });
        }
        ClubFile::parse(&text)
    } else {
        Ok(LoadedClub { club: ClubSpec::preset(spec)?, sections: ModelSections::default() })
    }
}
