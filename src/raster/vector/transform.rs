//! The model-view-projection vertex shader, the perspective divide, the
//! viewport transform and the snap, for eight vertices at once: one vertex
//! per lane, eight lanes of `f32` in one AVX2 register (and, for the
//! `f64` steps, two registers of four).
//!
//! It does the one-vertex path's arithmetic operation for operation, in
//! the same order and the same precision (the transform and the light in
//! `f32`, the divide and the snap in `f64`), so each lane gets the bits
//! that path gives; IEEE arithmetic, square root and division included,
//! rounds the same in a lane as alone. Only the common case is done
//! here: a vertex inside every clip plane, finite, that snaps within the
//! guard band. A lane that is not is left clear in
//! [`Lanes::on_screen`], and the caller runs the one-vertex path on it,
//! which finds its out-code or says why it is refused. So a lane this
//! code wrongly left to the one-vertex path would cost only time; a lane
//! it wrongly kept would be wrong, and the tests look for those on each
//! plane's last `f32` and on random vertices, NaN and infinities
//! included.
//!
//! The clip planes' tests are the signs of `f64` sums of exact products,
//! which are the signs of comparisons: `z + w >= 0` is `z >= -w`, and the
//! guard plane `x + g w >= 0` (`g` the guard-band factor of
//! [`Uniforms::guard`]) is `x >= -(g w)`, with `g w` exact in `f64` (a
//! product of two `f32` has at most 48 significant bits).

#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::*;

/// What the shader computes with, the same for every vertex of a draw.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Uniforms {
    /// `projection * view * model`, by columns.
    pub mvp: [[f32; 4]; 4],
    /// The normal matrix, by columns.
    pub normal_matrix: [[f32; 3]; 3],
    /// The light evaluated per vertex, if any: its direction, ambient and
    /// diffuse parts.
    pub light: Option<([f32; 3], f32, f32)>,
    /// The clip volume's guard-band factors: `|x| <= g[0] w`, `|y| <= g[1] w`.
    pub guard: [f32; 2],
    /// The smallest `w` the clip volume keeps.
    pub w_min: f32,
    /// The viewport's width and height in pixels.
    pub size: [f64; 2],
}

/// Eight vertices' inputs as records of twelve `f32` each, a mesh
/// vertex's layout: position (3), normal (3), texture coordinates (2),
/// colour (4; alpha passes through unchanged).
pub(crate) type Records = [[f32; 12]; 8];

/// Eight vertices' results, one array per component.
#[derive(Copy, Clone, Debug, Default)]
pub(crate) struct Lanes {
    /// Bit `i` set: vertex `i` is inside every clip plane and snapped, and
    /// its results below are set. Clear: the one-vertex path must shade it.
    pub on_screen: u8,
    /// Snapped position, raw fixed-point units.
    pub x: [i32; 8],
    /// Snapped position, raw fixed-point units.
    pub y: [i32; 8],
    /// Depth in `[0, 1]`.
    pub depth: [f32; 8],
    /// `1 / w`.
    pub inv_w: [f32; 8],
    /// World-space normal.
    pub normal: [[f32; 8]; 3],
    /// Colour, lit when the uniforms have a light.
    pub rgb: [[f32; 8]; 3],
}

/// Shades, divides and snaps eight vertices into `out`, if this CPU has
/// AVX2 (and the tests allow it); false, with nothing written, if not.
/// Each record is read as three rows of four floats, and the rows are
/// transposed into lanes in registers.
#[inline]
pub(crate) fn shade(uniforms: &Uniforms, records: &Records, out: &mut Lanes) -> bool {
    #[cfg(target_arch = "x86_64")]
    if super::widest().min(super::allowed()) == super::Width::Avx2 {
        // SAFETY: the CPU has AVX2, checked just above.
        unsafe { shade_avx2(uniforms, records, out) };
        return true;
    }
    let _ = (uniforms, records, out);
    false
}

/// Broadcasts `x` to every lane.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn splat(x: f32) -> __m256 {
    _mm256_set1_ps(x)
}

/// `((c0 a + c1 b) + c2 c)`: a matrix row applied to three lanes, in
/// glam's order.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn row(c: [f32; 3], [a, b, d]: [__m256; 3]) -> __m256 {
    let ab = _mm256_add_ps(_mm256_mul_ps(splat(c[0]), a), _mm256_mul_ps(splat(c[1]), b));
    _mm256_add_ps(ab, _mm256_mul_ps(splat(c[2]), d))
}

/// `(a0 b0 + a1 b1) + a2 b2`, glam's dot product, lane by lane.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn dot(a: [__m256; 3], b: [__m256; 3]) -> __m256 {
    let xy = _mm256_add_ps(_mm256_mul_ps(a[0], b[0]), _mm256_mul_ps(a[1], b[1]));
    _mm256_add_ps(xy, _mm256_mul_ps(a[2], b[2]))
}

/// The lanes where `|v|` is finite.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn finite(v: __m256) -> __m256 {
    let magnitude = _mm256_andnot_ps(splat(-0.0), v);
    _mm256_cmp_ps::<_CMP_LT_OQ>(magnitude, splat(f32::INFINITY))
}

/// Lanes 0..4 (`HALF` 0) or 4..8 (`HALF` 1), widened to `f64`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn widen<const HALF: i32>(v: __m256) -> __m256d {
    _mm256_cvtps_pd(_mm256_extractf128_ps::<HALF>(v))
}

/// The divide, viewport transform and snap of four lanes of a half.
#[cfg(target_arch = "x86_64")]
struct Half {
    /// Lanes inside the guard planes whose snapped position is in the
    /// guard band.
    ok: i32,
    x: __m128i,
    y: __m128i,
    depth: __m128,
    inv_w: __m128,
}

/// [`Half`] of the clip-space lanes `x, y, z, w` (`HALF` as in [`widen`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn divide_and_snap<const HALF: i32>(u: &Uniforms, [x, y, z, w]: [__m256; 4]) -> Half {
    let (x, y, z, w) = (
        widen::<HALF>(x),
        widen::<HALF>(y),
        widen::<HALF>(z),
        widen::<HALF>(w),
    );
    let one = _mm256_set1_pd(1.0);
    let half = _mm256_set1_pd(0.5);
    let negate = |v| _mm256_xor_pd(v, _mm256_set1_pd(-0.0));
    // The guard planes: exact products, compared.
    let gx = _mm256_mul_pd(_mm256_set1_pd(u.guard[0].into()), w);
    let gy = _mm256_mul_pd(_mm256_set1_pd(u.guard[1].into()), w);
    let inside = _mm256_and_pd(
        _mm256_and_pd(
            _mm256_cmp_pd::<_CMP_GE_OQ>(x, negate(gx)),
            _mm256_cmp_pd::<_CMP_LE_OQ>(x, gx),
        ),
        _mm256_and_pd(
            _mm256_cmp_pd::<_CMP_GE_OQ>(y, negate(gy)),
            _mm256_cmp_pd::<_CMP_LE_OQ>(y, gy),
        ),
    );
    // Viewport::to_screen.
    let px = _mm256_mul_pd(
        _mm256_mul_pd(_mm256_add_pd(_mm256_div_pd(x, w), one), half),
        _mm256_set1_pd(u.size[0]),
    );
    let py = _mm256_mul_pd(
        _mm256_mul_pd(_mm256_sub_pd(one, _mm256_div_pd(y, w)), half),
        _mm256_set1_pd(u.size[1]),
    );
    let depth = _mm256_mul_pd(_mm256_add_pd(_mm256_div_pd(z, w), one), half);
    let depth = _mm256_min_pd(_mm256_max_pd(depth, _mm256_setzero_pd()), one);
    let inv_w = _mm256_div_pd(one, w);
    // Fixed::snap_f64: rounded to nearest, ties to even, in 1/256 pixel;
    // refused at the guard band (NaN and infinities fail the test too).
    let scale = _mm256_set1_pd(crate::raster::fixed::SUBPIXEL_SCALE as f64);
    let limit = _mm256_set1_pd(
        (crate::raster::fixed::GUARD_BAND * crate::raster::fixed::SUBPIXEL_SCALE) as f64,
    );
    let round = |v| {
        _mm256_round_pd::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(_mm256_mul_pd(
            v, scale,
        ))
    };
    let (sx, sy) = (round(px), round(py));
    let magnitude = |v| _mm256_andnot_pd(_mm256_set1_pd(-0.0), v);
    let in_band = _mm256_and_pd(
        _mm256_cmp_pd::<_CMP_LT_OQ>(magnitude(sx), limit),
        _mm256_cmp_pd::<_CMP_LT_OQ>(magnitude(sy), limit),
    );
    Half {
        ok: _mm256_movemask_pd(_mm256_and_pd(inside, in_band)),
        x: _mm256_cvtpd_epi32(sx),
        y: _mm256_cvtpd_epi32(sy),
        depth: _mm256_cvtpd_ps(depth),
        inv_w: _mm256_cvtpd_ps(inv_w),
    }
}

/// [`shade`] on a CPU with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn shade_avx2(u: &Uniforms, r: &Records, out: &mut Lanes) {
    // Floats `at..at + 4` of every record, as four lanes of components:
    // rows 0-3 in the low halves and 4-7 in the high ones, then the
    // classic 4x4 transpose in each half.
    let columns = |at: usize| {
        let row = |k: usize| {
            let four = &r[k][at..at + 4];
            // SAFETY: `four` is four readable `f32`; no alignment needed.
            unsafe { _mm_loadu_ps(four.as_ptr()) }
        };
        let pair = |k: usize| _mm256_insertf128_ps::<1>(_mm256_castps128_ps256(row(k)), row(k + 4));
        let (t0, t1, t2, t3) = (pair(0), pair(1), pair(2), pair(3));
        let (low01, high01) = (_mm256_unpacklo_ps(t0, t1), _mm256_unpackhi_ps(t0, t1));
        let (low23, high23) = (_mm256_unpacklo_ps(t2, t3), _mm256_unpackhi_ps(t2, t3));
        [
            _mm256_shuffle_ps::<0x44>(low01, low23),
            _mm256_shuffle_ps::<0xee>(low01, low23),
            _mm256_shuffle_ps::<0x44>(high01, high23),
            _mm256_shuffle_ps::<0xee>(high01, high23),
        ]
    };
    let [px, py, pz, nx] = columns(0);
    let [ny, nz, _, _] = columns(4);
    let [red, green, blue, _] = columns(8);
    let (position, normal, mut rgb) = ([px, py, pz], [nx, ny, nz], [red, green, blue]);
    let store = |a: &mut [f32; 8], value| {
        // SAFETY: `a` is eight writable `f32`; the store needs no alignment.
        unsafe { _mm256_storeu_ps(a.as_mut_ptr(), value) }
    };
    // Transform::shade: the normal by the normal matrix (glam's Mat3 * Vec3).
    let m = u.normal_matrix;
    let normal = [0, 1, 2].map(|k| row([m[0][k], m[1][k], m[2][k]], normal));
    if let Some((direction, ambient, diffuse)) = u.light {
        // DirectionalLight::intensity: glam's normalize_or_zero, the dot
        // product with the light, at least 0, scaled and lifted.
        let length = _mm256_sqrt_ps(dot(normal, normal));
        let reciprocal = _mm256_div_ps(splat(1.0), length);
        let usable = _mm256_and_ps(
            _mm256_cmp_ps::<_CMP_GT_OQ>(reciprocal, _mm256_setzero_ps()),
            finite(reciprocal),
        );
        let unit = normal.map(|n| _mm256_and_ps(_mm256_mul_ps(n, reciprocal), usable));
        let facing = dot(unit, direction.map(|d| splat(d)));
        let facing = _mm256_max_ps(facing, _mm256_setzero_ps());
        let intensity = _mm256_add_ps(splat(ambient), _mm256_mul_ps(splat(diffuse), facing));
        rgb = rgb.map(|c| _mm256_mul_ps(c, intensity));
    }
    // The position by the model-view-projection matrix (glam's Mat4 *
    // Vec4 with w = 1: the last column is added as it is).
    let clip = [0, 1, 2, 3].map(|k| {
        let m = u.mvp;
        _mm256_add_ps(row([m[0][k], m[1][k], m[2][k]], position), splat(m[3][k]))
    });
    let [_, _, z, w] = clip;
    // Finite, and inside the near, far and w planes.
    let all_finite = _mm256_and_ps(
        _mm256_and_ps(finite(clip[0]), finite(clip[1])),
        _mm256_and_ps(finite(z), finite(w)),
    );
    let negative_w = _mm256_xor_ps(w, splat(-0.0));
    let planes = _mm256_and_ps(
        _mm256_and_ps(
            _mm256_cmp_ps::<_CMP_GE_OQ>(z, negative_w),
            _mm256_cmp_ps::<_CMP_GE_OQ>(w, z),
        ),
        _mm256_cmp_ps::<_CMP_GE_OQ>(w, splat(u.w_min)),
    );
    let (low, high) = (divide_and_snap::<0>(u, clip), divide_and_snap::<1>(u, clip));
    let on_screen = _mm256_movemask_ps(_mm256_and_ps(all_finite, planes)) & (low.ok | high.ok << 4);
    out.on_screen = on_screen as u8;
    // SAFETY: each destination is eight writable `i32` or `f32`, stored in
    // halves of four; the stores need no alignment.
    unsafe {
        _mm_storeu_si128(out.x.as_mut_ptr().cast(), low.x);
        _mm_storeu_si128(out.x.as_mut_ptr().add(4).cast(), high.x);
        _mm_storeu_si128(out.y.as_mut_ptr().cast(), low.y);
        _mm_storeu_si128(out.y.as_mut_ptr().add(4).cast(), high.y);
        _mm_storeu_ps(out.depth.as_mut_ptr(), low.depth);
        _mm_storeu_ps(out.depth.as_mut_ptr().add(4), high.depth);
        _mm_storeu_ps(out.inv_w.as_mut_ptr(), low.inv_w);
        _mm_storeu_ps(out.inv_w.as_mut_ptr().add(4), high.inv_w);
    }
    for (o, n) in out.normal.iter_mut().zip(normal) {
        store(o, n);
    }
    for (o, c) in out.rgb.iter_mut().zip(rgb) {
        store(o, c);
    }
}
