//! Presets: the conventions of well-known assignments, bundled under a
//! name that says what they are (`check --preset NAME`).
//!
//! A preset sets what a teacher's configuration would (the kind, the rule
//! or line convention, the origin and the snapping) and nothing else: a
//! configuration file (`--config`) and the command line's own options win
//! over it. docs/check.md says which course grades in which.
//!
//! ```
//! use rasterlab::check::{preset, CheckRequest, Origin, Snapping, SubjectSpec};
//! let mut request = CheckRequest::new(SubjectSpec::Backend("bbox".into()));
//! preset("opengl-window")?.config.apply(&mut request)?;
//! assert_eq!(request.origin, Origin::BottomLeft);
//! assert_eq!(request.snapping, Snapping::AsGiven);
//! assert!(preset("cs184").is_err());
//! # Ok::<(), rasterlab::Error>(())
//! ```

use super::config::CheckConfig;
use crate::error::{Error, Result};

/// A named set of conventions.
#[derive(Clone, Debug)]
pub struct Preset {
    /// The name `--preset` takes.
    pub name: &'static str,
    /// What it is, in a line.
    pub what: &'static str,
    /// The assignments that grade in it.
    pub courses: &'static str,
    /// What it sets.
    pub config: CheckConfig,
}

fn config(
    kind: &str,
    rule: Option<&str>,
    convention: Option<&str>,
    origin: &str,
    snap: &str,
) -> CheckConfig {
    CheckConfig {
        kind: Some(kind.into()),
        rule: rule.map(Into::into),
        convention: convention.map(Into::into),
        origin: Some(origin.into()),
        snap: Some(snap.into()),
        ..CheckConfig::default()
    }
}

/// Every preset.
pub fn presets() -> Vec<Preset> {
    vec![
        Preset {
            name: "direct3d",
            what: "triangles, y down, vertices snapped to 1/256 px, the top-left rule (the default)",
            courses: "Direct3D and Vulkan hardware; courses that teach the fixed-point rule",
            config: config("triangles", Some("top-left"), None, "top-left", "1/256"),
        },
        Preset {
            name: "opengl-window",
            what: "triangles, y up from the lower-left corner, nothing snapped, the top-left rule as the picture shows it",
            courses: "CMU Scotty3D A1 (rasterize_triangle; window coordinates with y up, floating point)",
            config: config("triangles", Some("top-left"), None, "bottom-left", "none"),
        },
        Preset {
            name: "inclusive-float",
            what: "triangles, y down, nothing snapped, a sample on an edge covered (the inclusive rule)",
            courses: "Berkeley CS184 HW1 and Stanford CS248 A1 (the top-left rule encouraged, not required)",
            config: config("triangles", Some("inclusive"), None, "top-left", "none"),
        },
        Preset {
            name: "opengl-window-lines",
            what: "lines, y up from the lower-left corner, nothing snapped, the diamond-exit rule with ties settled by moving the ends by (e, e^2)",
            courses: "CMU Scotty3D A1 (rasterize_line)",
            config: config("lines", None, Some("diamond-nudged"), "bottom-left", "none"),
        },
    ]
}

/// The preset called `name`.
pub fn preset(name: &str) -> Result<Preset> {
    presets()
        .into_iter()
        .find(|p| p.name == name)
        .ok_or_else(|| {
            let known: Vec<&str> = presets().iter().map(|p| p.name).collect();
            Error::InvalidArgument(format!(
                "unknown preset `{name}`: expected one of {}",
                known.join(", ")
            ))
        })
}
