//! A camera that frames a mesh: view and projection matrices (the software-rasterizer article).

use glam::{Mat4, Vec3};

/// A perspective camera looking at a point.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Camera {
    /// Eye position (world space).
    pub eye: Vec3,
    /// The point looked at.
    pub target: Vec3,
    /// Up direction.
    pub up: Vec3,
    /// Vertical field of view, radians.
    pub fov_y: f32,
    /// Width / height.
    pub aspect: f32,
    /// Near plane distance (> 0).
    pub near: f32,
    /// Far plane distance (> near).
    pub far: f32,
}

impl Camera {
    /// A camera that frames the bounding box `(min, max)` whole: it looks at
    /// the box centre from the direction given by `azimuth` (degrees around
    /// the vertical axis, 0 = from +Z) and `elevation` (degrees above the
    /// horizon), far enough for the bounding sphere to fit the narrower
    /// field of view, divided by `zoom`. Near and far planes hug the sphere.
    pub fn framing(
        bounds: (Vec3, Vec3),
        aspect: f32,
        azimuth: f32,
        elevation: f32,
        zoom: f32,
    ) -> Camera {
        let (lo, hi) = bounds;
        let centre = (lo + hi) * 0.5;
        let radius = ((hi - lo).length() * 0.5).max(1e-6);
        let fov_y = 40f32.to_radians();
        let fov_narrow = if aspect < 1.0 {
            2.0 * ((fov_y * 0.5).tan() * aspect).atan()
        } else {
            fov_y
        };
        let distance = radius / (fov_narrow * 0.5).tan() / zoom.max(1e-3);
        let (az, el) = (azimuth.to_radians(), elevation.to_radians());
        let dir = Vec3::new(el.cos() * az.sin(), el.sin(), el.cos() * az.cos());
        Camera {
            eye: centre + dir * distance,
            target: centre,
            up: Vec3::Y,
            fov_y,
            aspect,
            near: (distance - radius * 1.01).max(distance * 1e-3),
            far: distance + radius * 1.01,
        }
    }

    /// World space to view space (right-handed, looking down -Z).
    pub fn view(&self) -> Mat4 {
        Mat4::look_at_rh(self.eye, self.target, self.up)
    }

    /// View space to clip space, OpenGL convention (`-w <= z <= w`), as in
    /// the software-rasterizer article.
    pub fn projection(&self) -> Mat4 {
        Mat4::perspective_rh_gl(self.fov_y, self.aspect, self.near, self.far)
    }
}
