//! The mesh's vertices renumbered in the order its triangles first use
//! them, so that drawing reads the vertex data nearly in order.

/// New vertex numbers in the order the triangles first use the vertices
/// (unused vertices after them, in their order): `new_index[old]`.
///
/// Drawing then reads the vertex data nearly in order: the vertex shader
/// pass as before, and the fragment stage, which fetches a fragment's
/// three vertices, finds those of consecutive triangles side by side
/// instead of scattered over the mesh. Nothing computed changes (each
/// vertex is shaded by itself, the triangles keep their order), so the
/// image is the same bits. `None` when an index is out of range: the
/// pipeline then reports it as it stands.
pub(super) fn first_use_order(vertex_count: usize, triangles: &[[u32; 3]]) -> Option<Vec<u32>> {
    const UNSEEN: u32 = u32::MAX;
    let mut new_index = vec![UNSEEN; vertex_count];
    let mut next = 0u32;
    for &i in triangles.iter().flatten() {
        let slot = new_index.get_mut(i as usize)?;
        if *slot == UNSEEN {
            *slot = next;
            next += 1;
        }
    }
    for slot in new_index.iter_mut().filter(|s| **s == UNSEEN) {
        *slot = next;
        next += 1;
    }
    Some(new_index)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_use_order_is_a_permutation_in_order_of_use() {
        let order = first_use_order(6, &[[4, 2, 4], [0, 2, 3]]).unwrap();
        assert_eq!(order, vec![2, 4, 1, 3, 0, 5]);
        assert_eq!(first_use_order(3, &[[0, 1, 3]]), None);
    }
}
