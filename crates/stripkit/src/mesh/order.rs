//! Vertex orders as plain id lists: the first-use order of an index stream and its
//! inverse map. The mesh path ([`crate::first_use_order`], above the door) and the
//! glTF scene writer (`io::gltf`) both renumber vertices with these two.

/// The vertices `indices` uses (each below `vertex_count`), in the order of their
/// first use.
pub(crate) fn first_use(indices: impl IntoIterator<Item = u32>, vertex_count: usize) -> Vec<u32> {
    let mut seen = vec![false; vertex_count];
    indices.into_iter().filter(|&v| !std::mem::replace(&mut seen[v as usize], true)).collect()
}

/// The inverse of `order` (old ids listed by new id): for each of `vertex_count` old
/// vertices its new id, `u32::MAX` where `order` leaves it out.
pub(crate) fn ids_of(order: &[u32], vertex_count: usize) -> Vec<u32> {
    let mut new_id = vec![u32::MAX; vertex_count];
    for (k, &v) in order.iter().enumerate() {
        new_id[v as usize] = k as u32;
    }
    new_id
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_use_and_its_inverse() {
        let order = first_use([3, 1, 3, 0, 1], 5);
        assert_eq!(order, [3, 1, 0]);
        assert_eq!(ids_of(&order, 5), [2, 1, u32::MAX, 0, u32::MAX]);
    }
}
