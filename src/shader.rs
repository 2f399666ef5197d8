//! Built-in fragment shaders.
//!
//! A fragment shader calculates the colour of a fragment (seed 000, step 5).
//! [`Flat`] colours the whole primitive with its first (provoking)
//! vertex's colour; [`Gouraud`] interpolates the vertex colours with the
//! barycentric coordinates (seed 004: `c = alpha c_a + beta c_b + gamma c_c`).

use crate::stage::{FragmentInput, FragmentShader};
use glam::Vec4;

/// One colour per primitive: the provoking (first) vertex's.
#[derive(Copy, Clone, Debug, Default)]
pub struct Flat;

impl FragmentShader for Flat {
    fn shade(&self, input: &FragmentInput) -> Vec4 {
        input.flat.color
    }
}

/// Vertex colours interpolated across the primitive.
#[derive(Copy, Clone, Debug, Default)]
pub struct Gouraud;

impl FragmentShader for Gouraud {
    fn shade(&self, input: &FragmentInput) -> Vec4 {
        input.varyings.color
    }
}

/// A fixed colour for everything (seed 000's blue triangle, wireframes).
#[derive(Copy, Clone, Debug)]
pub struct Constant(pub Vec4);

impl FragmentShader for Constant {
    fn shade(&self, _input: &FragmentInput) -> Vec4 {
        self.0
    }
}
