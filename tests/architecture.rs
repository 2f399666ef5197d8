//! The crate's rooms depend only on the rooms above them (see the crate
//! page's map): the core (`raster`) on nothing but the shared error,
//! output, markup and naming modules; `geometry` on the core; `measure` on both;
//! `teaching` on those; `check` on those; `lab` on everything. A `use` or
//! path that reaches down the list (a cycle in the making) fails here,
//! naming the file and line.

use std::path::{Path, PathBuf};

/// The rooms in order: each may use those before it.
const ROOMS: [&str; 6] = ["raster", "geometry", "measure", "teaching", "check", "lab"];
/// Shared by every room, and using none (`test_support` only by unit tests).
const SHARED: [&str; 5] = ["error", "output", "names", "markup", "test_support"];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The room a file of `src/` belongs to: its first folder, or its stem.
fn room_of(relative: &Path) -> String {
    let first = relative.components().next().unwrap().as_os_str();
    Path::new(first)
        .file_stem()
        .unwrap()
        .to_string_lossy()
        .into_owned()
}

/// Every `crate::ROOM` named in code (not in comments) of `text`.
fn rooms_used(text: &str) -> Vec<(usize, String)> {
    let mut used = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let code = line.split("//").next().unwrap();
        let mut rest = code;
        while let Some(i) = rest.find("crate::") {
            let after = &rest[i + "crate::".len()..];
            let name: String = after
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            used.push((n + 1, name));
            rest = after;
        }
    }
    used
}

#[test]
fn rooms_depend_only_on_the_rooms_above_them() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let rank = |room: &str| ROOMS.iter().position(|r| *r == room);
    let mut wrong = Vec::new();
    let mut checked = 0;
    for file in &files {
        let relative = file.strip_prefix(&src).unwrap();
        let room = room_of(relative);
        // The binary (main.rs, cli/) is wiring and may use every room;
        // lib.rs is the map and re-exports from every room.
        if ["main", "cli", "lib"].contains(&room.as_str()) {
            continue;
        }
        checked += 1;
        let own = rank(&room);
        assert!(
            own.is_some() || SHARED.contains(&room.as_str()),
            "{} is in no room of the map",
            relative.display()
        );
        for (line, used) in rooms_used(&std::fs::read_to_string(file).unwrap()) {
            let allowed = match (own, rank(&used)) {
                // Error and Result are re-exported at the root.
                _ if SHARED.contains(&used.as_str())
                    || ["Error", "Result"].contains(&used.as_str()) =>
                {
                    true
                }
                (Some(own), Some(other)) => other <= own,
                (None, Some(_)) => false,
                (_, None) => false,
            };
            if !allowed {
                wrong.push(format!("{}:{line}: {room} uses {used}", relative.display()));
            }
        }
    }
    assert!(checked > 40, "only {checked} files were read");
    assert!(
        wrong.is_empty(),
        "uses against the map:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_check_sees_a_use_against_the_map() {
    let used = rooms_used("use crate::teaching::trace; // crate::lab in a comment\n");
    assert_eq!(used, vec![(1, "teaching".to_string())]);
}

/// The module a file of `src/` is: `raster::triangle::tiled` for
/// `raster/triangle/tiled.rs`, `raster::triangle` for its `mod.rs`.
fn module_of(relative: &Path) -> Vec<String> {
    let mut parts: Vec<String> = relative
        .with_extension("")
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts
}

/// The paths, from the crate root, that the code (not the comments) of
/// `module` names as `crate::a::b` or `super::a` (`super` is the module's
/// parent, for a `mod.rs` as for any other file).
fn paths_used(text: &str, module: &[String]) -> Vec<Vec<String>> {
    let parent = module[..module.len().saturating_sub(1)].to_vec();
    let mut used = Vec::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap();
        for (prefix, base) in [("crate::", Vec::new()), ("super::", parent.clone())] {
            let mut rest = code;
            while let Some(i) = rest.find(prefix) {
                let before = rest[..i].chars().last();
                let after = &rest[i + prefix.len()..];
                rest = after;
                // `$crate::` and the second `super::` of `super::super::`.
                if before
                    .is_some_and(|c| c.is_ascii_alphanumeric() || c == '_' || c == '$' || c == ':')
                {
                    continue;
                }
                let path: String = after
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '_' || *c == ':')
                    .collect();
                let mut full = base.clone();
                full.extend(path.split("::").filter(|s| !s.is_empty()).map(String::from));
                used.push(full);
            }
        }
    }
    used
}

/// Modules that use each other, directly or through others: every cycle
/// of the graph of uses between modules neither of which contains the
/// other (a module using its ancestors is how Rust nests).
fn cycles_between_modules() -> (usize, Vec<String>) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut modules: Vec<(Vec<String>, String)> = Vec::new();
    for file in &files {
        let relative = file.strip_prefix(&src).unwrap();
        if ["main", "cli", "lib"].contains(&room_of(relative).as_str()) {
            continue;
        }
        modules.push((module_of(relative), std::fs::read_to_string(file).unwrap()));
    }
    let names: Vec<&Vec<String>> = modules.iter().map(|m| &m.0).collect();
    // The longest module that is a prefix of `path`.
    let target = |path: &[String]| {
        (0..names.len())
            .filter(|&k| path.starts_with(names[k]))
            .max_by_key(|&k| names[k].len())
    };
    let mut edges = vec![std::collections::BTreeSet::new(); names.len()];
    for (i, (module, text)) in modules.iter().enumerate() {
        for path in paths_used(text, module) {
            if let Some(j) = target(&path) {
                if !module.starts_with(names[j]) && !names[j].starts_with(module) {
                    edges[i].insert(j);
                }
            }
        }
    }
    let uses = edges.iter().map(|e| e.len()).sum();
    // A cycle through i -> j exists when i is reachable back from j.
    let reaches = |from: usize, to: usize| {
        let mut seen = vec![false; names.len()];
        let mut todo = vec![from];
        while let Some(k) = todo.pop() {
            if k == to {
                return true;
            }
            if !std::mem::replace(&mut seen[k], true) {
                todo.extend(edges[k].iter().copied());
            }
        }
        false
    };
    let mut cycles = Vec::new();
    for i in 0..names.len() {
        for &j in &edges[i] {
            if reaches(j, i) {
                cycles.push(format!(
                    "{} uses {}, which leads back",
                    names[i].join("::"),
                    names[j].join("::")
                ));
            }
        }
    }
    (uses, cycles)
}

#[test]
fn no_two_modules_use_each_other() {
    let (uses, cycles) = cycles_between_modules();
    assert!(uses > 80, "only {uses} uses between modules were found");
    assert!(
        cycles.is_empty(),
        "modules in a cycle:\n{}",
        cycles.join("\n")
    );
}

/// Every file of `src/` is named in docs/architecture.md, by its path
/// within its room's folder in backquotes (`stage/merge.rs` for
/// `src/raster/stage/merge.rs`, `error.rs` for `src/error.rs`), so that
/// the map cannot drift from the code; a room's own `mod.rs` is its row.
#[test]
fn every_source_file_is_on_the_map() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let map = std::fs::read_to_string(root.join("docs/architecture.md")).unwrap();
    let src = root.join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut missing = Vec::new();
    for file in &files {
        let relative = file.strip_prefix(&src).unwrap();
        let mut parts: Vec<String> = relative
            .components()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect();
        if parts.len() > 1 {
            parts.remove(0); // the room's folder
        }
        let within_room = parts.join("/");
        if within_room == "mod.rs" {
            continue;
        }
        if !map.contains(&format!("`{within_room}`")) {
            missing.push(relative.display().to_string());
        }
    }
    assert!(files.len() > 100, "only {} files were found", files.len());
    missing.sort();
    assert!(
        missing.is_empty(),
        "files of src/ docs/architecture.md does not name (as `path/within/room.rs`):\n{}",
        missing.join("\n")
    );
}

/// Every suite of `tests/` is a row of docs/tests.md's table.
#[test]
fn every_test_suite_is_described() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let described = std::fs::read_to_string(root.join("docs/tests.md")).unwrap();
    let mut missing = Vec::new();
    let mut suites = 0;
    for entry in std::fs::read_dir(root.join("tests")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "rs") {
            suites += 1;
            let name = path.file_stem().unwrap().to_string_lossy().into_owned();
            if !described.contains(&format!("`{name}`")) {
                missing.push(name);
            }
        }
    }
    assert!(suites > 20, "only {suites} suites were found");
    missing.sort();
    assert!(
        missing.is_empty(),
        "suites docs/tests.md does not describe: {}",
        missing.join(", ")
    );
}
