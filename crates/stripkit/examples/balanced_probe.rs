//! Prints the `balanced` figures of each model given: `stripify_mesh` with
//! `CacheOptions::balanced(16)`, a bound of 0.8 and `Diagonals::Auto` (what
//! `stripkit strip --algo balanced` runs): indices_restart, acmr16, verification, time.
//!
//! `cargo run --release --example balanced_probe -- models/bunny.obj ..`

use std::time::Instant;
use stripkit::metrics::{figures, CacheModel};
use stripkit::stripify::cache::{self, CacheOptions, Diagonals};

fn main() {
    for path in std::env::args().skip(1) {
        let mesh = stripkit::mesh::io::read(std::path::Path::new(&path)).expect("readable mesh");
        let t0 = Instant::now();
        let m = cache::stripify_mesh(
            &mesh,
            &CacheOptions::balanced(16),
            Some(0.8),
            Diagonals::Auto,
        );
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        let f = figures(&m.triangles, &m.strips, CacheModel::fifo(16));
        println!(
            "{path}: T {} strips {} indices_restart {} ({:.4}/tri) acmr16 {:.4} (reported {:.4}) acmr32 {:.3} qstrip {} verified {} {ms:.0} ms",
            f.triangles,
            f.strips,
            f.indices_restart,
            f.indices_per_triangle,
            f.acmr16,
            m.acmr,
            f.acmr32,
            m.qstrip_diagonals,
            f.verified
        );
    }
}
