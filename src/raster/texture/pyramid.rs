//! The mip pyramid (Williams 1983): each level box-filtered from the one
//! before it, down to 1x1.
//!
//! A level of side `n` gives the next a side of `max(1, floor(n / 2))`,
//! Scotty3D's `generate_mipmap` rule. Each texel of the new level is the
//! exact average of the old level over the new texel's square, so a side
//! is weighted as follows (the weights of the two sides multiply):
//!
//! * side 1 stays 1: the one texel, weight 1;
//! * an even side `2n` becomes `n`: texel `i` takes old texels `2i` and
//!   `2i + 1`, each with weight `1/2`;
//! * an odd side `2n + 1` (`n >= 1`) becomes `n`: texel `i` covers
//!   `(2n + 1) / n` old texels, from `2i + i/n` to `2i + 2 + (i + 1)/n`,
//!   so it takes old texels `2i`, `2i + 1` and `2i + 2` with weights
//!   `(n - i) / (2n + 1)`, `n / (2n + 1)` and `(i + 1) / (2n + 1)`: the
//!   share of each old texel under the new one's square. A side of 3
//!   becomes 1 with weights `1/3, 1/3, 1/3`; a side of 5 becomes 2 with
//!   `2/5, 2/5, 1/5` and `1/5, 2/5, 2/5`.
//!
//! Every old texel thus gives the new level the same total weight, and the
//! last level, 1x1, is the average of the whole texture.

use super::Image;
use glam::Vec4;

/// The old texels one new texel of a side takes, with their weights: up
/// to three, unused ones with weight 0 (at index 0).
fn taps(old: u32, new_index: u32) -> [(u32, f32); 3] {
    let i = new_index;
    if old == 1 {
        [(0, 1.0), (0, 0.0), (0, 0.0)]
    } else if old.is_multiple_of(2) {
        [(2 * i, 0.5), (2 * i + 1, 0.5), (0, 0.0)]
    } else {
        let n = old / 2;
        let whole = f64::from(old);
        [
            (2 * i, (f64::from(n - i) / whole) as f32),
            (2 * i + 1, (f64::from(n) / whole) as f32),
            (2 * i + 2, (f64::from(i + 1) / whole) as f32),
        ]
    }
}

/// The next side after `side`: `max(1, floor(side / 2))`.
pub(super) fn next_side(side: u32) -> u32 {
    (side / 2).max(1)
}

/// The level after `level`, box-filtered from it.
pub(super) fn next_level(level: &Image) -> Image {
    let (width, height) = (next_side(level.width), next_side(level.height));
    let mut texels = Vec::with_capacity(width as usize * height as usize);
    for y in 0..height {
        let rows = taps(level.height, y);
        for x in 0..width {
            let columns = taps(level.width, x);
            let mut sum = Vec4::ZERO;
            for &(ty, wy) in &rows {
                for &(tx, wx) in &columns {
                    if wx * wy > 0.0 {
                        sum += level.texel(tx, ty) * (wx * wy);
                    }
                }
            }
            texels.push(sum);
        }
    }
    Image {
        width,
        height,
        texels,
    }
}

/// The sizes of a pyramid whose level 0 is `width` x `height`, level 0
/// first, down to 1x1.
pub(super) fn sizes(width: u32, height: u32) -> Vec<(u32, u32)> {
    let mut out = vec![(width, height)];
    let (mut w, mut h) = (width, height);
    while w > 1 || h > 1 {
        (w, h) = (next_side(w), next_side(h));
        out.push((w, h));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each new texel's weights sum to 1, and every old texel gets the
    /// same total weight over the new side (`new / old`).
    #[test]
    fn the_weights_of_a_side_are_a_box_filter() {
        for old in 1..200u32 {
            let new = next_side(old);
            let mut total = vec![0.0f64; old as usize];
            for i in 0..new {
                let t = taps(old, i);
                let sum: f64 = t.iter().map(|&(_, w)| f64::from(w)).sum();
                assert!((sum - 1.0).abs() < 1e-6, "side {old}, texel {i}: {sum}");
                for (k, w) in t {
                    assert!(k < old || w == 0.0, "side {old}, texel {i} reads {k}");
                    total[k as usize] += f64::from(w);
                }
            }
            let share = f64::from(new) / f64::from(old);
            for (k, t) in total.iter().enumerate() {
                assert!((t - share).abs() < 1e-6, "side {old}, old texel {k}: {t}");
            }
        }
    }

    #[test]
    fn sizes_follow_the_floor_rule_down_to_one() {
        assert_eq!(sizes(4, 6), vec![(4, 6), (2, 3), (1, 1)]);
        assert_eq!(sizes(5, 3), vec![(5, 3), (2, 1), (1, 1)]);
        assert_eq!(sizes(1, 7), vec![(1, 7), (1, 3), (1, 1)]);
        assert_eq!(sizes(1, 1), vec![(1, 1)]);
        assert_eq!(sizes(256, 512).len(), 10);
    }
}
