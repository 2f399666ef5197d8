//! Indexed triangle meshes and their loaders.
//!
//! A [`Mesh`] is the course's *vertex specification* (the course chapter, step 1) for
//! real data: an array of vertex positions and an array of triangles, each
//! three indices into it. Loaders:
//!
//! * [`ply`]: PLY, ASCII or binary, optionally gzip-compressed (the Stanford
//!   scans): the header and binary payloads read with the `ply-rs-bw`
//!   crate, ASCII payloads line by line into columns, a compressed file
//!   inflated on a second thread while the first parses;
//! * [`obj`]: Wavefront OBJ (`v`, `vt`, `vn`, `f`).
//!
//! Every loader reports a malformed file as [`Error::Parse`] naming the file
//! and, where the format has lines, the line. Faces with more than three
//! vertices are split into triangles by [`face::triangulate_face`] (a fan
//! when convex, a constrained Delaunay triangulation when concave). Missing normals are computed from the faces
//! (area-weighted, [`Mesh::compute_normals`]); missing texture coordinates can
//! be generated ([`Mesh::planar_uvs`]).

pub(crate) mod face;
mod inflate;
pub(crate) mod obj;
pub(crate) mod ply;
mod ply_ascii;
mod ply_blocks;
mod ply_payload;

pub use face::triangulate_face;
pub use obj::{load_obj, parse_obj};
pub use ply::{load_ply, read_ply};

use crate::error::{Error, Result};
use glam::{Vec2, Vec3, Vec4};
use std::path::Path;

/// The largest coordinate magnitude a mesh vertex may have: framing a mesh
/// squares its coordinates, which past about 1e19 overflow `f32`.
pub const MAX_COORDINATE: f32 = 1e15;

/// Errors unless every coordinate of `p` is finite and at most
/// [`MAX_COORDINATE`] in magnitude; the message names the coordinate.
pub(crate) fn check_position(p: Vec3) -> std::result::Result<(), String> {
    match p
        .to_array()
        .into_iter()
        .find(|c| !c.is_finite() || c.abs() > MAX_COORDINATE)
    {
        Some(c) if !c.is_finite() => Err(format!("coordinate {c} is not a finite number")),
        Some(c) => Err(format!(
            "coordinate {c} is beyond the largest a mesh may use (|coordinate| <= {MAX_COORDINATE})"
        )),
        None => Ok(()),
    }
}

/// An indexed triangle mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// Vertex positions (model space).
    pub positions: Vec<Vec3>,
    /// One unit normal per vertex (from the file, or computed).
    pub normals: Vec<Vec3>,
    /// Texture coordinates per vertex, when the file has them.
    pub uvs: Option<Vec<Vec2>>,
    /// Linear RGBA colour per vertex, when the file has them.
    pub colors: Option<Vec<Vec4>>,
    /// Triangles as three vertex indices, in file order.
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// A mesh from positions and triangles, with computed normals.
    ///
    /// Errors: no triangles, a non-finite position, or an index out of range.
    ///
    /// ```
    /// use glam::Vec3;
    /// use rasterlab::geometry::Mesh;
    ///
    /// let quad = Mesh::new(
    ///     vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )
    /// .unwrap();
    /// assert_eq!(quad.normals[0], Vec3::Z);
    /// assert!(Mesh::new(vec![Vec3::ZERO], vec![[0, 0, 7]]).is_err());
    /// ```
    pub fn new(positions: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> Result<Mesh> {
        validate(&positions, &triangles)?;
        Mesh::from_checked(positions, triangles, None)
    }

    /// A mesh from positions and triangles a loader has checked (finite
    /// positions within [`MAX_COORDINATE`], indices in range), with the
    /// file's normals made unit length or, without them, computed ones.
    /// Errors only if there are no triangles.
    fn from_checked(
        positions: Vec<Vec3>,
        triangles: Vec<[u32; 3]>,
        normals: Option<Vec<Vec3>>,
    ) -> Result<Mesh> {
        if triangles.is_empty() {
            return Err(Error::Empty("mesh (no triangles)".into()));
        }
        let normals = match normals {
            Some(normals) => normals
                .into_iter()
                .map(|n| n.normalize_or(Vec3::Z))
                .collect(),
            None => compute_normals(&positions, &triangles),
        };
        Ok(Mesh {
            positions,
            normals,
            uvs: None,
            colors: None,
            triangles,
        })
    }

    /// Loads a mesh by file extension: `.ply`, `.ply.gz` or `.obj`.
    pub fn load(path: &Path) -> Result<Mesh> {
        match MeshFormat::of(path) {
            Some(MeshFormat::Ply) => ply::load_ply(path),
            Some(MeshFormat::Obj) => obj::load_obj(path),
            None => Err(Error::Parse {
                path: path.to_path_buf(),
                line: None,
                message: "unknown mesh format: expected a .ply, .ply.gz or .obj file".into(),
            }),
        }
    }

    /// Whether a path names a mesh file this module can load (by its
    /// extension, in any case).
    pub fn is_mesh_path(path: &Path) -> bool {
        MeshFormat::of(path).is_some()
    }

    /// Replaces the normals by area-weighted face normals (the cross product
    /// of two edges is twice the face's area times its unit normal, so
    /// summing un-normalised cross products weights each face by its area).
    pub fn compute_normals(&mut self) {
        self.normals = compute_normals(&self.positions, &self.triangles);
    }

    /// The axis-aligned bounding box `(min, max)` of the positions.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        )
    }

    /// Texture coordinates generated by a planar mapping: the positions
    /// projected onto the plane of the bounding box's two longest sides,
    /// scaled so the longest side spans `[0, 1]` (no seams, unlike a
    /// spherical mapping).
    pub fn planar_uvs(&self) -> Vec<Vec2> {
        let (lo, hi) = self.bounds();
        let size = hi - lo;
        let mut axes = [0usize, 1, 2];
        axes.sort_by(|&a, &b| size[b].total_cmp(&size[a]));
        let (u_axis, v_axis) = (axes[0].min(axes[1]), axes[0].max(axes[1]));
        let scale = 1.0 / size[axes[0]].max(f32::MIN_POSITIVE);
        self.positions
            .iter()
            .map(|p| {
                Vec2::new(
                    (p[u_axis] - lo[u_axis]) * scale,
                    (hi[v_axis] - p[v_axis]) * scale,
                )
            })
            .collect()
    }

    /// The texture coordinates from the file, or generated ones.
    pub fn uvs_or_generated(&self) -> Vec<Vec2> {
        self.uvs.clone().unwrap_or_else(|| self.planar_uvs())
    }
}

/// The mesh formats, told apart by file name.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum MeshFormat {
    Ply,
    Obj,
}

impl MeshFormat {
    /// `.ply` or `.ply.gz`, `.obj` (any case); `None` otherwise.
    fn of(path: &Path) -> Option<MeshFormat> {
        let name = path.file_name()?.to_string_lossy().to_lowercase();
        if name.ends_with(".ply") || name.ends_with(".ply.gz") {
            Some(MeshFormat::Ply)
        } else if name.ends_with(".obj") {
            Some(MeshFormat::Obj)
        } else {
            None
        }
    }
}

/// Checks a mesh's data: at least one triangle, finite positions within
/// [`MAX_COORDINATE`], indices in range.
fn validate(positions: &[Vec3], triangles: &[[u32; 3]]) -> Result<()> {
    if triangles.is_empty() {
        return Err(Error::Empty("mesh (no triangles)".into()));
    }
    if let Some((i, message)) = positions
        .iter()
        .enumerate()
        .find_map(|(i, &p)| check_position(p).err().map(|m| (i, m)))
    {
        return Err(Error::InvalidArgument(format!("vertex {i}: {message}")));
    }
    Error::check_indices(triangles.iter().flatten(), positions.len())
}

/// Area-weighted vertex normals; vertices on no face get `+Z`.
fn compute_normals(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let mut sum = vec![Vec3::ZERO; positions.len()];
    for t in triangles {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let n = (b - a).cross(c - a);
        for &i in t {
            sum[i as usize] += n;
        }
    }
    sum.into_iter().map(|n| n.normalize_or(Vec3::Z)).collect()
}
