//! A triangle clipped in homogeneous clip space as the 3D pipeline clips
//! it (the software-rasterizer article: clip against the near plane, then
//! split what is left into a fan): each vertex's out-code, then for every
//! plane a vertex lies outside, Sutherland and Hodgman's pass over the
//! polygon's edges (each vertex kept or dropped, each crossing's new
//! vertex at `t = d_a / (d_a - d_b)`), the polygon after that plane, the
//! fan of triangles from its first vertex, and each vertex divided by `w`
//! and mapped to the viewport.

use super::check_trace_length;
use crate::error::{Error, Result};
use crate::geometry::{ClipPlanes, ClipResult, ClipVertex, ClipVolume, Viewport, PLANE_NAMES};
use crate::raster::primitive::Varyings;
use crate::teaching::trace_table::{Column, Trace, TraceRow};
use glam::Vec4;

/// The clip-space corners the trace takes when given none: a perspective
/// camera (90 degree field of view, near plane 1, far 100) looking at
/// eye-space points `(-1, -1, -2)` and `(1, -1, -2)` in front of it and
/// `(0, 1, 0.5)` behind it, as `x y z w` each.
pub const BEHIND_THE_CAMERA: [f64; 12] = [
    -1.0,
    -1.0,
    2.0 * 101.0 / 99.0 - 200.0 / 99.0,
    2.0,
    1.0,
    -1.0,
    2.0 * 101.0 / 99.0 - 200.0 / 99.0,
    2.0,
    0.0,
    1.0,
    -0.5 * 101.0 / 99.0 - 200.0 / 99.0,
    -0.5,
];

/// Each plane's inequality, as [`PLANE_NAMES`] orders them, the guard
/// band's (or the viewport's) factor `g` written in.
fn inequality(plane: usize, g: [f32; 2]) -> String {
    match plane {
        0 => "z + w >= 0".into(),
        1 => "w - z >= 0".into(),
        2 => "w >= 1e-5".into(),
        3 => format!("x + {} w >= 0", g[0]),
        4 => format!("{} w - x >= 0", g[0]),
        5 => format!("{} w - y >= 0", g[1]),
        _ => format!("y + {} w >= 0", g[1]),
    }
}

/// What a plane that no vertex of the polygon lies outside does.
const UNCHANGED: &str =
    "every vertex inside (d >= 0, the least shown): the polygon passes unchanged";

fn point(p: Vec4) -> String {
    format!("({:.3}, {:.3}, {:.3}, {:.3})", p.x, p.y, p.z, p.w)
}

/// The clipping trace of the triangle whose clip-space corners are
/// `numbers` (`x y z w` three times), for a `width x height` viewport
/// whose side planes are `planes`.
///
/// ```
/// use rasterlab::geometry::ClipPlanes;
/// use rasterlab::teaching::{trace_triangle_clip, BEHIND_THE_CAMERA};
/// let text = trace_triangle_clip(&BEHIND_THE_CAMERA, ClipPlanes::GuardBand, 16, 16)
///     .unwrap()
///     .to_text();
/// assert!(text.contains("after near: 4 vertices"));
/// assert!(text.contains("fan of 2 triangles"));
/// ```
pub fn trace_triangle_clip(
    numbers: &[f64],
    planes: ClipPlanes,
    width: u32,
    height: u32,
) -> Result<Trace> {
    if numbers.len() != 12 {
        return Err(Error::InvalidArgument(format!(
            "clip-triangle takes a triangle in clip space: x y z w for each of its 3 vertices (12 numbers, or none for the example), not {}",
            numbers.len()
        )));
    }
    if numbers.iter().any(|v| !v.is_finite() || v.abs() > 1e30) {
        return Err(Error::InvalidArgument(
            "clip-triangle's coordinates must be finite numbers within 1e30".into(),
        ));
    }
    let corner = |k: usize| ClipVertex {
        position: Vec4::new(
            numbers[4 * k] as f32,
            numbers[4 * k + 1] as f32,
            numbers[4 * k + 2] as f32,
            numbers[4 * k + 3] as f32,
        ),
        varyings: Varyings::default(),
    };
    let triangle = [corner(0), corner(1), corner(2)];
    let volume = ClipVolume::with_planes(width, height, planes);
    let g = volume.guard();
    let codes = triangle.map(|v| volume.outcode(v.position));
    let mut trace = Trace::default();
    trace.header.push(format!(
        "clip-triangle: Sutherland-Hodgman in homogeneous clip space, before the divide, for a {width}x{height} viewport with its {planes} planes"
    ));
    trace.header.push(format!(
        "planes, kept where >= 0: {}",
        (0..7)
            .map(|k| format!("{}: {}", PLANE_NAMES[k], inequality(k, g)))
            .collect::<Vec<_>>()
            .join("; ")
    ));
    let outside = |code: u8| -> String {
        let names: Vec<&str> = (0..7)
            .filter(|k| code & (1 << k) != 0)
            .map(|k| PLANE_NAMES[k])
            .collect();
        if names.is_empty() {
            "inside every plane".into()
        } else {
            format!("outside {}", names.join(", "))
        }
    };
    for (k, v) in triangle.iter().enumerate() {
        trace.header.push(format!(
            "v{k} = {}: out-code {:07b}, {}",
            point(v.position),
            codes[k],
            outside(codes[k])
        ));
    }
    trace.columns = vec![
        Column::left("plane", 12, 0),
        Column::left("edge", 6, 2),
        Column::right("d_a", 9, 2),
        Column::right("d_b", 9, 2),
        Column::left("Sutherland-Hodgman", 0, 2),
    ];
    let mut polygon: Vec<(String, ClipVertex)> = triangle
        .iter()
        .enumerate()
        .map(|(k, v)| (format!("v{k}"), *v))
        .collect();
    let mut made = 0;
    let verdict = if codes[0] | codes[1] | codes[2] == 0 {
        "inside every plane: the triangle goes on as it is".to_string()
    } else if codes[0] & codes[1] & codes[2] != 0 {
        let plane = (0..7).find(|k| codes[0] & codes[1] & codes[2] & (1 << k) != 0);
        format!(
            "all three vertices outside {}: the triangle is rejected",
            PLANE_NAMES[plane.unwrap_or(0)]
        )
    } else {
        let mut next = Vec::new();
        for (plane, plane_name) in PLANE_NAMES.iter().enumerate() {
            if codes.iter().all(|c| c & (1 << plane) == 0) {
                continue;
            }
            let mut named = Vec::new();
            let n = polygon.len();
            let values: Vec<f64> = polygon
                .iter()
                .map(|(_, v)| volume.plane_value(plane, v.position))
                .collect();
            if values.iter().all(|&d| d >= 0.0) {
                // What an earlier plane cut away held the vertices
                // outside this one: nothing is left to cut.
                trace.rows.push(TraceRow::new(vec![
                    plane_name.to_string(),
                    "-".into(),
                    format!("{:.4}", values.iter().fold(f64::INFINITY, |a, &b| a.min(b))),
                    String::new(),
                    UNCHANGED.into(),
                ]));
                continue;
            }
            for i in 0..n {
                let (a_name, a) = &polygon[i];
                let (b_name, b) = &polygon[(i + 1) % n];
                let (da, db) = (
                    volume.plane_value(plane, a.position),
                    volume.plane_value(plane, b.position),
                );
                let mut said = Vec::new();
                if da >= 0.0 {
                    named.push(a_name.clone());
                    said.push(format!("{a_name} inside: kept"));
                } else {
                    said.push(format!("{a_name} outside: dropped"));
                }
                if (da >= 0.0) != (db >= 0.0) {
                    let t = da / (da - db);
                    let name = format!("p{made}");
                    made += 1;
                    let cut = a.lerp(b, t);
                    said.push(format!(
                        "the edge {} the plane at t = {t:.4}: new vertex {name} = {}",
                        if da >= 0.0 { "leaves" } else { "enters" },
                        point(cut.position)
                    ));
                    named.push(name);
                }
                trace.rows.push(TraceRow::new(vec![
                    if i == 0 {
                        plane_name.to_string()
                    } else {
                        String::new()
                    },
                    format!("{a_name}-{b_name}"),
                    format!("{da:.4}"),
                    format!("{db:.4}"),
                    said.join("; "),
                ]));
            }
            let cut: Vec<ClipVertex> = polygon.iter().map(|(_, v)| *v).collect();
            volume.clip_to_plane(plane, &cut, &mut next);
            polygon = named.into_iter().zip(next.iter().copied()).collect();
            trace.rows.push(TraceRow::note(format!(
                "after {plane_name}: {} vertices, {}",
                polygon.len(),
                polygon
                    .iter()
                    .map(|(n, _)| n.as_str())
                    .collect::<Vec<_>>()
                    .join(" ")
            )));
            if polygon.len() < 3 {
                break;
            }
        }
        // The library's own clipping, for the same polygon.
        let mut library = Vec::new();
        match volume.clip_triangle(&triangle, codes, &mut library) {
            ClipResult::Cut(n) if n == polygon.len() => {}
            ClipResult::Cut(0) if polygon.len() < 3 => {}
            other => {
                return Err(Error::InvalidArgument(format!(
                    "the traced polygon of {} vertices is not the pipeline's ({other:?})",
                    polygon.len()
                )))
            }
        }
        if polygon.len() < 3 {
            "nothing is left: the triangle is dropped".into()
        } else {
            let fan: Vec<String> = (1..polygon.len() - 1)
                .map(|i| format!("({} {} {})", polygon[0].0, polygon[i].0, polygon[i + 1].0))
                .collect();
            format!(
                "re-triangulated as a fan from {}: a fan of {} triangles, {}",
                polygon[0].0,
                fan.len(),
                fan.join(", ")
            )
        }
    };
    check_trace_length(trace.rows.len() as u64, "lines")?;
    trace.footer.push(verdict);
    if polygon.len() >= 3 && (codes[0] & codes[1] & codes[2]) == 0 {
        let viewport = Viewport { width, height };
        for (name, v) in &polygon {
            let line = match viewport.to_screen(v.position) {
                Ok((p, depth, _)) => {
                    let (x, y) = p.to_f64();
                    format!(
                        "{name}: divided by w = {:.3} and mapped to the viewport: ({x:.3}, {y:.3}) px, depth {depth:.4}",
                        v.position.w
                    )
                }
                Err(e) => format!("{name}: {e}"),
            };
            trace.footer.push(line);
        }
    }
    Ok(trace)
}
