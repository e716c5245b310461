//! `draw_picture`, the whole picture in one call: the counts it reports against the
//! input's, the colours it paints, the size it resizes to, and the errors it refuses
//! with. Each check prints one line of figures.

mod support;

use stripkit::{gen, stripify, StripOptions};
use stripkit_render::paint::{FRONT, GREY, WIRE};
use stripkit_render::{draw_picture, ColorBy, FrameError, PictureError, PictureOptions, Scene, Shading};
use support::renderer;

/// The strips' triangles of `mesh`, numbered by strip, and the positions.
fn strips_of(mesh: &stripkit::Mesh) -> (Vec<(usize, [u32; 3])>, Vec<[f32; 3]>) {
    let strips = stripify(mesh, &StripOptions::default()).expect("strips");
    let mut triangles = Vec::new();
    for (k, s) in strips.strips.iter().enumerate() {
        stripkit::for_each_triangle(s, |t| triangles.push((k, t)));
    }
    (triangles, strips.with_added_vertices(&mesh.positions))
}

fn count(image: &stripkit_render::Image, rgb: [u8; 4]) -> usize {
    image.rgba().chunks_exact(4).filter(|p| p[..3] == rgb[..3]).count()
}

#[test]
fn counts_colours_and_size() {
    let sphere = gen::shuffle_faces(&gen::icosphere(3), 7);
    let (triangles, positions) = strips_of(&sphere);
    let scene = Scene { positions: &positions, triangles: &triangles, morph: None, frame: &positions, scale: 1.0 };
    let mut r = renderer();
    let options = PictureOptions {
        size: (200, 120),
        shading: Shading::Unlit,
        color_by: ColorBy::Cull { view: None },
        view: [0.0, 0.0, 1.0],
        ..PictureOptions::default()
    };
    let picture = draw_picture(&mut r, &scene, &options).expect("picture");
    assert_eq!((picture.image.width(), picture.image.height()), (200, 120), "resized to the options' size");
    assert_eq!(picture.triangles, sphere.triangle_count());
    // A sphere seen from a framing distance (close): well under half its triangles
    // face the eye (472 of 1280 here).
    let share = picture.front as f64 / picture.triangles as f64;
    println!("icosphere 3: {} triangles, {} facing the eye ({share:.3})", picture.triangles, picture.front);
    assert!((0.3..0.5).contains(&share), "{share}");
    // Unlit and culled from the eye itself: every drawn pixel is the front colour.
    let front = count(&picture.image, FRONT);
    let white = count(&picture.image, [255, 255, 255, 255]);
    assert_eq!(front + white, 200 * 120);
    assert!(front > 200 * 120 / 4, "{front}");
    assert_eq!(picture.edges, None);

    // A grey wireframe: every edge of the mesh, once.
    let options = PictureOptions { color_by: ColorBy::None, wireframe: true, ..options };
    let picture = draw_picture(&mut r, &scene, &options).expect("picture");
    let edges = 3 * sphere.triangle_count() / 2;
    println!("icosphere 3 wireframe: {:?} edges, {} wire pixels", picture.edges, count(&picture.image, WIRE));
    assert_eq!(picture.edges, Some(edges));
    assert!(count(&picture.image, WIRE) > 1000 && count(&picture.image, GREY) > 1000);
}

#[test]
fn refusals() {
    let grid = gen::grid(3, 3);
    let (triangles, positions) = strips_of(&grid);
    let bad = |options: PictureOptions| options.check().unwrap_err();
    let base = PictureOptions::default();
    assert!(matches!(bad(PictureOptions { view: [0.0; 3], ..base }), PictureError::Frame(FrameError::ZeroView)));
    assert!(matches!(bad(PictureOptions { up: [0.3, 0.4, 1.0], ..base }), PictureError::Frame(FrameError::BadUp)));
    let cull = PictureOptions { color_by: ColorBy::Cull { view: Some([0.0; 3]) }, ..base };
    assert!(matches!(bad(cull), PictureError::ZeroCullView));
    assert!(base.check().is_ok());

    let mut r = renderer();
    let none: Vec<(usize, [u32; 3])> = Vec::new();
    let empty = Scene { positions: &positions, triangles: &none, morph: None, frame: &positions, scale: 1.0 };
    assert!(matches!(draw_picture(&mut r, &empty, &base), Err(PictureError::NoFaces)));
    let past = [(0, [0, 1, positions.len() as u32])];
    let scene = Scene { triangles: &past, ..empty };
    let err = draw_picture(&mut r, &scene, &base).unwrap_err();
    assert!(err.to_string().contains("past"), "{err}");
    let nothing = Scene { positions: &positions, triangles: &triangles, morph: None, frame: &[], scale: 1.0 };
    assert!(matches!(draw_picture(&mut r, &nothing, &base), Err(PictureError::Frame(FrameError::NothingToFrame))));
}
