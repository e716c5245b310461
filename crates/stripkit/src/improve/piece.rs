//! What the move generators of [`refine`] share, below all of them: the sizes of a
//! move ([`FLIP_LINKS`], [`REFINE_CUTS`], [`MOVE_SLOTS`]), the empty marker [`NONE`] and
//! [`Piece`], a part of an old walk. `slots`, `moves`, `tunnels`, `flips` and `refine`
//! import from here, each only from files below it, so the files form no circle.
//!
//! [`refine`]: super::refine::refine

/// No triangle, slot or FIFO entry.
pub(super) const NONE: u32 = u32::MAX;

/// Most links one flip of [`refine`] can drop (the size of its fixed arrays); each
/// call sets its own limit, [`Effort::flip_links`]: cycles of up to twice that many
/// dual edges, paths of one more.
///
/// [`refine`]: super::refine::refine
/// [`Effort::flip_links`]: super::refine::Effort::flip_links
pub(super) const FLIP_LINKS: usize = 4;

/// Most links a tunnel of `refine` cuts (measured on bunny: 4 saves a few more indices
/// for a third more time).
pub(super) const REFINE_CUTS: usize = 3;

/// Most strips one move of [`refine`] changes: a tunnel of [`REFINE_CUTS`] cuts, or a
/// flip of [`FLIP_LINKS`] dropped links ([`Flips`] makes no move of more slots).
///
/// [`refine`]: super::refine::refine
/// [`Flips`]: super::flips::Flips
pub(super) const MOVE_SLOTS: usize = if REFINE_CUTS + 2 > FLIP_LINKS {
    REFINE_CUTS + 2
} else {
    FLIP_LINKS
};

/// A part of a walk in a tunnel of [`refine`]: `walks[slot][lo..hi]`, read backwards
/// when `rev`.
///
/// [`refine`]: super::refine::refine
#[derive(Clone, Copy)]
pub(super) struct Piece {
    pub(super) slot: u32,
    pub(super) lo: u32,
    pub(super) hi: u32,
    pub(super) rev: bool,
}

impl Piece {
    pub(super) fn len(&self) -> usize {
        (self.hi - self.lo) as usize
    }

    pub(super) fn reversed(self) -> Piece {
        Piece {
            rev: !self.rev,
            ..self
        }
    }

    /// The walk `self` then `b` as a new strip reads it: in the direction of its longer
    /// part's old strip (the pair, read backwards and swapped where that is against).
    pub(super) fn join(self, b: Piece) -> (Piece, Piece) {
        let flip = if self.len() >= b.len() {
            self.rev
        } else {
            b.rev
        };
        if flip {
            (b.reversed(), self.reversed())
        } else {
            (self, b)
        }
    }

    /// A part cut off and left alone, in its old strip's direction.
    pub(super) fn alone(self) -> Piece {
        Piece { rev: false, ..self }
    }

    /// Triangle `j` in the piece's direction.
    #[inline]
    pub(super) fn at(&self, walks: &[Vec<u32>], j: usize) -> u32 {
        let w = &walks[self.slot as usize];
        if self.rev {
            w[self.hi as usize - 1 - j]
        } else {
            w[self.lo as usize + j]
        }
    }

    /// Appends the piece to `pool` in its direction.
    pub(super) fn extend(&self, walks: &[Vec<u32>], pool: &mut Vec<u32>) {
        let w = &walks[self.slot as usize][self.lo as usize..self.hi as usize];
        if self.rev {
            pool.extend(w.iter().rev());
        } else {
            pool.extend_from_slice(w);
        }
    }
}

/// The end triangles of a walk (one for a single triangle).
pub(super) fn ends(w: &[u32]) -> ([u32; 2], usize) {
    match w.len() {
        0 => ([NONE; 2], 0),
        1 => ([w[0], NONE], 1),
        n => ([w[0], w[n - 1]], 2),
    }
}

