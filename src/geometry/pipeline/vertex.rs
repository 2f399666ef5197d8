//! Vertex specification and the vertex shader (the course chapter, steps 1 and 2;
//! the software-rasterizer article's frame changes).
//!
//! A vertex shader takes one vertex and returns its position in homogeneous
//! **clip space** plus the values to interpolate across the triangle. It is
//! a trait ([`VertexShader`]), implemented by any closure
//! `Fn(&V) -> ClipVertex`, and by [`Transform`], the usual
//! model-view-projection shader: `clip = P V M p`, with normals taken to
//! world space by the inverse transpose of the model matrix's upper 3x3
//! (so they stay perpendicular to surfaces under non-uniform scaling).

use super::clip::ClipVertex;
use crate::error::{Error, Result};
use crate::raster::primitive::Varyings;
use crate::raster::shader::DirectionalLight;
use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};

/// Runs once per vertex: model space in, clip space out.
pub trait VertexShader<V>: Sync {
    /// The vertex's clip-space position and varyings.
    fn shade(&self, vertex: &V) -> ClipVertex;

    /// When this shader is the model-view-projection [`Transform`] of
    /// [`MeshVertex`]es: itself and `vertices` as such. The pipeline then
    /// shades them eight at a time in vector registers, with the bits
    /// [`shade`](Self::shade) gives. Other shaders keep this default, `None`.
    fn as_transform<'v>(&self, vertices: &'v [V]) -> Option<(&Transform, &'v [MeshVertex])> {
        let _ = vertices;
        None
    }
}

impl<V, F> VertexShader<V> for F
where
    F: Fn(&V) -> ClipVertex + Sync,
{
    fn shade(&self, vertex: &V) -> ClipVertex {
        self(vertex)
    }
}

/// The course chapter's vertex specification: a flat array of `x, y, z` floats, three
/// per vertex, as in its C listing.
///
/// ```
/// use rasterlab::geometry::positions_from_floats;
///
/// // The course's array: v0 = (-1, 0, 0), v1 = (0, -1, 0), v2 = (-1, -1, 0).
/// let v = positions_from_floats(&[-1., 0., 0., 0., -1., 0., -1., -1., 0.]).unwrap();
/// assert_eq!(v.len(), 3);
/// assert!(positions_from_floats(&[1.0, 2.0]).is_err());
/// ```
pub fn positions_from_floats(values: &[f32]) -> Result<Vec<Vec3>> {
    if !values.len().is_multiple_of(3) {
        return Err(Error::BadArrayLength {
            what: "vertex array",
            len: values.len(),
            unit: "vertex",
        });
    }
    Ok(values.chunks_exact(3).map(Vec3::from_slice).collect())
}

/// A vertex of a mesh, as fed to [`Transform`].
///
/// Laid out as twelve `f32` (`repr(C)`, no padding): position, normal,
/// texture coordinates, colour. The vertex shader's AVX2 lanes read eight
/// of them as rows of floats and transpose them in registers.
#[derive(Copy, Clone, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct MeshVertex {
    /// Model-space position.
    pub position: Vec3,
    /// Model-space normal.
    pub normal: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// Linear RGBA colour.
    pub color: Vec4,
}

/// The model-view-projection vertex shader.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Transform {
    /// Model space to world space.
    pub model: Mat4,
    /// World space to view (camera) space.
    pub view: Mat4,
    /// View space to clip space.
    pub projection: Mat4,
    /// `projection * view * model`.
    pub mvp: Mat4,
    /// Inverse transpose of the model matrix's 3x3 part, for normals.
    pub normal_matrix: Mat3,
    /// When set, the light is evaluated per vertex and the result scales
    /// the vertex colour (Gouraud lighting); when not, the colour passes
    /// through and a fragment shader may light per fragment.
    pub vertex_light: Option<DirectionalLight>,
}

impl Transform {
    /// The shader for these three matrices, without per-vertex lighting.
    pub fn new(model: Mat4, view: Mat4, projection: Mat4) -> Transform {
        Transform {
            model,
            view,
            projection,
            mvp: projection * view * model,
            normal_matrix: Mat3::from_mat4(model).inverse().transpose(),
            vertex_light: None,
        }
    }

    /// The identity: positions are already in clip space (the course chapter).
    pub fn identity() -> Transform {
        Transform::new(Mat4::IDENTITY, Mat4::IDENTITY, Mat4::IDENTITY)
    }

    /// Lights every vertex with `light`.
    pub fn with_vertex_light(mut self, light: DirectionalLight) -> Transform {
        self.vertex_light = Some(light);
        self
    }
}

impl VertexShader<MeshVertex> for Transform {
    fn as_transform<'v>(
        &self,
        vertices: &'v [MeshVertex],
    ) -> Option<(&Transform, &'v [MeshVertex])> {
        Some((self, vertices))
    }

    #[inline]
    fn shade(&self, v: &MeshVertex) -> ClipVertex {
        let normal = self.normal_matrix * v.normal;
        let color = match self.vertex_light {
            Some(light) => (v.color.truncate() * light.intensity(normal)).extend(v.color.w),
            None => v.color,
        };
        ClipVertex {
            position: self.mvp * v.position.extend(1.0),
            varyings: Varyings {
                color,
                uv: v.uv,
                normal,
            },
        }
    }
}

impl VertexShader<Vec3> for Transform {
    #[inline]
    fn shade(&self, p: &Vec3) -> ClipVertex {
        ClipVertex {
            position: self.mvp * p.extend(1.0),
            varyings: Varyings::color(Vec4::ONE),
        }
    }
}
