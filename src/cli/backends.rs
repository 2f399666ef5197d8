//! `rasterlab backends`: every back-end, one per line.

use rasterlab::raster::all_backends;
use rasterlab::Result;

/// Prints the registry as `NAME KIND DESCRIPTION` lines.
pub fn run() -> Result<()> {
    let listing: String = all_backends()
        .iter()
        .map(|b| format!("{} {} {}\n", b.name, b.kind, b.description))
        .collect();
    super::print::out(listing)
}
