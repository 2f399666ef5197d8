//! The stage for a line's pixels: steps 1 to 7 for a pixel of a line,
//! its depth and varyings from the pixel centre's projection onto the
//! segment, and a line whose colour is uniform shaded once.

use super::{color_of, merge_pixel, FragmentStage, Sample, Source};
use crate::raster::fragment::LineFragment;
use crate::raster::shader::{to_rgba8, FragmentShader};
use crate::raster::target::DepthTest;

impl<S: FragmentShader + ?Sized> FragmentStage<'_, S> {
    /// One line fragment: steps 1 to 7 of the stage for a pixel of a
    /// line (its depth and varyings from the pixel centre's projection
    /// onto the segment). Always inlined into the one-fragment and the
    /// many-fragment calls, so that a segment's pixels go through one
    /// loop rather than a call each (the `lines` workload of the
    /// `side_by_side` benchmark measures it).
    #[inline(always)]
    pub(super) fn line_sample(&mut self, f: &LineFragment) {
        // With the depth test off and a colour uniform per line, nothing
        // of the line's data depends on the pixel: it is shaded once and
        // its fragments only written (blended by their coverage), the
        // same bits as shading each, for a fraction of the cost of a short
        // line.
        let depth_off = self.depth.test == DepthTest::Always && !self.depth.write;
        if depth_off && self.shader.uniform_per_primitive() {
            let (color, rgba8) = match self.line_colour {
                Some((id, color, rgba8)) if id == f.line => (color, rgba8),
                _ => {
                    let Some(line) = self.lines.get(f.line as usize) else {
                        debug_assert!(false, "no vertex data for line {}", f.line);
                        return;
                    };
                    let sample = Sample {
                        x: f.x,
                        y: f.y,
                        primitive: f.line,
                        depth: line.vertices[0].depth,
                        screen: [1.0, 0.0],
                        vertices: line.vertices,
                        coverage: 1.0,
                    };
                    let color = color_of(self.shader, self.interpolation, &sample);
                    let rgba8 = to_rgba8(color);
                    self.line_colour = Some((f.line, color, rgba8));
                    (color, rgba8)
                }
            };
            // The test `always` reads no depth.
            if let Some(idx) = self.depth_test(f.x, f.y, 0.0) {
                let source = if f.coverage >= 1.0 {
                    Source::Rgba8(rgba8)
                } else {
                    Source::Shaded {
                        color,
                        coverage: f.coverage,
                    }
                };
                merge_pixel(self.blend, source, &mut self.target.color[idx], None);
            }
            return;
        }
        let Some(line) = self.lines.get(f.line as usize).copied() else {
            debug_assert!(false, "no vertex data for line {}", f.line);
            return;
        };
        // Parameter of the pixel centre's projection onto the snapped segment.
        let (ax, ay) = line.from.to_f64();
        let (bx, by) = line.to.to_f64();
        let (dx, dy) = (bx - ax, by - ay);
        let len2 = dx * dx + dy * dy;
        let (px, py) = (f64::from(f.x) + 0.5, f64::from(f.y) + 0.5);
        let t = if len2 > 0.0 {
            (((px - ax) * dx + (py - ay) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let [v0, v1] = line.vertices;
        let z0 = f64::from(v0.depth);
        let z = (z0 + t * (f64::from(v1.depth) - z0)) as f32 + self.line_depth_offset;
        let Some(idx) = self.depth_test(f.x, f.y, z) else {
            return;
        };
        let screen = [(1.0 - t) as f32, t as f32];
        self.write(
            idx,
            Sample {
                x: f.x,
                y: f.y,
                primitive: f.line,
                depth: z,
                screen,
                vertices: line.vertices,
                coverage: f.coverage,
            },
        );
    }
}
