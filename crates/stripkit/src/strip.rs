//! Strips: the [`StripSet`] every stripifier returns, and the decoder that turns strips
//! back into triangles by the rule of METRICS.md.
//!
//! Triangle `i` of a strip `s` is `(s[i], s[i+1], s[i+2])` for even `i` and
//! `(s[i+1], s[i], s[i+2])` for odd `i`; a triangle with a repeated index is
//! degenerate and draws nothing.

/// A set of triangle strips, stored flat.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StripSet {
    /// Indices of all strips, concatenated.
    pub indices: Vec<u32>,
    /// `indices[offsets[s]..offsets[s + 1]]` is strip `s`. Always holds the leading 0.
    pub offsets: Vec<u32>,
}

impl StripSet {
    /// An empty set.
    pub fn new() -> Self {
        StripSet { indices: Vec::new(), offsets: vec![0] }
    }

    /// A set from separate strips.
    pub fn from_strips<S: AsRef<[u32]>>(strips: &[S]) -> Self {
        let mut set = StripSet::new();
        for s in strips {
            set.push(s.as_ref());
        }
        set
    }

    /// Appends a strip.
    pub fn push(&mut self, strip: &[u32]) {
        if self.offsets.is_empty() {
            self.offsets.push(0);
        }
        self.indices.extend_from_slice(strip);
        self.offsets.push(self.indices.len() as u32);
    }

    /// Number of strips.
    pub fn len(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// True when there are no strips.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Strip `s`.
    pub fn strip(&self, s: usize) -> &[u32] {
        &self.indices[self.offsets[s] as usize..self.offsets[s + 1] as usize]
    }

    /// Iterates over the strips.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        self.offsets.windows(2).map(move |w| &self.indices[w[0] as usize..w[1] as usize])
    }
}

/// Calls `emit` with every non-degenerate triangle of one strip, in order, with the
/// winding the METRICS.md rule gives it.
pub fn for_each_triangle(strip: &[u32], mut emit: impl FnMut([u32; 3])) {
    for i in 0..strip.len().saturating_sub(2) {
        let t = if i % 2 == 0 {
            [strip[i], strip[i + 1], strip[i + 2]]
        } else {
            [strip[i + 1], strip[i], strip[i + 2]]
        };
        if t[0] != t[1] && t[1] != t[2] && t[2] != t[0] {
            emit(t);
        }
    }
}

/// Decodes ("unstripifies") every strip into its non-degenerate triangles, in order.
pub fn decode(strips: &StripSet) -> Vec<[u32; 3]> {
    let mut out = Vec::with_capacity(strips.indices.len());
    for s in strips.iter() {
        for_each_triangle(s, |t| out.push(t));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decode_alternates_winding_and_skips_degenerates() {
        let set = StripSet::from_strips(&[vec![0, 1, 2, 3, 3, 4], vec![5, 6]]);
        assert_eq!(set.len(), 2);
        // 0:(0,1,2) 1:(2,1,3) 2:(2,3,3)x 3:(3,3,4)x
        assert_eq!(decode(&set), vec![[0, 1, 2], [2, 1, 3]]);
    }
}
