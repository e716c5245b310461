//! Strips: the [`StripSet`] every stripifier returns, the decoder that turns strips
//! back into triangles by the rule of docs/metrics.md, the three ways of joining strips into
//! buffers, and [`verify`], the independent check every output goes through.
//!
//! Triangle `i` of a strip `s` is `(s[i], s[i+1], s[i+2])` for even `i` and
//! `(s[i+1], s[i], s[i+2])` for odd `i`; a triangle with a repeated index is
//! degenerate and draws nothing.
//!
//! Joins:
//! * [`encode_restart`]: one buffer, strips separated by a primitive-restart index;
//! * [`encode_stitched`]: one strip, strips joined by degenerate triangles, winding kept
//!   (2 extra indices per join when the next strip lands on an even position, 3 otherwise);
//! * [`encode_separate`]: one list per strip.

mod order;

/// A set of triangle strips, stored flat.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StripSet {
    /// Indices of all strips, concatenated.
    pub indices: Vec<u32>,
    /// `indices[offsets[s]..offsets[s + 1]]` is strip `s`. Always holds the leading 0.
    pub offsets: Vec<u32>,
}

impl Default for StripSet {
    /// The same as [`StripSet::new`]: the offsets hold their leading `0`.
    fn default() -> Self {
        StripSet::new()
    }
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
/// winding the strip reading rule (docs/metrics.md) gives it.
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

/// Strips per part where [`decode_with`] cuts a set.
const DECODE_PART: usize = 1024;

/// [`decode`] with the strips cut into parts of 1,024 strips decoded in parallel when
/// `threads` allows: each part's triangles are counted first, so the list is sized
/// once and every part writes its own range of it. The same list at any thread count.
pub fn decode_with(strips: &StripSet, threads: crate::parallel::Threads) -> Vec<[u32; 3]> {
    use crate::parallel::{fill_parts, map_range};
    const PART: usize = DECODE_PART;
    if threads.is_serial() || strips.len() <= PART {
        return decode(strips);
    }
    let parts = strips.len().div_ceil(PART);
    let range = |k: usize| k * PART..((k + 1) * PART).min(strips.len());
    let counts = map_range(threads, parts, |k| {
        let mut n = 0;
        for s in range(k) {
            for_each_triangle(strips.strip(s), |_| n += 1);
        }
        n
    });
    let starts: Vec<usize> = counts.iter().scan(0, |at, &n| Some(std::mem::replace(at, *at + n))).collect();
    let mut out = vec![[0u32; 3]; counts.iter().sum()];
    fill_parts(threads, &mut out, &starts, |k, part| {
        let mut at = 0;
        for s in range(k) {
            for_each_triangle(strips.strip(s), |t| {
                part[at] = t;
                at += 1;
            });
        }
    });
    out
}

/// The primitive-restart index used unless told otherwise (`0xFFFF_FFFF`, what
/// `GL_PRIMITIVE_RESTART_FIXED_INDEX` uses for 32-bit indices).
pub const DEFAULT_RESTART: u32 = u32::MAX;

impl StripSet {
    /// Total number of indices over all strips (`indices_separate` of docs/metrics.md).
    pub fn index_count(&self) -> usize {
        self.indices.len()
    }

    /// Length of the single buffer with a restart index between strips
    /// (`indices_restart` of docs/metrics.md): all indices plus one per strip boundary.
    pub fn restart_len(&self) -> usize {
        (self.index_count() + self.len()).saturating_sub(1)
    }

    /// Number of triangle windows (degenerate ones included) over all strips.
    pub fn window_count(&self) -> usize {
        self.iter().map(|s| s.len().saturating_sub(2)).sum()
    }

    /// Largest index used plus one (0 for an empty set).
    pub fn vertex_bound(&self) -> usize {
        self.indices.iter().map(|&i| i as usize + 1).max().unwrap_or(0)
    }
}

/// Joins each strip to the one before it where the earlier ends on the vertex the
/// later starts with and the later would start at an even position of the joined
/// strip: `[.., x, y] + [y, u, v, ..]` becomes `[.., x, y, y, u, v, ..]`. The two
/// windows at the join, `(x, y, y)` and `(y, y, u)`, are degenerate, so the joined strip
/// decodes to the same triangles in the same order with the same winding, and it saves
/// the restart index between the two (one index per join; a vertex cache sees the
/// same triangles in the same order). Strips of fewer than 3 indices are kept as they
/// are. Returns the number of joins. O(total length), in place.
pub fn join_shared_ends(strips: &mut StripSet) -> usize {
    let n = strips.len();
    let mut joins = 0;
    // No index moves: a join only drops the offset between the two strips.
    let mut offsets: Vec<u32> = Vec::with_capacity(n + 1);
    offsets.push(0);
    for s in 0..n {
        if s > 0 && joins_at_vertex(strips.strip(s - 1), strips.strip(s)) {
            if let Some(end) = offsets.last_mut() {
                *end = strips.offsets[s + 1];
            }
            joins += 1;
        } else {
            offsets.push(strips.offsets[s + 1]);
        }
    }
    strips.offsets = offsets;
    joins
}

/// Whether strip `b`, right after strip `a`, is joined to it by [`join_shared_ends`]:
/// both draw something, `a` has an even length and ends on the vertex `b` starts
/// with. Every strip joined onto another starts at an even position of the joined
/// strip, so `a`'s own length decides where `b` lands.
#[inline]
pub fn joins_at_vertex(a: &[u32], b: &[u32]) -> bool {
    a.len() >= 3 && b.len() >= 3 && a.len() % 2 == 0 && a[a.len() - 1] == b[0]
}

/// All strips in one buffer, separated by `restart` (no restart before the first or
/// after the last strip). Length `indices_separate + strips - 1`. The caller makes sure
/// no strip uses `restart` as a vertex index (see [`decode_restart`]).
pub fn encode_restart(strips: &StripSet, restart: u32) -> Vec<u32> {
    let mut out = Vec::with_capacity(strips.indices.len() + strips.len());
    for (k, s) in strips.iter().enumerate() {
        if k > 0 {
            out.push(restart);
        }
        out.extend_from_slice(s);
    }
    out
}

/// Splits a buffer at every `restart` index into strips: the inverse of
/// [`encode_restart`]. An empty buffer gives no strips.
pub fn decode_restart(buffer: &[u32], restart: u32) -> StripSet {
    let mut set = StripSet::new();
    if buffer.is_empty() {
        return set;
    }
    for s in buffer.split(|&i| i == restart) {
        set.push(s);
    }
    set
}

/// Length of [`encode_stitched`]'s buffer, counted without writing it (the figures
/// ask for it on every stripify call).
pub fn stitched_len(strips: &StripSet) -> usize {
    let mut len = Count(0);
    stitch(strips, &mut len);
    len.0
}

/// All strips stitched into one strip with degenerate triangles, every triangle keeping
/// its winding. Between strip `a` and strip `b` the join repeats `a`'s last index and
/// `b`'s first: `..a, a_last, b0, b..` (2 extra) when `b` starts at an even position.
/// When it would start at an odd one, `b` is re-encoded to start there (its first
/// triangle written `(a, c, b)` instead of `(a, b, c)`, which also changes where it
/// needs swaps; read from whichever end is shorter) and joined with 2 extra indices if
/// that is no longer than the plain `..a, a_last, a_last, b0, b..` (3 extra).
/// Strips of fewer than 3 indices draw nothing and are left out. O(total length).
pub fn encode_stitched(strips: &StripSet) -> Vec<u32> {
    let mut out: Vec<u32> = Vec::with_capacity(strips.indices.len() + 3 * strips.len());
    stitch(strips, &mut out);
    out
}

/// Where [`stitch`] puts the stitched strip: a buffer, or a count of its length.
trait Stitched {
    fn len(&self) -> usize;
    /// The last index put (any value where only the length is kept).
    fn last(&self) -> u32;
    fn put(&mut self, indices: &[u32]);
}

impl Stitched for Vec<u32> {
    fn len(&self) -> usize {
        Vec::len(self)
    }
    fn last(&self) -> u32 {
        self[self.len() - 1]
    }
    fn put(&mut self, indices: &[u32]) {
        self.extend_from_slice(indices);
    }
}

/// The length of a stitched strip, nothing written.
struct Count(usize);

impl Stitched for Count {
    fn len(&self) -> usize {
        self.0
    }
    fn last(&self) -> u32 {
        0
    }
    fn put(&mut self, indices: &[u32]) {
        self.0 += indices.len();
    }
}

/// The stitching of [`encode_stitched`] into `out`.
fn stitch(strips: &StripSet, out: &mut impl Stitched) {
    let mut tris: Vec<[u32; 3]> = Vec::new();
    let mut odd: Vec<u32> = Vec::new();
    for s in strips.iter().filter(|s| s.len() >= 3) {
        if out.len() > 0 {
            let last = out.last();
            if out.len() & 1 == 0 {
                out.put(&[last, s[0]]);
            } else {
                tris.clear();
                for_each_triangle(s, |t| tris.push(t));
                if encode_odd_start(&tris, &mut odd) && odd.len() < s.len() + 1 {
                    out.put(&[last, odd[0]]);
                    out.put(&odd);
                    continue;
                }
                out.put(&[last, last, s[0]]);
            }
        }
        out.put(s);
    }
}

/// Encodes the triangle walk `tris` (each sharing an edge with the next, consistently
/// oriented) as a strip meant to start at an odd position, read from whichever end is
/// shorter. False when `tris` is not such a walk; the result is checked by decoding.
fn encode_odd_start(tris: &[[u32; 3]], out: &mut Vec<u32>) -> bool {
    out.clear();
    let n = tris.len();
    if n == 0 {
        return false;
    }
    let mut buf = Vec::with_capacity(n + 8);
    let mut found = false;
    for reverse in [false, true] {
        let at = |i: usize| if reverse { tris[n - 1 - i] } else { tris[i] };
        buf.clear();
        if odd_walk(n, at, &mut buf) && reads_back_odd(&buf, n, at) && (!found || buf.len() < out.len()) {
            std::mem::swap(out, &mut buf);
            found = true;
        }
    }
    found
}

/// True when `strip`, read from an odd position, draws exactly `at(0), .., at(n-1)`.
fn reads_back_odd(strip: &[u32], n: usize, at: impl Fn(usize) -> [u32; 3]) -> bool {
    let mut k = 0;
    for i in 0..strip.len().saturating_sub(2) {
        // Window i sits at position 1 + i: odd positions swap the first two.
        let t = if i % 2 == 1 {
            [strip[i], strip[i + 1], strip[i + 2]]
        } else {
            [strip[i + 1], strip[i], strip[i + 2]]
        };
        if is_degenerate(&t) {
            continue;
        }
        if k >= n || canonical(t) != canonical(at(k)) {
            return false;
        }
        k += 1;
    }
    k == n
}

/// The odd-start strip of the walk `at(0), at(1), ..` into `out`; false when two
/// consecutive triangles do not share an edge the way a strip needs.
fn odd_walk(n: usize, at: impl Fn(usize) -> [u32; 3], out: &mut Vec<u32>) -> bool {
    let t0 = at(0);
    if is_degenerate(&t0) {
        return false;
    }
    if n == 1 {
        // At an odd position (s1, s0, s2) is the triangle: write (a, c, b).
        out.extend_from_slice(&[t0[0], t0[2], t0[1]]);
        return true;
    }
    let t1 = at(1);
    // The edge x -> y of t0 that t1 runs y -> x.
    let Some(j) = (0..3).find(|&j| {
        let (x, y) = (t0[j], t0[(j + 1) % 3]);
        (0..3).any(|k| t1[k] == y && t1[(k + 1) % 3] == x)
    }) else {
        return false;
    };
    let (x, y, a) = (t0[j], t0[(j + 1) % 3], t0[(j + 2) % 3]);
    out.extend_from_slice(&[a, y, x]);
    // Newest index x, the one before it y.
    let (mut p, mut q) = (y, x);
    for i in 1..n {
        let t = at(i);
        if is_degenerate(&t) || !t.contains(&p) || !t.contains(&q) {
            return false;
        }
        let Some(&r) = t.iter().find(|&&v| v != p && v != q) else { return false };
        if i + 1 < n {
            let next = at(i + 1);
            // The exit edge holds r and one of p, q.
            if next.contains(&r) && next.contains(&q) {
                out.push(r);
                p = q;
            } else if next.contains(&r) && next.contains(&p) {
                out.extend_from_slice(&[p, r]);
            } else {
                return false;
            }
            q = r;
        } else {
            out.push(r);
        }
    }
    true
}

/// One list per strip.
pub fn encode_separate(strips: &StripSet) -> Vec<Vec<u32>> {
    strips.iter().map(|s| s.to_vec()).collect()
}

/// Triangles of `strip` (the windows [`for_each_triangle`] reads, counted before its
/// dropping) with a repeated index: the swaps of a generalized strip and the
/// degenerate triangles that stitch strips together. A loader that reads a strip
/// triangle by triangle and keeps every one (trimesh) counts these as faces.
pub fn degenerate_windows(strip: &[u32]) -> usize {
    strip.windows(3).filter(|w| w[0] == w[1] || w[1] == w[2] || w[0] == w[2]).count()
}

/// True when a triangle repeats an index.
#[inline]
pub fn is_degenerate(t: &[u32; 3]) -> bool {
    t[0] == t[1] || t[1] == t[2] || t[2] == t[0]
}

/// The rotation of `t` that starts at its smallest index: equal for triangles that are
/// equal up to rotation.
#[inline]
pub fn canonical(t: [u32; 3]) -> [u32; 3] {
    if t[0] <= t[1] && t[0] <= t[2] {
        t
    } else if t[1] <= t[2] {
        [t[1], t[2], t[0]]
    } else {
        [t[2], t[0], t[1]]
    }
}

/// The result of [`verify`]: how the decoded triangles differ from the expected ones.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Verification {
    /// Non-degenerate expected triangles.
    pub expected: usize,
    /// Degenerate expected triangles (repeated index), left out of the comparison.
    pub dropped_degenerate: usize,
    /// Non-degenerate triangles decoded from the strips.
    pub decoded: usize,
    /// Expected triangles missing from the output (flipped ones not included).
    pub lost: usize,
    /// Output triangles that are not expected (flipped ones not included).
    pub added: usize,
    /// Expected triangles that came out with the opposite winding.
    pub flipped: usize,
}

impl Verification {
    /// True when the decoded multiset of oriented triangles equals the expected one.
    pub fn ok(&self) -> bool {
        self.lost == 0 && self.added == 0 && self.flipped == 0
    }
}

impl std::fmt::Display for Verification {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} triangles expected, {} decoded: {} lost, {} added, {} flipped",
            self.expected, self.decoded, self.lost, self.added, self.flipped
        )
    }
}

/// Checks strips against the triangles they should draw: the multiset of oriented,
/// non-degenerate triangles decoded by the strip reading rule (docs/metrics.md) must equal the multiset of
/// the non-degenerate `expected` triangles, up to rotation. Degenerate expected
/// triangles are counted in `dropped_degenerate` and not required. O(n) on a mesh:
/// both lists are ordered by a counting sort on each triangle's lowest index (see
/// `strip/order.rs`), then merged.
pub fn verify(expected: &[[u32; 3]], strips: &StripSet) -> Verification {
    verify_with(expected, strips, crate::parallel::Threads::SERIAL)
}

/// [`verify`] for an already decoded triangle list (degenerate entries are skipped).
/// Both lists are read straight into their buckets: no copy of either is sorted.
pub fn verify_triangles(expected: &[[u32; 3]], decoded: &[[u32; 3]]) -> Verification {
    let threads = crate::parallel::Threads::SERIAL;
    let keys = keys_above(decoded.as_flattened());
    merge_sorted(&sorted_expected(expected, threads), &order::sorted_from(threads, &NonDegenerate(decoded), keys))
}

/// [`verify_triangles`] taking the decoded list by value: it is canonicalized and
/// sorted in place, so the check holds one more list (the expected one, canonical)
/// beside the two it is given: 12 bytes per triangle on meshes of millions.
pub fn verify_decoded(expected: &[[u32; 3]], got: Vec<[u32; 3]>) -> Verification {
    verify_decoded_with(expected, got, crate::parallel::Threads::SERIAL)
}

/// [`verify`] in parallel when `threads` allows (the two sides side by side, each
/// one's buckets in parts); the same result at any thread count (the sorted lists are
/// the same, and the comparison after them runs on one thread). Each side is written
/// straight into its buckets, the strips as they are decoded and the expected
/// triangles as they are read: no unsorted list or copy is made.
pub fn verify_with(expected: &[[u32; 3]], strips: &StripSet, threads: crate::parallel::Threads) -> Verification {
    let (want, got) = crate::parallel::join(
        threads,
        || sorted_expected(expected, threads),
        || {
            order::sorted_from(threads, &Decoded(strips), keys_above(&strips.indices))
        },
    );
    merge_sorted(&want, &got)
}

/// [`verify_decoded_with`] for the triangles of polygon faces (`offsets` into
/// `indices`, as a [`crate::Mesh`] holds them, each face a fan from its first corner):
/// the faces are written straight into their buckets and freed before the expected
/// side is made, so the check holds the faces and one sorted list, or two sorted
/// lists, at a time (and no unsorted list of triangles). The sides are made one after
/// the other, each one's buckets finished in parallel when `threads` allows; the same
/// result at any thread count.
pub(crate) fn verify_faces_with(
    expected: &[[u32; 3]],
    (offsets, indices): (Vec<u32>, Vec<u32>),
    threads: crate::parallel::Threads,
) -> Verification {
    let got = order::sorted_from(threads, &Fans { offsets: &offsets, indices: &indices }, keys_above(&indices));
    drop((offsets, indices));
    merge_sorted(&sorted_expected(expected, threads), &got)
}

/// The non-degenerate fan triangles of polygon faces, canonical: the decoded side of
/// [`verify_faces_with`].
struct Fans<'a> {
    offsets: &'a [u32],
    indices: &'a [u32],
}

impl order::Source for Fans<'_> {
    fn for_each(&self, mut emit: impl FnMut([u32; 3])) {
        for w in self.offsets.windows(2) {
            let face = &self.indices[w[0] as usize..w[1] as usize];
            for i in 1..face.len().saturating_sub(1) {
                let t = [face[0], face[i], face[i + 1]];
                if !is_degenerate(&t) {
                    emit(canonical(t));
                }
            }
        }
    }
}

/// The triangles `strips` draw, canonical: the decoded side of [`verify_with`],
/// decoded straight into its buckets (no unsorted list).
struct Decoded<'a>(&'a StripSet);

impl order::Source for Decoded<'_> {
    fn for_each(&self, mut emit: impl FnMut([u32; 3])) {
        for s in self.0.iter() {
            for_each_triangle(s, |t| emit(canonical(t)));
        }
    }
}

/// The non-degenerate expected triangles, canonical: the expected side of the check,
/// written straight into its buckets (no copy of the caller's list).
struct NonDegenerate<'a>(&'a [[u32; 3]]);

impl order::Source for NonDegenerate<'_> {
    fn for_each(&self, mut emit: impl FnMut([u32; 3])) {
        for &t in self.0 {
            if !is_degenerate(&t) {
                emit(canonical(t));
            }
        }
    }
}

/// [`verify_decoded`] with its ordering in parallel when `threads` allows (the two
/// lists side by side, each one's buckets in parts); the same result at any thread
/// count.
pub fn verify_decoded_with(expected: &[[u32; 3]], got: Vec<[u32; 3]>, threads: crate::parallel::Threads) -> Verification {
    let (want, got) = crate::parallel::join(threads, || sorted_expected(expected, threads), || sorted_got(got, threads));
    merge_sorted(&want, &got)
}

/// Whether `joined` draws exactly the triangles of `strips`, shown without sorting:
/// true when the two sets are equal, or when `joined` decodes to the triangles of each
/// strip in turn, each strip's run forward or backward (what stitching does), up to
/// rotation. False says nothing (a joined form may legally draw them in another
/// order): the caller then runs the full check. O(n), the decoding in parallel when
/// `threads` allows, the walk on one thread; the same answer at any thread count.
pub(crate) fn draws_in_order(strips: &StripSet, joined: &StripSet, threads: crate::parallel::Threads) -> bool {
    if strips == joined {
        return true;
    }
    let got = decode_with(joined, threads);
    let mut at = 0;
    let mut mine: Vec<[u32; 3]> = Vec::new();
    for s in strips.iter() {
        mine.clear();
        for_each_triangle(s, |t| mine.push(canonical(t)));
        let Some(run) = got.get(at..at + mine.len()) else {
            return false;
        };
        let same = |a: &[u32; 3], b: &[u32; 3]| canonical(*a) == *b;
        if !run.iter().zip(&mine).all(|(a, b)| same(a, b)) && !run.iter().rev().zip(&mine).all(|(a, b)| same(a, b)) {
            return false;
        }
        at += mine.len();
    }
    at == got.len()
}

/// The expected side of the check, ready for [`compare_sorted`].
pub(crate) struct SortedExpected {
    /// The non-degenerate expected triangles, canonical and sorted.
    want: Vec<[u32; 3]>,
    /// How many expected triangles were degenerate.
    dropped_degenerate: usize,
}

/// The non-degenerate `expected` triangles, canonical and sorted (in parallel when
/// `threads` allows).
pub(crate) fn sorted_expected(expected: &[[u32; 3]], threads: crate::parallel::Threads) -> SortedExpected {
    let want = order::sorted_from(threads, &NonDegenerate(expected), keys_above(expected.as_flattened()));
    SortedExpected { dropped_degenerate: expected.len() - want.len(), want }
}

/// [`sorted_expected`] of a list the caller gives up: sorted in place, no copy.
pub(crate) fn sorted_expected_owned(mut expected: Vec<[u32; 3]>, threads: crate::parallel::Threads) -> SortedExpected {
    let before = expected.len();
    expected.retain_mut(|t| {
        *t = canonical(*t);
        !is_degenerate(t)
    });
    let dropped_degenerate = before - expected.len();
    order::sort_triangles(threads, &mut expected);
    SortedExpected { want: expected, dropped_degenerate }
}

/// The check's comparison: `got` (decoded triangles, in any order) made canonical and
/// sorted in place, then merged with the expected list on one thread.
pub(crate) fn compare_sorted(expected: &SortedExpected, got: Vec<[u32; 3]>, threads: crate::parallel::Threads) -> Verification {
    merge_sorted(expected, &sorted_got(got, threads))
}

/// The non-degenerate decoded triangles, canonical and sorted in place: the same
/// preparation as the expected side's.
fn sorted_got(got: Vec<[u32; 3]>, threads: crate::parallel::Threads) -> Vec<[u32; 3]> {
    sorted_expected_owned(got, threads).want
}

/// One more than the largest of `indices` (0 for none): the bound [`order::sorted_from`]
/// buckets first indices under.
fn keys_above(indices: &[u32]) -> usize {
    indices.iter().copied().max().map_or(0, |i| i as usize + 1)
}

/// Merges the two sorted lists on one thread: what is only on one side is lost or
/// added, a lost triangle found reversed among the added ones is a flip.
fn merge_sorted(expected: &SortedExpected, got: &[[u32; 3]]) -> Verification {
    let SortedExpected { want, dropped_degenerate } = expected;
    let dropped_degenerate = *dropped_degenerate;
    let mut v = Verification { expected: want.len(), dropped_degenerate, decoded: got.len(), ..Verification::default() };
    let (mut lost, mut added) = (Vec::new(), Vec::new());
    let (mut i, mut j) = (0, 0);
    while i < want.len() || j < got.len() {
        if j == got.len() || (i < want.len() && want[i] < got[j]) {
            lost.push(want[i]);
            i += 1;
        } else if i == want.len() || got[j] < want[i] {
            added.push(got[j]);
            j += 1;
        } else {
            i += 1;
            j += 1;
        }
    }
    // A lost triangle that reappears reversed among the added ones is a flip.
    let mut lost_flipped: Vec<[u32; 3]> = lost.iter().map(|t| canonical([t[0], t[2], t[1]])).collect();
    lost_flipped.sort_unstable();
    let (mut i, mut j) = (0, 0);
    while i < lost_flipped.len() && j < added.len() {
        match lost_flipped[i].cmp(&added[j]) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                v.flipped += 1;
                i += 1;
                j += 1;
            }
        }
    }
    v.lost = lost.len() - v.flipped;
    v.added = added.len() - v.flipped;
    v
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

    #[test]
    fn shared_ends_join_only_at_even_positions() {
        // [0 1 2 3] ends on 3 with an even length: [3 4 5] joins it (one index saved,
        // the restart). [3 4 5] has an odd length, so [5 6 7] after it stays apart:
        // joined, its first triangle would land on an odd position and flip.
        let mut set = StripSet::from_strips(&[
            vec![0, 1, 2, 3],
            vec![3, 4, 5],
            vec![5, 6, 7],
            vec![7, 8],
            vec![8, 9, 10, 11],
        ]);
        let before = decode(&set);
        let len = set.restart_len();
        assert_eq!(join_shared_ends(&mut set), 1);
        assert_eq!(set.len(), 4);
        assert_eq!(set.strip(0), &[0, 1, 2, 3, 3, 4, 5]);
        assert_eq!(set.restart_len(), len - 1);
        // Same triangles, same order, same winding.
        assert_eq!(decode(&set), before);
        // A chain: each joined strip starts at an even position of the joined one.
        let mut set = StripSet::from_strips(&[vec![0, 1, 2, 3], vec![3, 4, 5, 6], vec![6, 7, 8]]);
        let before = decode(&set);
        assert_eq!(join_shared_ends(&mut set), 2);
        assert_eq!(set.strip(0), &[0, 1, 2, 3, 3, 4, 5, 6, 6, 7, 8]);
        assert_eq!(decode(&set), before);
        // A strip of fewer than 3 indices joins nothing and is joined to nothing.
        let mut set = StripSet::from_strips(&[vec![0, 1], vec![1, 2, 3], vec![9]]);
        assert_eq!(join_shared_ends(&mut set), 0);
        assert_eq!(set.len(), 3);
    }

    #[test]
    fn stitching_keeps_winding_with_two_or_three_extra_indices() {
        // First strip has 4 indices: the next starts at 4 + 2 = 6 (even): 2 extra.
        let set = StripSet::from_strips(&[vec![0, 1, 2, 3], vec![4, 5, 6]]);
        let one = encode_stitched(&set);
        assert_eq!(one, vec![0, 1, 2, 3, 3, 4, 4, 5, 6]);
        assert_eq!(stitched_len(&set), one.len());
        assert!(verify(&decode(&set), &StripSet::from_strips(&[one])).ok());
        // First strip has 3 indices: the next starts at an odd position, so it is
        // written (4, 6, 5) there: window 5 reads (6, 4, 5), still 2 extra.
        let set = StripSet::from_strips(&[vec![0, 1, 2], vec![4, 5, 6]]);
        let one = encode_stitched(&set);
        assert_eq!(one, vec![0, 1, 2, 2, 4, 4, 6, 5]);
        assert_eq!(stitched_len(&set), one.len());
        assert!(verify(&decode(&set), &StripSet::from_strips(&[one])).ok());
        // A strip that is not one walk (two triangles without a shared edge) cannot be
        // re-encoded: 3 extra.
        let set = StripSet::from_strips(&[vec![0, 1, 2], vec![4, 5, 6, 6, 8, 8, 9, 10]]);
        let one = encode_stitched(&set);
        assert_eq!(one, vec![0, 1, 2, 2, 2, 4, 4, 5, 6, 6, 8, 8, 9, 10]);
        assert_eq!(stitched_len(&set), one.len());
        assert!(verify(&decode(&set), &StripSet::from_strips(&[one])).ok());
        // A fan of four around 0 needs one swap from either end and at either parity:
        // at an odd position it still costs 7 indices, joined with 2 extra.
        let fan = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]];
        let fan_strip = vec![1, 2, 0, 3, 0, 4, 5];
        assert!(verify(&fan, &StripSet::from_strips(std::slice::from_ref(&fan_strip))).ok());
        let set = StripSet::from_strips(&[vec![7, 8, 9], fan_strip]);
        let one = encode_stitched(&set);
        assert_eq!(one.len(), 3 + 2 + 7);
        assert_eq!(stitched_len(&set), one.len());
        assert!(verify(&decode(&set), &StripSet::from_strips(&[one])).ok());
    }

    #[test]
    fn a_joined_form_in_strip_order_is_shown_without_sorting() {
        use crate::parallel::Threads;
        // Odd starts re-encoded (the fan), a strip of two indices, one with degenerates.
        let set = StripSet::from_strips(&[
            vec![0, 1, 2, 3],
            vec![4, 5, 6],
            vec![7, 8, 9, 10, 11],
            vec![1, 2, 0, 3, 0, 4, 5],
            vec![12, 13],
            vec![4, 5, 6, 6, 8, 8, 9, 10],
        ]);
        for joined in [
            StripSet::from_strips(&[encode_stitched(&set)]),
            decode_restart(&encode_restart(&set, 99), 99),
            StripSet::from_strips(&encode_separate(&set)),
        ] {
            assert!(verify(&decode(&set), &joined).ok());
            for t in [Threads::SERIAL, Threads::new(3)] {
                assert!(draws_in_order(&set, &joined, t));
            }
        }
        // The same triangles in another strip order: not shown (the full check decides).
        let two = StripSet::from_strips(&[vec![0, 1, 2, 3], vec![4, 5, 6]]);
        let swapped = StripSet::from_strips(&[vec![4, 5, 6], vec![0, 1, 2, 3]]);
        assert!(verify(&decode(&two), &swapped).ok());
        assert!(!draws_in_order(&two, &swapped, Threads::SERIAL));
        // A flipped, a lost and an added triangle are never shown.
        for bad in [
            vec![vec![0, 2, 1, 3], vec![4, 5, 6]],
            vec![vec![0, 1, 2], vec![4, 5, 6]],
            vec![vec![0, 1, 2, 3], vec![4, 5, 6, 7]],
        ] {
            let bad = StripSet::from_strips(&bad);
            assert!(!verify(&decode(&two), &bad).ok());
            assert!(!draws_in_order(&two, &bad, Threads::SERIAL));
        }
    }

    #[test]
    fn restart_round_trip() {
        let set = StripSet::from_strips(&[vec![0, 1, 2, 3], vec![4, 5, 6]]);
        let buf = encode_restart(&set, 99);
        assert_eq!(buf, vec![0, 1, 2, 3, 99, 4, 5, 6]);
        assert_eq!(decode_restart(&buf, 99), set);
        assert!(decode_restart(&[], 99).is_empty());
    }

    #[test]
    fn verify_counts_lost_added_flipped() {
        let tris = [[0, 1, 2], [2, 1, 3], [3, 4, 5]];
        let good = StripSet::from_strips(&[vec![0, 1, 2, 3], vec![3, 4, 5]]);
        assert!(verify(&tris, &good).ok());
        let v = verify(&tris, &StripSet::from_strips(&[vec![0, 1, 2, 3], vec![3, 5, 4], vec![7, 8, 9]]));
        assert_eq!((v.lost, v.added, v.flipped), (0, 1, 1));
        let v = verify(&tris, &StripSet::from_strips(&[vec![1, 2, 0]]));
        assert_eq!((v.lost, v.added, v.flipped), (2, 0, 0));
    }

    #[test]
    fn the_owned_check_counts_as_the_borrowed_one() {
        // Rotated, reordered, one flipped, one added, one lost, degenerate entries on both sides.
        let expected = [[0, 1, 2], [2, 1, 3], [3, 4, 5], [5, 6, 7], [1, 1, 2]];
        let decoded = vec![[7, 5, 6], [4, 5, 3], [1, 3, 2], [8, 9, 10], [2, 2, 3], [0, 2, 1]];
        let borrowed = verify_triangles(&expected, &decoded);
        let owned = verify_decoded(&expected, decoded);
        assert_eq!(owned, borrowed);
        assert_eq!((owned.expected, owned.dropped_degenerate, owned.decoded), (4, 1, 5));
        assert_eq!((owned.lost, owned.added, owned.flipped), (0, 1, 1));
        assert!(verify_decoded(&expected[..4], vec![[3, 4, 5], [1, 2, 0], [6, 7, 5], [3, 2, 1]]).ok());
    }

    #[test]
    fn faces_count_as_their_fan_triangles() {
        // A shuffled grid of 2 x 60 x 60 triangles (past the short-list fallback), read
        // back as faces: triangles, some pairs joined into quads (two fan triangles),
        // degenerate faces, then errors planted; the counts are those of the fans'
        // list, at 1 and 3 threads.
        let w = 61u32;
        let mut next = crate::test_support::xorshift(0x51_7cc1_b727_220a);
        let mut want: Vec<[u32; 3]> = Vec::new();
        for y in 0..60 {
            for x in 0..60 {
                let a = y * w + x;
                want.push([a, a + 1, a + w]);
                want.push([a + 1, a + w + 1, a + w]);
            }
        }
        for plant in 0..4 {
            let mut faces: Vec<Vec<u32>> = Vec::new();
            let mut k = 0;
            while k < want.len() {
                let [a, b, c] = want[k];
                if k % 7 == 0 && k % 2 == 0 {
                    // The quad b, d, c, a: fans (b, d, c) and (b, c, a), the grid's own two.
                    faces.push(vec![b, want[k + 1][1], c, a]);
                    k += 2;
                    continue;
                }
                faces.push(vec![b, c, a]);
                k += 1;
            }
            faces.push(vec![3, 3, 4]);
            match plant {
                1 => faces.push(vec![7, 8, 9]),
                2 => {
                    faces.swap_remove(next(faces.len() as u32) as usize);
                }
                3 => faces[next(100) as usize].swap(0, 1),
                _ => (),
            };
            for i in (1..faces.len()).rev() {
                faces.swap(i, next(i as u32 + 1) as usize);
            }
            let mut offsets = vec![0u32];
            let mut indices = Vec::new();
            for f in &faces {
                indices.extend_from_slice(f);
                offsets.push(indices.len() as u32);
            }
            let fans: Vec<[u32; 3]> = faces
                .iter()
                .flat_map(|f| (1..f.len() - 1).map(move |i| [f[0], f[i], f[i + 1]]))
                .collect();
            let reference = verify_decoded(&want, fans);
            assert_eq!(reference.ok(), plant == 0, "{reference}");
            for threads in [crate::parallel::Threads::SERIAL, crate::parallel::Threads::new(3)] {
                assert_eq!(verify_faces_with(&want, (offsets.clone(), indices.clone()), threads), reference);
            }
        }
    }
}
