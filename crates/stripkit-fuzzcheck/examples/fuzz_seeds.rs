//! Writes the `scene` target's seeds into a folder (fuzz/seed.sh runs it):
//!     cargo run -p stripkit-fuzzcheck --example fuzz_seeds -- fuzz/corpus/scene
//! and, given `--defects`, only the defect inputs (for fuzz/regressions/scene).

fn main() -> std::io::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let defects = args.iter().any(|a| a == "--defects");
    let Some(dir) = args.iter().find(|a| !a.starts_with("--")) else {
        eprintln!("usage: fuzz_seeds [--defects] DIR");
        std::process::exit(2);
    };
    std::fs::create_dir_all(dir)?;
    let seeds = if defects {
        stripkit_fuzzcheck::seeds::defects()
    } else {
        stripkit_fuzzcheck::seeds::scenes()
    };
    for (name, bytes) in &seeds {
        std::fs::write(std::path::Path::new(dir).join(name), bytes)?;
    }
    println!("{} seeds in {dir}", seeds.len());
    Ok(())
}
