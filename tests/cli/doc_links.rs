//! The manual and the research hold together: every relative Markdown link in README.md, ARCHITECTURE.md,
//! docs/ and research/ resolves to a file, every path under docs/ or research/ that the sources, tests, scripts
//! and pages name exists, and each index (docs/README.md, research/README.md) links every page of its folder.

#![allow(clippy::unwrap_used)]

use std::path::{Path, PathBuf};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// Every file under `dir` (relative to the repository) whose name ends with one of `exts`, sorted.
fn files(dir: &str, exts: &[&str]) -> Vec<PathBuf> {
    fn walk(path: &Path, exts: &[&str], out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(path) else { return };
        for entry in entries {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, exts, out);
            } else if exts.iter().any(|e| path.to_string_lossy().ends_with(e)) {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(&Path::new(ROOT).join(dir), exts, &mut out);
    out.sort();
    out
}

/// The Markdown pages whose links are checked.
fn pages() -> Vec<PathBuf> {
    let mut pages = vec![Path::new(ROOT).join("README.md"), Path::new(ROOT).join("ARCHITECTURE.md")];
    pages.extend(files("docs", &[".md"]));
    pages.extend(files("research", &[".md"]));
    pages
}

/// The targets of the page's inline links and images (`[text](target)`), outside fenced code blocks, with
/// their line numbers.
fn links(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut fenced = false;
    for (n, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        let mut rest = line;
        while let Some(at) = rest.find("](") {
            let after = &rest[at + 2..];
            let Some(end) = after.find(')') else { break };
            out.push((n + 1, after[..end].trim().to_string()));
            rest = &after[end..];
        }
    }
    out
}

/// A link to a file in this repository: not a URL, not an anchor on the same page.
fn is_relative(target: &str) -> bool {
    !(target.is_empty() || target.starts_with('#') || target.contains("://") || target.starts_with("mailto:"))
}

#[test]
fn every_relative_markdown_link_resolves() {
    let mut broken = Vec::new();
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        for (line, target) in links(&text) {
            if !is_relative(&target) {
                continue;
            }
            let file = target.split('#').next().unwrap();
            if !page.parent().unwrap().join(file).exists() {
                let page = page.strip_prefix(ROOT).unwrap().display().to_string();
                broken.push(format!("{page}:{line}: {target}"));
            }
        }
    }
    assert!(broken.is_empty(), "links to no file:\n{}", broken.join("\n"));
}

/// `docs/NAME.EXT` or `research/NAME.EXT` (a page, a figure, a script or a test) named anywhere in `text`.
fn repository_paths(text: &str) -> Vec<String> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    for prefix in ["docs/", "research/"] {
        let mut from = 0;
        while let Some(at) = text[from..].find(prefix) {
            let start = from + at;
            from = start + prefix.len();
            // Only a path of the repository's own: not `foo/docs/...`, a URL's or another repository's.
            if start > 0 && (bytes[start - 1].is_ascii_alphanumeric() || b"/._-".contains(&bytes[start - 1])) {
                continue;
            }
            let end = text[start..]
                .find(|c: char| !(c.is_ascii_alphanumeric() || "/._-".contains(c)))
                .map_or(text.len(), |e| start + e);
            let path = text[start..end].trim_end_matches('.');
            let name = path.rsplit('/').next().unwrap();
            if [".md", ".svg", ".json", ".json5", ".py", ".sh", ".rs"].iter().any(|e| name.ends_with(e)) {
                out.push(path.to_string());
            }
        }
    }
    out
}

/// Paths of other repositories that the text names beside their repository (libgolf's, `gdifiore/libgolf`).
const OTHER_REPOSITORIES: &[&str] = &["docs/aerodynamic_model.md"];

#[test]
fn every_docs_or_research_path_named_exists() {
    let mut named = Vec::new();
    for dir in ["src", "crates", "tests", "benches", "examples", "scripts", "research", "docs", ".ci"] {
        named.extend(files(dir, &[".rs", ".md", ".py", ".sh", ".toml"]));
    }
    for file in ["README.md", "ARCHITECTURE.md", "Cargo.toml"] {
        named.push(Path::new(ROOT).join(file));
    }
    // This file names made-up paths to test the reader.
    named.retain(|f| !f.ends_with("tests/cli/doc_links.rs"));
    let mut missing = Vec::new();
    for file in named {
        let text = std::fs::read_to_string(&file).unwrap();
        for path in repository_paths(&text) {
            if !Path::new(ROOT).join(&path).exists() && !OTHER_REPOSITORIES.contains(&path.as_str()) {
                missing.push(format!("{}: {path}", file.strip_prefix(ROOT).unwrap().display()));
            }
        }
    }
    missing.dedup();
    assert!(missing.is_empty(), "paths named that do not exist:\n{}", missing.join("\n"));
}

/// Each index links every page of its folder: nothing in the manual or the research is left unlisted.
#[test]
fn each_index_lists_every_page_of_its_folder() {
    for dir in ["docs", "research"] {
        let index = Path::new(ROOT).join(dir).join("README.md");
        let text = std::fs::read_to_string(&index).unwrap();
        let linked: Vec<PathBuf> = links(&text)
            .into_iter()
            .filter(|(_, t)| is_relative(t))
            .map(|(_, t)| index.parent().unwrap().join(t.split('#').next().unwrap()))
            .collect();
        let unlisted: Vec<String> = std::fs::read_dir(Path::new(ROOT).join(dir))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "md") && *p != index)
            .filter(|p| !linked.contains(p))
            .map(|p| p.strip_prefix(ROOT).unwrap().display().to_string())
            .collect();
        assert!(unlisted.is_empty(), "{dir}/README.md does not link {unlisted:?}");
    }
}

#[test]
fn the_link_parser_reads_links_and_skips_code() {
    let text = "a [b](c.md) and ![d](e.svg#x)\n```\n[no](skip.md)\n```\n[f](https://x.org) [g](#h)";
    let got: Vec<String> = links(text).into_iter().map(|(_, t)| t).collect();
    assert_eq!(got, ["c.md", "e.svg#x", "https://x.org", "#h"]);
    assert_eq!(
        repository_paths("see docs/a.md, `research/scripts/b.py` and foo/docs/c.md or docs/ alone"),
        ["docs/a.md", "research/scripts/b.py"]
    );
}
