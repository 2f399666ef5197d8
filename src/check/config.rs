//! A teacher's configuration of `rasterlab check`: the rule (or, for
//! lines, the convention) an assignment asks for, which way y grows, how
//! many cases of which seed, the time limit a case, and what each family
//! of cases is worth, read from a JSON file (`check --config FILE`).
//!
//! JSON, because the check's report, the schema it follows and
//! Gradescope's `results.json` are JSON already: a grader reads one
//! format and rasterlab needs no other parser. Every key is optional;
//! an unknown key, an unknown family or a weight that is not a number
//! from 0 to 1,000,000 is refused with what was expected. A family's
//! weight is the points it is worth in a grader's report, shared among
//! its cases; a family left out is worth one point a case, as without a
//! configuration; a weight of 0 leaves a family unscored but still
//! reported.
//!
//! ```
//! use rasterlab::check::{gradescope, run, CheckConfig, CheckRequest, SubjectSpec};
//!
//! let config = CheckConfig::from_json(
//!     r#"{ "rule": "inclusive", "cases": 20, "seed": 3, "weights": { "ties": 10, "zero-area": 0 } }"#,
//! )
//! .unwrap();
//! let mut request = CheckRequest::new(SubjectSpec::Backend("bbox".into()));
//! config.apply(&mut request).unwrap();
//! request.keep_going = true;
//! let results = gradescope(&run(&request).unwrap());
//! let ties = results["tests"].as_array().unwrap().iter().find(|t| t["name"] == "family ties").unwrap();
//! assert_eq!(ties["max_score"], 10.0);
//! ```

use super::case::Origin;
use super::generate::{EXACT_FAMILIES, LINE_FAMILIES, MESH_FAMILIES, PIXEL_INDEX_FAMILIES};
use super::image::ImageConfig;
use super::polygons::POLYGON_FAMILIES;
use super::request::{timeout_from_seconds, CheckRequest, ConventionChoice, Kind, RuleChoice};
use super::snapping::Snapping;
use crate::error::{Error, Result};
use crate::raster::polygon::WindingRule;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

/// What a configuration file may hold; every key optional.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckConfig {
    /// What the cases hold: `triangles`, `lines` or `polygons`.
    pub kind: Option<String>,
    /// Triangles: a fill rule, `watertight`, `crack-free` or `any`, as
    /// `--rule` takes it.
    pub rule: Option<String>,
    /// Lines: a convention, as `--convention` takes it.
    pub convention: Option<String>,
    /// Polygons: the fill rule, `even-odd` or `nonzero`, as `--fill`
    /// takes it.
    pub fill: Option<String>,
    /// Where the subject's origin is: `top-left` (y down) or
    /// `bottom-left` (y up), as `--origin` takes it.
    pub origin: Option<String>,
    /// How vertices are snapped before judging: `1/256` (the default),
    /// another power of two down to `1`, or `none`, as `--snap` takes it.
    pub snap: Option<String>,
    /// How many cases.
    pub cases: Option<u32>,
    /// The generator's seed.
    pub seed: Option<u64>,
    /// Seconds a program may take on one case.
    pub timeout: Option<f64>,
    /// Points per family, by the family's name.
    #[serde(default)]
    pub weights: BTreeMap<String, f64>,
    /// `check --image`: the thresholds and the tests (scenes, sizes,
    /// settings, each test's thresholds and weight); other checks ignore it.
    pub images: Option<ImageConfig>,
}

impl CheckConfig {
    /// Reads a configuration from JSON text.
    pub fn from_json(text: &str) -> Result<CheckConfig> {
        serde_json::from_str(text)
            .map_err(|e| Error::InvalidArgument(format!("the check's configuration: {e}")))
    }

    /// Reads a configuration file (`file: line: ...` on a mistake).
    pub fn read(path: &Path) -> Result<CheckConfig> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        serde_json::from_str(&text).map_err(|e| Error::Parse {
            path: path.to_path_buf(),
            line: Some(e.line()),
            message: e.to_string(),
        })
    }

    /// Sets what the configuration names in `request`, after checking
    /// every name and number in it.
    pub fn apply(&self, request: &mut CheckRequest) -> Result<()> {
        if let Some(k) = &self.kind {
            request.kind = Some(k.parse()?);
        }
        if let Some(r) = &self.rule {
            request.rule = Some(r.parse::<RuleChoice>()?);
        }
        if let Some(c) = &self.convention {
            request.convention = Some(c.parse::<ConventionChoice>()?);
        }
        if let Some(f) = &self.fill {
            request.fill = Some(f.parse::<WindingRule>()?);
        }
        if let Some(o) = &self.origin {
            request.origin = o.parse::<Origin>()?;
        }
        if let Some(s) = &self.snap {
            request.snapping = s.parse::<Snapping>()?;
        }
        if let Some(n) = self.cases {
            request.cases = n;
        }
        if let Some(s) = self.seed {
            request.seed = s;
        }
        if let Some(t) = self.timeout {
            request.timeout = timeout_from_seconds(t)?;
        }
        let kind = if request.kind == Some(Kind::Lines) || request.convention.is_some() {
            Kind::Lines
        } else if request.kind == Some(Kind::Polygons) || request.fill.is_some() {
            Kind::Polygons
        } else {
            Kind::Triangles
        };
        for (family, &points) in &self.weights {
            if !known_families(kind).contains(&family.as_str()) {
                return Err(Error::UnknownName {
                    what: "family",
                    name: family.clone(),
                    known: known_families(kind).join(", "),
                });
            }
            if !(points.is_finite() && (0.0..=1e6).contains(&points)) {
                return Err(Error::InvalidArgument(format!(
                    "the weight of family {family} must be a number from 0 to 1000000, not {points}"
                )));
            }
        }
        request.weights = self.weights.iter().map(|(f, &w)| (f.clone(), w)).collect();
        Ok(())
    }
}

/// The families a weight may name: those of triangles, of lines or of
/// polygons.
fn known_families(kind: Kind) -> Vec<&'static str> {
    let mut all: Vec<&'static str> = match kind {
        Kind::Lines => LINE_FAMILIES
            .iter()
            .chain(PIXEL_INDEX_FAMILIES.iter())
            .copied()
            .collect(),
        Kind::Polygons => POLYGON_FAMILIES.to_vec(),
        Kind::Triangles => EXACT_FAMILIES
            .iter()
            .chain(MESH_FAMILIES.iter())
            .copied()
            .collect(),
    };
    let mut seen = std::collections::BTreeSet::new();
    all.retain(|f| seen.insert(*f));
    all
}
