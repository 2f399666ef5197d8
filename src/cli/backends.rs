//! `rasterlab backends`: every back-end, one per line.

use rasterlab::raster::{all_backends, polygon_backends};
use rasterlab::Result;

/// Prints the registry as `NAME KIND DESCRIPTION` lines.
pub fn run() -> Result<()> {
    let mut listing: String = all_backends()
        .iter()
        .map(|b| format!("{} {} {}\n", b.name, b.kind, b.description))
        .collect();
    for b in polygon_backends() {
        let d = b.descriptor();
        listing += &format!("{} polygon {}\n", d.name, d.description);
    }
    super::print::out(listing)
}
