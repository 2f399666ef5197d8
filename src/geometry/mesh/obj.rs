//! Wavefront OBJ meshes: `v`, `vt`, `vn` and `f` statements.
//!
//! Faces refer to positions, texture coordinates and normals through
//! separate 1-based (or negative, relative) indices, `f 1/1/1 2/2/2 3/3/3`;
//! each distinct `position/uv/normal` triple becomes one mesh vertex.
//! Polygons are split into triangles (`face.rs`: a fan when convex,
//! a constrained Delaunay triangulation when concave); groups, objects, materials and smoothing
//! statements are ignored.
//!
//! The reader is written here rather than taken from a crate because the
//! OBJ crates report malformed input without a line number, and every error
//! here names the file and the line (`file.obj:12: ...`).

use super::{face::triangulate_face, Mesh};
use crate::error::{Error, Result};
use glam::{Vec2, Vec3, Vec4};
use std::collections::HashMap;
use std::path::Path;

/// Loads an OBJ file.
pub fn load_obj(path: &Path) -> Result<Mesh> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, &e))?;
    parse_obj(&text, path)
}

/// Parses OBJ text; `path` is used in error messages only.
///
/// ```
/// use std::path::Path;
/// let mesh = rasterlab::geometry::parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", Path::new("t.obj")).unwrap();
/// assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
/// let err = rasterlab::geometry::parse_obj("v 0 0 0\nf 1 2 3\n", Path::new("t.obj")).unwrap_err();
/// assert_eq!(err.to_string(), "t.obj:2: position index 2 is out of range (1 defined so far)");
/// ```
pub fn parse_obj(text: &str, path: &Path) -> Result<Mesh> {
    let mut positions: Vec<Vec3> = Vec::new();
    let mut colors: Vec<Vec4> = Vec::new();
    let mut uvs: Vec<Vec2> = Vec::new();
    let mut normals: Vec<Vec3> = Vec::new();
    // Distinct (position, uv, normal) triples and their mesh vertex index.
    let mut corners: HashMap<(u32, Option<u32>, Option<u32>), u32> = HashMap::new();
    let mut corner_list: Vec<(u32, Option<u32>, Option<u32>)> = Vec::new();
    // The position of each corner, by corner index.
    let mut corner_positions: Vec<Vec3> = Vec::new();
    let mut triangles = Vec::new();
    let mut face = Vec::new();

    // A UTF-8 byte-order mark, as some editors write, is not content.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let err = |message: String| Error::Parse {
            path: path.to_path_buf(),
            line: Some(line),
            message,
        };
        let content = raw.split('#').next().unwrap_or("").trim();
        let mut words = content.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let args: Vec<&str> = words.collect();
        match keyword {
            "v" => {
                let v = floats(&args, 3, 7, "v").map_err(err)?;
                let p = Vec3::new(v[0], v[1], v[2]);
                super::check_position(p).map_err(err)?;
                positions.push(p);
                if v.len() >= 6 {
                    colors.push(Vec4::new(v[3], v[4], v[5], 1.0));
                }
            }
            "vt" => {
                let v = floats(&args, 1, 3, "vt").map_err(err)?;
                uvs.push(Vec2::new(v[0], v.get(1).copied().unwrap_or(0.0)));
            }
            "vn" => {
                let v = floats(&args, 3, 3, "vn").map_err(err)?;
                normals.push(Vec3::new(v[0], v[1], v[2]));
            }
            "f" => {
                if args.len() < 3 {
                    return Err(err(format!(
                        "a face needs at least 3 vertices, found {}",
                        args.len()
                    )));
                }
                face.clear();
                for corner in &args {
                    let mut parts = corner.split('/');
                    let p = resolve(parts.next(), positions.len(), "position").map_err(err)?;
                    let t = resolve(parts.next(), uvs.len(), "texture coordinate").map_err(err)?;
                    let n = resolve(parts.next(), normals.len(), "normal").map_err(err)?;
                    let Some(p) = p else {
                        return Err(err(format!("face corner `{corner}` has no position index")));
                    };
                    let key = (p, t, n);
                    let next = corner_list.len() as u32;
                    let id = *corners.entry(key).or_insert_with(|| {
                        corner_list.push(key);
                        corner_positions.push(positions[p as usize]);
                        next
                    });
                    face.push(id);
                }
                triangulate_face(&corner_positions, &face, &mut triangles).map_err(err)?;
            }
            "o" | "g" | "s" | "usemtl" | "mtllib" | "l" | "p" | "vp" => {}
            other => return Err(err(format!("unknown statement `{other}`"))),
        }
    }
    if triangles.is_empty() {
        return Err(Error::Parse {
            path: path.to_path_buf(),
            line: None,
            message: "no faces".into(),
        });
    }
    let mesh_positions = corner_list
        .iter()
        .map(|c| positions[c.0 as usize])
        .collect();
    let mut mesh = Mesh::new(mesh_positions, triangles).map_err(|e| Error::Parse {
        path: path.to_path_buf(),
        line: None,
        message: e.to_string(),
    })?;
    if corner_list.iter().all(|c| c.1.is_some()) {
        mesh.uvs = Some(
            corner_list
                .iter()
                .map(|c| uvs[c.1.unwrap_or(0) as usize])
                .collect(),
        );
    }
    if corner_list.iter().all(|c| c.2.is_some()) {
        mesh.normals = corner_list
            .iter()
            .map(|c| normals[c.2.unwrap_or(0) as usize].normalize_or(Vec3::Z))
            .collect();
    }
    if colors.len() == positions.len() {
        mesh.colors = Some(corner_list.iter().map(|c| colors[c.0 as usize]).collect());
    }
    Ok(mesh)
}

/// Between `min` and `max` finite numbers.
fn floats(args: &[&str], min: usize, max: usize, what: &str) -> Result<Vec<f32>, String> {
    if args.len() < min || args.len() > max {
        return Err(format!(
            "`{what}` takes {min} to {max} numbers, found {}",
            args.len()
        ));
    }
    args.iter()
        .map(|a| match a.parse::<f32>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(format!("`{a}` is not a finite number")),
            Err(_) => Err(format!("`{a}` is not a number")),
        })
        .collect()
}

/// A 1-based or negative (relative) OBJ index, resolved against `count`
/// elements defined so far; `None` for an empty field.
fn resolve(field: Option<&str>, count: usize, what: &str) -> Result<Option<u32>, String> {
    let Some(field) = field.filter(|f| !f.is_empty()) else {
        return Ok(None);
    };
    let i: i64 = field
        .parse()
        .map_err(|_| format!("`{field}` is not a {what} index"))?;
    let zero_based = if i > 0 { i - 1 } else { count as i64 + i };
    if i == 0 || zero_based < 0 || zero_based >= count as i64 {
        return Err(format!(
            "{what} index {i} is out of range ({count} defined so far)"
        ));
    }
    Ok(Some(zero_based as u32))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error_line(text: &str) -> Option<usize> {
        match parse_obj(text, Path::new("m.obj")) {
            Err(Error::Parse { line, .. }) => line,
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    #[test]
    fn reads_quads_uvs_normals_and_negative_indices() {
        let text = "# a quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 2\ng quad\nf -4/1/1 -3/2/1 -2/3/1 -1/4/1\n";
        let m = parse_obj(text, Path::new("q.obj")).unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.uvs.as_ref().unwrap()[2], Vec2::new(1.0, 1.0));
        assert_eq!(m.normals[3], Vec3::Z);
    }

    #[test]
    fn malformed_lines_are_named() {
        assert_eq!(error_line("v 0 0\n"), Some(1));
        assert_eq!(error_line("v 0 0 0\nv 1 x 0\n"), Some(2));
        assert_eq!(error_line("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"), Some(4));
        assert_eq!(error_line("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n"), Some(4));
        assert_eq!(
            error_line("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/5 2 3\n"),
            Some(4)
        );
        assert_eq!(error_line("v 0 0 0\nv inf 0 0\n"), Some(2));
        assert_eq!(error_line("bogus 1 2\n"), Some(1));
        assert_eq!(error_line("v 0 0 0\n"), None);
    }
}
