//! The Rust library's side of the C examples' checks (scripts/test) and timing
//! (docs/experiments/c-api.md): the same OBJ, the same calls, the same printout.
//!
//! ```text
//! cargo run -p stripkit-c --example reference -- [--mesh] [--algorithm N] [--join N] [--time RUNS] mesh.obj
//! ```
//!
//! Prints one strip index per line, then `added X Y Z A B` for each vertex `single`
//! added (position bits in hex, the edge it splits), as examples/c/strip_obj.c does;
//! `--time RUNS` prints the median CPU time of `stripify_indices` instead (the C
//! example's measure: the process's CPU clock). With `--c-library target/release/libstripkit.so`
//! (64-bit Linux) it loads the C library into this process and alternates, call by
//! call, `stripify_indices` with the C symbol `stripkit_stripify` on the same input,
//! so that both run on the same heap and machine state; it prints both medians.

use libstripkit::{io, stripify, stripify_indices, Algorithm, Join, Mesh, StripOptions};

/// The process's CPU time in milliseconds (`clock_gettime(CLOCK_PROCESS_CPUTIME_ID)`, as
/// examples/c/strip_obj.c reads it): the library runs on the calling thread.
#[cfg(all(target_os = "linux", target_pointer_width = "64"))]
fn cpu_ms() -> f64 {
    #[repr(C)]
    struct Timespec {
        seconds: i64,
        nanoseconds: i64,
    }
    extern "C" {
        fn clock_gettime(clock: i32, time: *mut Timespec) -> i32;
    }
    const CLOCK_PROCESS_CPUTIME_ID: i32 = 2;
    let mut t = Timespec { seconds: 0, nanoseconds: 0 };
    // SAFETY: a valid clock id and a writable timespec (64-bit Linux layout).
    unsafe { clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &mut t) };
    t.seconds as f64 * 1e3 + t.nanoseconds as f64 / 1e6
}

/// Elsewhere: wall time since the first call.
#[cfg(not(all(target_os = "linux", target_pointer_width = "64")))]
fn cpu_ms() -> f64 {
    use std::sync::OnceLock;
    static START: OnceLock<std::time::Instant> = OnceLock::new();
    START.get_or_init(std::time::Instant::now).elapsed().as_secs_f64() * 1e3
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut mesh_level, mut runs, mut path, mut c_library) = (false, 0usize, None, None);
    let mut options = StripOptions::default();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--mesh" => mesh_level = true,
            "--algorithm" => {
                let n: usize = args.next().ok_or("--algorithm needs a number")?.parse()?;
                options = options.algorithm(Algorithm::NAMES.get(n).ok_or("unknown algorithm")?.parse::<Algorithm>()?);
            }
            "--join" => {
                let join = match args.next().as_deref() {
                    Some("0") => Join::Restart,
                    Some("1") => Join::Degenerate,
                    _ => return Err("--join takes 0 or 1".into()),
                };
                options = options.join(join);
            }
            "--time" => runs = args.next().ok_or("--time needs a number")?.parse()?,
            "--c-library" => c_library = Some(args.next().ok_or("--c-library needs a path")?),
            _ => path = Some(arg),
        }
    }
    let path = path.ok_or("usage: reference [--mesh] [--algorithm N] [--join N] [--time RUNS [--c-library PATH]] mesh.obj")?;
    // Vertex ids are then the file's `v` records, as the C example reads them.
    let mesh = io::read_with(path, &io::ReadOptions::default().positions_only(true))?;
    let tris = mesh.triangulate().tris;
    let flat: Vec<u32> = tris.iter().flatten().copied().collect();
    if let (true, Some(library)) = (runs > 0, &c_library) {
        return c_library_bench(library, &flat, mesh.vertex_count(), runs);
    }
    if runs > 0 {
        let mut times = Vec::with_capacity(runs);
        let mut written = 0;
        for _ in 0..runs {
            let start = cpu_ms();
            written = stripify_indices(&flat, mesh.vertex_count(), &options)?.len();
            times.push(cpu_ms() - start);
        }
        times.sort_by(f64::total_cmp);
        println!(
            "rust {} triangles: median {:.3} ms CPU over {runs} runs ({written} indices)",
            tris.len(),
            times[runs / 2]
        );
        return Ok(());
    }
    let mut out = String::new();
    if mesh_level {
        // What a C caller gives stripkit_stripify_mesh: positions and triangles only.
        let strips = stripify(&Mesh::from_triangles(mesh.positions.clone(), &tris), &options)?;
        let buffer = if strips.join == Join::Degenerate { strips.stitched() } else { strips.restart_buffer() };
        for i in buffer {
            out.push_str(&format!("{i}\n"));
        }
        for (p, [a, b]) in strips.added_positions.iter().zip(&strips.added_from) {
            let [x, y, z] = p.map(f32::to_bits);
            out.push_str(&format!("added {x:08x} {y:08x} {z:08x} {a} {b}\n"));
        }
    } else {
        for i in stripify_indices(&flat, mesh.vertex_count(), &options)? {
            out.push_str(&format!("{i}\n"));
        }
    }
    print!("{out}");
    Ok(())
}

/// `stripkit_stripify`'s C signature (include/stripkit.h).
type CStripify = unsafe extern "C" fn(*mut u32, usize, *const u32, usize, usize, u32, *const std::ffi::c_void) -> i64;

/// The C library's `stripkit_stripify`, loaded with the C library's own loader.
#[cfg(all(target_os = "linux", target_pointer_width = "64"))]
fn load_c_stripify(library: &str) -> Result<CStripify, Box<dyn std::error::Error>> {
    use std::ffi::{c_char, c_void, CString};
    extern "C" {
        fn dlopen(file: *const c_char, mode: i32) -> *mut c_void;
        fn dlsym(handle: *mut c_void, name: *const c_char) -> *mut c_void;
    }
    const RTLD_NOW: i32 = 2;
    let file = CString::new(library)?;
    // SAFETY: C strings that outlive the calls; the handle is kept for the process.
    let handle = unsafe { dlopen(file.as_ptr(), RTLD_NOW) };
    if handle.is_null() {
        return Err(format!("cannot load {library}").into());
    }
    let symbol = unsafe { dlsym(handle, c"stripkit_stripify".as_ptr()) };
    if symbol.is_null() {
        return Err(format!("{library} has no stripkit_stripify").into());
    }
    // SAFETY: the symbol is the header's stripkit_stripify, of this signature.
    Ok(unsafe { std::mem::transmute::<*mut c_void, CStripify>(symbol) })
}

#[cfg(not(all(target_os = "linux", target_pointer_width = "64")))]
fn load_c_stripify(_: &str) -> Result<CStripify, Box<dyn std::error::Error>> {
    Err("--c-library needs 64-bit Linux".into())
}

/// Alternates the Rust call and the C call on the same input, `runs` times each.
fn c_library_bench(
    library: &str,
    flat: &[u32],
    vertex_count: usize,
    runs: usize,
) -> Result<(), Box<dyn std::error::Error>> {
    let c_stripify = load_c_stripify(library)?;
    let options = StripOptions::default();
    let (mut rust_times, mut c_times) = (Vec::with_capacity(runs), Vec::with_capacity(runs));
    let mut destination = vec![0u32; libstripkit::stripify_bound(flat.len())];
    // Each call in turn goes first, so that neither always finds the heap as the other left it.
    for run in 0..runs {
        let mut rust = Vec::new();
        let mut written = 0;
        for turn in [run % 2, 1 - run % 2] {
            let start = cpu_ms();
            if turn == 0 {
                rust = stripify_indices(flat, vertex_count, &options)?;
                rust_times.push(cpu_ms() - start);
            } else {
                // SAFETY: arrays of the lengths given; null options are the defaults.
                written = unsafe {
                    c_stripify(
                        destination.as_mut_ptr(),
                        destination.len(),
                        flat.as_ptr(),
                        flat.len(),
                        vertex_count,
                        u32::MAX,
                        std::ptr::null(),
                    )
                };
                c_times.push(cpu_ms() - start);
            }
        }
        if written < 0 || destination[..written as usize] != rust[..] {
            return Err(format!("the C call gave {written} indices, not the Rust call's {}", rust.len()).into());
        }
    }
    rust_times.sort_by(f64::total_cmp);
    c_times.sort_by(f64::total_cmp);
    let (rust, c) = (rust_times[runs / 2], c_times[runs / 2]);
    println!(
        "{} triangles, {runs} runs each, alternated: median rust {rust:.3} ms CPU, C {c:.3} ms CPU, C / rust {:.4}",
        flat.len() / 3,
        c / rust
    );
    Ok(())
}
