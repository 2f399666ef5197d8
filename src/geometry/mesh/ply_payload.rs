//! What a PLY file's elements hold once read, whatever their encoding
//! (ASCII lines or binary records): the vertex columns the mesh keeps and
//! the faces' indices. Both readers ([`super::ply`]'s binary path and
//! [`super::ply_ascii`]) fill one [`Payload`].

use super::{face::triangulate_face, Mesh};
use crate::error::{Error, Result};
use glam::{Vec2, Vec3, Vec4};
use ply_rs_bw::ply::ElementDef;

/// Elements reserved at most from a header's count.
const MAX_RESERVED: usize = 1 << 24;

/// Reserves room for `n` more elements (at most [`MAX_RESERVED`]), so
/// that a column read from a file is written once, where it stays,
/// instead of copied at every doubling into memory touched for the first
/// time. Reserving takes address space, not memory: pages are only
/// given when written, so a header claiming more elements than the file
/// holds costs nothing. Where even the address space is refused, the
/// column grows as it is read.
fn reserve<T>(column: &mut Vec<T>, n: usize) {
    if column.try_reserve_exact(n.min(MAX_RESERVED)).is_err() {
        column.reserve(n.min(1 << 16));
    }
}

/// A vertex property the mesh keeps, in the order of a vertex's columns.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum VertexColumn {
    X,
    Y,
    Z,
    Nx,
    Ny,
    Nz,
    Red,
    Green,
    Blue,
    U,
    V,
}

impl VertexColumn {
    /// The number of columns.
    pub(super) const COUNT: usize = 11;

    /// The column of a vertex property, by its name.
    pub(super) fn of(name: &str) -> Option<VertexColumn> {
        use VertexColumn::*;
        Some(match name {
            "x" => X,
            "y" => Y,
            "z" => Z,
            "nx" => Nx,
            "ny" => Ny,
            "nz" => Nz,
            "red" => Red,
            "green" => Green,
            "blue" => Blue,
            "u" | "s" | "texture_u" | "texture_s" => U,
            "v" | "t" | "texture_v" | "texture_t" => V,
            _ => return None,
        })
    }

    /// Whether the column is a colour channel.
    pub(super) fn is_color(self) -> bool {
        matches!(
            self,
            VertexColumn::Red | VertexColumn::Green | VertexColumn::Blue
        )
    }
}

/// What a PLY file's elements hold, whatever its encoding: the vertices'
/// columns, and the faces' indices one after the other.
#[derive(Default)]
pub(super) struct Payload {
    positions: Vec<Vec3>,
    /// Normals, colours and texture coordinates, when the vertex element
    /// declares them.
    normals: Option<Vec<Vec3>>,
    colors: Option<Vec<Vec3>>,
    uvs: Option<Vec<Vec2>>,
    /// Every face's vertex indices, one face after the other.
    pub(super) indices: Vec<u32>,
    /// Where each face's indices end in `indices`.
    pub(super) face_ends: Vec<usize>,
    /// The first face whose indices are unusable, and why.
    pub(super) face_error: Option<(usize, String)>,
}

impl Payload {
    /// Empties the vertices, keeping the columns `def` declares.
    pub(super) fn clear_vertices(&mut self, def: &ElementDef) {
        let declared = |columns: &[VertexColumn]| {
            def.properties
                .keys()
                .any(|name| VertexColumn::of(name).is_some_and(|c| columns.contains(&c)))
        };
        use VertexColumn::*;
        self.positions.clear();
        self.normals = declared(&[Nx, Ny, Nz]).then(Vec::new);
        self.colors = declared(&[Red, Green, Blue]).then(Vec::new);
        self.uvs = declared(&[U, V]).then(Vec::new);
    }

    /// Empties the faces.
    pub(super) fn clear_faces(&mut self) {
        self.indices.clear();
        self.face_ends.clear();
        self.face_error = None;
    }

    /// Room for `n` more vertices.
    pub(super) fn reserve_vertices(&mut self, n: usize) {
        reserve(&mut self.positions, n);
        for c in [&mut self.normals, &mut self.colors].into_iter().flatten() {
            reserve(c, n);
        }
        if let Some(uvs) = &mut self.uvs {
            reserve(uvs, n);
        }
    }

    /// Room for `n` faces of three vertices.
    pub(super) fn reserve_faces(&mut self, n: usize) {
        reserve(&mut self.face_ends, n);
        reserve(&mut self.indices, n.saturating_mul(3));
    }

    /// Appends a vertex from its columns (`VertexColumn` order).
    #[inline]
    pub(super) fn push_vertex(&mut self, v: &[f64; VertexColumn::COUNT]) {
        let v = v.map(|c| c as f32);
        self.positions.push(Vec3::new(v[0], v[1], v[2]));
        if let Some(normals) = &mut self.normals {
            normals.push(Vec3::new(v[3], v[4], v[5]));
        }
        if let Some(colors) = &mut self.colors {
            colors.push(Vec3::new(v[6], v[7], v[8]));
        }
        if let Some(uvs) = &mut self.uvs {
            uvs.push(Vec2::new(v[9], v[10]));
        }
    }

    /// The mesh, once its positions and faces are checked; errors name
    /// the line of the vertex or face at fault (`located`).
    pub(super) fn into_mesh(
        self,
        vertex_line: usize,
        face_line: usize,
        located: impl Fn(usize, String) -> Error,
    ) -> Result<Mesh> {
        for (i, &p) in self.positions.iter().enumerate() {
            super::check_position(p)
                .map_err(|m| located(vertex_line + i, format!("vertex {i}: {m}")))?;
        }
        let positions = self.positions;
        let mut triangles = Vec::with_capacity(self.face_ends.len());
        let mut start = 0;
        for (i, &end) in self.face_ends.iter().enumerate() {
            let line = face_line + i;
            let face = &self.indices[start..end];
            start = end;
            if let Some((_, message)) = self.face_error.as_ref().filter(|(k, _)| *k == i) {
                return Err(located(line, format!("face {i}: {message}")));
            }
            if face.len() < 3 {
                return Err(located(
                    line,
                    format!(
                        "face {i} has {} vertices; a face needs at least 3",
                        face.len()
                    ),
                ));
            }
            if let Some(&bad) = face.iter().find(|&&k| k as usize >= positions.len()) {
                return Err(located(
                    line,
                    format!(
                        "face {i}: vertex index {bad} is out of range for {} vertices",
                        positions.len()
                    ),
                ));
            }
            if let &[a, b, c] = face {
                triangles.push([a, b, c]);
            } else {
                triangulate_face(&positions, face, &mut triangles)
                    .map_err(|m| located(line, format!("face {i}: {m}")))?;
            }
        }
        let mut mesh =
            Mesh::new(positions, triangles).map_err(|e| located(face_line, e.to_string()))?;
        if let Some(normals) = self.normals {
            mesh.normals = normals
                .into_iter()
                .map(|n| n.normalize_or(Vec3::Z))
                .collect();
        }
        mesh.colors = self
            .colors
            .map(|c| c.into_iter().map(|c| Vec4::from((c, 1.0))).collect());
        mesh.uvs = self.uvs;
        Ok(mesh)
    }
}
