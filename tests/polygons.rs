//! Polygons filled directly by the edge table, against triangulation and
//! against the exact winding-number oracle: on simple polygons with holes
//! its pixels are the union of spade's triangles' top-left fragments, each
//! pixel once; on rings that cross, every pixel centre agrees with the
//! winding number under both rules; polygons sharing edges leave no gap
//! and draw no pixel twice.

mod common;

use common::*;
use glam::Vec4;
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use rasterlab::geometry::Scene2D;
use rasterlab::geometry::{Outline, Polygon};
use rasterlab::raster::polygon::{edge_table::EdgeTable, PolygonRasterizer, WindingRule};
use rasterlab::raster::triangle::scanline::Scanline;
use rasterlab::raster::{
    polygon_backends, FillRule, FixedPoint, Flat, FragmentList, FragmentStage, RenderTarget,
    ShadedVertex, TriangleData,
};

/// How many times each pixel of the target each back-end fills `outlines`
/// (each with its index as id) under `rule`, one count per pixel.
fn filled_counts(
    backend: &dyn PolygonRasterizer,
    outlines: &[Outline],
    rule: WindingRule,
) -> Vec<u32> {
    let setups: Vec<_> = outlines
        .iter()
        .enumerate()
        .map(|(i, o)| o.setup(i as u32))
        .collect();
    let mut list = FragmentList::default();
    let work = backend.rasterize(&setups, rule, viewport(), &mut list);
    assert_eq!(work.work.fragments, list.triangles.len() as u64);
    coverage_counts(&list)
}

/// The pixels whose centres `outline` covers under `rule`, by the oracle.
fn oracle_counts(outline: &Outline, rule: WindingRule) -> Vec<u32> {
    (0..SIZE * SIZE)
        .map(|i| {
            let centre = FixedPoint::pixel_centre((i % SIZE) as i32, (i / SIZE) as i32);
            u32::from(outline.covers(centre, rule))
        })
        .collect()
}

/// The first pixel where two count maps differ, said in words.
fn first_difference(what: &str, got: &[u32], expected: &[u32]) -> Result<(), TestCaseError> {
    match (0..got.len()).find(|&i| got[i] != expected[i]) {
        None => Ok(()),
        Some(i) => Err(TestCaseError::fail(format!(
            "{what}: pixel ({}, {}) filled {} times, expected {}",
            i as u32 % SIZE,
            i as u32 / SIZE,
            got[i],
            expected[i]
        ))),
    }
}

/// Scan conversion equals triangulation then the top-left rule, and the
/// oracle, under both winding rules.
fn check_union(polygon: &Polygon) -> Result<(), TestCaseError> {
    let triangles = fragments(&Scanline, &triangulation(polygon), FillRule::TopLeft);
    let union = coverage_counts(&triangles);
    prop_assert!(union.iter().all(|&n| n <= 1), "triangulation draws twice");
    let outline = Outline::of_polygon(polygon);
    for rule in WindingRule::ALL {
        for backend in polygon_backends() {
            let filled = filled_counts(*backend, std::slice::from_ref(&outline), rule);
            first_difference(&format!("{} {rule}", backend.name()), &filled, &union)?;
        }
        first_difference(
            &format!("oracle {rule}"),
            &oracle_counts(&outline, rule),
            &union,
        )?;
    }
    Ok(())
}

/// Every pixel centre of the target filled as the winding number says.
fn check_winding(outline: &Outline) -> Result<(), TestCaseError> {
    for rule in WindingRule::ALL {
        let expected = oracle_counts(outline, rule);
        for backend in polygon_backends() {
            let filled = filled_counts(*backend, std::slice::from_ref(outline), rule);
            first_difference(&format!("{} {rule}", backend.name()), &filled, &expected)?;
        }
    }
    Ok(())
}

/// 1 to 3 rings of 3 to 9 vertices anywhere around the target: they cross
/// themselves and each other, repeat vertices and run along each other
/// (whole and half pixels make that common).
fn crossing_rings() -> impl Strategy<Value = Outline> {
    quantum().prop_flat_map(|q| {
        let ring = proptest::collection::vec(point(-6.0, SIZE as f32 + 6.0, q), 3..10);
        proptest::collection::vec(ring, 1..=3)
            .prop_map(|rings| Outline::new(rings).expect("rings of 3 or more"))
    })
}

/// 1 to 3 rings of 3 to 6 vertices up to the guard band's edge (32,000 px
/// out): long edges of every slope across the small target, where an
/// overflow or a rounded crossing would show.
fn huge_rings() -> impl Strategy<Value = Outline> {
    let ring = proptest::collection::vec(point(-32_000.0, 32_000.0, None), 3..7);
    proptest::collection::vec(ring, 1..=3)
        .prop_map(|rings| Outline::new(rings).expect("rings of 3 or more"))
}

/// A grid of `n x n` quadrilaterals whose shared corners are jittered by up
/// to a quarter of a cell (so every quadrilateral stays simple), partly
/// off the target, and the ring around the whole grid.
fn jittered_grid() -> impl Strategy<Value = (Vec<Outline>, Outline)> {
    (2usize..6, 4.0f32..12.0, -10.0f32..10.0, quantum()).prop_flat_map(|(n, cell, at, q)| {
        let corners = (n + 1) * (n + 1);
        let jitter = cell / 4.0;
        proptest::collection::vec((-jitter..jitter, -jitter..jitter), corners).prop_map(
            move |offsets| {
                let corner = |i: usize, j: usize| {
                    let (dx, dy) = offsets[j * (n + 1) + i];
                    let (x, y) = (at + i as f32 * cell + dx, at + j as f32 * cell + dy);
                    snap(quantize(x, q), quantize(y, q))
                };
                let quads = (0..n)
                    .flat_map(|j| (0..n).map(move |i| (i, j)))
                    .map(|(i, j)| {
                        let ring = vec![
                            corner(i, j),
                            corner(i + 1, j),
                            corner(i + 1, j + 1),
                            corner(i, j + 1),
                        ];
                        Outline::new(vec![ring]).expect("4 corners")
                    })
                    .collect();
                let mut boundary: Vec<FixedPoint> = (0..n).map(|i| corner(i, 0)).collect();
                boundary.extend((0..n).map(|j| corner(n, j)));
                boundary.extend((0..n).map(|i| corner(n - i, n)));
                boundary.extend((0..n).map(|j| corner(0, n - j)));
                (quads, Outline::new(vec![boundary]).expect("a ring"))
            },
        )
    })
}

/// The quadrilaterals of the grid fill each pixel of the whole grid's
/// outline once and nothing else, under both rules.
fn check_shared_edges((quads, boundary): &(Vec<Outline>, Outline)) -> Result<(), TestCaseError> {
    for rule in WindingRule::ALL {
        let expected = oracle_counts(boundary, rule);
        for backend in polygon_backends() {
            let filled = filled_counts(*backend, quads, rule);
            first_difference(&format!("{} {rule}", backend.name()), &filled, &expected)?;
        }
    }
    Ok(())
}

/// The polygon filled by the edge table through the shared fragment stage
/// gives the image, depth and coverage buffers of its triangulation drawn
/// by `scanline` in the polygon's colour, bit for bit.
fn check_stage_image(polygon: &Polygon) -> Result<(), TestCaseError> {
    let look = [ShadedVertex::flat(0.25, Vec4::new(0.9, 0.4, 0.1, 1.0)); 3];
    let triangles = triangulation(polygon);
    let scene = Scene2D {
        width: SIZE,
        height: SIZE,
        vertices: vec![look; triangles.len()],
        triangles,
    };
    let (expected, _) = scene.render(&Scanline, FillRule::TopLeft, &Flat).unwrap();
    let mut target = RenderTarget::new(SIZE, SIZE).unwrap();
    let data = TriangleData::of_triangles(&[], &[look]);
    let mut stage = FragmentStage::new(&mut target, &Flat).with_triangles(&data);
    let setup = Outline::of_polygon(polygon).setup(0);
    EdgeTable.rasterize(&[setup], WindingRule::EvenOdd, viewport(), &mut stage);
    prop_assert!(target == expected, "the images differ");
    Ok(())
}

proptest! {
    #![proptest_config(crate::common::proptest_config(1000, "tests/proptest-regressions/polygons.txt"))]

    /// Through the shared stage, the same image as the triangulation's.
    #[test]
    fn through_the_stage_the_image_is_the_triangulations(polygon in polygon()) {
        check_stage_image(&polygon)?;
    }

    /// On simple polygons with and without a hole, scan conversion fills
    /// exactly the pixels of spade's triangulation under the top-left rule.
    #[test]
    fn scan_conversion_is_the_union_of_the_triangulation(polygon in polygon()) {
        check_union(&polygon)?;
    }

    /// On rings that cross, every pixel agrees with the winding number.
    #[test]
    fn crossing_rings_fill_as_the_winding_number_says(outline in crossing_rings()) {
        check_winding(&outline)?;
    }

    /// Rings reaching the guard band: still exactly the winding number.
    #[test]
    fn rings_up_to_the_guard_band_fill_as_the_winding_number_says(outline in huge_rings()) {
        check_winding(&outline)?;
    }

    /// Quadrilaterals sharing edges and corners: no gap, no pixel twice.
    #[test]
    fn polygons_sharing_edges_fill_each_pixel_once(grid in jittered_grid()) {
        check_shared_edges(&grid)?;
    }
}

fn px(x: f64, y: f64) -> FixedPoint {
    FixedPoint::snap_f64(x, y).unwrap()
}

/// The pentagram: its centre winds twice, a hole under even-odd and
/// filled under nonzero; its points wind once, filled under both.
#[test]
fn a_pentagram_differs_between_the_rules_in_its_centre_only() {
    let star = Outline::new(vec![vec![
        px(20., 2.),
        px(31., 36.),
        px(2., 14.),
        px(38., 14.),
        px(9., 36.),
    ]])
    .unwrap();
    let even_odd = filled_counts(
        &EdgeTable,
        std::slice::from_ref(&star),
        WindingRule::EvenOdd,
    );
    let nonzero = filled_counts(
        &EdgeTable,
        std::slice::from_ref(&star),
        WindingRule::Nonzero,
    );
    let centre = (22 * SIZE + 20) as usize;
    assert_eq!((even_odd[centre], nonzero[centre]), (0, 1));
    assert!((0..even_odd.len()).all(|i| even_odd[i] <= nonzero[i]));
    let (odd, any): (u32, u32) = (even_odd.iter().sum(), nonzero.iter().sum());
    assert!(odd < any && odd > 0, "{odd} < {any}");
}

/// `fragments` with the polygon back-end and `--fill`: the bundled
/// polygon gives the triangulation's pixels, a bow tie (refused for
/// triangulation) is filled, and `--fill` with a triangle back-end is
/// refused.
#[test]
fn fragments_fill_polygons_with_the_edge_table() {
    let pixels = |out: &std::process::Output| {
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let mut v: Vec<(u32, u32)> = String::from_utf8_lossy(&out.stdout)
            .lines()
            .map(|l| {
                let mut w = l.split(' ').map(|n| n.parse::<u32>().unwrap());
                (w.next().unwrap(), w.next().unwrap())
            })
            .collect();
        v.sort_unstable();
        v
    };
    let scan = rasterlab(&[
        "fragments",
        "--backend",
        "edge-table",
        "--size",
        "40x40",
        "assets/polygon.txt",
    ]);
    let tri = rasterlab(&[
        "fragments",
        "--backend",
        "scanline",
        "--size",
        "40x40",
        "assets/polygon.txt",
    ]);
    assert_eq!(pixels(&scan), pixels(&tri));
    let dir = tempfile::tempdir().unwrap();
    let bowtie = dir.path().join("bowtie.txt");
    std::fs::write(&bowtie, "polygon 0 0 8 8 8 0 0 8\n").unwrap();
    let bowtie = bowtie.to_str().unwrap();
    let filled = rasterlab(&[
        "fragments",
        "--backend",
        "edge-table",
        "--fill",
        "nonzero",
        "--size",
        "8x8",
        bowtie,
    ]);
    assert_eq!(pixels(&filled).len(), 32);
    for refused in [
        rasterlab(&[
            "fragments",
            "--backend",
            "edge-table",
            "--size",
            "8x8",
            bowtie,
        ]),
        rasterlab(&[
            "fragments",
            "--backend",
            "scanline",
            "--size",
            "8x8",
            bowtie,
        ]),
    ] {
        assert_eq!(refused.status.code(), Some(2));
        let stderr = String::from_utf8_lossy(&refused.stderr);
        assert!(
            stderr.contains("polygon is not simple: two edges touch or cross"),
            "{stderr}"
        );
    }
    let fill_for_triangles = rasterlab(&[
        "fragments",
        "--backend",
        "scanline",
        "--fill",
        "nonzero",
        "--size",
        "8x8",
        bowtie,
    ]);
    assert_eq!(fill_for_triangles.status.code(), Some(2));
}

/// `explain --backend edge-table`: the edge table, then each row's active
/// edges sorted by x with their windings, and the spans, for a square
/// whose corners are pixel centres (left and top edges in, right and
/// bottom out).
#[test]
fn explain_walks_the_edge_table_row_by_row() {
    let out = rasterlab(&[
        "explain",
        "--backend",
        "edge-table",
        "--size",
        "8x8",
        "1.5",
        "1.5",
        "4.5",
        "1.5",
        "4.5",
        "3.5",
        "1.5",
        "3.5",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.contains("ET[1]: e0 (4.5, 1.5)-(4.5, 3.5) down"),
        "{text}"
    );
    let rows: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("   1 ") || l.starts_with("   2 "))
        .collect();
    assert_eq!(rows.len(), 2, "{text}");
    for row in &rows {
        assert!(
            row.contains("e1 1 -1, e0 4 +1") && row.ends_with("1..=3 (3 px)"),
            "{row}"
        );
    }
    assert!(rows[0].contains("e0 e1"), "{}", rows[0]);
    assert!(
        text.ends_with("2 rows, 4 edges visited, 2 spans, 6 fragments\n"),
        "{text}"
    );
    let nonzero = rasterlab(&[
        "explain",
        "--backend",
        "edge-table",
        "--fill",
        "nonzero",
        "0",
        "0",
        "4",
        "4",
        "4",
        "0",
        "0",
        "4",
    ]);
    assert!(nonzero.status.success());
    assert!(String::from_utf8_lossy(&nonzero.stdout).contains("edge-table, nonzero"));
    for refused in [
        rasterlab(&[
            "explain",
            "--backend",
            "edge-table",
            "0",
            "0",
            "4",
            "4",
            "4",
        ]),
        rasterlab(&[
            "explain",
            "--backend",
            "edge-table",
            "--msaa",
            "4",
            "0",
            "0",
            "4",
            "4",
            "4",
            "0",
        ]),
        rasterlab(&[
            "explain",
            "--backend",
            "scanline",
            "--fill",
            "nonzero",
            "0",
            "0",
            "4",
            "4",
            "4",
            "0",
        ]),
    ] {
        assert_eq!(
            refused.status.code(),
            Some(2),
            "{}",
            String::from_utf8_lossy(&refused.stderr)
        );
    }
}

/// `explain --backend edge-table --ring`: a hole typed the same way round
/// as its outer ring winds twice, so even-odd leaves it empty and nonzero
/// fills it; typed the other way round it is a hole under both rules. The
/// picture's green cells are the trace's fragments, and its labels the
/// exact winding numbers.
#[test]
fn a_ring_running_the_same_way_is_a_hole_under_even_odd_only() {
    use rasterlab::teaching::{trace_polygon_rings, GridPicture};
    let outer = vec![(1.0, 1.0), (15.0, 2.0), (14.0, 11.0), (2.0, 10.0)];
    let same = vec![(5.0, 4.0), (11.0, 4.0), (10.0, 8.0), (6.0, 8.0)];
    let against: Vec<(f64, f64)> = same.iter().rev().copied().collect();
    let fragments = |rings: &[Vec<(f64, f64)>], rule| {
        let text = trace_polygon_rings(rings, rule, 16, 12).unwrap().to_text();
        let last = text.lines().last().unwrap().to_string();
        last.rsplit(", ").next().unwrap().to_string()
    };
    let (even_odd, nonzero) = (WindingRule::EvenOdd, WindingRule::Nonzero);
    let with_same = [outer.clone(), same.clone()];
    let with_against = [outer.clone(), against];
    assert_eq!(fragments(&with_same, even_odd), "97 fragments");
    assert_eq!(fragments(&with_same, nonzero), "117 fragments");
    assert_eq!(fragments(&with_against, even_odd), "97 fragments");
    assert_eq!(fragments(&with_against, nonzero), "97 fragments");
    let snapped: Vec<Vec<FixedPoint>> = with_same
        .iter()
        .map(|r| {
            r.iter()
                .map(|&(x, y)| FixedPoint::snap_f64(x, y).unwrap())
                .collect()
        })
        .collect();
    for (rule, filled) in [(even_odd, 97), (nonzero, 117)] {
        let picture = GridPicture::of_polygon(&snapped, rule, 16, 12).unwrap();
        assert_eq!(picture.inside_cells(), filled, "{rule}");
        // Pixel (8, 6) lies inside both rings, (3, 3) inside the outer only.
        assert_eq!(picture.labels[6 * 16 + 8], "-2");
        assert_eq!(picture.labels[3 * 16 + 3], "-1");
        assert_eq!(picture.labels[0], "");
    }
    let out = rasterlab(&[
        "explain",
        "--backend",
        "edge-table",
        "--fill",
        "nonzero",
        "--size",
        "16x12",
        "1",
        "1",
        "15",
        "2",
        "14",
        "11",
        "2",
        "10",
        "--ring",
        "5 4 11 4 10 8 6 8",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    assert!(text.contains("ring 1 runs clockwise, as ring 0"), "{text}");
    assert!(text.ends_with(", 117 fragments\n"), "{text}");
    for bad in ["5 4 11 4 10", "5 4 x 4 10 8", "5 4 11 4"] {
        let refused = rasterlab(&[
            "explain",
            "--backend",
            "edge-table",
            "1",
            "1",
            "15",
            "2",
            "14",
            "11",
            "--ring",
            bad,
        ]);
        assert_eq!(refused.status.code(), Some(2), "{bad}");
    }
    let not_a_polygon = rasterlab(&[
        "explain",
        "--backend",
        "bbox",
        "1",
        "1",
        "9",
        "2",
        "3",
        "7",
        "--ring",
        "5 4 11 4 10 8",
    ]);
    assert_eq!(not_a_polygon.status.code(), Some(2));
}
