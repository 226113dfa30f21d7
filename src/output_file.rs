//! Creating output files by one rule, `run --record`'s: an existing file is replaced only with `--overwrite`.
//! Every command that writes a file it was named (recordings, `recover -o`, `replay -o`, `fit -o`) opens it here.

use std::fs::File;
use std::path::{Path, PathBuf};

/// Why an output file could not be created.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("{} exists; choose a new name or pass --overwrite", .path.display())]
    Exists {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("creating {}: {source}", .path.display())]
    Create {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

/// Creates `path` for writing: an existing file is replaced (truncated) only with `overwrite`.
pub fn create_output(path: &Path, overwrite: bool) -> Result<File, OutputError> {
    let mut open = std::fs::OpenOptions::new();
    open.write(true);
    if overwrite {
        open.create(true).truncate(true);
    } else {
        open.create_new(true);
    }
    open.open(path).map_err(|source| {
        let path = path.to_path_buf();
        if source.kind() == std::io::ErrorKind::AlreadyExists {
            OutputError::Exists { path, source }
        } else {
            OutputError::Create { path, source }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_existing_file_is_replaced_only_with_overwrite() {
        let dir = std::env::temp_dir().join(format!("impactd-output-file-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("out.txt");
        let _ = std::fs::remove_file(&path);
        create_output(&path, false).unwrap();
        let e = create_output(&path, false).unwrap_err();
        assert!(matches!(e, OutputError::Exists { .. }) && e.to_string().contains("--overwrite"), "{e}");
        create_output(&path, true).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
