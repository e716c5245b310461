//! Property tests: any mesh (any finite coordinates, any polygon faces) and any strip
//! set survive a write and read in every format that can hold them.

use proptest::prelude::*;
use stripkit::io::{read_bytes, write_bytes, Format, WriteOptions};
use stripkit::{decode, StripSet};
use stripkit::Mesh;

fn finite_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        any::<u32>().prop_map(f32::from_bits).prop_filter("finite", |v| v.is_finite()),
        (-1000i32..1000).prop_map(|v| v as f32 / 8.0),
        Just(-0.0f32),
    ]
}

fn mesh_strategy() -> impl Strategy<Value = Mesh> {
    (1usize..40).prop_flat_map(|nv| {
        let positions = prop::collection::vec([finite_f32(), finite_f32(), finite_f32()], nv);
        let faces = prop::collection::vec(prop::collection::vec(0..nv as u32, 3..7), 0..30);
        (positions, faces).prop_map(|(p, f)| Mesh::from_polygons(p, &f))
    })
}

fn bits(m: &Mesh) -> Vec<[u32; 3]> {
    m.positions.iter().map(|p| p.map(f32::to_bits)).collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn polygon_formats_round_trip_bit_for_bit(mesh in mesh_strategy()) {
        let path = std::path::Path::new("prop");
        for (format, ascii) in [(Format::Obj, false), (Format::Off, false), (Format::Ply, false), (Format::Ply, true)] {
            let bytes = write_bytes(format, &mesh, None, &WriteOptions::default().ply_ascii(ascii)).unwrap();
            let back = read_bytes(path, format, &bytes).unwrap();
            prop_assert_eq!(bits(&back), bits(&mesh), "{:?} ascii={}", format, ascii);
            prop_assert_eq!(&back.face_offsets, &mesh.face_offsets);
            prop_assert_eq!(&back.face_indices, &mesh.face_indices);
        }
        for format in [Format::Gltf, Format::Glb] {
            let bytes = write_bytes(format, &mesh, None, &WriteOptions::default()).unwrap();
            let back = read_bytes(path, format, &bytes).unwrap();
            prop_assert_eq!(bits(&back), bits(&mesh));
            let tris: Vec<[u32; 3]> = back.faces().map(|f| [f[0], f[1], f[2]]).collect();
            prop_assert_eq!(tris, mesh.triangulate().tris);
        }
    }

    #[test]
    fn strips_round_trip_as_their_decoded_triangles(
        mesh in mesh_strategy(),
        raw in prop::collection::vec(prop::collection::vec(any::<u32>(), 0..12), 0..8),
    ) {
        let nv = mesh.vertex_count() as u32;
        let strips: Vec<Vec<u32>> = raw.iter().map(|s| s.iter().map(|&i| i % nv).collect()).collect();
        let set = StripSet::from_strips(&strips);
        let path = std::path::Path::new("prop");
        for (format, ascii) in [(Format::Ply, false), (Format::Ply, true), (Format::Gltf, false), (Format::Glb, false)] {
            let bytes = write_bytes(format, &mesh, Some(&set), &WriteOptions::default().ply_ascii(ascii)).unwrap();
            let back = read_bytes(path, format, &bytes).unwrap();
            prop_assert_eq!(bits(&back), bits(&mesh));
            let tris: Vec<[u32; 3]> = back.faces().map(|f| [f[0], f[1], f[2]]).collect();
            prop_assert_eq!(tris, decode(&set), "{:?} ascii={}", format, ascii);
        }
    }
}
