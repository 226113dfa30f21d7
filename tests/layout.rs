//! The house's boundaries that the compiler does not check (ARCHITECTURE.md section 1, "Layout").
//!
//! The live path (the pipeline, the models, the kinematics, flight, pairing and the daemon's live loop) never
//! names the offline tools (`crate::offline`: identification, plots, synthetic swings, evaluation), so the code a
//! rig runs on every sample stays small enough to audit for latency. A file's own `#[cfg(test)]` module may use
//! them (tests draw synthetic swings).

#![allow(clippy::unwrap_used)]

use std::path::{Path, PathBuf};

const LIVE_PATH: [&str; 8] = [
    "src/pipeline.rs",
    "src/impact",
    "src/kinematics",
    "src/flight",
    "src/pairing",
    "src/integrate.rs",
    "src/face.rs",
    "src/daemon/live",
];

fn rust_files(path: &Path, out: &mut Vec<PathBuf>) {
    if path.is_dir() {
        let mut entries: Vec<_> = std::fs::read_dir(path).unwrap().map(|e| e.unwrap().path()).collect();
        entries.sort();
        for entry in entries {
            rust_files(&entry, out);
        }
    } else if path.extension().is_some_and(|e| e == "rs") {
        out.push(path.to_path_buf());
    }
}

/// The lines of `text` outside its `#[cfg(test)]` items (a file's test module comes last, as in every file here).
fn outside_tests(text: &str) -> &str {
    text.find("#[cfg(test)]").map_or(text, |at| &text[..at])
}

fn names_offline(code: &str) -> Vec<String> {
    code.lines()
        .filter(|line| line.contains("offline::") || line.contains("mod offline"))
        .map(|line| line.trim().to_string())
        .collect()
}

#[test]
fn the_live_path_never_names_the_offline_tools() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for part in LIVE_PATH {
        rust_files(&root.join(part), &mut files);
    }
    assert!(files.len() > 40, "the live path's files were not found ({} files)", files.len());
    let mut found = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for line in names_offline(outside_tests(&text)) {
            found.push(format!("{}: {line}", file.strip_prefix(root).unwrap().display()));
        }
    }
    assert!(found.is_empty(), "live-path files name the offline tools:\n{}", found.join("\n"));
}

#[test]
fn the_check_sees_a_use_of_the_offline_tools() {
    // The check must be able to fail: a live file that used a synthetic swing would be caught.
    let code = "use crate::offline::swing::Swing;\nfn f() {}\n#[cfg(test)]\nmod tests { use crate::offline::plot; }";
    assert_eq!(names_offline(outside_tests(code)), vec!["use crate::offline::swing::Swing;".to_string()]);
    assert!(names_offline("pub offline_m: Real,").is_empty(), "a field named offline_m is not the module");
}
