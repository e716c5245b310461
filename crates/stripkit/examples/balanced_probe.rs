//! Prints the `balanced` figures of each model given, through the front door with
//! `Algorithm::balanced(0.8)` and the default split (what `stripkit strip --algo
//! balanced` runs): indices_restart, acmr16, the split used, verification, time.
//!
//! `cargo run --release --example balanced_probe -- models/bunny.obj ..`

use stripkit::{stripify, Algorithm, StripOptions};

fn main() {
    let options = StripOptions::default().algorithm(Algorithm::balanced(0.8));
    for path in std::env::args().skip(1) {
        let mesh = stripkit::io::read(std::path::Path::new(&path)).expect("readable mesh");
        let s = stripify(&mesh, &options).expect("verified strips");
        let ms = s.stripify_time.as_secs_f64() * 1e3;
        let f = &s.figures;
        println!(
            "{path}: T {} strips {} indices_restart {} ({:.4}/tri) acmr16 {:.4} acmr32 {:.3} split {} verified {} {ms:.0} ms",
            f.triangles,
            f.strips,
            f.indices_restart,
            f.indices_per_triangle,
            f.acmr16,
            f.acmr32,
            s.split.name(),
            f.verified
        );
    }
}
