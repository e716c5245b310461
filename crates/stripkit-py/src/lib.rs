//! `stripkit._stripkit`: the Python extension module under the `stripkit` package.
//!
//! Thin wrappers over the library's public API, one per entry point: arrays in,
//! arrays out, the GIL released around the library call, [`stripkit::Error`] mapped
//! to `ValueError` / `stripkit.VerificationError` / `OSError` with the library's
//! message. Dtype, shape and contiguity are settled by the Python layer
//! (`python/stripkit/__init__.py`), which hands over contiguous `uint32` / `float32`
//! arrays; those are read in place (no copy).

use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::str::FromStr;
use std::sync::Arc;
use stripkit::io::{Format, WriteOptions};
use stripkit::{Algorithm, Join, StripOptions};

create_exception!(_stripkit, VerificationError, pyo3::exceptions::PyException, "An output failed stripkit's independent check.");

/// The library's error as the Python exception that fits it.
fn to_py(e: stripkit::Error) -> PyErr {
    match e {
        stripkit::Error::Verification(_) => VerificationError::new_err(e.to_string()),
        stripkit::Error::Io { .. } => PyOSError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// A contiguous array's data, or a `ValueError` (the Python layer makes arrays contiguous).
fn slice<'a, T: numpy::Element>(a: &'a PyReadonlyArray1<'_, T>) -> PyResult<&'a [T]> {
    a.as_slice().map_err(|_| PyValueError::new_err("the array is not contiguous"))
}

/// A flat buffer as rows of `width` (a view of the new array, no copy).
fn rows<T: numpy::Element>(py: Python<'_>, flat: Vec<T>, width: usize) -> PyResult<Bound<'_, PyArray2<T>>> {
    let n = flat.len() / width;
    flat.into_pyarray(py).reshape([n, width])
}

fn positions(vertices: &PyReadonlyArray2<'_, f32>) -> PyResult<Vec<[f32; 3]>> {
    let flat = vertices.as_slice().map_err(|_| PyValueError::new_err("vertices are not contiguous"))?;
    if vertices.shape()[1] != 3 {
        return Err(PyValueError::new_err("vertices must have shape (n, 3)"));
    }
    Ok(flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
}

/// Options from the keyword arguments the Python layer passes on.
fn options(algorithm: &str, restart_index: u32, cache_size: usize, join: &str, weld: bool) -> PyResult<StripOptions> {
    let algorithm = Algorithm::from_str(algorithm).map_err(to_py)?;
    let join = Join::from_str(join).map_err(to_py)?;
    Ok(StripOptions::default()
        .algorithm(algorithm)
        .restart_index(restart_index)
        .cache_size(cache_size)
        .join(join)
        .weld(weld))
}

/// The address of a contiguous `uint32` array's data as the binding reads it: the
/// tests compare it with the caller's buffer to show no copy is made.
#[pyfunction]
fn _data_address(indices: PyReadonlyArray1<'_, u32>) -> PyResult<usize> {
    Ok(slice(&indices)?.as_ptr() as usize)
}

/// stripkit::stripify_indices on a flat contiguous uint32 array.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn stripify_indices<'py>(
    py: Python<'py>,
    indices: PyReadonlyArray1<'py, u32>,
    vertex_count: usize,
    algorithm: &str,
    restart_index: u32,
    cache_size: usize,
    join: &str,
) -> PyResult<Bound<'py, PyArray1<u32>>> {
    let options = options(algorithm, restart_index, cache_size, join, true)?;
    let data = slice(&indices)?;
    let out = py.detach(|| stripkit::stripify_indices(data, vertex_count, &options)).map_err(to_py)?;
    Ok(out.into_pyarray(py))
}

/// stripkit::stripify_bound.
#[pyfunction]
fn stripify_bound(index_count: usize) -> usize {
    stripkit::stripify_bound(index_count)
}

/// stripkit::unstripify on a flat contiguous uint32 array.
#[pyfunction]
fn unstripify<'py>(py: Python<'py>, strip: PyReadonlyArray1<'py, u32>, restart_index: u32) -> PyResult<Bound<'py, PyArray1<u32>>> {
    let data = slice(&strip)?;
    let out = py.detach(|| stripkit::unstripify(data, restart_index));
    Ok(out.into_pyarray(py))
}

/// stripkit::acmr: FIFO cache misses per triangle of a triangle list drawn in order.
#[pyfunction]
fn acmr(py: Python<'_>, indices: PyReadonlyArray1<'_, u32>, vertex_count: usize, cache_size: usize) -> PyResult<f64> {
    let data = slice(&indices)?;
    if data.len() % 3 != 0 {
        return Err(PyValueError::new_err(format!("{} indices is not a whole number of triangles", data.len())));
    }
    if cache_size == 0 || cache_size > stripkit::MAX_CACHE_SIZE {
        return Err(PyValueError::new_err(format!(
            "cache_size {cache_size} is not between 1 and {}",
            stripkit::MAX_CACHE_SIZE
        )));
    }
    if let Some(i) = data.iter().position(|&v| v as usize >= vertex_count) {
        return Err(PyValueError::new_err(format!("index {i} is vertex {} but there are {vertex_count} vertices", data[i])));
    }
    let tris: Vec<[u32; 3]> = data.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    Ok(py.detach(|| stripkit::acmr(&tris, vertex_count, cache_size, stripkit::CacheKind::Fifo)))
}

/// A polygon mesh (stripkit::Mesh): positions, faces, attributes kept as read.
#[pyclass(module = "stripkit._stripkit", frozen)]
struct Mesh {
    inner: Arc<stripkit::Mesh>,
}

#[pymethods]
impl Mesh {
    /// Positions, shape (n, 3), float32.
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        rows(py, self.inner.positions.iter().flatten().copied().collect(), 3)
    }
    /// Start of each face in `face_indices`, plus the total (CSR offsets), uint32.
    #[getter]
    fn face_offsets<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u32>> {
        PyArray1::from_slice(py, &self.inner.face_offsets)
    }
    /// Vertex ids of all faces, concatenated, uint32.
    #[getter]
    fn face_indices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u32>> {
        PyArray1::from_slice(py, &self.inner.face_indices)
    }
    /// The faces fanned into triangles, shape (t, 3), uint32.
    #[getter]
    fn triangles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u32>>> {
        let tris = self.inner.triangulate().tris;
        let flat: Vec<u32> = tris.into_iter().flatten().collect();
        rows(py, flat, 3)
    }
    fn __repr__(&self) -> String {
        format!("Mesh({} vertices, {} faces)", self.inner.vertex_count(), self.inner.face_count())
    }
}

/// A mesh from positions (n, 3) float32 and flat polygon faces of `face_size` vertices
/// each (3 for triangles, 4 for quads), indices checked against the vertex count.
#[pyfunction]
fn mesh_from_arrays(vertices: PyReadonlyArray2<'_, f32>, faces: PyReadonlyArray1<'_, u32>, face_size: usize) -> PyResult<Mesh> {
    let positions = positions(&vertices)?;
    let faces = slice(&faces)?;
    let mesh = stripkit::Mesh::from_polygons(positions, &faces.chunks_exact(face_size.max(3)).collect::<Vec<_>>());
    stripkit::validate(&mesh).map_err(to_py)?;
    Ok(Mesh { inner: Arc::new(mesh) })
}

/// Verified strips of a mesh (stripkit::Strips) and the mesh they index.
#[pyclass(module = "stripkit._stripkit", frozen)]
struct Strips {
    inner: stripkit::Strips,
    mesh: Arc<stripkit::Mesh>,
}

#[pymethods]
impl Strips {
    /// The joined buffer: restart-separated strips (join="restart") or one stitched
    /// strip per face group (join="degenerate"), uint32.
    #[getter]
    fn indices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u32>> {
        match self.inner.join {
            Join::Degenerate => self.inner.stitched(),
            _ => self.inner.restart_buffer(),
        }
        .into_pyarray(py)
    }
    /// Each strip as its own uint32 array.
    #[getter]
    fn strips<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray1<u32>>> {
        self.inner.strips.iter().map(|s| PyArray1::from_slice(py, s)).collect()
    }
    /// Every figure of docs/metrics.md as JSON (the Python layer makes it a dict).
    fn _figures_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.inner.figures).map_err(|e| PyValueError::new_err(e.to_string()))
    }
    /// The positions the strips index: the mesh's, followed by any `single` added.
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let all = self.inner.with_added_vertices(&self.mesh.positions);
        let flat: Vec<f32> = all.into_iter().flatten().collect();
        rows(py, flat, 3)
    }
    /// The algorithm that ran ("auto" resolved).
    #[getter]
    fn algorithm(&self) -> &'static str {
        self.inner.algorithm.name()
    }
    /// The file bytes of the strips in `format` ("ply", "obj", "gltf", "glb"), as
    /// `stripkit strip` writes a mesh output with the input's vertex order.
    fn to_bytes<'py>(&self, py: Python<'py>, format: &str, ascii: bool) -> PyResult<Bound<'py, PyBytes>> {
        let format = parse_format(format)?;
        let options = WriteOptions::default().ply_ascii(ascii);
        let bytes = py.detach(|| self.inner.to_file_bytes_with(&self.mesh, format, &options)).map_err(to_py)?;
        Ok(PyBytes::new(py, &bytes))
    }
}

fn parse_format(name: &str) -> PyResult<Format> {
    let path = std::path::PathBuf::from(format!("x.{}", name.trim_start_matches('.')));
    Format::from_path(&path)
        .map(|(f, _)| f)
        .ok_or_else(|| PyValueError::new_err(format!("`{name}` is not a mesh format: obj, ply, off, stl, gltf or glb")))
}

/// stripkit::stripify on a mesh.
#[pyfunction]
fn stripify_mesh(py: Python<'_>, mesh: &Mesh, algorithm: &str, restart_index: u32, cache_size: usize, join: &str, weld: bool) -> PyResult<Strips> {
    let options = options(algorithm, restart_index, cache_size, join, weld)?;
    let inner = py.detach(|| stripkit::stripify(&mesh.inner, &options)).map_err(to_py)?;
    Ok(Strips { inner, mesh: mesh.inner.clone() })
}

/// stripkit::io::read (a file with no faces is refused, as the CLI does).
#[pyfunction]
fn read(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Mesh> {
    let mesh = py.detach(|| stripkit::io::read(&path)).map_err(to_py)?;
    if mesh.face_count() == 0 {
        return Err(PyValueError::new_err(format!("no faces in {}", path.display())));
    }
    Ok(Mesh { inner: Arc::new(mesh) })
}

/// stripkit::io::write_with: the mesh's faces, or `strips` where the format holds them;
/// replaced atomically.
#[pyfunction]
#[pyo3(signature = (path, mesh, strips=None, ascii=false))]
fn write(py: Python<'_>, path: std::path::PathBuf, mesh: &Mesh, strips: Option<&Strips>, ascii: bool) -> PyResult<()> {
    let options = WriteOptions::default().ply_ascii(ascii);
    py.detach(|| match strips {
        Some(s) => s.inner.write_file(&s.mesh, &path, &options),
        None => stripkit::io::write_with(&path, &mesh.inner, None, &options),
    })
    .map_err(to_py)
}

/// stripkit::simplify::simplify to `ratio` of the triangles (or `triangles` of them):
/// the simplified mesh, the collapses (removed, kept) as (c, 2) uint32 and their errors.
#[pyfunction]
#[pyo3(signature = (mesh, ratio=0.5, triangles=None))]
#[allow(clippy::type_complexity)]
fn simplify<'py>(
    py: Python<'py>,
    mesh: &Mesh,
    ratio: f64,
    triangles: Option<usize>,
) -> PyResult<(Mesh, Bound<'py, PyArray2<u32>>, Bound<'py, PyArray1<f64>>)> {
    use stripkit::simplify::{Options, Target};
    let target = triangles.map_or(Target::Ratio(ratio), Target::Triangles);
    let options = Options::default().target(target);
    let out = py.detach(|| stripkit::simplify::simplify(&mesh.inner, &options, &mut |_| {})).map_err(to_py)?;
    let c = &out.sequence.collapses;
    let pairs: Vec<u32> = c.iter().flat_map(|c| [c.removed, c.kept]).collect();
    let errors: Vec<f64> = c.iter().map(|c| c.error).collect();
    let pairs = rows(py, pairs, 2)?;
    Ok((Mesh { inner: Arc::new(out.mesh) }, pairs, errors.into_pyarray(py)))
}

/// stripkit::matching::solve on an edge list: a perfect matching of maximum weight
/// (or minimum cost); the mate of each node (0xFFFFFFFF unmatched), the matched edge
/// ids, whether it is perfect and its total weight.
#[pyfunction]
#[allow(clippy::type_complexity)]
fn match_edges<'py>(
    py: Python<'py>,
    node_count: usize,
    edges: PyReadonlyArray1<'py, u32>,
    weights: PyReadonlyArray1<'py, i64>,
    minimize: bool,
) -> PyResult<(Bound<'py, PyArray1<u32>>, Bound<'py, PyArray1<u32>>, bool, i64)> {
    use stripkit::matching::{solve, Graph, Objective};
    let ends: Vec<[u32; 2]> = slice(&edges)?.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
    let weights = slice(&weights)?.to_vec();
    let objective = if minimize { Objective::MinCost } else { Objective::MaxWeight };
    let m = py
        .detach(|| Graph::new(node_count, ends, weights).and_then(|g| solve(&g, objective)))
        .map_err(|e| to_py(e.into()))?;
    Ok((m.mate.into_pyarray(py), m.edges.into_pyarray(py), m.perfect, m.total_weight))
}

/// A multiresolution strip model (stripkit::lod::Model): a `.sets` built here or a
/// `.sets` / `.lodseq` read from a file.
#[pyclass(module = "stripkit._stripkit", frozen)]
struct Lod {
    inner: stripkit::lod::Model,
}

#[pymethods]
impl Lod {
    /// The last level (collapses of the whole sequence); `None` for an animation,
    /// whose key frames each have their own.
    #[getter]
    fn levels(&self) -> Option<u32> {
        match &self.inner {
            stripkit::lod::Model::Sets(s) => Some(s.levels()),
            stripkit::lod::Model::Seq(_) => None,
        }
    }
    /// One level as arrays: (positions (n, 3) float32, strips as uint32 arrays, level,
    /// triangles); `spec` is ("level", n), ("triangles", n) or ("ratio", r).
    #[allow(clippy::type_complexity)]
    fn extract<'py>(
        &self,
        py: Python<'py>,
        kind: &str,
        value: f64,
        frame: Option<f64>,
    ) -> PyResult<(Bound<'py, PyArray2<f32>>, Vec<Bound<'py, PyArray1<u32>>>, u32, u32)> {
        use stripkit::lod::LevelSpec;
        let spec = match kind {
            "level" if value >= 0.0 && value <= u32::MAX as f64 => LevelSpec::Level(value as u32),
            "triangles" if value >= 0.0 => LevelSpec::Triangles(value as u64),
            "ratio" => LevelSpec::Ratio(value),
            "level" | "triangles" => return Err(PyValueError::new_err(format!("{kind} {value} is out of range"))),
            _ => return Err(PyValueError::new_err(format!("`{kind}` names no level: level, triangles or ratio"))),
        };
        let e = py.detach(|| self.inner.extract(spec, frame)).map_err(to_py)?;
        let strips = e.strips.iter().map(|s| PyArray1::from_slice(py, s)).collect();
        Ok((rows(py, e.positions.into_iter().flatten().collect(), 3)?, strips, e.level, e.triangles))
    }
    /// Writes a `.sets` model (replaced atomically by the library's writer).
    fn write(&self, py: Python<'_>, path: std::path::PathBuf) -> PyResult<usize> {
        match &self.inner {
            stripkit::lod::Model::Sets(s) => py.detach(|| s.write(&path)).map_err(to_py),
            stripkit::lod::Model::Seq(s) => py.detach(|| s.write(&path)).map_err(to_py),
        }
    }
}

/// stripkit::lod::build with its default options: strips, simplifies as far as the
/// simplifier goes, re-strips the levels past 1.6 indices per triangle (SETS), every
/// level checked against a replay.
#[pyfunction]
fn lod_build(py: Python<'_>, mesh: &Mesh, algorithm: &str, cache_size: usize) -> PyResult<Lod> {
    let strip = options(algorithm, stripkit::DEFAULT_RESTART, cache_size, "restart", false)?;
    let options = stripkit::lod::BuildOptions::default().strip(strip);
    let built = py.detach(|| stripkit::lod::build(&mesh.inner, &options, &mut |_| {})).map_err(to_py)?;
    Ok(Lod { inner: stripkit::lod::Model::Sets(built.sets) })
}

/// stripkit::lod::Model::read: a `.sets` or `.lodseq` file.
#[pyfunction]
fn lod_read(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Lod> {
    Ok(Lod { inner: py.detach(|| stripkit::lod::Model::read(&path)).map_err(to_py)? })
}

/// The extension module.
/// The triangles a strip buffer draws (strips separated by `restart`), each with the
/// number of its strip, or those of a triangle list (one strip); degenerate ones left out.
fn numbered_triangles(buffer: &[u32], restart: u32, triangle_list: bool) -> Vec<(usize, [u32; 3])> {
    let mut out = Vec::new();
    if triangle_list {
        for t in buffer.chunks_exact(3) {
            if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                out.push((0, [t[0], t[1], t[2]]));
            }
        }
    } else {
        for (k, s) in stripkit::decode_restart(buffer, restart).iter().enumerate() {
            stripkit::for_each_triangle(s, |t| out.push((k, t)));
        }
    }
    out
}

/// A picture error as the Python exception that fits it: no EGL is an `OSError`
/// (saying what to install), a failed GL call a `RuntimeError`, the rest `ValueError`.
fn picture_to_py(e: stripkit_render::PictureError) -> PyErr {
    use stripkit_render::{PictureError, RenderError};
    match e {
        PictureError::Render(RenderError::NoEgl(_)) | PictureError::Render(RenderError::Io { .. }) => {
            PyOSError::new_err(e.to_string())
        }
        PictureError::Render(RenderError::Gl(_)) => pyo3::exceptions::PyRuntimeError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// stripkit_render::draw_picture: the picture `stripkit render` draws of strips (a
/// restart-separated buffer) or of a triangle list, as an (height, width, 4) RGBA array.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn render<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f32>,
    buffer: PyReadonlyArray1<'py, u32>,
    restart_index: u32,
    triangle_list: bool,
    size: (u32, u32),
    color_by: &str,
    cull_view: Option<[f32; 3]>,
    shading: &str,
    wireframe: bool,
    view: [f32; 3],
    up: [f32; 3],
    fov: f32,
    zoom: f32,
    background: [u8; 3],
) -> PyResult<Bound<'py, numpy::PyArray3<u8>>> {
    use stripkit_render::{ColorBy, PictureOptions, Renderer, Scene, Shading};
    let positions = positions(&vertices)?;
    let data = slice(&buffer)?;
    let color_by = match color_by {
        "strips" => ColorBy::Strips,
        "order" => ColorBy::Order,
        "cull" => ColorBy::Cull { view: cull_view },
        "none" => ColorBy::None,
        other => return Err(PyValueError::new_err(format!("color_by `{other}`: use strips, order, cull or none"))),
    };
    let shading = Shading::from_str(shading).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let options = PictureOptions { size, view, up, fov_y_degrees: fov, zoom, background, shading, wireframe, color_by };
    options.check().map_err(picture_to_py)?;
    let image = py.detach(|| {
        let triangles = numbered_triangles(data, restart_index, triangle_list);
        let mut used = vec![false; positions.len()];
        for &(_, t) in &triangles {
            for v in t {
                if let Some(u) = used.get_mut(v as usize) {
                    *u = true;
                }
            }
        }
        // The camera frames the vertices the triangles use, as `stripkit render` frames
        // those the faces use.
        let frame: Vec<[f32; 3]> = positions.iter().zip(&used).filter(|(_, &u)| u).map(|(p, _)| *p).collect();
        let scale = stripkit::unit_scale(&frame) as f32;
        let scene = Scene { positions: &positions, triangles: &triangles, morph: None, frame: &frame, scale };
        let mut renderer = Renderer::new(size.0, size.1)?;
        stripkit_render::draw_picture(&mut renderer, &scene, &options).map(|p| p.image)
    });
    let image = image.map_err(picture_to_py)?;
    let (w, h) = (image.width() as usize, image.height() as usize);
    image.rgba().to_vec().into_pyarray(py).reshape([h, w, 4])
}


#[pymodule]
fn _stripkit(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("VerificationError", m.py().get_type::<VerificationError>())?;
    m.add("DEFAULT_RESTART", stripkit::DEFAULT_RESTART)?;
    m.add_class::<Mesh>()?;
    m.add_class::<Strips>()?;
    m.add_class::<Lod>()?;
    m.add_function(wrap_pyfunction!(lod_build, m)?)?;
    m.add_function(wrap_pyfunction!(lod_read, m)?)?;
    m.add_function(wrap_pyfunction!(_data_address, m)?)?;
    m.add_function(wrap_pyfunction!(stripify_indices, m)?)?;
    m.add_function(wrap_pyfunction!(stripify_bound, m)?)?;
    m.add_function(wrap_pyfunction!(acmr, m)?)?;
    m.add_function(wrap_pyfunction!(unstripify, m)?)?;
    m.add_function(wrap_pyfunction!(mesh_from_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(stripify_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_function(wrap_pyfunction!(write, m)?)?;
    m.add_function(wrap_pyfunction!(simplify, m)?)?;
    m.add_function(wrap_pyfunction!(match_edges, m)?)?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    Ok(())
}
