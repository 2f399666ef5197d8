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
/// columns, and the faces: each a triangle in one array, which becomes the
/// mesh's as it is when every face is a triangle (the scans), and any
/// other face's indices kept aside.
#[derive(Default)]
#[cfg_attr(test, derive(Debug))]
pub(super) struct Payload {
    positions: Vec<Vec3>,
    /// Normals, colours and texture coordinates, when the vertex element
    /// declares them.
    normals: Option<Vec<Vec3>>,
    colors: Option<Vec<Vec3>>,
    uvs: Option<Vec<Vec2>>,
    /// One entry per face: its indices if it is a triangle, zeros if not.
    faces: Vec<[u32; 3]>,
    /// The faces that are not triangles: the entry of each in `faces`, and
    /// where its indices end in `other_indices`.
    other_faces: Vec<(usize, usize)>,
    other_indices: Vec<u32>,
    /// The indices of the face being read.
    pub(super) pending: Vec<u32>,
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
        self.clear_face_columns();
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
        reserve(&mut self.faces, n);
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

    /// An empty payload with the same vertex columns as this one: what
    /// one block of lines is read into before [`Payload::append`] joins
    /// it to the rest.
    pub(super) fn empty_like(&self) -> Payload {
        Payload {
            positions: Vec::new(),
            normals: self.normals.as_ref().map(|_| Vec::new()),
            colors: self.colors.as_ref().map(|_| Vec::new()),
            uvs: self.uvs.as_ref().map(|_| Vec::new()),
            faces: Vec::new(),
            other_faces: Vec::new(),
            other_indices: Vec::new(),
            pending: Vec::new(),
            face_error: None,
        }
    }

    /// Appends the elements `next` holds, read from the lines that follow
    /// this payload's: its vertices after these, its faces after these
    /// (the other faces' places moved past the faces here), and its unusable
    /// face only if none came before.
    pub(super) fn append(&mut self, next: &Payload) {
        self.positions.extend_from_slice(&next.positions);
        for (column, more) in [
            (&mut self.normals, &next.normals),
            (&mut self.colors, &next.colors),
        ] {
            if let (Some(column), Some(more)) = (column, more) {
                column.extend_from_slice(more);
            }
        }
        if let (Some(uvs), Some(more)) = (&mut self.uvs, &next.uvs) {
            uvs.extend_from_slice(more);
        }
        let (faces, indices) = (self.faces.len(), self.other_indices.len());
        self.other_faces.extend(
            next.other_faces
                .iter()
                .map(|&(face, end)| (faces + face, indices + end)),
        );
        self.other_indices.extend_from_slice(&next.other_indices);
        self.faces.extend_from_slice(&next.faces);
        if self.face_error.is_none() {
            self.face_error.clone_from(&next.face_error);
        }
    }

    /// Empties every column, keeping their memory.
    pub(super) fn clear(&mut self) {
        self.positions.clear();
        for column in [&mut self.normals, &mut self.colors].into_iter().flatten() {
            column.clear();
        }
        if let Some(uvs) = &mut self.uvs {
            uvs.clear();
        }
        self.clear_face_columns();
    }

    /// Empties the faces, keeping their memory.
    fn clear_face_columns(&mut self) {
        self.faces.clear();
        self.other_faces.clear();
        self.other_indices.clear();
        self.pending.clear();
        self.face_error = None;
    }

    /// Adds a triangle.
    #[inline(always)]
    pub(super) fn push_triangle(&mut self, triangle: [u32; 3]) {
        self.faces.push(triangle);
    }

    /// Adds a face of any number of vertices (fewer than three is an
    /// error, reported in file order with the others by
    /// [`Payload::into_mesh`]).
    pub(super) fn push_face(&mut self, indices: &[u32]) {
        if let &[a, b, c] = indices {
            self.faces.push([a, b, c]);
        } else {
            self.other_indices.extend_from_slice(indices);
            self.other_faces
                .push((self.faces.len(), self.other_indices.len()));
            self.faces.push([0; 3]);
        }
    }

    /// Adds the face whose indices are [`Payload::pending`], and empties
    /// it.
    pub(super) fn push_pending_face(&mut self) {
        let pending = std::mem::take(&mut self.pending);
        self.push_face(&pending);
        self.pending = pending;
        self.pending.clear();
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
                .map_err(|m| located(vertex_line + i, format!("`vertex` {i}: {m}")))?;
        }
        let positions = self.positions;
        let out_of_range = |i: usize, bad: u32| {
            located(
                face_line + i,
                format!(
                    "`face` {i}: vertex index {bad} is out of range for {} vertices",
                    positions.len()
                ),
            )
        };
        let triangles =
            if self.other_faces.is_empty() && self.face_error.is_none() {
                // Every face a triangle: the array is the mesh's, once its
                // indices are checked.
                let n = positions.len();
                if let Some((i, bad)) = self.faces.iter().enumerate().find_map(|(i, face)| {
                    face.iter().find(|&&k| k as usize >= n).map(|&bad| (i, bad))
                }) {
                    return Err(out_of_range(i, bad));
                }
                self.faces
            } else {
                let mut triangles = Vec::with_capacity(self.faces.len());
                let mut others = self.other_faces.iter().peekable();
                let mut start = 0;
                for (i, triangle) in self.faces.iter().enumerate() {
                    let line = face_line + i;
                    let face = match others.next_if(|&&(face, _)| face == i) {
                        Some(&(_, end)) => {
                            let face = &self.other_indices[start..end];
                            start = end;
                            face
                        }
                        None => triangle.as_slice(),
                    };
                    if let Some((_, message)) = self.face_error.as_ref().filter(|(k, _)| *k == i) {
                        return Err(located(line, format!("`face` {i}: {message}")));
                    }
                    if face.len() < 3 {
                        return Err(located(
                            line,
                            format!(
                                "`face` {i} has {} vertices; a face needs at least 3",
                                face.len()
                            ),
                        ));
                    }
                    if let Some(&bad) = face.iter().find(|&&k| k as usize >= positions.len()) {
                        return Err(out_of_range(i, bad));
                    }
                    if let &[a, b, c] = face {
                        triangles.push([a, b, c]);
                    } else {
                        triangulate_face(&positions, face, &mut triangles)
                            .map_err(|m| located(line, format!("`face` {i}: {m}")))?;
                    }
                }
                triangles
            };
        let mut mesh = Mesh::from_checked(positions, triangles, self.normals)
            .map_err(|e| located(face_line, e.to_string()))?;
        mesh.colors = self
            .colors
            .map(|c| c.into_iter().map(|c| Vec4::from((c, 1.0))).collect());
        mesh.uvs = self.uvs;
        Ok(mesh)
    }
}
