//! The grid pictures' property as a function of its input, shared by
//! the property test (`tests/pictures.rs`) and the named regression tests
//! of the cases it shrank to (`tests/regressions.rs`).
#![allow(dead_code)]

use crate::common::SIZE;
use proptest::prelude::*;
use rasterlab::geometry::setup_triangles;
use rasterlab::raster::triangle::WalkStep;
use rasterlab::raster::{triangle_backends, FillRule, FixedPoint, FragmentList, PixelRect};
use rasterlab::teaching::{is_fragment_green, GridPicture, TESTED_OUTSIDE};

/// The cell colour at an offset inside each cell of a PNG drawn at `zoom`
/// (clear of the borders and the centre dot; the outlines, which may cross
/// that point, are left out).
pub fn png_cells(picture: &GridPicture, zoom: u32) -> Vec<[u8; 3]> {
    let cells_only = GridPicture {
        outlines: Vec::new(),
        segments: Vec::new(),
        ..picture.clone()
    };
    let png = cells_only.to_png(zoom).unwrap();
    let mut cells = Vec::new();
    for y in 0..picture.height {
        for x in 0..picture.width {
            cells.push(png.get_pixel(x * zoom + 3, y * zoom + 3).0);
        }
    }
    cells
}

/// One triangle, every back-end, under the `rule_index`-th of top-left,
/// bottom-right, offscreen-point, inclusive and exclusive: as many green
/// cells as fragments, red cells exactly where a test failed, and the PNG
/// shows the same cells.
pub fn green_cells_are_the_fragments_and_red_cells_the_failed_tests(
    t: [FixedPoint; 3],
    rule_index: usize,
) -> Result<(), TestCaseError> {
    let rule = [
        FillRule::TopLeft,
        FillRule::BottomRight,
        FillRule::OffscreenPoint,
        FillRule::Inclusive,
        FillRule::Exclusive,
    ][rule_index];
    let setups = setup_triangles(&[t], rule);
    for backend in triangle_backends() {
        let picture = GridPicture::of_snapped_triangles(*backend, &[t], rule, SIZE, SIZE).unwrap();
        let grid = PixelRect::of_target(SIZE, SIZE);
        let mut list = FragmentList::default();
        let work = backend.rasterize(&setups, grid, &mut list);
        // The samples the walk tested, as its recording lists them.
        let mut tested = vec![false; (SIZE * SIZE) as usize];
        let mut sample_steps = 0u64;
        for t in &setups {
            for step in backend.record(t, grid, &mut FragmentList::default()).0 {
                if let WalkStep::Sample { x, y, .. } = step {
                    sample_steps += 1;
                    tested[(y * i64::from(SIZE) + x) as usize] = true;
                }
            }
        }
        let mut inside = vec![false; (SIZE * SIZE) as usize];
        for f in &list.triangles {
            inside[(f.y * SIZE + f.x) as usize] = true;
        }
        let failed = (0..inside.len())
            .filter(|&i| tested[i] && !inside[i])
            .count();
        prop_assert_eq!(
            picture.inside_cells() as u64,
            work.fragments,
            "{}",
            backend.name()
        );
        prop_assert_eq!(picture.outside_cells(), failed, "{}", backend.name());
        // Every back-end tests each sample at most once, and records every
        // test it counts: as many tested cells as samples counted.
        prop_assert_eq!(sample_steps, work.samples_tested, "{}", backend.name());
        prop_assert_eq!(
            tested.iter().filter(|&&b| b).count() as u64,
            work.samples_tested,
            "{}",
            backend.name()
        );
        match backend.name() {
            "naive" if !setups.is_empty() => prop_assert_eq!(
                picture.inside_cells() + picture.outside_cells(),
                (SIZE * SIZE) as usize
            ),
            "bbox" | "incremental" => prop_assert_eq!(
                (picture.inside_cells() + picture.outside_cells()) as u64,
                work.samples_tested
            ),
            "scanline" => prop_assert_eq!(picture.outside_cells(), 0),
            _ => {}
        }
        let png = png_cells(&picture, 12);
        prop_assert_eq!(
            png.iter().filter(|&&c| is_fragment_green(c)).count() as u64,
            work.fragments
        );
        prop_assert_eq!(png.iter().filter(|&&c| c == TESTED_OUTSIDE).count(), failed);
    }
    Ok(())
}
