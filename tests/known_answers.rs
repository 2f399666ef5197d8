//! Known answers, checked exactly: the rules' 15/10 split, each fill rule's
//! pattern on a triangle with pixel centres on all three edges, and seed
//! 002's depth-buffer example.

use rasterlab::geometry::{collect_fragments, setup_triangles, Scene2D, BLUE, RED};
use rasterlab::raster::{to_rgba8, triangle_backends, FillRule, FixedPoint, Flat};
use rasterlab::teaching::{ascii_count, ascii_rows};

fn snap(x: f32, y: f32) -> FixedPoint {
    FixedPoint::snap(x, y).unwrap()
}

/// The coverage of a triangle soup as ASCII art: `#` covered once, `.` not,
/// digits for pixels covered more than once.
fn pattern(
    backend_index: usize,
    tris: &[[FixedPoint; 3]],
    rule: FillRule,
    w: u32,
    h: u32,
) -> Vec<String> {
    let setups = setup_triangles(tris, rule);
    let (list, _) = collect_fragments(triangle_backends()[backend_index], &setups, w, h);
    let mut counts = vec![0u32; (w * h) as usize];
    for f in &list.triangles {
        counts[(f.y * w + f.x) as usize] += 1;
    }
    ascii_rows(0..i64::from(w), 0..i64::from(h), |x, y| {
        ascii_count(counts[(y * i64::from(w) + x) as usize])
    })
}

#[test]
fn the_split_square_covers_15_and_10_pixels() {
    let tris = [
        [snap(0., 0.), snap(5., 0.), snap(5., 5.)],
        [snap(0., 5.), snap(0., 0.), snap(5., 5.)],
    ];
    for backend in triangle_backends() {
        let (list, _) =
            collect_fragments(*backend, &setup_triangles(&tris, FillRule::TopLeft), 5, 5);
        let per_triangle = |t| list.triangles.iter().filter(|f| f.triangle == t).count();
        assert_eq!(
            (per_triangle(0), per_triangle(1)),
            (15, 10),
            "{}",
            backend.name()
        );
    }
}

#[test]
fn each_fill_rule_has_its_pattern_on_a_triangle_with_centres_on_every_edge() {
    // Top edge y = 0.5, left edge x = 0.5 and the hypotenuse x + y = 7 all
    // run through pixel centres.
    let tri = [[snap(0.5, 0.5), snap(6.5, 0.5), snap(0.5, 6.5)]];
    let expected: [(FillRule, [&str; 7]); 5] = [
        // Top and left edges own their ties, the hypotenuse (right) does not.
        (
            FillRule::TopLeft,
            [
                "######.", "#####..", "####...", "###....", "##.....", "#......", ".......",
            ],
        ),
        // The mirror: only the hypotenuse owns its ties.
        (
            FillRule::BottomRight,
            [
                ".......", ".#####.", ".####..", ".###...", ".##....", ".#.....", ".......",
            ],
        ),
        // The off-screen point (-100000, -70000) is inside the hypotenuse's
        // half-plane only: the same as bottom-right here.
        (
            FillRule::OffscreenPoint,
            [
                ".......", ".#####.", ".####..", ".###...", ".##....", ".#.....", ".......",
            ],
        ),
        (
            FillRule::Inclusive,
            [
                "#######", "######.", "#####..", "####...", "###....", "##.....", "#......",
            ],
        ),
        (
            FillRule::Exclusive,
            [
                ".......", ".####..", ".###...", ".##....", ".#.....", ".......", ".......",
            ],
        ),
    ];
    for (rule, rows) in expected {
        for b in 0..triangle_backends().len() {
            assert_eq!(
                pattern(b, &tri, rule, 7, 7),
                rows,
                "{rule} / {}",
                triangle_backends()[b].name()
            );
        }
    }
}

#[test]
fn a_horizontal_shared_edge_goes_to_the_triangle_below_it() {
    // Two triangles share the edge y = 2.5 through pixel centres; the lower
    // one has it as its top edge and owns it under top-left.
    let tris = [
        [snap(0.5, 2.5), snap(6.5, 2.5), snap(3.5, -0.5)],
        [snap(6.5, 2.5), snap(0.5, 2.5), snap(3.5, 5.5)],
    ];
    let setups = setup_triangles(&tris, FillRule::TopLeft);
    for backend in triangle_backends() {
        let (list, _) = collect_fragments(*backend, &setups, 7, 6);
        let on_edge: Vec<u32> = list
            .triangles
            .iter()
            .filter(|f| f.y == 2)
            .map(|f| f.triangle)
            .collect();
        assert_eq!(on_edge, vec![1; 6], "{}", backend.name());
    }
}

/// The rasterization slides' worked example, as written on the slides.
const DEPTH_AFTER_BOTH: [&str; 9] = [
    "1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 1.0 1.0 0.8 0.8 0.8 1.0 1.0 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 1.0 1.0 1.0 0.8 0.8 1.0 1.0 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 1.0 0.5 0.5 0.5 0.5 0.5 0.5 0.5 0.5 1.0 1.0 1.0",
    "1.0 1.0 0.5 0.5 0.5 0.5 0.5 0.5 1.0 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 0.5 0.5 0.5 0.5 1.0 0.8 0.8 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 0.5 1.0 1.0 1.0 1.0 1.0 0.8 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0",
];

/// The slide after the blue triangle alone.
const DEPTH_AFTER_BLUE: [&str; 9] = [
    "1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 1.0 0.5 0.5 0.5 0.5 0.5 0.5 0.5 0.5 1.0 1.0 1.0",
    "1.0 1.0 0.5 0.5 0.5 0.5 0.5 0.5 1.0 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 0.5 0.5 0.5 0.5 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 0.5 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0",
    "1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0 1.0",
];

fn matrix(depth: &[f32]) -> Vec<String> {
    depth
        .chunks(14)
        .map(|row| {
            row.iter()
                .map(|z| format!("{z:.1}"))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect()
}

#[test]
fn seed_002_depth_buffer_example_matches_the_slides_in_both_drawing_orders() {
    for backend in triangle_backends() {
        let blue_only = Scene2D {
            triangles: Scene2D::depth_example(true).triangles[..1].to_vec(),
            vertices: Scene2D::depth_example(true).vertices[..1].to_vec(),
            ..Scene2D::depth_example(true)
        };
        let (after_blue, _) = blue_only
            .render(*backend, FillRule::TopLeft, &Flat)
            .unwrap();
        assert_eq!(
            matrix(&after_blue.depth),
            DEPTH_AFTER_BLUE,
            "{}",
            backend.name()
        );

        let (blue_first, _) = Scene2D::depth_example(true)
            .render(*backend, FillRule::TopLeft, &Flat)
            .unwrap();
        let (red_first, _) = Scene2D::depth_example(false)
            .render(*backend, FillRule::TopLeft, &Flat)
            .unwrap();
        assert_eq!(
            matrix(&blue_first.depth),
            DEPTH_AFTER_BOTH,
            "{}",
            backend.name()
        );
        assert_eq!(blue_first.depth, red_first.depth);
        assert_eq!(blue_first.color, red_first.color);
        // The colour buffer agrees with the depth buffer cell by cell.
        for (z, c) in blue_first.depth.iter().zip(&blue_first.color) {
            let expected = match format!("{z:.1}").as_str() {
                "0.5" => to_rgba8(BLUE),
                "0.8" => to_rgba8(RED),
                _ => [0, 0, 0, 255],
            };
            assert_eq!(*c, expected);
        }
        // Depth values are exact, not merely close.
        assert!(blue_first
            .depth
            .iter()
            .all(|&z| z == 0.5 || z == 0.8 || z == 1.0));
    }
}

/// `rasterlab explain --backend depth-buffer`: the trace prints the
/// slides' matrices after each triangle, with the fragments kept and
/// hidden (blue: 19 cells at 0.5; red: 12 fragments, of which the 4 behind
/// blue are hidden and 8 reach the buffer at 0.8).
#[test]
fn seed_002_depth_buffer_trace_prints_the_slides_matrices() {
    let bbox = rasterlab::raster::triangle_backend("bbox").unwrap();
    let text = rasterlab::teaching::trace_depth_buffer(
        &Scene2D::depth_example(true),
        bbox,
        FillRule::TopLeft,
    )
    .unwrap()
    .to_text();
    let mut expected = vec![
        "depth buffer, 14 x 9, initialised with 1.0; each fragment f is kept if f.z < depthBuffer[f.xy]"
            .to_string(),
    ];
    expected.extend(std::iter::repeat_n("1.0 ".repeat(13) + "1.0", 9));
    expected.push(String::new());
    expected.push(
        "triangle 1 (z = 0.5, 0.5, 0.5): 19 fragments, 19 kept (nearer than the buffer), 0 hidden"
            .into(),
    );
    expected.extend(DEPTH_AFTER_BLUE.iter().map(|s| s.to_string()));
    expected.push(String::new());
    expected.push(
        "triangle 2 (z = 0.8, 0.8, 0.8): 12 fragments, 8 kept (nearer than the buffer), 4 hidden"
            .into(),
    );
    expected.extend(DEPTH_AFTER_BOTH.iter().map(|s| s.to_string()));
    assert_eq!(text.lines().collect::<Vec<_>>(), expected);
}
