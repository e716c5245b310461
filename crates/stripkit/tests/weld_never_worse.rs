//! Welding and "never worse than the source" (issue #31, item 8): an unindexed mesh
//! (every triangle its own three vertices, shuffled) welds back to its shared vertices
//! where position bits and every attribute agree, and only there; every primitive a
//! scene writes takes at most the index bytes of its source, a primitive of isolated
//! triangles keeping its list as read. Every corner's values are compared, and every
//! glTF written goes through the Khronos validator.

use serde_json::Value;
use std::collections::HashSet;
use std::path::Path;
use stripkit::io::{Format, ReadOptions};
use stripkit::scene::{Scene, SceneOptions};
use stripkit::{gen, stripify, Attribute, Group, Mesh, StripOptions};
use stripkit_testkit::XorShift64;

/// `mesh` with a TEXCOORD_0 of its own per vertex (a pattern, no seam).
fn with_uv(mut mesh: Mesh) -> Mesh {
    let uv: Vec<f32> = (0..mesh.vertex_count()).flat_map(|v| [(v % 7) as f32 / 7.0, (v % 5) as f32 / 5.0]).collect();
    mesh.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &uv));
    mesh
}

/// `mesh` unindexed: its triangles in a shuffled order, each with three vertices of its
/// own carrying every attribute.
fn deindexed(mesh: &Mesh, seed: u64) -> Mesh {
    let mut tris = mesh.triangulate().tris;
    XorShift64(seed).shuffle(&mut tris);
    let corners: Vec<u32> = tris.iter().flatten().copied().collect();
    let mut out = mesh.gather_vertices(&corners);
    for t in 0..tris.len() as u32 {
        out.push_face(&[3 * t, 3 * t + 1, 3 * t + 2]);
    }
    out
}

/// A vertex's values: position bits and every attribute's bytes.
fn key(mesh: &Mesh, v: u32) -> Vec<u8> {
    let mut k: Vec<u8> = mesh.positions[v as usize].iter().flat_map(|x| x.to_bits().to_le_bytes()).collect();
    for a in &mesh.attributes {
        let size = a.components as usize * a.scalar.size();
        k.extend_from_slice(&a.data[v as usize * size..(v as usize + 1) * size]);
    }
    k
}

/// The triangles as sorted corner values, each rotated to start at its least corner
/// (winding kept): what a renderer draws, whatever the vertex ids.
fn corner_multiset(mesh: &Mesh, tris: &[[u32; 3]]) -> Vec<[Vec<u8>; 3]> {
    let mut out: Vec<[Vec<u8>; 3]> = tris
        .iter()
        .map(|t| {
            let k = t.map(|v| key(mesh, v));
            let r = (0..3).min_by(|&a, &b| k[a].cmp(&k[b])).unwrap();
            [k[r].clone(), k[(r + 1) % 3].clone(), k[(r + 2) % 3].clone()]
        })
        .collect();
    out.sort();
    out
}

/// Distinct vertices of `mesh` by every value, counted by brute force.
fn distinct(mesh: &Mesh) -> usize {
    (0..mesh.vertex_count() as u32).map(|v| key(mesh, v)).collect::<HashSet<_>>().len()
}

#[test]
fn an_unindexed_shuffled_torus_welds_back_only_where_every_attribute_agrees() {
    let source = with_uv(gen::torus(48, 24, 1.0, 0.3));
    let mut flat = deindexed(&source, 31);
    // Ten corners get a UV of their own: those must stay apart.
    let uv = flat.attributes.iter_mut().find(|a| a.name == "TEXCOORD_0").unwrap();
    for c in 0..10usize {
        let at = 3 * c * 8;
        uv.data[at..at + 4].copy_from_slice(&(2.0f32 + c as f32).to_le_bytes());
    }
    assert_eq!(flat.vertex_count(), 6912);
    assert_eq!(distinct(&flat), 1152 + 10);

    let strips = stripify(&flat, &StripOptions::default()).unwrap();
    assert!(strips.figures.verified);
    assert_eq!(strips.welded, 6912 - 1162);
    assert_eq!(strips.figures.triangles, 2304);
    // Corner by corner, the strips draw the input's triangles with every value.
    let drawn = stripkit::decode(&strips.strips);
    assert_eq!(corner_multiset(&flat, &drawn), corner_multiset(&flat, &flat.triangulate().tris));
    // Welded, the torus strips like the indexed one: about 1.05 indices per triangle.
    assert!(strips.figures.indices_restart <= 2304 * 11 / 10, "{}", strips.figures.indices_restart);
    let used: HashSet<u32> = strips.strips.iter().flatten().copied().collect();
    assert_eq!(used.len(), 1162);

    let kept = stripify(&flat, &StripOptions::default().weld(false)).unwrap();
    assert_eq!(kept.welded, 0);
    assert_eq!(kept.figures.strips, 2304);
    assert_eq!(kept.figures.indices_restart, 2304 * 4 - 1);
}

/// The index bytes of each triangle primitive of a written document: its `indices`
/// (count x component size) plus its restart group's, by (mesh, primitive).
fn index_bytes(json: &Value) -> Vec<((usize, usize), usize, usize)> {
    let size = |a: &Value| {
        let acc = &json["accessors"][a.as_u64().unwrap() as usize];
        let width = match acc["componentType"].as_u64().unwrap() {
            5121 => 1,
            5123 => 2,
            _ => 4,
        };
        acc["count"].as_u64().unwrap() as usize * width
    };
    let mut out = Vec::new();
    for (m, mesh) in json["meshes"].as_array().unwrap().iter().enumerate() {
        let groups = mesh.pointer("/extensions/EXT_mesh_primitive_restart/primitiveGroups");
        for (p, prim) in mesh["primitives"].as_array().unwrap().iter().enumerate() {
            let own = prim.get("indices").map_or(0, size);
            let restart: usize = groups
                .and_then(Value::as_array)
                .into_iter()
                .flatten()
                .filter(|g| g["primitives"].as_array().unwrap().iter().any(|x| x.as_u64() == Some(p as u64)))
                .map(|g| size(&g["indices"]))
                .sum();
            out.push(((m, p), own, restart));
        }
    }
    out
}

/// Strips `scene`, writes it as glb under `dir/name`, validates it, and checks every
/// primitive: at most the source's index bytes in each drawn form, the same corners.
fn strip_and_check(mut scene: Scene, dir: &Path, name: &str, options: &StripOptions) -> stripkit::scene::SceneReport {
    let source_json = scene.json().clone();
    let before: Vec<(Mesh, Vec<[u32; 3]>)> =
        scene.primitives().iter().map(|p| (p.mesh.clone(), p.mesh.triangulate().tris)).collect();
    let report = scene.strip(options, &SceneOptions::default()).unwrap();
    let bytes = scene.to_bytes(Format::Glb).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, &bytes).unwrap();
    stripkit_testkit::gltf_validator::validate(&[&path]);
    let back = Scene::from_bytes(&path, Format::Glb, &bytes, &ReadOptions::default()).unwrap();
    let source_bytes = index_bytes(&source_json);
    for ((at, own, restart), (_, source_own, _)) in index_bytes(back.json()).iter().zip(&source_bytes) {
        // An unindexed source counts as the list of its vertices in 16-bit indices.
        let prim = &source_json["meshes"][at.0]["primitives"][at.1];
        let source = if prim.get("indices").is_some() {
            *source_own
        } else {
            let pos = prim["attributes"]["POSITION"].as_u64().unwrap() as usize;
            source_json["accessors"][pos]["count"].as_u64().unwrap() as usize * 2
        };
        assert!(*own <= source && *restart <= source, "{name} {at:?}: {own} / {restart} index bytes, source {source}");
    }
    for ((mesh, tris), b) in before.iter().zip(back.primitives()) {
        assert_eq!(corner_multiset(mesh, tris), corner_multiset(&b.mesh, &b.mesh.triangulate().tris), "{name}");
    }
    report
}

/// Isolated triangles: no two share a vertex value, so strips cannot beat the list.
fn isolated_triangles(n: u32, seed: u64) -> Mesh {
    let mut rng = XorShift64(seed);
    let positions: Vec<[f32; 3]> =
        (0..3 * n).map(|_| [0; 3].map(|_| (rng.below(1 << 20) as f32) / 1024.0)).collect();
    let tris: Vec<[u32; 3]> = (0..n).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    Mesh::from_triangles(positions, &tris)
}

#[test]
fn scene_primitives_never_take_more_index_bytes_than_their_source() {
    let dir = stripkit_testkit::scratch_dir("weld");
    // One primitive of an unindexed torus with UVs, one of isolated triangles.
    let torus = deindexed(&with_uv(gen::torus(48, 24, 1.0, 0.3)), 7);
    let mut isolated = isolated_triangles(300, 5);
    isolated.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &vec![0.5; 2 * isolated.vertex_count()]));
    let mut both = torus.clone();
    let offset = both.vertex_count() as u32;
    both.positions.extend_from_slice(&isolated.positions);
    both.attributes[0].data.extend_from_slice(&isolated.attributes[0].data);
    for f in isolated.faces() {
        both.push_face(&f.iter().map(|v| v + offset).collect::<Vec<_>>());
    }
    both.face_groups = (0..both.face_count()).map(|f| u32::from(f >= 2304)).collect();
    both.groups = vec![
        Group { name: "torus".into(), material: Some("a".into()) },
        Group { name: "isolated".into(), material: Some("b".into()) },
    ];
    let report = strip_and_check(Scene::from_mesh(&both).unwrap(), &dir, "both.glb", &StripOptions::default());
    assert_eq!(report.primitives.len(), 2);
    let (t, i) = (&report.primitives[0], &report.primitives[1]);
    assert_eq!((t.welded, t.kept_as_read, t.indices_read), (6912 - 1152, false, 6912));
    assert!(t.indices_stitched <= 2304 * 11 / 10, "{}", t.indices_stitched);
    assert_eq!((i.welded, i.kept_as_read, i.indices_stitched, i.indices_restart), (0, true, 900, None));
    assert_eq!((report.kept_as_read, report.welded), (1, 6912 - 1152));

    // Without welding the torus is isolated triangles too: both kept as read.
    let report = strip_and_check(
        Scene::from_mesh(&both).unwrap(),
        &dir,
        "both_no_weld.glb",
        &StripOptions::default().weld(false),
    );
    assert_eq!((report.kept_as_read, report.welded), (2, 0));

    // A truly unindexed primitive (no `indices`): welded and stripped, the strips
    // smaller than the list of its vertices.
    let glb = Scene::from_mesh(&torus).unwrap().to_bytes(Format::Glb).unwrap();
    let (mut json, bin) = stripkit_testkit::unglb(&glb);
    json["meshes"][0]["primitives"][0].as_object_mut().unwrap().remove("indices");
    let unindexed = Scene::from_bytes(Path::new("unindexed.glb"), Format::Glb, &stripkit_testkit::glb(&json, &bin), &ReadOptions::default())
        .unwrap();
    let report = strip_and_check(unindexed, &dir, "unindexed.glb", &StripOptions::default());
    assert_eq!((report.kept_as_read, report.welded, report.vertices), (0, 6912 - 1152, 1152));
    let _ = std::fs::remove_dir_all(&dir);
}
