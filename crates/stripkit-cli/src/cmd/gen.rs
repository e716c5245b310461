//! `stripkit gen`: procedural meshes and subdivision, written in any format.

use anyhow::Context;
use clap::{Subcommand, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::time::Instant;
use stripkit::{gen, Mesh};

/// Arguments of `stripkit gen`.
#[derive(clap::Args)]
#[command(after_help = "The output format follows the extension of -o (.obj, .ply, .off, .stl, .gltf, .glb, +.gz).

A one-million-triangle mesh is one command away:
  stripkit gen subdivide bunny.obj --scheme loop --levels 2 -o bunny_1m.ply
  stripkit gen icosphere 8 -o sphere_1m.ply        (1,310,720 triangles)
  stripkit gen grid 708 708 -o grid_1m.obj         (1,002,528 triangles)
Quad meshes: stripkit gen torus --quads --major 200 --minor 100 -o torus.obj,
  stripkit gen subdivide spot_quadrangulated.obj --scheme catmull-clark --levels 2 -o spot_47k_quads.obj")]
pub struct Args {
    #[command(subcommand)]
    what: What,
    /// Print one JSON object (output, what, vertices, faces, triangles, ms) on
    /// stdout instead of the line of text.
    #[arg(long, global = true)]
    json: bool,
    /// Write PLY as ASCII text instead of binary (PLY outputs only).
    #[arg(long, global = true)]
    ascii: bool,
    /// The format written to standard output (`-o -`): obj, ply, off, stl, gltf or
    /// glb (default for `subdivide -`: its --format). The report then goes to
    /// standard error.
    #[arg(long, global = true, value_name = "FORMAT", value_parser = super::parse_format)]
    output_format: Option<stripkit::io::Format>,
}

#[derive(Subcommand)]
enum What {
    /// A W x H grid of unit squares in the plane z = 0 (2WH triangles, or WH quads).
    Grid {
        /// Squares along x (at least 1).
        w: u32,
        /// Squares along y (at least 1).
        h: u32,
        /// Keep each square as one quad instead of two triangles.
        #[arg(long)]
        quads: bool,
        /// Output file; the extension picks the format.
        #[arg(short, long)]
        output: PathBuf,
    },
    /// A unit sphere from an icosahedron split LEVEL times (20 * 4^LEVEL triangles;
    /// level 8 = 1,310,720).
    Icosphere {
        /// Subdivision level, 0 to 9.
        level: u32,
        /// Output file; the extension picks the format.
        #[arg(short, long)]
        output: PathBuf,
    },
    /// A torus around the z axis (2 * major * minor triangles, or major * minor quads).
    Torus {
        /// Segments around the central circle (at least 3).
        #[arg(long, default_value_t = 48)]
        major: u32,
        /// Segments around the tube (at least 3).
        #[arg(long, default_value_t = 24)]
        minor: u32,
        /// Radius of the central circle.
        #[arg(long, default_value_t = 1.0)]
        radius: f32,
        /// Radius of the tube.
        #[arg(long, default_value_t = 0.3)]
        tube: f32,
        /// Quads instead of triangles.
        #[arg(long)]
        quads: bool,
        /// Output file; the extension picks the format.
        #[arg(short, long)]
        output: PathBuf,
    },
    /// The cube [-1,1]^3 as 6 quads (a Catmull-Clark classic), split LEVELS times by
    /// Catmull-Clark (6 * 4^LEVELS quads).
    Cube {
        /// Catmull-Clark levels applied to the cube.
        #[arg(long, default_value_t = 0)]
        levels: u32,
        /// Output file; the extension picks the format.
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Subdivide a mesh: Loop (triangle meshes; each level x4 triangles) or
    /// Catmull-Clark (any polygons; all quads after one level, x4 after that).
    /// Boundaries and non-manifold edges are kept as creases.
    Subdivide {
        /// The input mesh file.
        file: PathBuf,
        /// Subdivision scheme.
        #[arg(long, value_enum)]
        scheme: Scheme,
        /// How many times to subdivide.
        #[arg(long, default_value_t = 1)]
        levels: u32,
        /// Output file; the extension picks the format.
        #[arg(short, long)]
        output: PathBuf,
        #[command(flatten)]
        read: super::ReadArgs,
    },
}

/// Subdivision schemes.
#[derive(Clone, Copy, ValueEnum)]
enum Scheme {
    /// Loop subdivision (triangle meshes only).
    Loop,
    /// Catmull-Clark subdivision (any polygon mesh; output is quads).
    CatmullClark,
}

/// Runs the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let start = Instant::now();
    // The output is checked before any work: a typo must not cost a long build.
    let (format, ascii) = {
        let (output, input) = match &args.what {
            What::Grid { output, .. }
            | What::Icosphere { output, .. }
            | What::Torus { output, .. }
            | What::Cube { output, .. } => (output, None),
            What::Subdivide { output, file, read, .. } => (output, Some((file.as_path(), read))),
        };
        let format = super::output_format(output, args.output_format, input)?;
        if let Some((file, _)) = input {
            super::check_not_inputs(&[("input", file)], &[("-o", output)])?;
        }
        super::check_output_folder(output)?;
        (format, super::write_options(args.ascii, output, Some(format))?)
    };
    let (mesh, output, what) = match args.what {
        What::Grid { w, h, quads, output } => {
            anyhow::ensure!(w >= 1 && h >= 1, "a grid needs W and H of at least 1 (got {w} x {h})");
            gen::check_grid(w, h, quads)?;
            let mesh = if quads { gen::grid_quads(w, h) } else { gen::grid(w, h) };
            (mesh, output, format!("grid {w}x{h}"))
        }
        What::Icosphere { level, output } => {
            gen::check_icosphere(level)?;
            (gen::icosphere(level), output, format!("icosphere level {level}"))
        }
        What::Torus { major, minor, radius, tube, quads, output } => {
            anyhow::ensure!(major >= 3 && minor >= 3, "a torus needs --major and --minor of at least 3");
            anyhow::ensure!(radius.is_finite() && tube.is_finite(), "--radius and --tube must be finite numbers");
            gen::check_torus(major, minor)?;
            let mesh = if quads {
                gen::torus_quads(major, minor, radius, tube)
            } else {
                gen::torus(major, minor, radius, tube)
            };
            (mesh, output, format!("torus {major}x{minor}"))
        }
        What::Cube { levels, output } => {
            gen::check_subdivision(gen::cube().face_indices.len(), levels, "cube")?;
            let mesh = subdivide(gen::cube(), Scheme::CatmullClark, levels)?;
            (mesh, output, format!("cube, {levels} Catmull-Clark levels"))
        }
        What::Subdivide { file, scheme, levels, output, read } => {
            let mesh = read.read(&file)?;
            gen::check_subdivision(mesh.face_indices.len(), levels, &file.display().to_string())?;
            let name = match scheme {
                Scheme::Loop => "Loop",
                Scheme::CatmullClark => "Catmull-Clark",
            };
            let mesh = subdivide(mesh, scheme, levels).with_context(|| format!("{}", file.display()))?;
            (mesh, output, format!("{} after {levels} {name} levels", file.display()))
        }
    };
    let built = Instant::now();
    // Compressed by write_output for a .gz name.
    super::write_output(&output, &stripkit::io::write_bytes(format, &mesh, None, &ascii)?)?;
    let written = Instant::now();
    let report = serde_json::json!({
        "output": output.display().to_string(),
        "what": what,
        "vertices": mesh.vertex_count(),
        "faces": mesh.face_count(),
        "triangles": mesh.triangle_count(),
        "ms": (built - start).as_secs_f64() * 1e3,
        "write_ms": (written - built).as_secs_f64() * 1e3,
    });
    super::print_report_to(&super::Sink::for_output(&output), args.json, &report, |w, _| {
        use std::io::Write;
        writeln!(
            w,
            "wrote {}: {what}: {} vertices, {} faces ({} triangles) in {:.0} ms (+{:.0} ms to write)",
            output.display(),
            mesh.vertex_count(),
            mesh.face_count(),
            mesh.triangle_count(),
            (built - start).as_secs_f64() * 1e3,
            (written - built).as_secs_f64() * 1e3,
        )
    })
}

/// Subdivides level by level with a progress bar (hidden when stderr is not a terminal).
fn subdivide(mut mesh: Mesh, scheme: Scheme, levels: u32) -> anyhow::Result<Mesh> {
    let bar = ProgressBar::new(levels as u64);
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:30}] level {pos}/{len} {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message("subdividing");
    for _ in 0..levels {
        mesh = match scheme {
            Scheme::Loop => gen::subdivide_loop(&mesh, 1)?,
            Scheme::CatmullClark => gen::subdivide_catmull_clark(&mesh, 1)?,
        };
        bar.inc(1);
    }
    bar.finish_and_clear();
    Ok(mesh)
}
