//! Primitive assembly (the course chapter, step 3): grouping vertices into triangles.
//!
//! The vertex stream is either the vertices in order or an index buffer
//! into them, and its [`Topology`] says how consecutive entries form
//! triangles:
//!
//! | topology | triangle `i` | triangles from `n` entries |
//! |---|---|---|
//! | list | `(3i, 3i+1, 3i+2)` | `n / 3` (`n` must be a multiple of 3) |
//! | strip | `(i, i+1, i+2)`, the first two swapped for odd `i` so every triangle keeps the same winding | `n - 2` |
//! | fan | `(0, i+1, i+2)` | `n - 2` |
//!
//! ```
//! use rasterlab::geometry::{assemble, Topology};
//!
//! // The course chapter: three vertices, no index buffer, one triangle.
//! assert_eq!(assemble(Topology::List, None, 3).unwrap(), vec![[0, 1, 2]]);
//! assert_eq!(assemble(Topology::Strip, None, 5).unwrap(), vec![[0, 1, 2], [2, 1, 3], [2, 3, 4]]);
//! assert_eq!(assemble(Topology::Fan, Some(&[4, 0, 1, 2]), 5).unwrap(), vec![[4, 0, 1], [4, 1, 2]]);
//! assert!(assemble(Topology::List, Some(&[0, 1, 9]), 3).is_err());
//! ```

use crate::error::{Error, Result};

/// How a vertex stream forms triangles.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Topology {
    /// Every three entries form a triangle.
    #[default]
    List,
    /// Every entry after the second forms a triangle with the two before it.
    Strip,
    /// Every entry after the second forms a triangle with the one before it and the first.
    Fan,
}

impl Topology {
    /// Every topology.
    pub const ALL: [Topology; 3] = [Topology::List, Topology::Strip, Topology::Fan];
}

crate::names::named_enum!(
    Topology,
    "topology",
    List = "list",
    Strip = "strip",
    Fan = "fan"
);

/// Assembles triangles from `vertex_count` vertices, through `indices`
/// when given. Errors: an index out of range, or a list whose length is not
/// a multiple of three.
pub fn assemble(
    topology: Topology,
    indices: Option<&[u32]>,
    vertex_count: usize,
) -> Result<Vec<[u32; 3]>> {
    let stream: Vec<u32> = match indices {
        Some(ix) => {
            Error::check_indices(ix, vertex_count)?;
            ix.to_vec()
        }
        None => {
            let n = u32::try_from(vertex_count).map_err(|_| {
                Error::InvalidArgument(format!("{vertex_count} vertices are too many to index"))
            })?;
            (0..n).collect()
        }
    };
    let n = stream.len();
    Ok(match topology {
        Topology::List => {
            if !n.is_multiple_of(3) {
                return Err(Error::BadArrayLength {
                    what: "triangle list",
                    len: n,
                    unit: "triangle",
                });
            }
            stream.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
        }
        Topology::Strip => (0..n.saturating_sub(2))
            .map(|i| {
                let (a, b, c) = (stream[i], stream[i + 1], stream[i + 2]);
                if i % 2 == 0 {
                    [a, b, c]
                } else {
                    [b, a, c]
                }
            })
            .collect(),
        Topology::Fan => (1..n.saturating_sub(1))
            .map(|i| [stream[0], stream[i], stream[i + 1]])
            .collect(),
    })
}
