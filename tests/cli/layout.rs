//! The house's boundaries that the compiler does not check (ARCHITECTURE.md section 1, "Layout", and "Crates").
//! The compiler keeps the physics crate (`crates/golf-physics`) from naming impactd, and its manifest keeps the IO
//! crates out of it (checked here too, so a dependency added there is caught); inside each crate these hold:
//!
//! The live path (the pipeline, the models, the kinematics, flight, pairing and the daemon's live loop, with the
//! bridges, the recording and the session numbers it feeds) never names the offline tools (impactd's
//! `crate::offline`: identification, plots, evaluation; the physics crate's synthetic swings, `crate::swing`), so
//! the code a rig runs on every sample stays small enough to audit for latency. A file's own `#[cfg(test)]`
//! module may use them (tests draw synthetic swings).
//!
//! No module imports one that imports it back: the top-level modules of each crate, and inside `daemon` its
//! sub-modules, form no circle (ARCHITECTURE.md section 1).

#![allow(clippy::unwrap_used)]

use std::path::{Path, PathBuf};

/// The physics crate's sources, from impactd's root.
const PHYSICS_SRC: &str = "crates/golf-physics/src";

/// The live path: in the physics crate, whose offline tool is `swing`, and in impactd, whose are `offline`.
const LIVE_PATH: [(&str, &str); 11] = [
    ("crates/golf-physics/src/pipeline", "swing"),
    ("crates/golf-physics/src/impact", "swing"),
    ("crates/golf-physics/src/kinematics", "swing"),
    ("crates/golf-physics/src/flight", "swing"),
    ("src/pairing", "offline"),
    ("crates/golf-physics/src/integrate.rs", "swing"),
    ("crates/golf-physics/src/face.rs", "swing"),
    ("src/daemon/live", "offline"),
    ("src/daemon/bridges", "offline"),
    ("src/daemon/recording", "offline"),
    ("src/session", "offline"),
];

/// The crates' source folders, from impactd's root: impactd's own and the physics crate's.
fn crate_sources() -> [PathBuf; 2] {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    [root.join("src"), root.join(PHYSICS_SRC)]
}

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

/// The lines of `code` that name the module `tools` (`offline` in impactd, `swing` in the physics crate).
fn names_offline(code: &str, tools: &str) -> Vec<String> {
    let (path, declared) = (format!("crate::{tools}"), format!("mod {tools}"));
    let (inside, beside) = (format!("super::{tools}"), format!("{tools}::"));
    code.lines()
        .filter(|line| {
            line.contains(&path)
                || line.contains(&declared)
                || line.contains(&inside)
                || (tools == "offline" && line.contains(&beside))
        })
        .map(|line| line.trim().to_string())
        .collect()
}

#[test]
fn the_live_path_never_names_the_offline_tools() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for (part, tools) in LIVE_PATH {
        let mut part_files = Vec::new();
        rust_files(&root.join(part), &mut part_files);
        assert!(!part_files.is_empty(), "no sources in {part}");
        files.extend(part_files.into_iter().map(|f| (f, tools)));
    }
    assert!(files.len() > 40, "the live path's files were not found ({} files)", files.len());
    let mut found = Vec::new();
    // A test module in a file of its own (`#[cfg(test)] mod tests;`) is a test, as a file's own test module is.
    let is_test_file =
        |f: &Path| f.file_stem().is_some_and(|s| s == "tests" || s.to_string_lossy().ends_with("_tests"));
    for (file, tools) in files.iter().filter(|(f, _)| !is_test_file(f)) {
        let text = std::fs::read_to_string(file).unwrap();
        for line in names_offline(outside_tests(&text), tools) {
            found.push(format!("{}: {line}", file.strip_prefix(root).unwrap().display()));
        }
    }
    assert!(found.is_empty(), "live-path files name the offline tools:\n{}", found.join("\n"));
}

#[test]
fn the_check_sees_a_use_of_the_offline_tools() {
    // The check must be able to fail: a live file that used a synthetic swing would be caught.
    let code = "use crate::offline::swing::Swing;\nfn f() {}\n#[cfg(test)]\nmod tests { use crate::offline::plot; }";
    assert_eq!(names_offline(outside_tests(code), "offline"), vec!["use crate::offline::swing::Swing;".to_string()]);
    assert!(names_offline("pub offline_m: Real,", "offline").is_empty(), "a field named offline_m is not the module");
    // In the physics crate: its synthetic swings, not a local named `swing` or the `Swing` of a doc.
    let code =
        "use crate::swing::{sample, Swing};\nlet swing = 1;\n#[cfg(test)]\nmod tests { use crate::swing::Swing; }";
    assert_eq!(names_offline(outside_tests(code), "swing"), vec!["use crate::swing::{sample, Swing};".to_string()]);
}

/// The module path of a file under `src/`: `src/daemon/live/mod.rs` -> `daemon::live`, `src/face.rs` -> `face`.
fn module_of(relative: &Path) -> Vec<String> {
    let mut parts: Vec<String> = relative.iter().map(|p| p.to_string_lossy().to_string()).collect();
    if let Some(last) = parts.pop() {
        let stem = last.trim_end_matches(".rs");
        if stem != "mod" && stem != "lib" {
            parts.push(stem.to_string());
        }
    }
    parts
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// The first identifier of `text` and what follows it.
fn ident(text: &str) -> (&str, &str) {
    let end = text.find(|c: char| !is_ident(c)).unwrap_or(text.len());
    (&text[..end], &text[end..])
}

/// The paths one code line names through `crate::` or `super::`, absolute (without `crate`), for a file of
/// module `module`; a `{a, b::c}` group gives one path per member.
fn named_paths(module: &[String], line: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut rest = line;
    while let Some(at) = rest.find(['c', 's']) {
        let before = rest[..at].chars().last();
        let tail = &rest[at..];
        rest = &rest[at + 1..];
        if before.is_some_and(is_ident) {
            continue;
        }
        let mut path: Vec<String>;
        let mut after;
        if let Some(t) = tail.strip_prefix("crate::") {
            path = Vec::new();
            after = t;
        } else if tail.starts_with("super::") {
            path = module.to_vec();
            after = tail;
            while let Some(t) = after.strip_prefix("super::") {
                path.pop();
                after = t;
            }
        } else {
            continue;
        }
        loop {
            let (name, t) = ident(after);
            if name.is_empty() {
                break;
            }
            path.push(name.to_string());
            match t.strip_prefix("::") {
                Some(t) => after = t,
                None => {
                    after = t;
                    break;
                }
            }
        }
        if let Some(group) = after.strip_prefix('{') {
            let mut depth = 0;
            let mut member = String::new();
            for c in group.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        let (name, _) = ident(member.trim());
                        if !name.is_empty() && name != "self" {
                            out.push([path.clone(), vec![name.to_string()]].concat());
                        }
                        member.clear();
                        continue;
                    }
                    _ => {}
                }
                member.push(c);
            }
            let (name, _) = ident(member.trim());
            if !name.is_empty() && name != "self" {
                out.push([path.clone(), vec![name.to_string()]].concat());
            }
        }
        if !path.is_empty() {
            out.push(path);
        }
        rest = after;
    }
    out
}

/// What a folder's root file hands on (`pub use live::{run, RunOptions};` in `daemon/mod.rs`): the re-exported
/// path -> the module that defines it.
fn re_exports(module: &[String], code: &str) -> Vec<(Vec<String>, Vec<String>)> {
    let mut out = Vec::new();
    for line in code.lines() {
        let Some(rest) = line.trim().strip_prefix("pub use ") else { continue };
        let (sub, rest) = ident(rest);
        if sub.is_empty() || sub == "crate" || sub == "super" || !rest.starts_with("::") {
            continue;
        }
        let target = [module.to_vec(), vec![sub.to_string()]].concat();
        let rest = &rest[2..];
        let names: Vec<&str> = match rest.strip_prefix('{') {
            Some(group) => group.split(['}', ',']).map(|n| ident(n.trim()).0).filter(|n| !n.is_empty()).collect(),
            None => vec![ident(rest).0],
        };
        for name in names {
            out.push(([module.to_vec(), vec![name.to_string()]].concat(), target.clone()));
        }
    }
    out
}

/// Edges between units, each with the lines that make it (`file: line`).
type Graph = std::collections::BTreeMap<String, std::collections::BTreeMap<String, Vec<String>>>;

/// The unit graph of every folder of the crate, by the folder's module path (`[]` the crate, `["impact",
/// "continuous"]`, ...): its units are the modules directly inside it, an edge a -> b a line of a file inside `a`
/// naming something inside `b`.
fn folder_graphs(src: &Path) -> std::collections::BTreeMap<Vec<String>, Graph> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let texts: Vec<(Vec<String>, String, String)> = files
        .iter()
        .filter(|f| !f.ends_with("main.rs") || f.parent() != Some(src))
        .map(|f| {
            let relative = f.strip_prefix(src).unwrap();
            let text = std::fs::read_to_string(f).unwrap();
            (module_of(relative), format!("{}/{}", src.display(), relative.display()), outside_tests(&text).to_string())
        })
        .collect();
    // Every module path and its prefixes.
    let modules: std::collections::BTreeSet<Vec<String>> =
        texts.iter().flat_map(|(m, _, _)| (1..=m.len()).map(|k| m[..k].to_vec())).collect();
    let aliases: Vec<(Vec<String>, Vec<String>)> = texts
        .iter()
        .filter(|(_, file, _)| file.ends_with("mod.rs") || file.ends_with("lib.rs"))
        .flat_map(|(m, _, code)| re_exports(m, code))
        .collect();
    let mut graphs = std::collections::BTreeMap::<Vec<String>, Graph>::new();
    // A test module in a file of its own (`#[cfg(test)] mod tests;`) is a test, as a file's own test module is.
    let is_test = |m: &[String]| m.last().is_some_and(|n| n == "tests" || n.ends_with("_tests"));
    for (module, file, code) in texts.iter().filter(|(m, _, _)| !is_test(m)) {
        for line in code.lines().filter(|l| !l.trim_start().starts_with("//")) {
            for mut path in named_paths(module, line) {
                // Re-exports resolved to the module that defines the item, repeatedly (a re-export of one).
                for _ in 0..4 {
                    match aliases.iter().find(|(from, _)| path.starts_with(from)) {
                        Some((from, to)) => path = [to.clone(), path[from.len()..].to_vec()].concat(),
                        None => break,
                    }
                }
                let common = module.iter().zip(&path).take_while(|(a, b)| a == b).count();
                if common >= module.len() || common >= path.len() {
                    continue;
                }
                let folder = module[..common].to_vec();
                let (a, b) = (&module[common], &path[common]);
                if modules.contains(&[folder.clone(), vec![b.clone()]].concat()) {
                    let evidence = format!("{file}: {}", line.trim());
                    graphs
                        .entry(folder)
                        .or_default()
                        .entry(a.clone())
                        .or_default()
                        .entry(b.clone())
                        .or_default()
                        .push(evidence);
                }
            }
        }
    }
    graphs
}

/// The circles of a graph: its strongly connected components of more than one unit, sorted.
fn circles(graph: &Graph) -> Vec<Vec<String>> {
    let reach = |from: &String| {
        let mut seen = std::collections::BTreeSet::new();
        let mut stack = vec![from.clone()];
        while let Some(n) = stack.pop() {
            for next in graph.get(&n).into_iter().flat_map(|m| m.keys()) {
                if seen.insert(next.clone()) {
                    stack.push(next.clone());
                }
            }
        }
        seen
    };
    let nodes: std::collections::BTreeSet<String> =
        graph.iter().flat_map(|(a, m)| std::iter::once(a.clone()).chain(m.keys().cloned())).collect();
    let reaches: std::collections::BTreeMap<&String, _> = nodes.iter().map(|n| (n, reach(n))).collect();
    let mut out: Vec<Vec<String>> = Vec::new();
    for n in &nodes {
        if out.iter().any(|c| c.contains(n)) {
            continue;
        }
        let component: Vec<String> =
            nodes.iter().filter(|m| reaches[n].contains(*m) && reaches[*m].contains(n)).cloned().collect();
        if component.len() > 1 {
            out.push(component);
        }
    }
    out
}

/// A readable account of each circle: its units and the lines that tie them.
fn describe(graph: &Graph, found: &[Vec<String>]) -> String {
    let mut text = String::new();
    for component in found {
        text += &format!("circle: {}\n", component.join(" <-> "));
        for a in component {
            for (b, lines) in graph.get(a).into_iter().flat_map(|m| m.iter()) {
                if component.contains(b) {
                    text += &format!("  {a} -> {b} ({} lines), e.g. {}\n", lines.len(), lines[0]);
                }
            }
        }
    }
    text
}

#[test]
fn no_module_imports_one_that_imports_it_back() {
    let [impactd, physics] = crate_sources();
    let (graphs, physics_graphs) = (folder_graphs(&impactd), folder_graphs(&physics));
    let (top, daemon) = (&graphs[&Vec::new()], &graphs[&vec!["daemon".to_string()]]);
    let physics_top = &physics_graphs[&Vec::new()];
    assert!(top.len() > 8 && top.contains_key("daemon"), "impactd's top-level graph was not read: {:?}", top.keys());
    assert!(
        physics_top.len() > 8 && physics_top.contains_key("pipeline"),
        "the physics crate's top-level graph was not read: {:?}",
        physics_top.keys()
    );
    assert!(daemon.len() > 5 && daemon.contains_key("live"), "the daemon's graph was not read: {:?}", daemon.keys());
    let (top_circles, daemon_circles, physics_circles) = (circles(top), circles(daemon), circles(physics_top));
    assert!(
        top_circles.is_empty() && daemon_circles.is_empty() && physics_circles.is_empty(),
        "modules import each other in a circle:\n{}{}{}",
        describe(top, &top_circles),
        describe(daemon, &daemon_circles),
        describe(physics_top, &physics_circles)
    );
}

/// The same inside every folder, at every depth (`impact::continuous::law`, `offline::identify`, ...).
#[test]
fn no_folder_holds_modules_that_import_each_other() {
    let [impactd, physics] = crate_sources();
    let (graphs, physics_graphs) = (folder_graphs(&impactd), folder_graphs(&physics));
    let law = vec!["impact".to_string(), "continuous".to_string(), "law".to_string()];
    let identify = vec!["offline".to_string(), "identify".to_string()];
    assert!(
        graphs.len() > 10 && graphs.contains_key(&identify),
        "impactd's folders were not read: {:?}",
        graphs.keys()
    );
    assert!(
        physics_graphs.len() > 10 && physics_graphs.contains_key(&law),
        "the physics crate's folders were not read: {:?}",
        physics_graphs.keys()
    );
    let mut text = String::new();
    for (folder, graph) in graphs.iter().chain(&physics_graphs) {
        let found = circles(graph);
        if !found.is_empty() {
            text += &format!(
                "in {}:\n{}",
                if folder.is_empty() { "crate".into() } else { folder.join("::") },
                describe(graph, &found)
            );
        }
    }
    assert!(text.is_empty(), "modules import each other in a circle:\n{text}");
}

#[test]
fn the_cycle_check_sees_a_circle() {
    // Made-up graphs: a -> b -> c -> a (and c -> d) is one circle; a chain is none.
    let graph = |edges: &[(&str, &str)]| {
        let mut g = Graph::new();
        for (a, b) in edges {
            g.entry(a.to_string()).or_default().entry(b.to_string()).or_default().push(format!("{a}.rs"));
        }
        g
    };
    let looped = graph(&[("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")]);
    assert_eq!(circles(&looped), vec![vec!["a".to_string(), "b".to_string(), "c".to_string()]]);
    assert!(describe(&looped, &circles(&looped)).contains("c -> a"));
    assert!(circles(&graph(&[("a", "b"), ("b", "c"), ("a", "c")])).is_empty());
    // The lines are read as the check reads them: `super::` from a file, groups, and a folder's re-exports.
    let module: Vec<String> = vec!["daemon".into(), "bridges".into(), "peers".into()];
    let s = |p: &[&str]| p.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    assert_eq!(
        named_paths(&module, "use super::super::stats::RateLimiter;"),
        vec![s(&["daemon", "stats", "RateLimiter"])]
    );
    assert_eq!(
        named_paths(&module, "use crate::daemon::{wall_ns, live::x};"),
        vec![s(&["daemon", "wall_ns"]), s(&["daemon", "live"]), s(&["daemon"])]
    );
    assert!(named_paths(&module, "let supercrate::x = 1; // a_crate::y").is_empty());
    assert_eq!(
        re_exports(&s(&["daemon"]), "pub use live::{run, RunOptions};"),
        vec![(s(&["daemon", "run"]), s(&["daemon", "live"])), (s(&["daemon", "RunOptions"]), s(&["daemon", "live"]))]
    );
}

/// Small files, one job each (ARCHITECTURE.md section 7): no source file over 450 lines.
#[test]
fn no_source_file_is_over_450_lines() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for src in crate_sources() {
        rust_files(&src, &mut files);
    }
    assert!(files.len() > 100, "the sources were not found ({} files)", files.len());
    let long: Vec<String> = files
        .iter()
        .filter_map(|f| {
            let lines = std::fs::read_to_string(f).unwrap().lines().count();
            (lines > 450).then(|| format!("{}: {lines} lines", f.strip_prefix(root).unwrap().display()))
        })
        .collect();
    assert!(long.is_empty(), "files over 450 lines:\n{}", long.join("\n"));
}

/// The crates the physics crate must never depend on: IO, runtimes, transports, the CLI's and the tools'.
const IO_CRATES: [&str; 9] =
    ["tokio", "zenoh", "mcap", "clap", "anyhow", "tracing-subscriber", "indicatif", "rayon", "csv"];

/// The IO crates a manifest names among its dependencies of any kind (normal, dev, build; per target too).
fn io_crates_named(manifest: &str) -> Vec<String> {
    let value: toml::Table = manifest.parse().unwrap();
    let mut tables: Vec<&toml::Table> = vec![&value];
    if let Some(targets) = value.get("target").and_then(|t| t.as_table()) {
        tables.extend(targets.values().filter_map(|t| t.as_table()));
    }
    let mut found = Vec::new();
    for table in tables {
        for kind in ["dependencies", "dev-dependencies", "build-dependencies"] {
            for (name, spec) in table.get(kind).and_then(|d| d.as_table()).into_iter().flatten() {
                // A renamed dependency (`x = { package = "zenoh" }`) is the crate it names.
                let package = spec.get("package").and_then(|p| p.as_str()).unwrap_or(name);
                if IO_CRATES.contains(&package) {
                    found.push(format!("[{kind}] {name}"));
                }
            }
        }
    }
    found
}

#[test]
fn the_physics_crate_names_none_of_the_io_crates() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/golf-physics/Cargo.toml");
    let manifest = std::fs::read_to_string(&path).unwrap();
    assert!(manifest.contains("name = \"golf-physics\"") && manifest.contains("nalgebra"), "{}", path.display());
    let found = io_crates_named(&manifest);
    assert!(found.is_empty(), "crates/golf-physics/Cargo.toml depends on IO crates: {found:?}");
    // The check can fail: a manifest with a runtime among its dependencies, renamed or per target, is caught.
    let bad = "[dependencies]\nserde = \"1\"\nrt = { package = \"tokio\", version = \"1\" }\n\
               [target.'cfg(unix)'.dev-dependencies]\nzenoh = \"1\"\n";
    assert_eq!(io_crates_named(bad), ["[dependencies] rt", "[dev-dependencies] zenoh"]);
}

/// The daemon reads the wall clock only through `daemon::clock::Clock` (ARCHITECTURE.md section 2: one clock
/// handed to what stamps, so a test drives it).
#[test]
fn the_daemon_reads_the_wall_clock_only_through_its_clock() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src/daemon"), &mut files);
    assert!(files.len() > 50, "the daemon's sources were not found ({} files)", files.len());
    let readers: Vec<String> = files
        .iter()
        .filter(|f| !f.ends_with("daemon/clock.rs"))
        .filter(|f| outside_tests(&std::fs::read_to_string(f).unwrap()).contains("SystemTime::now"))
        .map(|f| f.strip_prefix(root).unwrap().display().to_string())
        .collect();
    assert!(readers.is_empty(), "read the wall clock without the daemon's Clock:\n{}", readers.join("\n"));
}
