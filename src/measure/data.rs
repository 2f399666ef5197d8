//! Where the benchmarks find the Stanford models that are not bundled.
//!
//! `assets/` bundles the smallest dragon decimation (`dragon_vrip_res4`,
//! 11,102 triangles). The full dragon (`dragon_vrip`, 871,414 triangles)
//! and the larger decimation `dragon_vrip_res2` (202,520) come from the
//! Stanford 3D Scanning Repository (Stanford University Computer Graphics
//! Laboratory). The benchmarks look for them in the folder named by the
//! environment variable `RASTERLAB_DATA`, or else in `../shared/data`
//! beside the crate; a model that is not there is a [`Skipped`] row,
//! printed with its reason, never a silent gap.
//!
//! ```
//! use rasterlab::measure::{find_in, FULL_DRAGON};
//! let missing = find_in(std::path::Path::new("/no/such/folder"), FULL_DRAGON);
//! let reason = missing.unwrap_err().to_string();
//! assert!(reason.starts_with("skipped: dragon_vrip.ply.gz not found in /no/such/folder"));
//! ```

use std::fmt;
use std::path::{Path, PathBuf};

/// The environment variable naming the folder of the Stanford models.
pub const DATA_ENV: &str = "RASTERLAB_DATA";

/// The full Stanford dragon's file name.
pub const FULL_DRAGON: &str = "dragon_vrip.ply.gz";

/// The second-largest dragon decimation's file name.
pub const DRAGON_RES2: &str = "dragon_vrip_res2.ply.gz";

/// A row that could not be measured, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Skipped {
    /// Why the row is missing.
    pub reason: String,
}

impl fmt::Display for Skipped {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "skipped: {}", self.reason)
    }
}

impl std::error::Error for Skipped {}

/// The folder the models are looked for in: `$RASTERLAB_DATA`, or else
/// `../shared/data` beside the crate.
pub fn data_dir() -> PathBuf {
    std::env::var_os(DATA_ENV).map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data"),
        PathBuf::from,
    )
}

/// The model `file` in [`data_dir`].
pub fn find(file: &str) -> Result<PathBuf, Skipped> {
    find_in(&data_dir(), file)
}

/// The model `file` in `dir`, or a [`Skipped`] saying where it was looked
/// for and where it comes from.
pub fn find_in(dir: &Path, file: &str) -> Result<PathBuf, Skipped> {
    let path = dir.join(file);
    if path.is_file() {
        Ok(path)
    } else {
        Err(Skipped {
            reason: format!(
                "{file} not found in {}; it is not bundled: get it from the Stanford 3D \
                 Scanning Repository and set {DATA_ENV} to its folder",
                dir.display()
            ),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_model_is_a_skipped_row_that_says_where_to_get_it() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("no-data");
        let skipped = find_in(&dir, DRAGON_RES2).unwrap_err();
        let text = skipped.to_string();
        assert_eq!(
            text,
            format!(
                "skipped: dragon_vrip_res2.ply.gz not found in {}; it is not bundled: get it \
                 from the Stanford 3D Scanning Repository and set RASTERLAB_DATA to its folder",
                dir.display()
            )
        );
        let bundled = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
        assert_eq!(
            find_in(&bundled, "dragon_vrip_res4.ply.gz"),
            Ok(bundled.join("dragon_vrip_res4.ply.gz"))
        );
    }
}
