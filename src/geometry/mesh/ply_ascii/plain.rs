//! The plain readings of the two lines that make up nearly all of a
//! scanned mesh: a face whose one property is its list of integer indices
//! ([`PlainFace`]), and a vertex whose properties are all floats
//! ([`read_plain_vertex`]). Each reads its line without the general
//! reader's dispatch per value, and gives up (`None`) on anything else:
//! a sign, a value out of range, anything wrong. The general reader of
//! [`super`] then reads the line the same way, or names what is wrong
//! with it.

use super::super::ply_payload::{Payload, VertexColumn};
use super::{integer_range, is_space};
use ply_rs_bw::ply::ScalarType;

/// The common line of a face element whose one property is its list of
/// vertex indices, both its length and its indices of integer types:
/// plain decimal digits, no sign, separated by spaces or tabs, each in
/// its type's range (and the indices in `u32`'s), and nothing else on the
/// line. Most of a large mesh's lines are such faces, and this reads them
/// without the general reader's dispatch per value; any other line (a
/// sign, a value out of range, anything wrong) is left to the general
/// reader, which reads it the same way or says what is wrong with it.
#[derive(Copy, Clone, Debug)]
pub(super) struct PlainFace {
    /// The largest length the length's type holds.
    most_vertices: u64,
    /// The largest index both the index type and `u32` hold.
    largest_index: u64,
}

impl PlainFace {
    /// The plain reading of a list of `index` values whose length is a
    /// `count`; `None` unless both are integer types.
    pub(super) fn new(count: &ScalarType, index: &ScalarType) -> Option<PlainFace> {
        let (_, most_vertices) = integer_range(count)?;
        let (_, largest_index) = integer_range(index)?;
        Some(PlainFace {
            most_vertices: most_vertices as u64,
            largest_index: (largest_index as u64).min(u64::from(u32::MAX)),
        })
    }

    /// Reads the face at the start of `bytes` into `payload` and returns
    /// the bytes read, its line break included; `None`, with the payload
    /// as it was, if the line is not plain (or, unless `complete`, not
    /// whole in `bytes`).
    #[inline(always)]
    pub(super) fn read(
        &self,
        bytes: &[u8],
        complete: bool,
        payload: &mut Payload,
    ) -> Option<usize> {
        let mut at = 0;
        let count = plain_integer(bytes, &mut at, self.most_vertices)?;
        if count == 3 {
            let mut triangle = [0; 3];
            for index in &mut triangle {
                *index = plain_integer(bytes, &mut at, self.largest_index)? as u32;
            }
            let end = line_end(bytes, at, complete)?;
            payload.push_triangle(triangle);
            return Some(end);
        }
        payload.pending.clear();
        for _ in 0..count {
            let Some(index) = plain_integer(bytes, &mut at, self.largest_index) else {
                payload.pending.clear();
                return None;
            };
            payload.pending.push(index as u32);
        }
        let Some(end) = line_end(bytes, at, complete) else {
            payload.pending.clear();
            return None;
        };
        payload.push_pending_face();
        Some(end)
    }
}

/// Reads the vertex at the start of `bytes`, all its properties `float`,
/// into `vertex` (`columns` says where each goes) and returns the bytes
/// read, its line break included: the general reader's work without its
/// dispatch per value. `None` if a value is not a number followed by a
/// space, a tab or the line's end, if more follows the last (or, unless
/// `complete`, if the line is not whole in `bytes`): the general reader
/// then reads the line, or says what is wrong with it.
#[inline(always)]
pub(super) fn read_plain_vertex(
    columns: &[Option<VertexColumn>],
    bytes: &[u8],
    complete: bool,
    vertex: &mut [f64; VertexColumn::COUNT],
) -> Option<usize> {
    let mut at = 0;
    for &column in columns {
        while bytes.get(at).copied().is_some_and(is_space) {
            at += 1;
        }
        let (value, n) = fast_float2::parse_partial::<f32, _>(&bytes[at..]).ok()?;
        at += n;
        if n == 0 || !value_ends(bytes, at) {
            return None;
        }
        if let Some(column) = column {
            vertex[column as usize] = f64::from(value);
        }
    }
    line_end(bytes, at, complete)
}

/// Past the line break at `bytes[at..]`, after spaces or tabs: the end
/// of a line whose values are all read; `None` if something else is
/// there, or if the bytes end there and they are not `complete`.
#[inline(always)]
fn line_end(bytes: &[u8], mut at: usize, complete: bool) -> Option<usize> {
    while bytes.get(at).copied().is_some_and(is_space) {
        at += 1;
    }
    match (bytes.get(at), bytes.get(at + 1)) {
        (Some(b'\n'), _) => Some(at + 1),
        (Some(b'\r'), Some(b'\n')) => Some(at + 2),
        (None, _) if complete => Some(at),
        _ => None,
    }
}

/// The value of the plain decimal digits at `bytes[*at..]`, after spaces
/// or tabs, if there are at most ten, they make at most `most`, and a
/// space, a tab, a line break or the end of `bytes` follows them; `*at`
/// moves past them.
#[inline(always)]
fn plain_integer(bytes: &[u8], at: &mut usize, most: u64) -> Option<u64> {
    while bytes.get(*at).copied().is_some_and(is_space) {
        *at += 1;
    }
    let start = *at;
    let mut value = 0u64;
    while let Some(&digit) = bytes.get(*at) {
        if !digit.is_ascii_digit() || *at - start == 10 {
            break;
        }
        value = value * 10 + u64::from(digit - b'0');
        *at += 1;
    }
    (*at > start && value_ends(bytes, *at) && value <= most).then_some(value)
}

/// Whether a value ending at `bytes[at]` is followed by a space, a tab, a
/// line break or the end of `bytes`.
#[inline(always)]
fn value_ends(bytes: &[u8], at: usize) -> bool {
    bytes
        .get(at)
        .is_none_or(|&b| is_space(b) || b == b'\n' || b == b'\r')
}
