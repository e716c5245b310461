//! The morph on the CPU: what the vertex shader draws at a morph weight, for the
//! geometry built from drawn positions (smooth normals, wireframe bands).

/// The positions drawn at morph weight `t` ([`crate::DrawParams::morph`]): each
/// `base + (target - base) * t`, so 0 gives `base` and 1 gives `target`. Pairs
/// `base[i]` with `target[i]`; a longer slice's extra positions are left out.
pub fn morph_positions(base: &[[f32; 3]], target: &[[f32; 3]], t: f32) -> Vec<[f32; 3]> {
    base.iter().zip(target).map(|(a, b)| std::array::from_fn(|d| a[d] + (b[d] - a[d]) * t)).collect()
}

#[cfg(test)]
mod tests {
    use super::morph_positions;

    #[test]
    fn the_ends_are_base_and_target_and_the_middle_is_halfway() {
        let base = [[0.0, 2.0, -4.0], [1.0, 1.0, 1.0]];
        let target = [[2.0, 2.0, 4.0], [3.0, -1.0, 1.0]];
        assert_eq!(morph_positions(&base, &target, 0.0), base);
        assert_eq!(morph_positions(&base, &target, 1.0), target);
        assert_eq!(morph_positions(&base, &target, 0.5), [[1.0, 2.0, 0.0], [2.0, 0.0, 1.0]]);
    }
}
