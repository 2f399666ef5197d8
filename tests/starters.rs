//! The starters of `examples/starters/` (Python, C++, JavaScript) under
//! `rasterlab check`, in both protocols:
//!
//! - each as shipped (the course's naive loop and direct evaluation) gets
//!   a verdict and a named cause, not a broken-program error;
//! - each helper, with a correct rasterizer written here in its language
//!   (the top-left rule on 1/256 px vertices in integers, and integer
//!   Bresenham for pixel-index lines), passes: the protocol in each
//!   language stays right.
//!
//! A language whose tool (`python3`, `g++`, `node`) is missing is reported
//! as not run, or fails under `RASTERLAB_REQUIRE_STARTERS=1`, which
//! `.ci/run` sets after installing them.

mod common;

use common::{part_missing, rasterlab};
use std::path::{Path, PathBuf};
use std::process::Command;

const REQUIRED: &str = "RASTERLAB_REQUIRE_STARTERS";

fn starters() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/starters")
}

fn has(tool: &str) -> bool {
    Command::new(tool)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// `rasterlab check` with `args`, in `dir`, writing its files in `out`:
/// the exit code and standard output and error together.
fn check(dir: &Path, out: &Path, args: &[&str]) -> (Option<i32>, String) {
    let mut all = vec!["check", "--out", out.to_str().unwrap()];
    all.extend_from_slice(args);
    let o = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .current_dir(dir)
        .args(&all)
        .output()
        .expect("the binary runs");
    (
        o.status.code(),
        format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        ),
    )
}

/// One language: how to build it (if at all) and the commands of both
/// protocols, from the folder holding its files.
struct Language {
    name: &'static str,
    tool: &'static str,
    folder: &'static str,
    helper: &'static str,
    student: &'static str,
    /// The student's file, correct.
    correct: &'static str,
    /// The persistent command and the per-case one.
    commands: [&'static str; 2],
}

const PYTHON_CORRECT: &str = r#"
from rasterlab_check import run

def snap(v):
    return round(v * 256)  # ties to even

def e(p, q, x, y):
    return (q[1] - p[1]) * x + (p[0] - q[0]) * y + q[0] * p[1] - p[0] * q[1]

def rasterize_triangle(a, b, c, width, height):
    a, b, c = [(snap(x), snap(y)) for x, y in (a, b, c)]
    area = e(a, b, c[0], c[1])
    if area == 0:
        return []
    if area < 0:
        b, c = c, b
    edges = [(b, c), (c, a), (a, b)]
    bias = [0 if q[1] > p[1] or (q[1] == p[1] and q[0] < p[0]) else -1 for p, q in edges]
    xs, ys = [a[0], b[0], c[0]], [a[1], b[1], c[1]]
    out = []
    for y in range(max(0, min(ys) // 256), min(height - 1, max(ys) // 256) + 1):
        for x in range(max(0, min(xs) // 256), min(width - 1, max(xs) // 256) + 1):
            X, Y = 256 * x + 128, 256 * y + 128
            if all(e(p, q, X, Y) + k >= 0 for (p, q), k in zip(edges, bias)):
                out.append((x, y))
    return out

def rasterize_segment(p0, p1, width, height):
    x, y = round(p0[0]), round(p0[1])
    x1, y1 = round(p1[0]), round(p1[1])
    dx, dy = abs(x1 - x), abs(y1 - y)
    sx, sy = (1 if x1 > x else -1), (1 if y1 > y else -1)
    steep = dy > dx
    if steep:
        x, y, x1, y1, dx, dy, sx, sy = y, x, y1, x1, dy, dx, sy, sx
    d = 2 * dy - dx
    out = []
    for _ in range(dx + 1):
        px, py = (y, x) if steep else (x, y)
        if 0 <= px < width and 0 <= py < height:
            out.append((px, py))
        if d > 0:
            y += sy
            d -= 2 * dx
        d += 2 * dy
        x += sx
    return out

run(rasterize_triangle, rasterize_segment)
"#;

const CPP_CORRECT: &str = r#"
#include <cmath>
#include <utility>
#include "rasterlab_check.hpp"
using rasterlab_check::Pixel;
using rasterlab_check::Point;
typedef long long i64;
struct P { i64 x, y; };
static P snap(Point p) { return {(i64)std::nearbyint(p.x * 256), (i64)std::nearbyint(p.y * 256)}; }
static i64 e(P p, P q, i64 x, i64 y) { return (q.y - p.y) * x + (p.x - q.x) * y + q.x * p.y - p.x * q.y; }
static i64 fdiv(i64 a, i64 b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
std::vector<Pixel> triangle(Point pa, Point pb, Point pc, int w, int h) {
    P a = snap(pa), b = snap(pb), c = snap(pc);
    std::vector<Pixel> out;
    i64 area = e(a, b, c.x, c.y);
    if (area == 0) return out;
    if (area < 0) std::swap(b, c);
    P edges[3][2] = {{b, c}, {c, a}, {a, b}};
    i64 bias[3];
    for (int i = 0; i < 3; ++i) {
        P p = edges[i][0], q = edges[i][1];
        bias[i] = (q.y > p.y || (q.y == p.y && q.x < p.x)) ? 0 : -1;
    }
    i64 x0 = std::max<i64>(0, fdiv(std::min({a.x, b.x, c.x}), 256));
    i64 x1 = std::min<i64>(w - 1, fdiv(std::max({a.x, b.x, c.x}), 256));
    i64 y0 = std::max<i64>(0, fdiv(std::min({a.y, b.y, c.y}), 256));
    i64 y1 = std::min<i64>(h - 1, fdiv(std::max({a.y, b.y, c.y}), 256));
    for (i64 y = y0; y <= y1; ++y)
        for (i64 x = x0; x <= x1; ++x) {
            bool in = true;
            for (int i = 0; i < 3; ++i)
                in = in && e(edges[i][0], edges[i][1], 256 * x + 128, 256 * y + 128) + bias[i] >= 0;
            if (in) out.push_back({x, y});
        }
    return out;
}
std::vector<Pixel> segment(Point p0, Point p1, int w, int h) {
    i64 x = std::llround(p0.x), y = std::llround(p0.y), x1 = std::llround(p1.x), y1 = std::llround(p1.y);
    i64 dx = std::llabs(x1 - x), dy = std::llabs(y1 - y), sx = x1 > x ? 1 : -1, sy = y1 > y ? 1 : -1;
    bool steep = dy > dx;
    if (steep) { std::swap(x, y); std::swap(x1, y1); std::swap(dx, dy); std::swap(sx, sy); }
    i64 d = 2 * dy - dx;
    std::vector<Pixel> out;
    for (i64 k = 0; k <= dx; ++k) {
        i64 px = steep ? y : x, py = steep ? x : y;
        if (px >= 0 && px < w && py >= 0 && py < h) out.push_back({px, py});
        if (d > 0) { y += sy; d -= 2 * dx; }
        d += 2 * dy;
        x += sx;
    }
    return out;
}
int main(int argc, char** argv) { return rasterlab_check::run(argc, argv, triangle, segment); }
"#;

const JS_CORRECT: &str = r#"
"use strict";
const { run } = require("./rasterlab_check");
function snap(v) {
  const s = v * 256, r = Math.round(s);
  return Math.abs(s % 1) === 0.5 ? 2 * Math.round(s / 2) : r; // ties to even
}
const e = (p, q, x, y) => (q[1] - p[1]) * x + (p[0] - q[0]) * y + q[0] * p[1] - p[0] * q[1];
function rasterizeTriangle(pa, pb, pc, width, height) {
  let [a, b, c] = [pa, pb, pc].map((p) => p.map(snap));
  const area = e(a, b, c[0], c[1]);
  if (area === 0) return [];
  if (area < 0) [b, c] = [c, b];
  const edges = [[b, c], [c, a], [a, b]];
  const bias = edges.map(([p, q]) => (q[1] > p[1] || (q[1] === p[1] && q[0] < p[0]) ? 0 : -1));
  const xs = [a[0], b[0], c[0]], ys = [a[1], b[1], c[1]];
  const out = [];
  for (let y = Math.max(0, Math.floor(Math.min(...ys) / 256)); y <= Math.min(height - 1, Math.floor(Math.max(...ys) / 256)); y++)
    for (let x = Math.max(0, Math.floor(Math.min(...xs) / 256)); x <= Math.min(width - 1, Math.floor(Math.max(...xs) / 256)); x++)
      if (edges.every(([p, q], i) => e(p, q, 256 * x + 128, 256 * y + 128) + bias[i] >= 0)) out.push([x, y]);
  return out;
}
function rasterizeSegment(p0, p1, width, height) {
  let [x, y] = p0.map(Math.round), [x1, y1] = p1.map(Math.round);
  let dx = Math.abs(x1 - x), dy = Math.abs(y1 - y), sx = x1 > x ? 1 : -1, sy = y1 > y ? 1 : -1;
  const steep = dy > dx;
  if (steep) [x, y, x1, y1, dx, dy, sx, sy] = [y, x, y1, x1, dy, dx, sy, sx];
  let d = 2 * dy - dx;
  const out = [];
  for (let k = 0; k <= dx; k++) {
    const [px, py] = steep ? [y, x] : [x, y];
    if (px >= 0 && px < width && py >= 0 && py < height) out.push([px, py]);
    if (d > 0) { y += sy; d -= 2 * dx; }
    d += 2 * dy;
    x += sx;
  }
  return out;
}
run(rasterizeTriangle, rasterizeSegment);
"#;

const LANGUAGES: [Language; 3] = [
    Language {
        name: "Python",
        tool: "python3",
        folder: "python",
        helper: "rasterlab_check.py",
        student: "rasterizer.py",
        correct: PYTHON_CORRECT,
        commands: [
            "python3 rasterizer.py",
            "python3 rasterizer.py {input} {width} {height}",
        ],
    },
    Language {
        name: "C++",
        tool: "g++",
        folder: "cpp",
        helper: "rasterlab_check.hpp",
        student: "rasterizer.cpp",
        correct: CPP_CORRECT,
        commands: ["./rasterizer", "./rasterizer {input} {width} {height}"],
    },
    Language {
        name: "JavaScript",
        tool: "node",
        folder: "js",
        helper: "rasterlab_check.js",
        student: "rasterizer.js",
        correct: JS_CORRECT,
        commands: [
            "node rasterizer.js",
            "node rasterizer.js {input} {width} {height}",
        ],
    },
];

/// Copies the helper and writes `student` beside it in a fresh folder,
/// built when the language is compiled.
fn project(language: &Language, student: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let from = starters().join(language.folder);
    std::fs::copy(from.join(language.helper), dir.path().join(language.helper)).unwrap();
    std::fs::write(dir.path().join(language.student), student).unwrap();
    if language.tool == "g++" {
        let built = Command::new("g++")
            .current_dir(dir.path())
            .args(["-O2", "-std=c++17", "-Wall", "-Wextra", "-Werror"])
            .args(["-o", "rasterizer", language.student])
            .output()
            .unwrap();
        assert!(
            built.status.success(),
            "{}",
            String::from_utf8_lossy(&built.stderr)
        );
    }
    dir
}

/// The languages whose tool is here; the others are reported.
fn available(test: &str) -> Vec<&'static Language> {
    LANGUAGES
        .iter()
        .filter(|l| {
            let here = has(l.tool);
            if !here {
                part_missing(&format!("{test} ({})", l.name), l.tool, REQUIRED);
            }
            here
        })
        .collect()
}

#[test]
fn each_starter_as_shipped_gets_a_verdict_and_a_named_cause() {
    for language in available("each_starter_as_shipped_gets_a_verdict_and_a_named_cause") {
        let shipped =
            std::fs::read_to_string(starters().join(language.folder).join(language.student))
                .unwrap();
        let dir = project(language, &shipped);
        let out = dir.path().join("out");
        for (args, cause) in [
            (vec![], "cause: ties decided by the inclusive rule"),
            (
                vec![
                    "--kind",
                    "lines",
                    "--convention",
                    "pixel-index-left-to-right",
                ],
                "cause: a steep line drawn one pixel per column",
            ),
        ] {
            // The persistent protocol: the per-case one is the next
            // test's, on passing cases (a failure's shrinking would start
            // the program a few hundred times).
            let mut all = args.clone();
            all.extend(["--persistent", "--exec", language.commands[0]]);
            let (code, text) = check(dir.path(), &out, &all);
            assert_eq!(code, Some(1), "{}: {all:?}: {text}", language.name);
            assert!(
                text.contains(cause),
                "{}: {all:?}: no `{cause}` in\n{text}",
                language.name
            );
        }
    }
}

#[test]
fn each_helper_passes_a_correct_rasterizer_in_both_protocols() {
    for language in available("each_helper_passes_a_correct_rasterizer_in_both_protocols") {
        let dir = project(language, language.correct);
        let out = dir.path().join("out");
        for args in [
            vec!["--keep-going"],
            vec![
                "--keep-going",
                "--kind",
                "lines",
                "--convention",
                "pixel-index",
            ],
        ] {
            // Every case in the persistent protocol; fewer in the
            // per-case one, which starts the program each time.
            for (i, command) in language.commands.iter().enumerate() {
                let mut all = args.clone();
                let cases = if i == 0 { "150" } else { "24" };
                if i == 0 {
                    all.push("--persistent");
                }
                all.extend(["--cases", cases, "--exec", command]);
                let (code, text) = check(dir.path(), &out, &all);
                assert_eq!(code, Some(0), "{}: {all:?}: {text}", language.name);
                assert!(
                    text.contains(&format!("{cases}/{cases}")),
                    "{}: {text}",
                    language.name
                );
            }
        }
    }
}

#[test]
fn a_persistent_command_with_per_case_placeholders_is_refused() {
    let out = rasterlab(&["check", "--persistent", "--exec", "python3 x.py {input}"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("{input} in a --persistent command"));
    let out = rasterlab(&["check", "--persistent", "--backend", "bbox"]);
    assert_eq!(out.status.code(), Some(2));
}

/// A persistent subject in `sh` (which starts in a millisecond, where
/// Python takes a tenth of a second: shrinking a program that dies
/// restarts it a hundred times): it counts a case's primitives in `$n`
/// and, at the case's `end`, runs `on_end`.
fn persistent_sh(on_end: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let program = format!(
        "n=0\nwhile IFS= read -r line; do\n  case \"$line\" in\n    end) {on_end}; n=0 ;;\n    '#'*) ;;\n    *) n=$((n + 1)) ;;\n  esac\ndone\n"
    );
    std::fs::write(dir.path().join("subject.sh"), program).unwrap();
    dir
}

#[test]
fn a_persistent_program_that_breaks_is_reported_restarted_and_shrunk() {
    for (on_end, message) in [
        // Dies on any case of more than one primitive: the shrinking
        // reruns it on smaller cases, each after a restart.
        (
            "if [ $n -gt 1 ]; then exit 3; fi; echo end",
            "exited before its answer's `end` line, exit status: 3",
        ),
        // Reports that it cannot draw.
        (
            "if [ $n -gt 1 ]; then echo 'error too many triangles for me'; else echo end; fi",
            "too many triangles for me",
        ),
        // Hangs.
        (
            "if [ $n -gt 1 ]; then sleep 60; fi; echo end",
            "longer than 0.5 s",
        ),
        // Answers one case, then exits: a per-case program.
        (
            "echo end; exit 0",
            "after answering 1 case(s): under --persistent a program reads case after case",
        ),
        // Prints something that is not a fragment.
        ("echo hello world; echo end", "is not `x y id`"),
    ] {
        let dir = persistent_sh(on_end);
        let out = dir.path().join("out");
        let (code, text) = check(
            dir.path(),
            &out,
            &[
                "--persistent",
                "--exec",
                "sh subject.sh",
                "--timeout",
                "0.5",
                "--cases",
                "20",
                "--keep-going",
            ],
        );
        assert!(
            text.contains(message),
            "{on_end}: no `{message}` in\n{text}"
        );
        if on_end.contains("hello") {
            // Nonsense on every input, the simplest included: broken.
            assert_eq!(code, Some(2), "{on_end}: {text}");
            continue;
        }
        // Under --keep-going a case without an answer costs that case:
        // the others are scored, and the program restarted for them.
        assert_eq!(code, Some(1), "{on_end}: {text}");
        assert!(text.contains("no answer on "), "{on_end}: {text}");
        if on_end.contains("exit 3") || on_end.contains("error") {
            // Shrunk, through restarts, to the smallest case that breaks it.
            assert!(
                text.contains("to 2 primitive(s) on a 1x1 target: no answer"),
                "{on_end}: {text}"
            );
        }
    }
}
