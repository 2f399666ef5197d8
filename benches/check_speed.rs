//! How long `rasterlab check` takes a course: the program under test
//! started once per case against once for the whole check
//! (`--persistent`), on the checks a student and a teacher run.
//!
//! ```text
//! cargo bench --bench check_speed                     # 3 rounds
//! cargo bench --bench check_speed -- --rounds 5 --survey
//! ```
//!
//! Each round runs every check once, in the same order (so that the
//! protocols share the machine's state alike); the table gives each
//! check's median wall time over the rounds, its range, and the
//! per-case time over the persistent one. `--survey` adds
//! `sh examples/adapters/survey.sh` (every subject of the check guide's
//! survey, minutes; it needs the Python packages and Mesa of `.ci/run`).
//! A check whose language is missing (`python3`, `node`, `g++`) is
//! listed as not run.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Instant;

/// One timed check: its name and `rasterlab check` arguments.
struct Timed {
    name: &'static str,
    needs: &'static str,
    args: Vec<String>,
}

fn words(s: &[&str]) -> Vec<String> {
    s.iter().map(|w| w.to_string()).collect()
}

fn has(tool: &str) -> bool {
    Command::new(tool)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let rounds: usize = args
        .iter()
        .position(|a| a == "--rounds")
        .and_then(|i| args.get(i + 1))
        .and_then(|r| r.parse().ok())
        .unwrap_or(3);
    let survey = args.iter().any(|a| a == "--survey");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = tempfile::tempdir().expect("a temporary folder");
    let cpp = out.path().join("rasterizer");
    let built = has("g++")
        && Command::new("g++")
            .args(["-O2", "-std=c++17", "-o"])
            .arg(&cpp)
            .arg(root.join("examples/starters/cpp/rasterizer.cpp"))
            .status()
            .is_ok_and(|s| s.success());
    let student = "python3 examples/student/rasterizer.py";
    let starter = "python3 examples/starters/python/rasterizer.py";
    let checks = [
        Timed {
            name: "student check to its counterexample, per case",
            needs: "python3",
            args: words(&[
                "--rule",
                "watertight",
                "--exec",
                &format!("{student} {{input}} {{width}} {{height}}"),
            ]),
        },
        Timed {
            name: "student check to its counterexample, persistent",
            needs: "python3",
            args: words(&["--rule", "watertight", "--persistent", "--exec", student]),
        },
        Timed {
            name: "Python starter, 150 cases --keep-going, per case",
            needs: "python3",
            args: words(&[
                "--keep-going",
                "--exec",
                &format!("{starter} {{input}} {{width}} {{height}}"),
            ]),
        },
        Timed {
            name: "Python starter, 150 cases --keep-going, persistent",
            needs: "python3",
            args: words(&["--keep-going", "--persistent", "--exec", starter]),
        },
        Timed {
            name: "JavaScript starter, 150 cases --keep-going, persistent",
            needs: "node",
            args: words(&[
                "--keep-going",
                "--persistent",
                "--exec",
                "node examples/starters/js/rasterizer.js",
            ]),
        },
        Timed {
            name: "C++ starter, 150 cases --keep-going, persistent",
            needs: if built { "g++" } else { "a C++ build" },
            args: words(&[
                "--keep-going",
                "--persistent",
                "--exec",
                cpp.to_str().expect("a UTF-8 path"),
            ]),
        },
    ];
    let runnable: Vec<&Timed> = checks
        .iter()
        .filter(|c| has(c.needs) || (c.needs == "g++" && built))
        .collect();
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); runnable.len()];
    let mut survey_times = Vec::new();
    for round in 0..rounds {
        eprintln!("round {} of {rounds}", round + 1);
        for (i, c) in runnable.iter().enumerate() {
            let start = Instant::now();
            let status = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
                .current_dir(root)
                .arg("check")
                .args(&c.args)
                .arg("--out")
                .arg(out.path().join("check"))
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .status()
                .expect("rasterlab runs");
            times[i].push(start.elapsed().as_secs_f64());
            assert!(
                matches!(status.code(), Some(0 | 1)),
                "{}: exit {status}",
                c.name
            );
        }
        if survey {
            let start = Instant::now();
            let status = Command::new("sh")
                .current_dir(root)
                .arg("examples/adapters/survey.sh")
                .status()
                .expect("sh runs");
            survey_times.push(start.elapsed().as_secs_f64());
            assert!(status.success(), "the survey: {status}");
        }
    }
    let median = |v: &[f64]| {
        let mut v = v.to_vec();
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    println!("\n{:<56} {:>10} {:>17}", "check", "median s", "range s");
    for (c, t) in runnable.iter().zip(&times) {
        let (lo, hi) = t
            .iter()
            .fold((f64::MAX, 0f64), |(lo, hi), &x| (lo.min(x), hi.max(x)));
        println!(
            "{:<56} {:>10.2} {:>8.2} - {:<6.2}",
            c.name,
            median(t),
            lo,
            hi
        );
    }
    for c in checks
        .iter()
        .filter(|c| !runnable.iter().any(|r| r.name == c.name))
    {
        println!("{:<56} not run: {} is missing", c.name, c.needs);
    }
    if !survey_times.is_empty() {
        println!(
            "{:<56} {:>10.2}",
            "the survey (survey.sh, every subject)",
            median(&survey_times)
        );
    }
    let find = |name: &str| {
        runnable
            .iter()
            .position(|c| c.name == name)
            .map(|i| median(&times[i]))
    };
    for (what, once, persistent) in [
        (
            "student check",
            "student check to its counterexample, per case",
            "student check to its counterexample, persistent",
        ),
        (
            "Python starter",
            "Python starter, 150 cases --keep-going, per case",
            "Python starter, 150 cases --keep-going, persistent",
        ),
    ] {
        if let (Some(a), Some(b)) = (find(once), find(persistent)) {
            println!("{what}: per case / persistent = {:.1}x", a / b);
        }
    }
    println!("{rounds} round(s); medians over the rounds, each check run once a round in the order above");
}
