//! What a back-end did to each pixel of a small grid, recorded as it
//! draws: the fragments it emitted (with their coverage, for `wu`) and
//! the pixels where it evaluated the inside test (from the walk's
//! recorded steps). A grid picture's cells
//! are this record: green for fragments, sky blue for samples tested and
//! found outside, white for pixels never looked at.

use super::{mix, INSIDE, TESTED_OUTSIDE, UNTESTED};
use crate::raster::fragment::{FragmentSink, LineFragment, TriangleFragment};
use crate::raster::triangle::WalkStep;

/// Records what a back-end did to each pixel of a small grid.
pub(super) struct Recorder {
    width: u32,
    tested: Vec<bool>,
    weight: Vec<f32>,
}

impl Recorder {
    pub(super) fn new(width: u32, height: u32) -> Recorder {
        let n = (width * height) as usize;
        Recorder {
            width,
            tested: vec![false; n],
            weight: vec![0.0; n],
        }
    }

    fn index(&self, x: u32, y: u32) -> usize {
        (y * self.width + x) as usize
    }

    /// Green for fragments (strength = weight), red for tested-outside.
    pub(super) fn cells(&self) -> Vec<[u8; 3]> {
        self.weight
            .iter()
            .zip(&self.tested)
            .map(|(&w, &tested)| {
                if w > 0.0 {
                    // Faint fragments stay visibly green.
                    mix(UNTESTED, INSIDE, w.clamp(0.1, 1.0))
                } else if tested {
                    TESTED_OUTSIDE
                } else {
                    UNTESTED
                }
            })
            .collect()
    }
}

impl FragmentSink for Recorder {
    fn triangle_fragment(&mut self, f: &TriangleFragment) {
        let i = self.index(f.x, f.y);
        self.weight[i] += 1.0;
    }

    fn line_fragment(&mut self, f: &LineFragment) {
        let i = self.index(f.x, f.y);
        self.weight[i] += f.coverage;
    }
}

impl Recorder {
    /// Marks the samples a triangle walk tested, as its steps recorded
    /// them.
    pub(super) fn tested_in(&mut self, steps: &[WalkStep]) {
        for step in steps {
            if let WalkStep::Sample { x, y, .. } = *step {
                let i = self.index(x as u32, y as u32);
                self.tested[i] = true;
            }
        }
    }
}
