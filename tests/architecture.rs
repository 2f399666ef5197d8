//! The crate's rooms depend only on the rooms above them (see the crate
//! page's map): the core (`raster`) on nothing but the shared error,
//! output and naming helpers; `geometry` on the core; `measure` on both;
//! `teaching` on those; `check` on those; `lab` on everything. A `use` or
//! path that reaches down the list (a cycle in the making) fails here,
//! naming the file and line.

use std::path::{Path, PathBuf};

/// The rooms in order: each may use those before it.
const ROOMS: [&str; 6] = ["raster", "geometry", "measure", "teaching", "check", "lab"];
/// Shared by every room, and using none.
const SHARED: [&str; 3] = ["error", "output", "names"];

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
