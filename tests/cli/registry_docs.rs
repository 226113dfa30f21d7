//! The README's model list and docs/club-files.md's sections and presets are the registry's (`impactd models`); regenerate
//! them with `scripts/registry-docs.sh` when a model or a section changes.

#![allow(clippy::unwrap_used)]

use std::process::Command;

fn region(path: &str, name: &str) -> String {
    let text = std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap();
    let start = format!("<!-- generated: {name} -->\n");
    let from = text.find(&start).unwrap_or_else(|| panic!("{path}: no region {name}")) + start.len();
    let to = from + text[from..].find("<!-- end -->").unwrap();
    text[from..to].to_string()
}

fn models(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_impactd")).arg("models").args(args).output().unwrap();
    assert!(out.status.success());
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn readme_lists_the_registrys_models() {
    assert_eq!(region("README.md", "models"), models(&[]), "run scripts/registry-docs.sh");
}

#[test]
fn club_files_doc_lists_the_registrys_sections() {
    assert_eq!(region("docs/club-files.md", "sections"), models(&["--sections"]), "run scripts/registry-docs.sh");
}

#[test]
fn club_files_doc_lists_the_presets() {
    assert_eq!(region("docs/club-files.md", "presets"), models(&["--presets"]), "run scripts/registry-docs.sh");
}
