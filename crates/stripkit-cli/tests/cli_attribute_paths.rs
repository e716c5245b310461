//! Issue #31's target, "0 attributes lost on any path": one procedural torus with a UV
//! seam, normals, a normalized byte colour and a custom float (`_WEIGHT`), written as
//! glb, OBJ (UV and normal) and PLY (the quad version, for `qstrip`), through every CLI
//! command that writes a mesh. Each output is read back and every attribute kind
//! checked: present, and corner by corner equal to the source where the path keeps the
//! vertices; where it makes new ones (single's Steiner vertices, subdivision, optimal
//! placement) within the source's range, normals unit length. Prints the table
//! (`--nocapture`) and asserts that no cell is lost or wrong.

mod support;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use stripkit::io::{self, Scene};
use stripkit::{Attribute, Mesh, Scalar};
use support::{gltf_validator, stripkit, tmp};

const KINDS: [&str; 4] = ["TEXCOORD_0", "NORMAL", "COLOR_0", "_WEIGHT"];

/// What a path may do to the vertices it writes.
#[derive(Clone, Copy, PartialEq)]
enum Expect {
    /// Every output triangle is a source triangle, every corner its source values.
    Same,
    /// Corners at a source position keep one of that position's values (a seam has
    /// two); corners elsewhere (new vertices) lie within the source's range.
    Survivors,
    /// New vertices everywhere (subdivision): values within the source's range.
    Range,
}

/// A torus cut open along one meridian: the seam column twice (u = 0 and u = 1, same
/// positions), quads or triangles on alternating diagonals, radii jittered, faces
/// shuffled; UVs, unit normals, an RGBA byte colour and a float weight per vertex.
fn torus(major: u32, minor: u32, quads: bool, scale: f32) -> Mesh {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let (mut positions, mut uv, mut normal, mut rgba, mut weight) = (vec![], vec![], vec![], vec![], vec![]);
    for i in 0..=major {
        let a = std::f32::consts::TAU * i as f32 / major as f32;
        for j in 0..minor {
            let b = std::f32::consts::TAU * j as f32 / minor as f32;
            let r = if i == 0 || i == major { 0.5 } else { 0.5 + (next() % 1000) as f32 * 2e-5 };
            let ring = 2.0 + r * b.cos();
            positions.push([scale * a.cos() * ring, scale * a.sin() * ring, scale * r * b.sin()]);
            uv.extend([i as f32 / major as f32, j as f32 / minor as f32]);
            normal.extend([a.cos() * b.cos(), a.sin() * b.cos(), b.sin()]);
            rgba.extend([(i * 29 % 256) as u8, (j * 53 % 256) as u8, 128, 255]);
            weight.push((i * minor + j) as f32 * 0.25);
        }
    }
    let id = |i: u32, j: u32| i * minor + j % minor;
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for i in 0..major {
        for j in 0..minor {
            let [a, b, c, d] = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            if quads {
                faces.push(vec![a, b, c, d]);
            } else if (i + j) % 2 == 0 {
                faces.extend([vec![a, b, c], vec![a, c, d]]);
            } else {
                faces.extend([vec![a, b, d], vec![b, c, d]]);
            }
        }
    }
    for k in (1..faces.len()).rev() {
        faces.swap(k, (next() % (k as u64 + 1)) as usize);
    }
    let mut mesh = Mesh::from_polygons(positions, &faces);
    mesh.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &uv));
    mesh.attributes.push(Attribute::from_f32("NORMAL", 3, &normal));
    let mut colour = Attribute::from_f32("COLOR_0", 4, &[]);
    (colour.scalar, colour.normalized, colour.data) = (Scalar::U8, true, rgba);
    mesh.attributes.push(colour);
    mesh.attributes.push(Attribute::from_f32("_WEIGHT", 1, &weight));
    mesh
}

/// An output file's mesh: glTF through the scene reader (primitives concatenated),
/// other formats through `io::read`.
fn read_back(path: &Path) -> Mesh {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    if ext != "glb" && ext != "gltf" {
        return io::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
    let scene = Scene::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let prims = scene.primitives();
    let mut out = prims[0].mesh.clone();
    for p in &prims[1..] {
        let base = out.positions.len() as u32;
        out.positions.extend(&p.mesh.positions);
        let tris = p.mesh.triangulate().tris;
        for t in tris {
            out.push_face(&t.map(|v| v + base));
        }
        out.attributes.retain(|a| p.mesh.attribute(&a.name).is_some());
        for a in &mut out.attributes {
            a.data.extend(&p.mesh.attribute(&a.name).unwrap().data);
        }
    }
    out
}

fn bits(p: [f32; 3]) -> [u32; 3] {
    p.map(f32::to_bits)
}

/// Three corners rotated to start at the smallest position: a triangle's key across
/// files that number vertices differently; returns the key and the rotation.
fn key(p: [[f32; 3]; 3]) -> ([[u32; 3]; 3], usize) {
    let b = p.map(bits);
    let r = (0..3).min_by_key(|&k| b[k]).unwrap();
    ([b[r], b[(r + 1) % 3], b[(r + 2) % 3]], r)
}

/// The source's lookups: triangles by key (vertex ids in key order), vertices by
/// position, per-component ranges.
struct Source {
    mesh: Mesh,
    tris: HashMap<[[u32; 3]; 3], [u32; 3]>,
    at: HashMap<[u32; 3], Vec<u32>>,
}

impl Source {
    fn new(mesh: Mesh) -> Source {
        let mut tris = HashMap::new();
        for t in mesh.triangulate().tris {
            let (k, r) = key(t.map(|v| mesh.positions[v as usize]));
            tris.insert(k, [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]);
        }
        let mut at: HashMap<[u32; 3], Vec<u32>> = HashMap::new();
        for (v, p) in mesh.positions.iter().enumerate() {
            at.entry(bits(*p)).or_default().push(v as u32);
        }
        Source { mesh, tris, at }
    }

    fn in_range(&self, name: &str, value: &[f64]) -> bool {
        let a = self.mesh.attribute(name).unwrap();
        // A normal blended and made unit length again may leave the source's box.
        let ok = name == "NORMAL" || (0..value.len()).all(|c| {
            let (lo, hi) = (0..a.len()).map(|v| a.get(v, c)).fold((f64::MAX, f64::MIN), |(l, h), x| (l.min(x), h.max(x)));
            value[c] >= lo - 1e-5 && value[c] <= hi + 1e-5
        });
        let unit = name != "NORMAL" || (value.iter().map(|x| x * x).sum::<f64>().sqrt() - 1.0).abs() < 1e-3;
        ok && unit
    }
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-5)
}

/// One cell of the table: `kept`, `changed (...)` as documented, `LOST`, `WRONG (...)`
/// or `-` where the format does not hold the kind.
fn check(src: &Source, out: &Mesh, name: &str, expect: Expect) -> String {
    let Some(got) = out.attribute(name) else { return "LOST".into() };
    let want = src.mesh.attribute(name).unwrap();
    let tris = out.triangulate().tris;
    if tris.is_empty() {
        return "WRONG (no triangles)".into();
    }
    if expect == Expect::Same && tris.len() != src.tris.len() {
        return format!("WRONG ({} of {} triangles)", tris.len(), src.tris.len());
    }
    let (mut exact, mut ranged) = (0, 0);
    for t in &tris {
        let p = t.map(|v| out.positions[v as usize]);
        let (k, r) = key(p);
        let source = if expect == Expect::Range { None } else { src.tris.get(&k) };
        for c in 0..3 {
            let corner = t[(r + c) % 3] as usize;
            let g = got.value(corner);
            if let Some(s) = source {
                if !close(&g, &want.value(s[c] as usize)) {
                    return format!("WRONG (corner of vertex {} is {g:?})", s[c]);
                }
                exact += 1;
                continue;
            }
            match (expect, src.at.get(&bits(out.positions[corner]))) {
                (Expect::Same, _) => return "WRONG (a triangle not in the source)".into(),
                (Expect::Survivors, Some(vs)) => {
                    if !vs.iter().any(|&v| close(&g, &want.value(v as usize))) {
                        return format!("WRONG (survivor at vertex {} is {g:?})", vs[0]);
                    }
                    exact += 1;
                }
                _ => {
                    if !src.in_range(name, &g) {
                        return format!("WRONG (new value {g:?} out of range)");
                    }
                    ranged += 1;
                }
            }
        }
    }
    match ranged {
        0 => format!("kept ({exact} corners)"),
        _ => format!("changed ({ranged} of {} corners new, in range)", exact + ranged),
    }
}

/// Runs one CLI path, reads its output and returns the row.
fn row(label: &str, args: &[&str], out: &Path, src: &Source, kinds: &[&str], expect: Expect) -> (String, Vec<String>) {
    let _ = std::fs::remove_file(out);
    let mut all: Vec<&str> = args.to_vec();
    all.extend(["-o", out.to_str().unwrap()]);
    let o = stripkit(&all);
    if !o.status.success() {
        let why = String::from_utf8_lossy(&o.stderr).lines().next().unwrap_or("").to_string();
        return (label.into(), vec![format!("FAILED ({why})")]);
    }
    let mesh = read_back(out);
    let cell = |k: &&str| check(src, &mesh, k, expect);
    let cells = KINDS.iter().map(|k| if kinds.contains(k) { cell(k) } else { "-".into() }).collect();
    (label.into(), cells)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn every_path_keeps_every_attribute_kind() {
    let dir = |name: &str| tmp("attrpaths", name);
    let tri = torus(16, 9, false, 1.0);
    let quad = torus(16, 9, true, 1.0);
    let (glb, ply, obj) = (dir("src.glb"), dir("src.ply"), dir("src.obj"));
    let (qply, qobj) = (dir("quad.ply"), dir("quad.obj"));
    for (path, mesh) in [(&glb, &tri), (&ply, &tri), (&obj, &tri), (&qply, &quad), (&qobj, &quad)] {
        io::write(path, mesh, None).unwrap();
    }
    // The sources as the files give them back (OBJ's decimals, glTF's triangles).
    let src = Source::new(read_back(&glb));
    let src_obj = Source::new(read_back(&obj));
    let src_quad = Source::new(read_back(&qply));
    let src_qobj = Source::new(read_back(&qobj));
    let all = &KINDS[..];
    let obj_kinds = &KINDS[..2];
    let mut rows = Vec::new();
    let mut gltfs: Vec<PathBuf> = vec![glb.clone()];
    let mut out = |name: &str| {
        let p = dir(name);
        if name.ends_with(".glb") || name.ends_with(".gltf") {
            gltfs.push(p.clone());
        }
        p
    };
    use Expect::*;
    // strip: every algorithm; glb -> glb is the scene path, the others the mesh path.
    for algo in ["auto", "greedy", "cache", "balanced", "single"] {
        let expect = if algo == "single" { Survivors } else { Same };
        for (input, to) in [(&glb, "glb"), (&glb, "ply"), (&ply, "ply"), (&ply, "glb")] {
            if algo == "single" && to == "glb" && input == &glb {
                continue; // refused for a scene (single adds vertices)
            }
            let a = ["strip", s(input), "--algo", algo];
            let from = input.extension().unwrap().to_str().unwrap();
            let label = format!("strip --algo {algo} {from}->{to}");
            rows.push(row(&label, &a, &out(&format!("{algo}_{from}.{to}")), &src, all, expect));
        }
        let a = ["strip", s(&obj), "--algo", algo];
        rows.push(row(&format!("strip --algo {algo} obj->obj"), &a, &out(&format!("{algo}.obj")), &src_obj, obj_kinds, expect));
    }
    // Cull weights with swaps off merge a loop by an edge split: one Steiner vertex.
    let a = ["strip", s(&ply), "--algo", "single", "--weights", "cull", "--swap-angle", "off"];
    rows.push(row("strip --algo single --weights cull --swap-angle off ply->glb", &a, &out("steiner.glb"), &src, all, Survivors));
    rows.push(row("strip --algo single --weights cull --swap-angle off ply->ply", &a, &out("steiner.ply"), &src, all, Survivors));
    // qstrip splits each quad on the diagonal it chooses: corners checked by position.
    let a = ["strip", s(&qply), "--algo", "qstrip"];
    rows.push(row("strip --algo qstrip quads ply->ply", &a, &out("qstrip.ply"), &src_quad, all, Survivors));
    rows.push(row("strip --algo qstrip quads ply->glb", &a, &out("qstrip.glb"), &src_quad, all, Survivors));
    let a = ["strip", s(&qobj), "--algo", "qstrip"];
    rows.push(row("strip --algo qstrip quads obj->obj", &a, &out("qstrip.obj"), &src_qobj, obj_kinds, Survivors));
    for join in ["restart", "degenerate", "separate"] {
        for (input, to) in [(&glb, "glb"), (&ply, "ply"), (&ply, "glb")] {
            if join == "separate" && input == &glb {
                continue; // refused for a scene
            }
            let from = input.extension().unwrap().to_str().unwrap();
            let a = ["strip", s(input), "--join", join];
            rows.push(row(&format!("strip --join {join} {from}->{to}"), &a, &out(&format!("{join}_{from}.{to}")), &src, all, Same));
        }
    }
    for (input, to) in [(&glb, "glb"), (&ply, "glb"), (&ply, "ply")] {
        let from = input.extension().unwrap().to_str().unwrap();
        let a = ["strip", s(input), "--vertex-order", "input"];
        rows.push(row(&format!("strip --vertex-order input {from}->{to}"), &a, &out(&format!("input_{from}.{to}")), &src, all, Same));
        if to == "glb" {
            let a = ["strip", s(input), "--compress"];
            rows.push(row(&format!("strip --compress {from}->{to}"), &a, &out(&format!("compress_{from}.glb")), &src, all, Same));
            let a = ["strip", s(input), "--join", "degenerate", "--compress"];
            let label = format!("strip --join degenerate --compress {from}->{to}");
            rows.push(row(&label, &a, &out(&format!("compress_deg_{from}.glb")), &src, all, Same));
        }
    }
    rows.push(row("strip glb->gltf (scene)", &["strip", s(&glb)], &out("scene.gltf"), &src, all, Same));
    for input in [&glb, &ply] {
        mesh_commands(input, &src, &mut rows, &mut out);
    }
    // lod build-seq on three frames (scaled copies), frame 1 extracted.
    for ext in ["glb", "ply"] {
        let frames = dir(&format!("{ext}_frames"));
        std::fs::create_dir_all(&frames).unwrap();
        for (k, scale) in [1.0, 1.1, 1.2].into_iter().enumerate() {
            io::write(frames.join(format!("f{k}.{ext}")), &torus(16, 9, false, scale), None).unwrap();
        }
        let src_frame = Source::new(read_back(&frames.join(format!("f1.{ext}"))));
        let anim = dir(&format!("anim_{ext}.lodseq"));
        let b = stripkit(&["lod", "build-seq", s(&frames), "-o", s(&anim)]);
        assert!(b.status.success(), "{}", String::from_utf8_lossy(&b.stderr));
        for (flag, value, expect) in [("--level", "0", Same), ("--ratio", "0.3", Survivors)] {
            let a = ["lod", "extract", s(&anim), "--frame", "1", flag, value];
            let label = format!("lod build-seq {ext} frames + extract --frame 1 {flag} {value} -o glb");
            rows.push(row(&label, &a, &out(&format!("seq_{ext}_{value}.glb")), &src_frame, all, expect));
        }
    }
    let a = ["gen", "subdivide", s(&qply), "--scheme", "catmull-clark", "--levels", "1"];
    rows.push(row("gen subdivide catmull-clark quads ply->ply", &a, &out("cc.ply"), &src_quad, all, Range));
    print_table(&rows);
    let paths: Vec<&Path> = gltfs.iter().map(|p| p.as_path()).filter(|p| p.exists()).collect();
    if let Some(reports) = gltf_validator::validate(&paths) {
        println!("{} glTF files through the Khronos validator, no error", reports.len());
    }
    let bad: Vec<_> = rows
        .iter()
        .filter(|(_, cells)| cells.iter().any(|c| c.starts_with("LOST") || c.contains("WRONG") || c.starts_with("FAILED")))
        .collect();
    assert!(bad.is_empty(), "{bad:#?}");
    println!("{} paths, none loses an attribute", rows.len());
}

/// simplify (with `--sequence` and the library's replay), lod build + extract at two
/// levels in three formats, and Loop subdivision, from `input`.
fn mesh_commands(input: &Path, src: &Source, rows: &mut Vec<(String, Vec<String>)>, out: &mut dyn FnMut(&str) -> PathBuf) {
    use Expect::*;
    let (all, obj_kinds) = (&KINDS[..], &KINDS[..2]);
    let from = input.extension().unwrap().to_str().unwrap().to_string();
    // Endpoint placement keeps positions: survivors keep their values; optimal moves.
    let a = ["simplify", s(input), "--ratio", "0.5"];
    rows.push(row(&format!("simplify --ratio 0.5 {from}->glb"), &a, &out(&format!("simplified_{from}.glb")), src, all, Survivors));
    let a = ["simplify", s(input), "--ratio", "0.5", "--placement", "optimal"];
    let label = format!("simplify --placement optimal {from}->glb");
    rows.push(row(&label, &a, &out(&format!("optimal_{from}.glb")), src, all, Survivors));
    let seq = out(&format!("seq_{from}.bin"));
    let a = ["simplify", s(input), "--ratio", "0.3", "--keep-unreferenced", "--sequence", s(&seq)];
    let kept = out(&format!("kept_{from}.glb"));
    rows.push(row(&format!("simplify --sequence {from}->glb"), &a, &kept, src, all, Survivors));
    rows.push(replay_row(input, &seq, &kept, src));
    let sets = out(&format!("model_{from}.sets"));
    assert!(stripkit(&["lod", "build", s(input), "-o", s(&sets)]).status.success());
    for ext in ["glb", "ply", "obj"] {
        let kinds = if ext == "obj" { obj_kinds } else { all };
        for (flag, value, expect) in [("--level", "0", Same), ("--ratio", "0.3", Survivors)] {
            let a = ["lod", "extract", s(&sets), flag, value];
            let label = format!("lod build {from} + extract {flag} {value} -o {ext}");
            rows.push(row(&label, &a, &out(&format!("lod_{from}_{value}.{ext}")), src, kinds, expect));
        }
    }
    let a = ["gen", "subdivide", s(input), "--scheme", "loop", "--levels", "1"];
    rows.push(row(&format!("gen subdivide loop {from}->glb"), &a, &out(&format!("loop_{from}.glb")), src, all, Range));
}

/// `simplify --sequence` replayed by the library on the input: every corner of the
/// replayed triangles equals the CLI's simplified output's.
fn replay_row(input: &Path, seq: &Path, simplified: &Path, src: &Source) -> (String, Vec<String>) {
    let label = format!("simplify --sequence {} + library replay", input.extension().unwrap().to_str().unwrap());
    let sequence = stripkit::simplify::CollapseSequence::read(seq).unwrap();
    let mesh = io::read(input).unwrap();
    let replayed = match sequence.replay(&mesh, sequence.len()) {
        Ok(r) => r.to_mesh(),
        Err(e) => return (label, vec![format!("FAILED ({e})")]),
    };
    let cli = Source::new(read_back(simplified));
    let cells = KINDS
        .iter()
        .map(|k| {
            let same = check(&cli, &replayed, k, Expect::Same);
            match same.starts_with("kept") {
                true => check(src, &replayed, k, Expect::Survivors),
                false => format!("{same} vs simplify -o"),
            }
        })
        .collect();
    (label, cells)
}

fn print_table(rows: &[(String, Vec<String>)]) {
    println!("| path | {} |", KINDS.join(" | "));
    println!("|---|{}", "---|".repeat(KINDS.len()));
    for (label, cells) in rows {
        println!("| {label} | {} |", cells.join(" | "));
    }
}
