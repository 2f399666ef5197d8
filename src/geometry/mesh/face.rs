//! Polygon faces split into triangles.
//!
//! A mesh file may give faces of any number of vertices. A triangle is kept
//! as it is; a convex polygon is split into a fan `(v0, v[i], v[i+1])`, as
//! the course splits polygons; a concave polygon (an L-shaped face, say)
//! would be wrongly covered by a fan, so it is projected onto its plane and
//! triangulated by `spade`'s constrained Delaunay triangulation, keeping
//! the triangles inside the ring.
//!
//! The plane is the face's Newell normal, the best-fit plane of its
//! vertices, so a slightly non-planar face is triangulated as seen along
//! its normal. A face whose projection has no area, repeats a vertex
//! position while concave, or crosses itself is an error: no triangulation
//! of it means what the file's author meant.
//!
//! ```
//! use glam::Vec3;
//! use rasterlab::geometry::triangulate_face;
//! // An L: six corners, concave at corner 3.
//! let p = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)]
//!     .map(|(x, y)| Vec3::new(x, y, 0.0));
//! let mut triangles = Vec::new();
//! triangulate_face(&p, &[0, 1, 2, 3, 4, 5], &mut triangles).unwrap();
//! assert_eq!(triangles.len(), 4);
//! // No triangle covers the missing corner (1.5, 1.5).
//! let area: f32 = triangles
//!     .iter()
//!     .map(|t| (p[t[1] as usize] - p[t[0] as usize]).cross(p[t[2] as usize] - p[t[0] as usize]).length() / 2.0)
//!     .sum();
//! assert_eq!(area, 3.0);
//! ```

use glam::{DVec2, DVec3, Vec3};
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// Appends the triangles of the face whose corners are `face` (indices
/// into `positions`, all in range) to `out`, in the face's winding.
///
/// Errors (as a message, for the caller to place at its line): a face of
/// fewer than three vertices, a concave face with no area, a repeated
/// position or crossing edges.
pub fn triangulate_face(
    positions: &[Vec3],
    face: &[u32],
    out: &mut Vec<[u32; 3]>,
) -> Result<(), String> {
    if face.len() < 3 {
        return Err(format!(
            "a face needs at least 3 vertices, found {}",
            face.len()
        ));
    }
    if face.len() == 3 {
        out.push([face[0], face[1], face[2]]);
        return Ok(());
    }
    let points: Vec<DVec3> = face
        .iter()
        .map(|&i| positions[i as usize].as_dvec3())
        .collect();
    let normal = newell_normal(&points);
    let flat = project(&points, normal);
    if is_convex(&flat) {
        for i in 1..face.len() - 1 {
            out.push([face[0], face[i], face[i + 1]]);
        }
        return Ok(());
    }
    if normal == DVec3::ZERO {
        return Err("the face has no area in any plane: it cannot be triangulated".into());
    }
    constrained(&flat, face, out)
}

/// The Newell normal: the sum of the polygon's edge cross terms, the
/// normal of the plane that fits its vertices best (zero for no area).
fn newell_normal(p: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for (i, a) in p.iter().enumerate() {
        let b = p[(i + 1) % p.len()];
        n += DVec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    n
}

/// The points seen along `normal`, in 2D, with the face's winding kept
/// counter-clockwise (positive area) when the normal is not zero.
fn project(p: &[DVec3], normal: DVec3) -> Vec<DVec2> {
    let a = normal.abs();
    // Drop the normal's largest axis; mirror if needed to keep the winding.
    let (axis, sign) = if a.x >= a.y && a.x >= a.z {
        (0, normal.x)
    } else if a.y >= a.z {
        (1, normal.y)
    } else {
        (2, normal.z)
    };
    p.iter()
        .map(|v| {
            let q = match axis {
                0 => DVec2::new(v.y, v.z),
                1 => DVec2::new(v.z, v.x),
                _ => DVec2::new(v.x, v.y),
            };
            if sign < 0.0 {
                DVec2::new(q.y, q.x)
            } else {
                q
            }
        })
        .collect()
}

/// True when every turn of the (counter-clockwise) ring is a left turn or
/// straight: a fan then covers exactly the polygon.
fn is_convex(p: &[DVec2]) -> bool {
    let n = p.len();
    let area: f64 = (0..n).map(|i| p[i].perp_dot(p[(i + 1) % n])).sum();
    area > 0.0
        && (0..n).all(|i| {
            let (a, b, c) = (p[i], p[(i + 1) % n], p[(i + 2) % n]);
            (b - a).perp_dot(c - b) >= 0.0
        })
}

/// Constrained Delaunay triangulation of a simple ring, keeping the
/// triangles whose centroid lies inside it.
fn constrained(p: &[DVec2], face: &[u32], out: &mut Vec<[u32; 3]>) -> Result<(), String> {
    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    let mut handles = Vec::with_capacity(p.len());
    for q in p {
        let h = cdt
            .insert(Point2::new(q.x, q.y))
            .map_err(|e| format!("the face cannot be triangulated: {e:?}"))?;
        if handles.contains(&h) {
            return Err("the concave face repeats a vertex position".into());
        }
        handles.push(h);
    }
    for i in 0..handles.len() {
        let (from, to) = (handles[i], handles[(i + 1) % handles.len()]);
        if !cdt.can_add_constraint(from, to) {
            return Err("the face crosses itself".into());
        }
        cdt.add_constraint(from, to);
    }
    if cdt.num_vertices() != p.len() {
        return Err("the face crosses itself".into());
    }
    let corner_of = |h: spade::handles::FixedVertexHandle| {
        handles.iter().position(|&k| k == h).map(|i| face[i])
    };
    for triangle in cdt.inner_faces() {
        let v = triangle.vertices();
        let centroid = v
            .iter()
            .map(|h| DVec2::new(h.position().x, h.position().y))
            .sum::<DVec2>()
            / 3.0;
        if !inside(p, centroid) {
            continue;
        }
        let [a, b, c] = v.map(|h| corner_of(h.fix()));
        if let (Some(a), Some(b), Some(c)) = (a, b, c) {
            // spade's faces are counter-clockwise, as the projected ring is.
            out.push([a, b, c]);
        }
    }
    Ok(())
}

/// Even-odd test of a point against a ring.
fn inside(p: &[DVec2], q: DVec2) -> bool {
    let mut inside = false;
    for i in 0..p.len() {
        let (a, b) = (p[i], p[(i + 1) % p.len()]);
        if (a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn convex_faces_are_fanned_and_self_crossing_faces_refused() {
        let square = [(0., 0.), (1., 0.), (1., 1.), (0., 1.)].map(|(x, y)| Vec3::new(x, y, 0.0));
        let mut out = Vec::new();
        triangulate_face(&square, &[0, 1, 2, 3], &mut out).unwrap();
        assert_eq!(out, vec![[0, 1, 2], [0, 2, 3]]);
        // A bow tie: edges 1-2 and 3-0 cross.
        let bow = [(0., 0.), (1., 1.), (1., 0.), (0., 1.)].map(|(x, y)| Vec3::new(x, y, 0.0));
        assert!(triangulate_face(&bow, &[0, 1, 2, 3], &mut Vec::new()).is_err());
        // The L face in the yz plane, wound the other way, keeps its winding.
        let l = [(0., 0.), (0., 1.), (1., 1.), (1., 2.), (2., 2.), (2., 0.)]
            .map(|(y, z)| Vec3::new(0.0, y, z));
        let mut out = Vec::new();
        triangulate_face(&l, &[0, 1, 2, 3, 4, 5], &mut out).unwrap();
        assert_eq!(out.len(), 4);
        let n = newell_normal(&l.map(|v| v.as_dvec3()));
        for t in &out {
            let [a, b, c] = t.map(|i| l[i as usize]);
            assert!(
                (b - a).cross(c - a).as_dvec3().dot(n) > 0.0,
                "{t:?} flips the winding"
            );
        }
    }
}
