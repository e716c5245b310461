//! Segment-tree back-face culling (`stripkit::cull`) on single strips and greedy strips
//! of procedural meshes (shuffled, jittered): the tree's invariants, every drawn range
//! decoded (front-facing or silhouette triangles only, input winding), every
//! front-facing triangle drawn, and the render front equal to the traversal from the
//! roots on random camera paths.

mod support;

use std::collections::HashMap;
use stripkit::cull::{
    bounding_sphere, helix_eyes, CullOptions, Culled, Facing, FacingCounter, Frustum, RenderFront, SegmentTree, Side,
    HELIX_VIEWS,
};
use stripkit::{gen, stripify, Algorithm, Mesh, SingleOptions, StripOptions, Strips, Weights};

use stripkit_testkit::geom::{cross, dot, sub};
use stripkit_testkit::XorShift64 as Rng;

fn jitter(mesh: &Mesh, amount: f32, seed: u64) -> Mesh {
    let mut rng = Rng(seed.wrapping_mul(0x9E3779B97F4A7C15) | 1);
    let mut m = mesh.clone();
    for p in &mut m.positions {
        for x in p.iter_mut() {
            *x += amount * (rng.unit() as f32 - 0.5);
        }
    }
    m
}

fn meshes() -> Vec<(&'static str, Mesh)> {
    let sphere = gen::icosphere(3);
    let torus = gen::torus(32, 12, 1.0, 0.35);
    let blob = jitter(&gen::subdivide_loop(&jitter(&gen::icosphere(1), 0.5, 3), 2).unwrap(), 0.02, 4);
    vec![
        ("icosphere", gen::shuffle_faces(&sphere, 7)),
        ("torus", gen::shuffle_faces(&jitter(&torus, 0.01, 5), 11)),
        ("loop blob", gen::renumber_vertices(&gen::shuffle_faces(&blob, 13), 17)),
        ("cube grid", gen::cube_grid(5)),
    ]
}

fn strip_with(mesh: &Mesh, algorithm: Algorithm) -> Strips {
    let s = stripify(mesh, &StripOptions::default().algorithm(algorithm)).unwrap();
    assert!(s.figures.verified && s.figures.winding_preserved);
    s
}

fn single(mesh: &Mesh, weights: Weights) -> Strips {
    strip_with(mesh, Algorithm::Single(SingleOptions::new(weights)))
}

fn p64(p: [f32; 3]) -> [f64; 3] {
    p.map(|x| x as f64)
}
fn unit_normal(t: [u32; 3], pos: &[[f32; 3]]) -> Option<[f64; 3]> {
    let [a, b, c] = t.map(|v| p64(pos[v as usize]));
    let n = cross(sub(b, a), sub(c, a));
    let l = dot(n, n).sqrt();
    (l > 1e-12).then(|| n.map(|x| x / l))
}
/// Signed distance of the eye above the triangle's plane: > 0 front-facing.
fn facing(t: [u32; 3], pos: &[[f32; 3]], eye: [f32; 3]) -> f64 {
    match unit_normal(t, pos) {
        Some(n) => dot(n, sub(p64(eye), p64(pos[t[0] as usize]))),
        None => 0.0,
    }
}
fn canonical(t: [u32; 3]) -> [u32; 3] {
    let k = (0..3).min_by_key(|&k| t[k]).unwrap();
    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
}
fn strip_triangle(idx: &[u32], i: usize) -> [u32; 3] {
    if i % 2 == 0 {
        [idx[i], idx[i + 1], idx[i + 2]]
    } else {
        [idx[i + 1], idx[i], idx[i + 2]]
    }
}
fn drawable(t: [u32; 3]) -> bool {
    t[0] != t[1] && t[1] != t[2] && t[0] != t[2]
}

/// The tree's invariants: each internal node is exactly the union of its two children
/// (consecutive in the strip), leaves are the strip's pairs, every cone holds its
/// triangles' normals and every sphere their vertices.
fn check_tree(name: &str, strips: &Strips, pos: &[[f32; 3]], tree: &SegmentTree) {
    let set = &strips.strips;
    let idx = &set.indices;
    // Leaves: the drawable pairs of each strip, in order, every drawable triangle once.
    let leaves: Vec<u32> = tree.leaves().collect();
    for (k, &l) in leaves.iter().enumerate() {
        assert_eq!(tree.nodes[l as usize].first_leaf as usize, k, "{name}");
    }
    let mut leaf = 0usize;
    for (s, strip) in set.iter().enumerate() {
        let base = set.offsets[s] as usize;
        for k in (0..strip.len().saturating_sub(2)).step_by(2) {
            let n = (k..(k + 2).min(strip.len() - 2)).filter(|&i| drawable(strip_triangle(strip, i))).count();
            if n == 0 {
                continue;
            }
            let l = &tree.nodes[leaves[leaf] as usize];
            assert_eq!((l.start as usize, l.strip as usize, l.triangles as usize), (base + k, s, n), "{name}");
            leaf += 1;
        }
    }
    assert_eq!(leaf, tree.leaf_count as usize, "{name}");
    let mut root_strips: Vec<u32> = tree.roots.iter().map(|&r| tree.nodes[r as usize].strip).collect();
    root_strips.dedup();
    assert_eq!(root_strips.len(), tree.roots.len(), "{name}: one root per strip");
    for (i, n) in tree.nodes.iter().enumerate() {
        // The range decodes to the node's triangles, each starting at an even triangle.
        let s = n.strip as usize;
        let base = set.offsets[s];
        assert_eq!((n.start - base) % 2, 0, "{name}: node {i} starts at an odd triangle");
        assert!(n.end <= set.offsets[s + 1]);
        let tris: Vec<[u32; 3]> = (0..(n.end - n.start) as usize - 2)
            .map(|j| strip_triangle(&idx[n.start as usize..n.end as usize], j))
            .filter(|&t| drawable(t))
            .collect();
        assert_eq!(tris.len(), n.triangles as usize, "{name}: node {i}");
        assert!(drawable(strip_triangle(&idx[n.start as usize..n.end as usize], (n.end - n.start) as usize - 3)));
        if n.is_leaf() {
            assert_eq!(n.end_leaf, n.first_leaf + 1);
        } else {
            let [a, b] = n.children.map(|c| tree.nodes[c as usize]);
            assert_eq!((a.parent, b.parent), (i as u32, i as u32));
            assert_eq!((a.first_leaf, a.end_leaf, b.end_leaf), (n.first_leaf, b.first_leaf, n.end_leaf), "{name}");
            assert_eq!((a.start, b.end, a.triangles + b.triangles), (n.start, n.end, n.triangles), "{name}");
            assert_eq!((a.strip, b.strip), (n.strip, n.strip));
        }
        if n.is_root() {
            assert!(tree.roots.contains(&(i as u32)));
        }
        // The average normal.
        let mut sum = [0.0f64; 3];
        for &t in &tris {
            let [a, b, c] = t.map(|v| p64(pos[v as usize]));
            let m = cross(sub(b, a), sub(c, a));
            sum = [sum[0] + m[0], sum[1] + m[1], sum[2] + m[2]];
        }
        let l = dot(sum, sum).sqrt();
        if l > 1e-9 {
            assert!(dot(sum, p64(n.normal)) / l > 1.0 - 1e-5, "{name}: node {i}: normal {:?} is not the average", n.normal);
        }
        let bd = &n.bounds;
        let axis = p64(bd.axis);
        let c = p64(bd.center);
        for t in tris {
            if let Some(m) = unit_normal(t, pos) {
                assert!(bd.angle >= 0.0, "{name}: node {i}: empty cone");
                let a = dot(cross(axis, m), cross(axis, m)).sqrt().atan2(dot(axis, m));
                assert!(a <= bd.angle as f64 + 1e-6, "{name}: node {i}: normal at {a} outside the cone {}", bd.angle);
            }
            for v in t {
                let d = sub(p64(pos[v as usize]), c);
                assert!(dot(d, d).sqrt() <= bd.radius as f64 * (1.0 + 1e-6), "{name}: node {i}: vertex outside");
            }
        }
    }
}

/// One view checked: ranges decoded against the input triangles and the eye.
fn check_view(name: &str, strips: &Strips, pos: &[[f32; 3]], tree: &SegmentTree, eye: [f32; 3], out: &Culled, eps: f64) {
    let set = &strips.strips;
    let idx = &set.indices;
    let mut input: HashMap<[u32; 3], usize> = HashMap::new();
    for &t in &strips.triangles {
        if drawable(t) {
            *input.entry(canonical(t)).or_default() += 1;
        }
    }
    let leaf_at: HashMap<u32, u32> = tree.leaves().map(|l| (tree.nodes[l as usize].start, l)).collect();
    let mut drawn: HashMap<[u32; 3], usize> = HashMap::new();
    let mut count = 0;
    for (k, r) in out.ranges.iter().enumerate() {
        assert!(r.start < r.end && r.end - r.start >= 3, "{name}: range {r:?}");
        if k > 0 {
            assert!(out.ranges[k - 1].end <= r.end, "{name}: ranges out of order");
        }
        let s = set.offsets.partition_point(|&o| o <= r.start) - 1;
        let base = set.offsets[s];
        assert!(r.end <= set.offsets[s + 1], "{name}: range {r:?} crosses a strip end");
        assert_eq!((r.start - base) % 2, 0, "{name}: range {r:?} starts at an odd triangle");
        let range = &idx[r.start as usize..r.end as usize];
        for j in 0..range.len() - 2 {
            let t = strip_triangle(range, j);
            if !drawable(t) {
                continue;
            }
            count += 1;
            assert!(input.contains_key(&canonical(t)), "{name}: {t:?} drawn with the wrong winding or not an input triangle");
            *drawn.entry(canonical(t)).or_default() += 1;
            if facing(t, pos, eye) < -eps {
                // A back-facing triangle drawn: only in a leaf across the silhouette.
                let g = r.start + j as u32;
                let pair = base + (g - base) / 2 * 2;
                let l = leaf_at[&pair];
                assert_eq!(tree.nodes[l as usize].bounds.classify(eye), Facing::Split, "{name}: back-facing {t:?} drawn");
            }
        }
    }
    assert_eq!(count, out.drawn_triangles, "{name}");
    let total: usize = input.values().sum();
    assert_eq!(out.drawn_triangles + out.culled_triangles, total, "{name}");
    for &t in &strips.triangles {
        if drawable(t) && facing(t, pos, eye) > eps {
            assert!(drawn.get(&canonical(t)).copied().unwrap_or(0) > 0, "{name}: front-facing {t:?} not drawn from {eye:?}");
        }
    }
}

/// A random camera path: smooth stretches on spheres of random radius around the mesh
/// (some inside it), jumps between them.
fn random_path(center: [f32; 3], radius: f32, views: usize, seed: u64) -> Vec<[f32; 3]> {
    let mut rng = Rng(seed.wrapping_mul(0x2545F4914F6CDD1D) | 1);
    let mut out = Vec::with_capacity(views);
    let (mut th, mut ph, mut d) = (0.0f64, 0.0f64, 3.0f64);
    for i in 0..views {
        if i % 40 == 0 {
            th = rng.unit() * std::f64::consts::TAU;
            ph = (rng.unit() * 2.0 - 1.0).acos();
            d = 0.2 + rng.unit() * 5.0;
        }
        th += 0.05 * (rng.unit() - 0.3);
        ph += 0.03 * (rng.unit() - 0.5);
        let r = radius as f64 * d;
        out.push([
            center[0] + (r * ph.sin() * th.cos()) as f32,
            center[1] + (r * ph.cos()) as f32,
            center[2] + (r * ph.sin() * th.sin()) as f32,
        ]);
    }
    out
}

fn check_strips(name: &str, strips: &Strips, mesh: &Mesh, options: CullOptions) {
    let pos = strips.with_added_vertices(&mesh.positions);
    let tree = SegmentTree::build(&strips.strips, &pos);
    check_tree(name, strips, &pos, &tree);
    let (c, r) = stripkit::cull::bounding_sphere(&pos);
    let eps = 1e-4 * r as f64;
    let mut eyes = helix_eyes(c, r, 60);
    eyes.extend(random_path(c, r, 200, name.len() as u64));
    let counter = FacingCounter::new(&strips.strips, &pos);
    // And a slow path, where most of the front is kept without a test.
    eyes.extend((0..80).map(|i| {
        let t = i as f32 * 0.002;
        [c[0] + 2.5 * r * t.cos(), c[1] + 0.3 * r, c[2] + 2.5 * r * t.sin()]
    }));
    let mut reused = 0;
    let mut front = RenderFront::new(&tree);
    let (mut a, mut b) = (Culled::default(), Culled::default());
    for (v, &eye) in eyes.iter().enumerate() {
        tree.cull(eye, &options, &mut a);
        front.cull(&tree, eye, &options, &mut b);
        assert_eq!(a.ranges, b.ranges, "{name}: view {v}: render front differs from the root traversal");
        assert_eq!((a.drawn_triangles, a.culled_triangles), (b.drawn_triangles, b.culled_triangles), "{name}");
        reused += b.reused;
        // The front is where the traversal from the roots stops (a fresh front's first
        // view traverses from the roots).
        let mut fresh = RenderFront::new(&tree);
        let mut c = Culled::default();
        fresh.cull(&tree, eye, &options, &mut c);
        assert_eq!((c.ranges.as_slice(), c.visited), (a.ranges.as_slice(), a.visited), "{name}");
        assert_eq!(fresh.nodes(), front.nodes(), "{name}: view {v}: the front is not the stopping nodes");
        let fc = counter.count(eye, &a.ranges);
        assert_eq!(fc.front_drawn, fc.front, "{name}: view {v}: front-facing triangles not drawn");
        assert_eq!(fc.back - fc.back_drawn, a.culled_triangles, "{name}: view {v}: culled triangles that face the eye");
        if options.min_triangles == 0 && options.max_gap == 0 {
            check_view(name, strips, &pos, &tree, eye, &a, eps);
        }
    }
    assert!(reused > 0, "{name}: the front never kept a node without a test");
}

#[test]
fn single_strips_cull_front_and_back_faces_correctly() {
    for (name, mesh) in meshes() {
        for w in [Weights::Cull, Weights::Uniform] {
            let s = single(&mesh, w.clone());
            check_strips(&format!("{name} {w}"), &s, &mesh, CullOptions::default());
        }
    }
}

#[test]
fn greedy_strips_and_small_leaves_keep_the_front_equal() {
    for (name, mesh) in meshes() {
        let s = strip_with(&mesh, Algorithm::greedy());
        check_strips(&format!("{name} greedy"), &s, &mesh, CullOptions::default());
        let s = single(&mesh, Weights::Cull);
        check_strips(&format!("{name} min 8"), &s, &mesh, CullOptions::default().min_triangles(8));
        check_strips(&format!("{name} gap 6"), &s, &mesh, CullOptions::default().max_gap(6));
        check_strips(&format!("{name} min 4 gap 30"), &s, &mesh, CullOptions::default().min_triangles(4).max_gap(30));
    }
}

/// Flat regions merge first: on a cube every within-face run of leaves becomes one
/// subtree of flat cones before any two runs join, so exactly `runs - 1` nodes per strip
/// have a cone wider than a degree.
#[test]
fn flat_regions_merge_before_sharp_features() {
    let mesh = gen::cube_grid(6);
    let s = single(&mesh, Weights::Cull);
    let tree = SegmentTree::build(&s.strips.clone(), &s.with_added_vertices(&mesh.positions));
    let flat = |l: u32| tree.nodes[l as usize].bounds.angle < 1f32.to_radians();
    let leaves: Vec<u32> = tree.leaves().collect();
    let mut runs = 0;
    for k in 0..leaves.len() {
        let (l, n) = (leaves[k], &tree.nodes[leaves[k] as usize]);
        let joins = k > 0 && {
            let p = &tree.nodes[leaves[k - 1] as usize];
            p.strip == n.strip && flat(l) && flat(leaves[k - 1]) && {
                let (a, b) = (p.bounds.axis, n.bounds.axis);
                a[0] * b[0] + a[1] * b[1] + a[2] * b[2] > 0.999
            }
        };
        if !joins {
            runs += 1;
        }
    }
    let wide = tree.nodes.iter().filter(|n| !n.is_leaf() && n.bounds.angle >= 1f32.to_radians()).count();
    assert_eq!(wide, runs - tree.roots.len(), "runs {runs}, roots {}", tree.roots.len());
    // The cube is culled in few segments: at most one per run.
    let (c, r) = stripkit::cull::bounding_sphere(&mesh.positions);
    let mut out = Culled::default();
    for eye in helix_eyes(c, r, HELIX_VIEWS) {
        tree.cull(eye, &CullOptions::default(), &mut out);
        assert!(out.ranges.len() <= runs);
        assert!(out.culled_triangles > 0);
    }
}

#[test]
fn helix_eyes_ascend_three_turns_at_three_radii() {
    let e = helix_eyes([1.0, 2.0, 3.0], 2.0, HELIX_VIEWS);
    assert_eq!(e.len(), 591);
    assert!((e[0][1] - (2.0 - 3.0)).abs() < 1e-5 && (e[590][1] - (2.0 + 3.0)).abs() < 1e-5);
    assert!((e[0][0] - 7.0).abs() < 1e-5 && (e[0][2] - 3.0).abs() < 1e-5);
    // A quarter turn in: +Z.
    assert!((e[49][2] - 3.0 - 6.0 * (6.0 * std::f32::consts::PI * 49.0 / 590.0).sin()).abs() < 1e-4);
    for p in &e {
        let h = ((p[0] - 1.0).powi(2) + (p[2] - 3.0).powi(2)).sqrt();
        assert!((h - 6.0).abs() < 1e-4);
    }
}

#[test]
fn empty_and_tiny_strip_sets() {
    let empty = SegmentTree::build(&stripkit::StripSet::new(), &[]);
    assert!(empty.is_empty() && empty.roots.is_empty());
    let mut out = Culled::default();
    empty.cull([0.0; 3], &CullOptions::default(), &mut out);
    assert!(out.ranges.is_empty());
    // One triangle, a swap-only strip: the swap pair is no leaf.
    let pos = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let set = stripkit::StripSet::from_strips(&[vec![0u32, 1, 2], vec![0, 0, 1, 1]]);
    let tree = SegmentTree::build(&set, &pos);
    assert_eq!((tree.leaf_count, tree.roots.len()), (1, 1));
    tree.cull([0.2, 0.2, 5.0], &CullOptions::default(), &mut out);
    assert_eq!(out.ranges, vec![0..3]);
    tree.cull([0.2, 0.2, -5.0], &CullOptions::default(), &mut out);
    assert!(out.ranges.is_empty());
    assert_eq!(out.culled_triangles, 1);
}

/// Fandisk (when ../shared/models is there): the cull-weight strip is cut into far
/// fewer segments per view than the uniform-weight one (measured 47.0 and 183.5).
#[test]
fn fandisk_cull_weights_need_fewer_segments() {
    let Some(mesh) = support::model("fandisk.obj") else { return };
    let (c, r) = stripkit::cull::bounding_sphere(&mesh.positions);
    let eyes = helix_eyes(c, r, HELIX_VIEWS);
    let mean = |w: Weights| {
        let s = single(&mesh, w);
        let pos = s.with_added_vertices(&mesh.positions);
        let tree = SegmentTree::build(&s.strips, &pos);
        let counter = FacingCounter::new(&s.strips, &pos);
        let mut out = Culled::default();
        let mut segments = 0;
        for &eye in &eyes {
            tree.cull(eye, &CullOptions::default(), &mut out);
            let f = counter.count(eye, &out.ranges);
            assert_eq!(f.front_drawn, f.front);
            segments += out.ranges.len();
        }
        segments as f64 / eyes.len() as f64
    };
    let (cull, uniform) = (mean(Weights::Cull), mean(Weights::Uniform));
    assert!(cull < 60.0 && cull * 2.5 < uniform, "cull {cull}, uniform {uniform}");
}

/// Frustum culling: a narrow camera along the helix skips what lies outside its
/// frustum, never a front-facing triangle with a vertex well inside, gives the same
/// ranges from the roots and from the render front, and a wide one changes nothing.
#[test]
fn frustum_culling_skips_only_what_lies_outside() {
    for (name, mesh) in meshes() {
        let strips = single(&mesh, Weights::Cull);
        let pos = strips.with_added_vertices(&mesh.positions);
        let tree = SegmentTree::build(&strips.strips, &pos);
        let (center, radius) = bounding_sphere(&pos);
        let mut front = RenderFront::new(&tree);
        let (mut a, mut b, mut plain) = (Culled::default(), Culled::default(), Culled::default());
        let mut outside_views = 0;
        for (v, eye) in helix_eyes(center, radius, 60).into_iter().enumerate() {
            // The helix's own camera (60 degrees) holds the whole model: no change.
            let wide = Frustum::perspective(eye, center, [0.0, 1.0, 0.0], 60.0, 1.0, 0.01, 100.0 * radius).unwrap();
            tree.cull(eye, &CullOptions::default(), &mut plain);
            tree.cull(eye, &CullOptions::default().frustum(Some(wide)), &mut a);
            assert_eq!(a.ranges, plain.ranges, "{name}: view {v}");
            assert_eq!(a.outside_triangles, 0);
            // A 12-degree camera aimed off-centre.
            let target = [center[0] + 0.3 * radius, center[1], center[2]];
            let narrow = Frustum::perspective(eye, target, [0.0, 1.0, 0.0], 12.0, 1.5, 0.01, 100.0 * radius).unwrap();
            let options = CullOptions::default().frustum(Some(narrow));
            tree.cull(eye, &options, &mut a);
            front.cull(&tree, eye, &options, &mut b);
            assert_eq!(a.ranges, b.ranges, "{name}: view {v}: the front equals the root traversal");
            assert_eq!(a.reused + b.reused, 0, "no reuse with a frustum");
            outside_views += (a.outside_triangles > 0) as usize;
            assert!(a.drawn_triangles <= plain.drawn_triangles);
            // Every front-facing triangle with a vertex inside the frustum (by a
            // margin) is drawn.
            let drawn = |i: usize| a.ranges.iter().any(|r| r.start as usize <= i && i + 3 <= r.end as usize);
            let inside = |p: [f32; 3]| {
                narrow.planes.iter().all(|pl| {
                    pl[0] as f64 * p[0] as f64 + pl[1] as f64 * p[1] as f64 + pl[2] as f64 * p[2] as f64 + pl[3] as f64
                        > 1e-3 * radius as f64
                })
            };
            for (si, strip) in strips.strips.iter().enumerate() {
                let base = strips.strips.offsets[si] as usize;
                for i in 0..strip.len().saturating_sub(2) {
                    let t = strip_triangle(strip, i);
                    if drawable(t) && facing(t, &pos, eye) > 1e-4 && t.iter().any(|&x| inside(pos[x as usize])) {
                        assert!(drawn(base + i), "{name}: view {v}: visible triangle {t:?} culled");
                    }
                }
            }
        }
        assert!(outside_views > 30, "{name}: the narrow camera leaves parts out ({outside_views} of 60 views)");
    }
    // Spheres against planes, and bad cameras.
    let f = Frustum::perspective([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], 60.0, 1.0, 0.1, 100.0).unwrap();
    assert_eq!(f.side([0.0; 3], 0.5), Side::Inside);
    assert_eq!(f.side([0.0, 0.0, 10.0], 0.5), Side::Outside, "behind the eye");
    assert_eq!(f.side([50.0, 0.0, 0.0], 1.0), Side::Outside);
    assert_eq!(f.side([2.88, 0.0, 0.0], 0.1), Side::Crossing, "on the right plane");
    assert!(Frustum::perspective([0.0; 3], [0.0; 3], [0.0, 1.0, 0.0], 60.0, 1.0, 0.1, 10.0).is_none());
    assert!(Frustum::perspective([0.0, 0.0, 5.0], [0.0; 3], [0.0, 0.0, 1.0], 60.0, 1.0, 0.1, 10.0).is_none());
    assert!(Frustum::perspective([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], 180.0, 1.0, 0.1, 10.0).is_none());
}
