//! Prints an FNV-1a hash of the strips of every stripifier mode on every model of the
//! shared models folder (and its `quads` folder), one line per (model, mode): a
//! refactoring that must not change any output is checked by diffing this output
//! before and after.
//!
//! `STRIPKIT_HASH_DIRS=DIR:DIR cargo test --release -p stripkit --lib strip_hashes --
//! --ignored --nocapture` (default: the shared models folder and its `quads` folder).
//! It is a test of the crate, not an example, because it reaches the stripifiers'
//! internals (raw triangle lists, every mode's options).

use std::path::{Path, PathBuf};
use std::time::Instant;
use crate::metrics::{self, CacheKind};
use crate::simplify;
use crate::strip::StripSet;
use crate::stripify::cache::{self, CacheOptions};
use crate::stripify::Split;
use crate::stripify::greedy::{self, GreedyOptions, Heuristic};
use crate::stripify::{quad, quad_single};

struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn u32(&mut self, x: u32) {
        for b in x.to_le_bytes() {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }
    fn strips(&mut self, s: &StripSet) {
        self.u32(s.indices.len() as u32);
        s.indices.iter().for_each(|&v| self.u32(v));
        self.u32(s.offsets.len() as u32);
        s.offsets.iter().for_each(|&v| self.u32(v));
    }
}

fn hash(s: &StripSet) -> String {
    let mut h = Fnv::new();
    h.strips(s);
    format!("{:016x} idx {} strips {}", h.0, s.restart_len(), s.len())
}

fn models(dirs: &[PathBuf]) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for d in dirs {
        let Ok(rd) = std::fs::read_dir(d) else { continue };
        let mut files: Vec<PathBuf> = rd
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.is_file()
                    && p.extension().and_then(|e| e.to_str()).is_some_and(|e| {
                        ["obj", "ply", "off", "stl", "gltf", "glb"].contains(&e)
                    })
            })
            .collect();
        files.sort();
        out.extend(files);
    }
    out
}

#[test]
#[ignore = "a tool: prints hashes of every output for diffing before and after a refactoring"]
fn strip_hashes() {
    let args: Vec<PathBuf> =
        std::env::var("STRIPKIT_HASH_DIRS").map(|v| v.split(':').map(PathBuf::from).collect()).unwrap_or_default();
    let dirs = if args.is_empty() {
        let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/models");
        vec![base.clone(), base.join("quads")]
    } else {
        args
    };
    let t_all = Instant::now();
    for path in models(&dirs) {
        let name = path
            .strip_prefix(path.parent().and_then(|p| p.parent()).unwrap_or(Path::new("")))
            .unwrap_or(&path)
            .display()
            .to_string();
        let mesh = match crate::test_support::read_surface(&path) {
            Ok(m) => m,
            Err(e) => {
                println!("{name}: unreadable: {e}");
                continue;
            }
        };
        let tris = mesh.triangulate().tris;
        let vc = mesh.vertex_count();
        let line = |mode: &str, s: String, t: Instant| {
            println!("{name} | {mode} | {s}");
            eprintln!("{name} {mode}: {:.0} ms", t.elapsed().as_secs_f64() * 1e3);
        };
        let t = Instant::now();
        line("facts", format!("{:?}", crate::topology::MeshFacts::of(&mesh).map_err(|e| e.to_string())), t);
        let t = Instant::now();
        let g = greedy::stripify(&tris, vc, &GreedyOptions::default());
        let d = crate::strip::decode(&g);
        let misses: Vec<usize> = [(16, CacheKind::Fifo), (32, CacheKind::Fifo), (3, CacheKind::Fifo), (16, CacheKind::Lru)]
            .iter()
            .map(|&(c, k)| metrics::cache_misses(&d, vc, c, k))
            .collect();
        line("greedy default", format!("{} misses {misses:?}", hash(&g)), t);
        let f = metrics::figures(&tris, &g, metrics::CacheModel::lru(8));
        line("greedy figures", format!("{f:?}"), Instant::now());
        if tris.len() < 30_000 {
            let diag = mesh.bounds().map_or(1.0, |(lo, hi)| {
                ((0..3).map(|i| ((hi[i] - lo[i]) as f64).powi(2)).sum::<f64>()).sqrt()
            });
            for (sname, pd) in [("simplify", None), ("simplify pairs", Some(0.01 * diag))] {
                let t = Instant::now();
                let o = simplify::Options::default().pair_distance(pd);
                let s = match simplify::simplify(&mesh, &o, &mut |_| {}) {
                    Ok(s) => {
                        let mut h = Fnv::new();
                        s.mesh.face_indices.iter().chain(&s.triangle_ids).for_each(|&v| h.u32(v));
                        s.mesh.positions.iter().flatten().for_each(|&x| h.u32(x.to_bits()));
                        s.sequence.to_bytes().iter().for_each(|&b| h.u32(b.into()));
                        format!("{:016x} out {} err {:016x}", h.0, s.triangles_out(), s.max_error.to_bits())
                    }
                    Err(e) => format!("error: {e}"),
                };
                line(sname, s, t);
            }
        }
        let t = Instant::now();
        let o = GreedyOptions::default().heuristic(Heuristic::Strips);
        line("greedy strips", hash(&greedy::stripify(&tris, vc, &o)), t);
        let t = Instant::now();
        let o = GreedyOptions { tunnel_cuts: None, ..GreedyOptions::default() };
        line("greedy paper", hash(&greedy::stripify(&tris, vc, &o)), t);
        let t = Instant::now();
        let o = GreedyOptions { tunnel_cuts: Some(3), ..GreedyOptions::default() };
        line("greedy tunnel3", hash(&greedy::stripify(&tris, vc, &o)), t);
        let t = Instant::now();
        line("cache::stripify raw", hash(&cache::stripify(&tris, vc, &CacheOptions::cache(16))), t);
        for (mode, o, bound) in [
            ("cache", CacheOptions::cache(16), None),
            ("cache --refine", CacheOptions { refine: true, ..CacheOptions::cache(16) }, None),
            ("balanced", CacheOptions::balanced(16), Some(0.8)),
        ] {
            for (dname, d) in [("auto", Split::Auto), ("fan", Split::Fan), ("qstrip", Split::Qstrip)] {
                if d != Split::Auto && quad::quad_fraction(&mesh) < 0.5 {
                    continue;
                }
                let t = Instant::now();
                let m = cache::stripify_mesh(&mesh, &o, bound, d, Default::default());
                let s = format!(
                    "{} w {:08x} acmr {:016x} q {}",
                    hash(&m.strips),
                    m.miss_weight.to_bits(),
                    m.acmr.to_bits(),
                    m.qstrip_diagonals
                );
                line(&format!("{mode} {dname}"), s, t);
            }
        }
        let t = Instant::now();
        let (q, all) = quad::qstrip_mesh(&mesh, &quad::QuadOptions::default());
        let check = crate::stripify::quad_verify::verify_quads(&mesh, &all).map_err(|e| e.to_string());
        line("qstrip verify", format!("{check:?}"), Instant::now());
        line(
            "qstrip_mesh",
            format!("{} | quads {} swaps {} forced {}", hash(&all), hash(&q.strips), q.swaps, q.forced_diagonals),
            t,
        );
        let t = Instant::now();
        let s = match quad_single::quad_single(&mesh) {
            Ok(s) => format!("{} cycles {} swaps {}", hash(&s.strips), s.cycles, s.swaps),
            Err(e) => format!("error: {e}"),
        };
        line("quad_single", s, t);
    }
    eprintln!("total {:.1} s", t_all.elapsed().as_secs_f64());
}
