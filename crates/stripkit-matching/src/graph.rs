//! The input graph: an edge list with integer weights plus a CSR adjacency, and the
//! DIMACS-style text reader.
//!
//! Input conventions (documented for callers and for the `stripkit match` command):
//! * vertices are `0..node_count` in the API, `1..=N` in files;
//! * self-loops are kept in the edge list but ignored by the solvers (a vertex cannot
//!   be matched to itself);
//! * parallel edges are allowed; the solvers use the best one (highest weight when
//!   maximizing, lowest when minimizing; on a tie the lower edge id).

use crate::error::{Error, Result};
use std::path::Path;

/// Largest absolute edge weight accepted, 2^40: with the internal doubling and the
/// dual drift of the search, every intermediate value stays far inside `i64`.
pub const MAX_WEIGHT: i64 = 1 << 40;

/// Whether `w` lies in `-MAX_WEIGHT..=MAX_WEIGHT`. Compares magnitudes with
/// `unsigned_abs`, which cannot overflow (`i64::MIN.abs()` wraps to `i64::MIN` in
/// release builds and would pass a `w.abs() > MAX_WEIGHT` test).
pub(crate) fn weight_in_range(w: i64) -> bool {
    w.unsigned_abs() <= MAX_WEIGHT.unsigned_abs()
}

/// How many nodes a DIMACS file may declare beyond those its edges can touch: a file
/// of `M` edge lines may announce at most `2 * M + DIMACS_SPARE_NODES` nodes
/// (2^20 = 1,048,576 spare, isolated nodes). The node count sizes every per-node array
/// of the graph and the solvers, so without this bound a 28-byte `p edge 2000000000 1`
/// would ask for gigabytes; with it, memory stays proportional to the file plus a few
/// megabytes. A graph with more isolated nodes can still be built with [`Graph::new`].
pub const DIMACS_SPARE_NODES: usize = 1 << 20;

/// An undirected graph with `i64` edge weights, stored as an edge list and a CSR
/// adjacency (`adjacency(v)` lists the ids of the edges at `v`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Graph {
    node_count: usize,
    edges: Vec<[u32; 2]>,
    weights: Vec<i64>,
    offsets: Vec<u32>,
    adj: Vec<u32>,
}

impl Graph {
    /// Builds a graph from `node_count` vertices and an edge list with one weight per
    /// edge. Fails when an endpoint is out of range, the lengths differ or a weight
    /// exceeds [`MAX_WEIGHT`] in absolute value. O(nodes + edges).
    pub fn new(node_count: usize, edges: Vec<[u32; 2]>, weights: Vec<i64>) -> Result<Graph> {
        if edges.len() != weights.len() {
            return Err(Error::Invalid(format!(
                "graph has {} edges but {} weights",
                edges.len(),
                weights.len()
            )));
        }
        if node_count >= u32::MAX as usize / 2 || edges.len() >= u32::MAX as usize / 4 {
            return Err(Error::Invalid("graph too large (more than 2^31 nodes or 2^30 edges)".into()));
        }
        for (i, e) in edges.iter().enumerate() {
            if e[0] as usize >= node_count || e[1] as usize >= node_count {
                return Err(Error::Invalid(format!(
                    "edge {i} joins {} and {} but the graph has {node_count} nodes",
                    e[0], e[1]
                )));
            }
            if !weight_in_range(weights[i]) {
                return Err(Error::Invalid(format!(
                    "edge {i} has weight {} beyond the supported range +-2^40",
                    weights[i]
                )));
            }
        }
        let mut offsets = vec![0u32; node_count + 1];
        for e in &edges {
            offsets[e[0] as usize + 1] += 1;
            if e[1] != e[0] {
                offsets[e[1] as usize + 1] += 1;
            }
        }
        for v in 0..node_count {
            offsets[v + 1] += offsets[v];
        }
        let mut fill = offsets.clone();
        let mut adj = vec![0u32; offsets[node_count] as usize];
        for (i, e) in edges.iter().enumerate() {
            adj[fill[e[0] as usize] as usize] = i as u32;
            fill[e[0] as usize] += 1;
            if e[1] != e[0] {
                adj[fill[e[1] as usize] as usize] = i as u32;
                fill[e[1] as usize] += 1;
            }
        }
        Ok(Graph { node_count, edges, weights, offsets, adj })
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.node_count
    }

    /// Number of edges (self-loops and parallel edges included).
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// The edge list.
    pub fn edges(&self) -> &[[u32; 2]] {
        &self.edges
    }

    /// One weight per edge.
    pub fn weights(&self) -> &[i64] {
        &self.weights
    }

    /// Ids of the edges at vertex `v` (a self-loop appears once).
    pub fn adjacency(&self, v: usize) -> &[u32] {
        &self.adj[self.offsets[v] as usize..self.offsets[v + 1] as usize]
    }

    /// Reads a DIMACS-style graph file (see [`Graph::parse_dimacs`]). The file must be
    /// UTF-8 text (a leading byte order mark is skipped); other bytes are an
    /// [`Error::Format`] naming the line that holds them, and UTF-16 is refused by
    /// name.
    pub fn read_dimacs(path: &Path) -> Result<Graph> {
        let bytes = std::fs::read(path).map_err(|source| Error::Io { path: path.to_path_buf(), source })?;
        let text = dimacs_text(&bytes, path)?;
        Graph::parse_dimacs(text, path)
    }

    /// Parses DIMACS-style text: comment lines `c ...`, blank lines, one problem line
    /// `p edge N M` (or `p N M`-style `p <word> N M`) before any edge, then exactly `M`
    /// lines `e U V W` with 1-based vertices and integer weights. `path` only names
    /// the file in errors. Counts are checked against the lines, never trusted for
    /// allocation beyond what the text itself can hold: the node count `N` may be at
    /// most `2 * M + DIMACS_SPARE_NODES` (see [`DIMACS_SPARE_NODES`]). A leading
    /// byte order mark (U+FEFF) is skipped.
    pub fn parse_dimacs(text: &str, path: &Path) -> Result<Graph> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let err = |line: usize, what: String| Error::Format {
            path: path.to_path_buf(),
            at: format!("line {line}"),
            what,
        };
        let mut header: Option<(usize, usize, usize)> = None; // (n, m, line)
        let mut edges = Vec::new();
        let mut weights = Vec::new();
        for (i, raw) in text.lines().enumerate() {
            let lno = i + 1;
            let line = raw.trim();
            if line.is_empty() || line.starts_with('c') {
                continue;
            }
            let mut it = line.split_whitespace();
            match it.next() {
                Some("p") => {
                    if header.is_some() {
                        return Err(err(lno, "second problem line `p ...`".into()));
                    }
                    let fields: Vec<&str> = it.collect();
                    if fields.len() != 3 {
                        return Err(err(lno, format!("expected `p edge N M`, found `{line}`")));
                    }
                    let n: usize = fields[1].parse().map_err(|_| {
                        err(lno, format!("node count `{}` is not a non-negative integer", fields[1]))
                    })?;
                    let m: usize = fields[2].parse().map_err(|_| {
                        err(lno, format!("edge count `{}` is not a non-negative integer", fields[2]))
                    })?;
                    if n >= (u32::MAX / 2) as usize {
                        return Err(err(lno, format!("node count {n} is too large")));
                    }
                    // Never allocate from the count: an edge line takes at least 8 bytes.
                    let cap = m.min(text.len() / 8 + 1);
                    edges.reserve(cap);
                    weights.reserve(cap);
                    header = Some((n, m, lno));
                }
                Some("e") => {
                    let Some((n, m, _)) = header else {
                        return Err(err(lno, "edge line before the problem line `p edge N M`".into()));
                    };
                    let fields: Vec<&str> = it.collect();
                    if fields.len() != 3 {
                        return Err(err(lno, format!("expected `e U V W`, found `{line}`")));
                    }
                    let mut vs = [0u32; 2];
                    for k in 0..2 {
                        let v: u64 = fields[k].parse().map_err(|_| {
                            err(lno, format!("vertex `{}` is not a positive integer", fields[k]))
                        })?;
                        if v == 0 || v > n as u64 {
                            return Err(err(
                                lno,
                                format!("vertex {v} out of range: vertices are 1..={n}"),
                            ));
                        }
                        vs[k] = (v - 1) as u32;
                    }
                    let w: i64 = fields[2].parse().map_err(|_| {
                        err(lno, format!("weight `{}` is not an integer", fields[2]))
                    })?;
                    if !weight_in_range(w) {
                        return Err(err(lno, format!("weight {w} beyond the supported range +-2^40")));
                    }
                    if edges.len() == m {
                        return Err(err(lno, format!("more edge lines than the {m} announced")));
                    }
                    edges.push(vs);
                    weights.push(w);
                }
                Some(other) => {
                    return Err(err(lno, format!("unknown line type `{other}` (expected c, p or e)")));
                }
                None => {}
            }
        }
        let Some((n, m, hline)) = header else {
            return Err(Error::Format {
                path: path.to_path_buf(),
                at: "end of file".into(),
                what: "no problem line `p edge N M`".into(),
            });
        };
        if edges.len() != m {
            return Err(err(
                hline,
                format!("problem line announces {m} edges but the file has {}", edges.len()),
            ));
        }
        let node_limit = m.saturating_mul(2).saturating_add(DIMACS_SPARE_NODES);
        if n > node_limit {
            return Err(err(
                hline,
                format!(
                    "node count {n} is more than the {m} edge lines can use: at most 2 x {m} + \
                     {DIMACS_SPARE_NODES} isolated nodes = {node_limit} (this bounds memory by the file's size)"
                ),
            ));
        }
        Graph::new(n, edges, weights)
    }

    /// Writes the graph as DIMACS-style text (`p edge N M`, `e U V W`, 1-based).
    pub fn to_dimacs(&self) -> String {
        use std::fmt::Write;
        let mut s = String::with_capacity(16 * self.edges.len() + 32);
        let _ = writeln!(s, "p edge {} {}", self.node_count, self.edges.len());
        for (e, w) in self.edges.iter().zip(&self.weights) {
            let _ = writeln!(s, "e {} {} {}", e[0] + 1, e[1] + 1, w);
        }
        s
    }

    /// Writes the edges `ids` (edge ids, as in [`crate::Matching::edges`]) as text, one
    /// `U V W` line each: 1-based vertices and the weight, as in the `e` lines of
    /// [`Graph::to_dimacs`]. Panics on an id that is not an edge of the graph.
    pub fn to_edge_lines(&self, ids: &[u32]) -> String {
        use std::fmt::Write;
        let mut s = String::with_capacity(16 * ids.len());
        for &e in ids {
            let [a, b] = self.edges[e as usize];
            let _ = writeln!(s, "{} {} {}", a + 1, b + 1, self.weights[e as usize]);
        }
        s
    }
}

/// The text of a DIMACS file's bytes: UTF-8 (a byte order mark is left for
/// [`Graph::parse_dimacs`] to skip), or an error naming the line of the first bytes
/// that are not, or saying the file is UTF-16.
fn dimacs_text<'a>(bytes: &'a [u8], path: &Path) -> Result<&'a str> {
    let format = |at: String, what: String| Error::Format { path: path.to_path_buf(), at, what };
    if let Some(kind) = [(&[0xFF, 0xFE], "UTF-16 little-endian"), (&[0xFE, 0xFF], "UTF-16 big-endian")]
        .iter()
        .find_map(|(bom, kind)| bytes.starts_with(*bom).then_some(*kind))
    {
        return Err(format("line 1".into(), format!("the file is {kind} text; save it as UTF-8 (or ASCII)")));
    }
    std::str::from_utf8(bytes).map_err(|e| {
        let at = e.valid_up_to();
        let line = 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
        let column = 1 + at - bytes[..at].iter().rposition(|&b| b == b'\n').map_or(0, |p| p + 1);
        format(
            format!("line {line}"),
            format!("byte 0x{:02X} at column {column} (file offset {at}) is not UTF-8 text", bytes[at]),
        )
    })
}

/// Scales floating-point weights to the integers the solvers work with: each weight
/// becomes `round(w / max|w| * 2^30)`, so the largest magnitude maps to 2^30 and the
/// result is exactly optimal for the rounded weights; against the original floats a
/// matching of `k` edges is optimal to within `k * max|w| / 2^30`. Non-finite weights
/// are an error. All-zero input gives all zeros.
pub fn scale_f64_weights(weights: &[f64]) -> Result<Vec<i64>> {
    let mut max = 0.0f64;
    for (i, &w) in weights.iter().enumerate() {
        if !w.is_finite() {
            return Err(Error::Invalid(format!("weight {i} is not finite ({w})")));
        }
        max = max.max(w.abs());
    }
    if max == 0.0 {
        return Ok(vec![0; weights.len()]);
    }
    let scale = (1u64 << 30) as f64 / max;
    Ok(weights.iter().map(|&w| (w * scale).round() as i64).collect())
}
