//! Quad meshes as the quad stripifiers ([`super::quad`], [`super::quad_single`]) and
//! [`super::quad_verify`] see them: which faces are quads, how a quad splits along a
//! diagonal, and [`QuadAdjacency`], the quads with their neighbours across manifold,
//! consistently oriented quad-quad edges and the diagonals forced where two quads share
//! two edges.

use crate::mesh::Mesh;
use crate::topology::EdgeMap;

/// No neighbour / no edge.
pub(super) const NONE: u32 = u32::MAX;
/// Diagonal not forced.
pub(super) const FREE: u8 = 2;
/// Quads on one edge sharing the same third vertex beyond which their diagonals are
/// forced one by one instead of pair by pair (a pathological, non-manifold input).
pub(super) const CLUSTER_CAP: usize = 64;

/// True for a face that QSTRIP takes: four vertices, all distinct.
pub fn is_quad(face: &[u32]) -> bool {
    face.len() == 4
        && face[0] != face[1]
        && face[0] != face[2]
        && face[0] != face[3]
        && face[1] != face[2]
        && face[1] != face[3]
        && face[2] != face[3]
}

/// Quads and their neighbours across manifold, consistently oriented quad-quad edges.
pub(super) struct QuadAdjacency<'m> {
    /// The four vertices of each quad, flat.
    pub(super) verts: Vec<u32>,
    /// Face id of each quad.
    pub(super) quad_face: Vec<u32>,
    /// `link[4 q + k]`: `(neighbour << 2) | neighbour's local edge` across local edge
    /// `k` (from `verts[4q+k]` to `verts[4q+(k+1)%4]`), or [`NONE`].
    pub(super) link: Vec<u32>,
    /// Forced diagonal per quad: 0 (v0-v2), 1 (v1-v3) or [`FREE`].
    pub(super) forced: Vec<u8>,
    pub(super) forced_pairs: usize,
    _mesh: std::marker::PhantomData<&'m Mesh>,
}

impl QuadAdjacency<'_> {
    pub(super) fn build<'m>(mesh: &'m Mesh, edges: &EdgeMap) -> QuadAdjacency<'m> {
        let quads = Quads::collect(mesh);
        let (link, odd_edges) = quads.link(mesh, edges);
        let mut f = Forcer {
            verts: &quads.verts,
            forced: vec![FREE; quads.len()],
            forced_pairs: 0,
            pairs: Vec::new(),
            clash: false,
            copies: Vec::new(),
            fixed: Vec::new(),
            big_cluster: false,
        };
        f.across_links(&link);
        f.on_odd_edges(&odd_edges, |h| quads.local(mesh, edges, h).0, edges);
        f.settle();
        let (forced, forced_pairs) = (f.forced, f.forced_pairs);
        QuadAdjacency {
            verts: quads.verts,
            quad_face: quads.quad_face,
            link,
            forced,
            forced_pairs,
            _mesh: std::marker::PhantomData,
        }
    }

    pub(super) fn len(&self) -> usize {
        self.quad_face.len()
    }
}

/// The quads of a mesh, the first step of [`QuadAdjacency::build`].
struct Quads {
    /// Quad of each face, or [`NONE`].
    quad_of_face: Vec<u32>,
    quad_face: Vec<u32>,
    verts: Vec<u32>,
}

impl Quads {
    fn collect(mesh: &Mesh) -> Quads {
        let mut quad_of_face = vec![NONE; mesh.face_count()];
        let mut quad_face = Vec::new();
        let mut verts = Vec::new();
        for (f, face) in mesh.faces().enumerate() {
            if is_quad(face) {
                quad_of_face[f] = quad_face.len() as u32;
                quad_face.push(f as u32);
                verts.extend_from_slice(face);
            }
        }
        Quads { quad_of_face, quad_face, verts }
    }

    fn len(&self) -> usize {
        self.quad_face.len()
    }

    /// The quad of half-edge `h` (or [`NONE`]) and its local edge there.
    fn local(&self, mesh: &Mesh, edges: &EdgeMap, h: u32) -> (u32, u32) {
        let f = edges.halfedge_face[h as usize];
        (self.quad_of_face[f as usize], h - mesh.face_offsets[f as usize])
    }

    /// `link` of [`QuadAdjacency`] over the plain two-quad edges, and the edges that
    /// are not plain two-quad edges (more faces, a flipped neighbour): the only places
    /// besides `link` where two quads can share an edge.
    fn link(&self, mesh: &Mesh, edges: &EdgeMap) -> (Vec<u32>, Vec<usize>) {
        let mut link = vec![NONE; 4 * self.len()];
        let mut odd_edges = Vec::new();
        for e in 0..edges.edge_count() {
            let hs = edges.halfedges(e);
            if hs.len() != 2 {
                if hs.len() > 2 {
                    odd_edges.push(e);
                }
                continue;
            }
            let (h1, h2) = (hs[0], hs[1]);
            let (q1, k1) = self.local(mesh, edges, h1);
            let (q2, k2) = self.local(mesh, edges, h2);
            if q1 == NONE || q2 == NONE || q1 == q2 {
                continue;
            }
            // Opposite directions: h1 starts where h2 ends.
            let next2 = edges.halfedge_next[h2 as usize];
            if mesh.face_indices[h1 as usize] != mesh.face_indices[next2 as usize] {
                odd_edges.push(e);
                continue;
            }
            link[(4 * q1 + k1) as usize] = (q2 << 2) | k2;
            link[(4 * q2 + k2) as usize] = (q1 << 2) | k1;
        }
        (link, odd_edges)
    }
}

/// The diagonals [`QuadAdjacency::build`] forces, and what its steps share on the way.
struct Forcer<'a> {
    verts: &'a [u32],
    forced: Vec<u8>,
    forced_pairs: usize,
    /// Every pair that could give coincident triangles.
    pairs: Vec<(u32, u32)>,
    /// The pairwise forcing painted itself into a corner.
    clash: bool,
    /// Copies of a quad in a big cluster that follow their first.
    copies: Vec<(u32, u32)>,
    /// Quads of big clusters whose diagonal was set directly: fixed for the solver.
    fixed: Vec<(u32, u8)>,
    big_cluster: bool,
}

impl Forcer<'_> {
    fn force(&mut self, q1: usize, q2: usize) {
        self.pairs.push((q1 as u32, q2 as u32));
        match force_pair(self.verts, &mut self.forced, q1, q2) {
            Forcing::Forced => self.forced_pairs += 1,
            Forcing::Clash => self.clash = true,
            Forcing::Nothing => {}
        }
    }

    /// Quads that share three or more vertices share an edge (any three corners of a
    /// quad include two of its edges, and a vertex has one diagonal partner): a `link`
    /// neighbour or a quad on an odd edge. Across a link the two shared vertices are
    /// known, so it takes a third: one of the other quad's far corners.
    fn across_links(&mut self, link: &[u32]) {
        let verts = self.verts;
        for q1 in 0..link.len() / 4 {
            for k in 0..4 {
                let l = link[4 * q1 + k];
                if l == NONE || (l >> 2) as usize <= q1 {
                    continue;
                }
                let q2 = (l >> 2) as usize;
                let k2 = (l & 3) as usize;
                let far = [verts[4 * q2 + (k2 + 2) % 4], verts[4 * q2 + (k2 + 3) % 4]];
                let mine = &verts[4 * q1..4 * q1 + 4];
                if mine.contains(&far[0]) || mine.contains(&far[1]) {
                    self.force(q1, q2);
                }
            }
        }
    }

    /// The quads on each odd edge (`quad_of(h)` for its half-edges), in half-edge
    /// order (the faces that are not quads left out first: an edge of k triangles and
    /// a quad or two is O(k), not O(k^2)). Two of them share three vertices when they
    /// share one of their two other corners: bucketing by those corners finds the
    /// pairs without trying all k^2.
    fn on_odd_edges(&mut self, odd_edges: &[usize], quad_of: impl Fn(u32) -> u32, edges: &EdgeMap) {
        let verts = self.verts;
        let mut on_edge: Vec<u32> = Vec::new();
        let mut corners: Vec<(u32, u32)> = Vec::new();
        let mut candidates: Vec<(u32, u32)> = Vec::new();
        for &e in odd_edges {
            let [u, v] = edges.edges[e];
            on_edge.clear();
            on_edge.extend(edges.halfedges(e).iter().map(|&h| quad_of(h)).filter(|&q| q != NONE));
            corners.clear();
            for (i, &q) in on_edge.iter().enumerate() {
                let qv = &verts[4 * q as usize..4 * q as usize + 4];
                corners.extend(qv.iter().filter(|&&w| w != u && w != v).map(|&w| (w, i as u32)));
            }
            corners.sort_unstable();
            candidates.clear();
            for group in corners.chunk_by(|a, b| a.0 == b.0) {
                if group.len() > CLUSTER_CAP {
                    self.big_cluster = true;
                    let found = Cluster {
                        on_edge: &on_edge,
                        candidates: &mut candidates,
                        copies: &mut self.copies,
                        fixed: &mut self.fixed,
                    };
                    self.forced_pairs += found.force(verts, &mut self.forced, [u, v, group[0].0], group);
                    continue;
                }
                for (a, &(_, i)) in group.iter().enumerate() {
                    candidates.extend(group[a + 1..].iter().map(|&(_, j)| (i.min(j), i.max(j))));
                }
            }
            // The pairs in half-edge order, as the all-pairs loop met them.
            candidates.sort_unstable();
            candidates.dedup();
            for &(i, j) in &candidates {
                let (qa, qb) = (on_edge[i as usize], on_edge[j as usize]);
                if qa == qb {
                    continue;
                }
                let (q1, q2) = (qa.min(qb) as usize, qa.max(qb) as usize);
                let a = &verts[4 * q1..4 * q1 + 4];
                let b = &verts[4 * q2..4 * q2 + 4];
                let common = a.iter().filter(|v| b.contains(v)).count();
                if common >= 3 {
                    self.force(q1, q2);
                }
            }
            follow_firsts(verts, &mut self.forced, &self.copies, false);
        }
    }

    /// When forcing pair by pair chose a diagonal that a later pair could not live
    /// with, or a cluster was too big to pair one by one: solves every pair of quads
    /// that could coincide at once (the pairs the quad check looks at); if there is
    /// no answer, the input forces a coincidence and the choices above stand. Past
    /// the solver's budget, only the pairs met above.
    fn settle(&mut self) {
        if !(self.clash || self.big_cluster) {
            return;
        }
        let verts = self.verts;
        let quads: Vec<&[u32]> = verts.chunks_exact(4).collect();
        if let Some(all) = candidate_pairs(&quads) {
            if let Some(d) = solve_diagonals(&quads, &all, &[]) {
                for &(a, b) in &all {
                    self.forced[a as usize] = d[a as usize];
                    self.forced[b as usize] = d[b as usize];
                }
                self.forced_pairs = all.len();
            }
        } else if self.clash {
            if let Some(d) = solve_diagonals(&quads, &self.pairs, &self.fixed) {
                for &(a, b) in &self.pairs {
                    self.forced[a as usize] = d[a as usize];
                    self.forced[b as usize] = d[b as usize];
                }
                self.forced_pairs = self.pairs.len();
                follow_firsts(verts, &mut self.forced, &self.copies, true);
            }
        }
    }
}

/// The two triangles of quad `v` split along diagonal `diag` (0: v0-v2, 1: v1-v3),
/// with the quad's orientation.
pub(super) fn split(v: &[u32], diag: u8) -> [[u32; 3]; 2] {
    let d = diag as usize;
    [[v[d], v[d + 1], v[(d + 2) % 4]], [v[d], v[(d + 2) % 4], v[(d + 3) % 4]]]
}

/// The two triangles of quad `v` split along diagonal `diag`, as sorted vertex sets.
pub(super) fn split_sets(v: &[u32], diag: u8) -> [[u32; 3]; 2] {
    split(v, diag).map(|mut t| {
        t.sort_unstable();
        t
    })
}

/// True when quads `a` and `b` are the same face: the same four vertices in the same
/// cyclic order (a face listed twice, perhaps from another corner). Their triangles
/// may coincide: that is the input's doing, not a wrong split, so no diagonal is
/// forced between them and the quad-level check accepts it.
pub(super) fn same_quad(a: &[u32], b: &[u32]) -> bool {
    a.len() == 4 && b.len() == 4 && (0..4).any(|r| (0..4).all(|i| a[i] == b[(i + r) % 4]))
}

pub(super) fn coincide(a: &[u32], da: u8, b: &[u32], db: u8) -> bool {
    let ta = split_sets(a, da);
    let tb = split_sets(b, db);
    ta.iter().any(|t| tb.contains(t))
}

/// Where [`QuadAdjacency::build`] records a cluster of more than [`CLUSTER_CAP`] quads
/// on one odd edge sharing the same third vertex: pairs to force (positions in
/// `on_edge`), copies that follow their first, and diagonals set directly.
struct Cluster<'a> {
    on_edge: &'a [u32],
    candidates: &'a mut Vec<(u32, u32)>,
    copies: &'a mut Vec<(u32, u32)>,
    fixed: &'a mut Vec<(u32, u8)>,
}

impl Cluster<'_> {
    /// Hundreds of quads on the same three vertices `uvw` (`group`: their positions
    /// in `on_edge`), in O(k log k) in place of the k^2 pairs. A quad whose four
    /// vertices no other quad here has takes the diagonal whose triangles avoid `uvw`.
    /// Quads on the same four vertices in other cyclic orders (a face and its flip)
    /// are paired, one copy of each order; further copies of one order follow their
    /// first. Returns how many diagonals it set.
    fn force(self, verts: &[u32], forced: &mut [u8], mut uvw: [u32; 3], group: &[(u32, u32)]) -> usize {
        uvw.sort_unstable();
        let quad = |i: u32| self.on_edge[i as usize] as usize;
        // (four vertices sorted, the cyclic order from the smallest, position)
        let mut members: Vec<([u32; 4], [u32; 4], u32)> = group
            .iter()
            .map(|&(_, i)| {
                let qv = &verts[4 * quad(i)..4 * quad(i) + 4];
                let mut set = [qv[0], qv[1], qv[2], qv[3]];
                set.sort_unstable();
                let r = (0..4).min_by_key(|&k| qv[k]).unwrap_or(0);
                (set, [qv[r], qv[(r + 1) % 4], qv[(r + 2) % 4], qv[(r + 3) % 4]], i)
            })
            .collect();
        members.sort_unstable();
        let mut set_here = 0;
        for same_set in members.chunk_by(|a, b| a.0 == b.0) {
            let orders: Vec<usize> =
                (0..same_set.len()).filter(|&m| m == 0 || same_set[m].1 != same_set[m - 1].1).collect();
            if orders.len() == 1 {
                for &(_, _, i) in same_set {
                    let q = quad(i);
                    if forced[q] == FREE {
                        forced[q] = u8::from(split_sets(&verts[4 * q..4 * q + 4], 0).contains(&uvw));
                        self.fixed.push((q as u32, forced[q]));
                        set_here += 1;
                    }
                }
                continue;
            }
            for (a, &ma) in orders.iter().enumerate() {
                for &mb in &orders[a + 1..] {
                    let (i, j) = (same_set[ma].2, same_set[mb].2);
                    self.candidates.push((i.min(j), i.max(j)));
                }
            }
            let mut first = 0;
            for m in 0..same_set.len() {
                if orders.contains(&m) {
                    first = m;
                } else {
                    self.copies.push((quad(same_set[m].2) as u32, quad(same_set[first].2) as u32));
                }
            }
        }
        set_here
    }
}

/// Gives each copy `c` of a face listed several times (`(c, first)` in `copies`) the
/// same diagonal as its first copy: the same two vertices, whatever corner each
/// listing starts from. Only free copies unless `all`.
fn follow_firsts(verts: &[u32], forced: &mut [u8], copies: &[(u32, u32)], all: bool) {
    for &(c, first) in copies {
        let (c, first) = (c as usize, first as usize);
        if forced[first] == FREE || !(all || forced[c] == FREE) {
            continue;
        }
        // Copy corner 0 is the first's corner k: copy diagonal d is the first's (d + k) % 2.
        let k = (0..4).position(|k| verts[4 * first + k] == verts[4 * c]).unwrap_or(0) as u8;
        forced[c] = (forced[first] + k) % 2;
    }
}

/// What [`force_pair`] did.
enum Forcing {
    /// The pair was fine as it was.
    Nothing,
    /// One or both diagonals were forced.
    Forced,
    /// Both were already forced into a clash.
    Clash,
}

/// Forces diagonals of `q1`, `q2` so that no triangle of one lies on the same three
/// vertices as a triangle of the other.
fn force_pair(verts: &[u32], forced: &mut [u8], q1: usize, q2: usize) -> Forcing {
    let a = &verts[4 * q1..4 * q1 + 4];
    let b = &verts[4 * q2..4 * q2 + 4];
    if same_quad(a, b) {
        // A quad listed twice: forcing its copies apart would gain nothing (their
        // triangles may coincide) and could force a clash with a real neighbour.
        return Forcing::Nothing;
    }
    let options = |f: u8| if f == FREE { vec![0u8, 1] } else { vec![f] };
    let bad = |d1: u8, d2: u8| coincide(a, d1, b, d2);
    if (0..2).all(|d1| (0..2).all(|d2| bad(d1, d2))) {
        // Every choice clashes (the same four vertices in another order): the
        // input's coincidence, which no forcing removes.
        return Forcing::Nothing;
    }
    if options(forced[q1])
        .iter()
        .all(|&d1| options(forced[q2]).iter().all(|&d2| !bad(d1, d2)))
    {
        return Forcing::Nothing;
    }
    // Prefer forcing one quad only: a diagonal of q1 that suits every choice of q2.
    for d1 in options(forced[q1]) {
        if options(forced[q2]).iter().all(|&d2| !bad(d1, d2)) {
            forced[q1] = d1;
            return Forcing::Forced;
        }
    }
    for d2 in options(forced[q2]) {
        if options(forced[q1]).iter().all(|&d1| !bad(d1, d2)) {
            forced[q2] = d2;
            return Forcing::Forced;
        }
    }
    for d1 in options(forced[q1]) {
        for d2 in options(forced[q2]) {
            if !bad(d1, d2) {
                forced[q1] = d1;
                forced[q2] = d2;
                return Forcing::Forced;
            }
        }
    }
    // Both already forced into a clash: a cluster that `build` solves as a whole.
    Forcing::Clash
}

/// A diagonal for every quad of `pairs` such that no pair gives two triangles on the
/// same three vertices, or `None` when there is none (the input then forces a
/// coincidence). Pairs that are one face listed twice, or that clash under every
/// choice, are left out: no choice helps them. Quads in `fixed` keep their diagonal. `quads[q]` are quad `q`'s four vertices; the answer is indexed like
/// `quads` (0: v0-v2, 1: v1-v3; quads in no pair get 0).
///
/// One boolean per quad (its diagonal) and one two-literal clause per clashing
/// combination of a pair: 2-SAT, solved in time linear in the pairs by the strongly
/// connected components of the implication graph (Tarjan, iterative).
pub(super) fn solve_diagonals(quads: &[&[u32]], pairs: &[(u32, u32)], fixed: &[(u32, u8)]) -> Option<Vec<u8>> {
    let n = quads.len();
    // Literal 2q + d: "quad q uses diagonal d"; its negation is 2q + 1 - d.
    let mut implications: Vec<(u32, u32)> = Vec::new();
    for &(q, d) in fixed {
        // A fixed diagonal: its negation implies it.
        let l = 2 * q + d as u32;
        implications.push((l ^ 1, l));
    }
    for &(a, b) in pairs {
        let (qa, qb) = (quads[a as usize], quads[b as usize]);
        let clashes = |da, db| coincide(qa, da, qb, db);
        if same_quad(qa, qb) || (0..2).all(|da| (0..2).all(|db| clashes(da, db))) {
            // One face listed twice, or a pair that clashes whatever the diagonals:
            // the input's coincidence, which no choice removes.
            continue;
        }
        for da in 0..2u8 {
            for db in 0..2u8 {
                if coincide(qa, da, qb, db) {
                    // Not both: a=da implies b!=db, and b=db implies a!=da.
                    let (la, lb) = (2 * a + da as u32, 2 * b + db as u32);
                    implications.push((la, lb ^ 1));
                    implications.push((lb, la ^ 1));
                }
            }
        }
    }
    let nodes = 2 * n;
    let mut start = vec![0u32; nodes + 1];
    for &(from, _) in &implications {
        start[from as usize + 1] += 1;
    }
    for i in 0..nodes {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut next = vec![0u32; implications.len()];
    for &(from, to) in &implications {
        next[fill[from as usize] as usize] = to;
        fill[from as usize] += 1;
    }
    // Tarjan: components numbered in the order they complete (sinks first).
    const UNSEEN: u32 = u32::MAX;
    let mut index = vec![UNSEEN; nodes];
    let mut low = vec![0u32; nodes];
    let mut comp = vec![UNSEEN; nodes];
    let mut on_stack = vec![false; nodes];
    let mut stack: Vec<u32> = Vec::new();
    let mut calls: Vec<(u32, u32)> = Vec::new();
    let (mut counter, mut comps) = (0u32, 0u32);
    for root in 0..nodes as u32 {
        if index[root as usize] != UNSEEN {
            continue;
        }
        calls.push((root, start[root as usize]));
        index[root as usize] = counter;
        low[root as usize] = counter;
        counter += 1;
        stack.push(root);
        on_stack[root as usize] = true;
        while let Some(&mut (v, ref mut e)) = calls.last_mut() {
            if *e < start[v as usize + 1] {
                let w = next[*e as usize];
                *e += 1;
                if index[w as usize] == UNSEEN {
                    index[w as usize] = counter;
                    low[w as usize] = counter;
                    counter += 1;
                    stack.push(w);
                    on_stack[w as usize] = true;
                    calls.push((w, start[w as usize]));
                } else if on_stack[w as usize] {
                    low[v as usize] = low[v as usize].min(index[w as usize]);
                }
                continue;
            }
            calls.pop();
            if let Some(&(parent, _)) = calls.last() {
                low[parent as usize] = low[parent as usize].min(low[v as usize]);
            }
            if low[v as usize] == index[v as usize] {
                while let Some(w) = stack.pop() {
                    on_stack[w as usize] = false;
                    comp[w as usize] = comps;
                    if w == v {
                        break;
                    }
                }
                comps += 1;
            }
        }
    }
    // A literal whose component completes first (nearer a sink) is the one to make
    // true; a quad whose two literals share a component has no consistent diagonal.
    (0..n)
        .map(|q| {
            let (c0, c1) = (comp[2 * q], comp[2 * q + 1]);
            (c0 != c1).then_some(u8::from(c1 < c0))
        })
        .collect()
}

/// Candidate pairs [`candidate_pairs`] works out before it gives up.
const SOLVE_BUDGET: usize = 1 << 20;

/// Every pair of `quads` that shares one of its four possible triangles (so three
/// vertices), sorted; `None` when more than about [`SOLVE_BUDGET`] pairs would be
/// listed (hundreds of quads on the same three vertices). QSTRIP solves these pairs
/// when a cluster needs it, and the quad check asks the same question, so the two
/// agree on which coincidences could have been avoided.
pub(super) fn candidate_pairs(quads: &[&[u32]]) -> Option<Vec<(u32, u32)>> {
    let mut by_triangle: Vec<([u32; 3], u32)> = Vec::with_capacity(4 * quads.len());
    for (i, v) in quads.iter().enumerate() {
        for d in 0..2 {
            by_triangle.extend(split_sets(v, d).map(|t| (t, i as u32)));
        }
    }
    by_triangle.sort_unstable();
    by_triangle.dedup();
    let groups = || by_triangle.chunk_by(|a, b| a.0 == b.0).filter(|g| g.len() > 1);
    if groups().map(|g| g.len() * g.len()).sum::<usize>() > 2 * SOLVE_BUDGET {
        return None;
    }
    let mut pairs: Vec<(u32, u32)> = groups()
        .flat_map(|g| (0..g.len()).flat_map(move |i| g[i + 1..].iter().map(move |b| (g[i].1, b.1))))
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    Some(pairs)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute force over every choice of diagonals: some choice leaves no pair (other
    /// than copies and pairs that clash whatever the choice) with coincident triangles.
    fn brute(quads: &[&[u32]], pairs: &[(u32, u32)]) -> bool {
        let counted: Vec<(usize, usize)> = pairs
            .iter()
            .map(|&(a, b)| (a as usize, b as usize))
            .filter(|&(a, b)| {
                !same_quad(quads[a], quads[b])
                    && !(0..2).all(|da| (0..2).all(|db| coincide(quads[a], da, quads[b], db)))
            })
            .collect();
        (0..1u32 << quads.len()).any(|bits| {
            let d = |q: usize| (bits >> q & 1) as u8;
            counted.iter().all(|&(a, b)| !coincide(quads[a], d(a), quads[b], d(b)))
        })
    }

    #[test]
    fn solve_diagonals_agrees_with_brute_force_on_random_clusters() {
        let mut x = 0x9E37_79B9u32;
        let mut rnd = |n: u32| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x % n
        };
        let (mut sat, mut unsat) = (0, 0);
        for _ in 0..3000 {
            let k = 2 + rnd(7) as usize;
            let flat: Vec<[u32; 4]> = (0..k)
                .map(|_| loop {
                    let q = [rnd(6), rnd(6), rnd(6), rnd(6)];
                    if is_quad(&q) {
                        break q;
                    }
                })
                .collect();
            let quads: Vec<&[u32]> = flat.iter().map(|q| &q[..]).collect();
            let pairs: Vec<(u32, u32)> =
                (0..k as u32).flat_map(|a| (a + 1..k as u32).map(move |b| (a, b))).collect();
            let got = solve_diagonals(&quads, &pairs, &[]);
            assert_eq!(got.is_some(), brute(&quads, &pairs), "{flat:?}");
            if let Some(d) = got {
                sat += 1;
                for &(a, b) in &pairs {
                    let (qa, qb) = (quads[a as usize], quads[b as usize]);
                    let hopeless = same_quad(qa, qb) || (0..2).all(|da| (0..2).all(|db| coincide(qa, da, qb, db)));
                    assert!(hopeless || !coincide(qa, d[a as usize], qb, d[b as usize]), "{flat:?} {d:?}");
                }
            } else {
                unsat += 1;
            }
        }
        // Both answers occur, so both branches were compared.
        assert!(sat > 100 && unsat > 100, "{sat} solvable, {unsat} not");
    }
}
