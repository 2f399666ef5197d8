//! Records the commit the code is built from, for the benchmarks'
//! context: `RASTERLAB_COMMIT` if set, else `git describe --always`, else
//! nothing (the code then says `unknown`). Runs again when the checkout's
//! HEAD moves.

use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    let text = String::from_utf8(out.stdout).ok()?.trim().to_string();
    (out.status.success() && !text.is_empty()).then_some(text)
}

fn main() {
    println!("cargo:rerun-if-env-changed=RASTERLAB_COMMIT");
    let commit = std::env::var("RASTERLAB_COMMIT")
        .ok()
        .or_else(|| git(&["describe", "--always", "--abbrev=7"]));
    if let Some(commit) = commit {
        println!("cargo:rustc-env=RASTERLAB_COMMIT={commit}");
    }
    // HEAD, the branch it names and the packed references: the files that
    // change when a commit is made or checked out (those that exist, so
    // that a missing one does not make every build run this again).
    let watched = [
        git(&["rev-parse", "--git-path", "HEAD"]),
        git(&["rev-parse", "--symbolic-full-name", "HEAD"])
            .and_then(|branch| git(&["rev-parse", "--git-path", &branch])),
        git(&["rev-parse", "--git-path", "packed-refs"]),
    ];
    for path in watched.into_iter().flatten() {
        if std::path::Path::new(&path).exists() {
            println!("cargo:rerun-if-changed={path}");
        }
    }
}
