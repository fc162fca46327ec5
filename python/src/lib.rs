//! Python bindings of kepler (PyO3 + maturin): the module `kepler._kepler`, which the Python
//! package `kepler` re-exports (see `python/kepler/__init__.py` and its stubs).
//!
//! Everything here converts and delegates: numpy arrays in, the library's calls, numpy arrays
//! and small objects out, and every library error raised as `kepler.KeplerError` with the
//! library's own message. No geometry is computed here.

use kepler::geometry::{Point3, Vector3};
use kepler::hidden::tiles::{TileDrawing, draw_tile, tile_windows};
use kepler::hidden::{self, Drawing, EdgeClass, EdgeSelection, Overlaps};
use kepler::mesh::{Mesh, Validation};
use kepler::output::{Finishing, SvgOptions, finish};
use kepler::queries::include::{IncludeIndex, Inclusion};
use kepler::queries::visp::{Visibility, VisibilityIndex};
use kepler::scene::{ObjectId, Scene as Graph, file};
use kepler::views::{View, ViewOptions, Window as Rectangle};
use nalgebra::Matrix4;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use std::path::Path;

create_exception!(
    _kepler,
    KeplerError,
    PyValueError,
    "An error from kepler: invalid input (a mesh, a file, a view, a scene), with the library's message."
);

/// Any displayable error as a `KeplerError`.
fn err(e: impl std::fmt::Display) -> PyErr {
    KeplerError::new_err(e.to_string())
}

/// An `(n, 3)` array of doubles as points.
fn points3(array: &PyReadonlyArray2<'_, f64>, what: &str) -> PyResult<Vec<Point3>> {
    let shape = array.shape();
    if shape[1] != 3 {
        return Err(err(format!("{what} must have shape (n, 3), not {shape:?}")));
    }
    let view = array.as_array();
    Ok(view
        .rows()
        .into_iter()
        .map(|r| Point3::new(r[0], r[1], r[2]))
        .collect())
}

/// Points from an `(n, 3)` array or a sequence of triples.
fn points_of(value: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Point3>> {
    let array: PyReadonlyArray2<'_, f64> = as_array(value, "float64")
        .and_then(|a| a.extract())
        .map_err(|_| err(format!("{what} must be an (n, 3) array of floats")))?;
    points3(&array, what)
}

/// `numpy.asarray(value, dtype)`.
fn as_array<'py>(value: &Bound<'py, PyAny>, dtype: &str) -> PyResult<Bound<'py, PyAny>> {
    value
        .py()
        .import("numpy")?
        .call_method1("asarray", (value, dtype))
}

/// Faces from a Python object: an `(m, k)` integer array or any sequence of index sequences
/// (polygons of any size), 0-based.
fn faces_of(faces: &Bound<'_, PyAny>) -> PyResult<Vec<Vec<u32>>> {
    let rectangular = as_array(faces, "int64")
        .ok()
        .and_then(|a| a.extract::<PyReadonlyArray2<'_, i64>>().ok());
    let rows: Vec<Vec<i64>> = match rectangular {
        Some(a) => a
            .as_array()
            .rows()
            .into_iter()
            .map(|r| r.to_vec())
            .collect(),
        None => faces
            .extract()
            .map_err(|_| err("faces must be an (m, k) integer array or a list of index lists"))?,
    };
    rows.into_iter()
        .enumerate()
        .map(|(f, row)| {
            row.into_iter()
                .map(|i| {
                    u32::try_from(i).map_err(|_| {
                        err(format!("face {f}: vertex index {i} is not a valid index"))
                    })
                })
                .collect()
        })
        .collect()
}

/// A mesh from vertices and polygon faces, placed by an optional transform.
fn mesh_of(
    vertices: Vec<Point3>,
    faces: Vec<Vec<u32>>,
    transform: Option<&Matrix4<f64>>,
) -> PyResult<Mesh> {
    let mesh = Mesh::from_polygons_with(vertices, faces, Validation::Repair).map_err(err)?;
    placed(mesh, transform)
}

/// An optional 4×4 transform (row-major homogeneous matrix) from Python.
fn transform_of(transform: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Matrix4<f64>>> {
    let Some(t) = transform else {
        return Ok(None);
    };
    let t: PyReadonlyArray2<'_, f64> = as_array(t, "float64")
        .and_then(|a| a.extract())
        .map_err(|_| err("transform must be a 4×4 array of floats"))?;
    if t.shape() != [4, 4] {
        return Err(err(format!("transform must be 4×4, not {:?}", t.shape())));
    }
    let a = t.as_array();
    Ok(Some(Matrix4::from_fn(|i, j| a[[i, j]])))
}

/// The mesh under an optional transform.
fn placed(mesh: Mesh, transform: Option<&Matrix4<f64>>) -> PyResult<Mesh> {
    match transform {
        Some(m) => mesh.transformed(m).map_err(err),
        None => Ok(mesh),
    }
}

/// A triple from a Python sequence.
fn triple(value: &Bound<'_, PyAny>, key: &str) -> PyResult<[f64; 3]> {
    value
        .extract::<[f64; 3]>()
        .map_err(|_| err(format!("view['{key}'] must be three numbers")))
}

/// The view a Python `view` argument describes over the scene's camera: `None` (the scene's
/// camera, or the standard view), or a dict with `view_dir` (orthographic), or `eye` and
/// `target` (perspective), and optionally `up` and `fov` — the command line's view options.
/// A perspective view is framed to `aspect` (width over height).
fn view_of(scene: &Graph, view: Option<&Bound<'_, PyDict>>, aspect: f64) -> PyResult<View> {
    let mut options = ViewOptions::default();
    if let Some(dict) = view {
        for (key, value) in dict.iter() {
            let key: String = key.extract()?;
            match key.as_str() {
                "view_dir" => options.view_dir = Some(Vector3::from(triple(&value, &key)?)),
                "up" => options.up = Some(Vector3::from(triple(&value, &key)?)),
                "eye" => options.eye = Some(Point3::from(triple(&value, &key)?)),
                "target" => options.target = Some(Point3::from(triple(&value, &key)?)),
                "fov" => options.fov = Some(value.extract()?),
                other => {
                    return Err(err(format!(
                        "unknown view key '{other}' (view_dir, up, eye, target, fov)"
                    )));
                }
            }
        }
    }
    let view = options.resolve(scene.camera()).map_err(err)?;
    if view.is_perspective() {
        view.with_aspect(aspect).map_err(err)
    } else {
        Ok(view)
    }
}

/// A polyline of a drawing: its points in view coordinates (`x` right, `y` up), its edge
/// class and whether it is visible.
#[pyclass(frozen, module = "kepler")]
struct Polyline {
    points: Vec<[f64; 2]>,
    class: EdgeClass,
    visible: bool,
}

#[pymethods]
impl Polyline {
    /// The points, an `(n, 2)` float64 array (a closed polyline repeats its first point).
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        Array2::from_shape_fn((self.points.len(), 2), |(i, k)| self.points[i][k]).into_pyarray(py)
    }

    /// `silhouette`, `boundary`, `crease`, `intersection` or `smooth`.
    #[getter]
    fn edge_class(&self) -> &'static str {
        self.class.name()
    }

    /// Whether the polyline is visible (else hidden).
    #[getter]
    fn visible(&self) -> bool {
        self.visible
    }

    fn __len__(&self) -> usize {
        self.points.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "Polyline({} {}, {} points)",
            if self.visible { "visible" } else { "hidden" },
            self.class.name(),
            self.points.len()
        )
    }
}

/// Which edges a string names.
fn edges_of(edges: &str) -> PyResult<EdgeSelection> {
    match edges {
        "feature" => Ok(EdgeSelection::Feature),
        "all" => Ok(EdgeSelection::All),
        "mesh" => Ok(EdgeSelection::Mesh),
        other => Err(err(format!(
            "edges must be 'feature', 'all' or 'mesh', not '{other}'"
        ))),
    }
}

/// The hidden-line options from Python's arguments.
fn options_of(
    edges: &str,
    hidden: bool,
    crease_angle: f64,
    overlaps: &str,
) -> PyResult<hidden::Options> {
    if !(crease_angle.is_finite() && (0.0..=180.0).contains(&crease_angle)) {
        return Err(err(format!(
            "crease_angle must be between 0 and 180 degrees, not {crease_angle}"
        )));
    }
    Ok(hidden::Options {
        edges: edges_of(edges)?,
        crease_angle,
        hidden,
        overlaps: overlaps_of(overlaps)?,
    })
}

/// What `overlaps` asks for: each stretch of line once, or every piece kept.
fn overlaps_of(overlaps: &str) -> PyResult<Overlaps> {
    match overlaps {
        "once" => Ok(Overlaps::Once),
        "keep" => Ok(Overlaps::Keep),
        other => Err(err(format!(
            "overlaps must be 'once' or 'keep', not '{other}'"
        ))),
    }
}

/// A drawing finished as the command line's `render` finishes it (the pass has drawn each
/// stretch of line once when asked): paths in pen order when `order`; as Python polylines.
fn finished(drawing: Drawing, order: bool) -> Vec<Polyline> {
    finish(drawing, &Finishing { order })
        .drawing
        .polylines
        .into_iter()
        .map(|p| Polyline {
            points: p.points,
            class: p.class,
            visible: p.visible,
        })
        .collect()
}

/// The view a drawing of the scene is made in (see [`view_of`], framed to the SVG page's
/// aspect); an error unless the scene has something to draw.
fn drawing_view(scene: &Graph, view: Option<&Bound<'_, PyDict>>) -> PyResult<View> {
    if scene.mesh_objects(scene.roots()).is_empty() {
        return Err(err("the scene has no objects to draw"));
    }
    view_of(scene, view, SvgOptions::default().drawing_aspect())
}

/// Draws the scene as the command line's `render` does (see [`finished`]).
#[allow(clippy::too_many_arguments)]
fn draw(
    py: Python<'_>,
    scene: &Graph,
    view: Option<&Bound<'_, PyDict>>,
    edges: &str,
    hidden: bool,
    crease_angle: f64,
    overlaps: &str,
    order: bool,
) -> PyResult<Vec<Polyline>> {
    let options = options_of(edges, hidden, crease_angle, overlaps)?;
    let view = drawing_view(scene, view)?;
    py.detach(|| {
        hidden::draw(scene, &view, &options)
            .map(|d| finished(d, order))
            .map_err(|e| e.to_string())
    })
    .map_err(err)
}

/// One call that built a scene, kept so that the scene can be rebuilt in another process (a
/// Dask worker): a pickled scene is its calls.
#[derive(Debug, Clone)]
enum Step {
    /// `Scene.load(path)`, with the path made absolute.
    Load(String),
    /// `add_group(name, parent)`.
    Group(String, Option<String>),
    /// `add_mesh` or `add_trimesh`: name, vertices, faces, transform, parent.
    Mesh(
        String,
        Vec<[f64; 3]>,
        Vec<Vec<u32>>,
        Option<[f64; 16]>,
        Option<String>,
    ),
    /// `add_file(path, name, transform, parent)`, with the path made absolute.
    File(String, Option<String>, Option<[f64; 16]>, Option<String>),
}

/// A transform as 16 numbers, row by row, and back.
fn row_major(m: &Matrix4<f64>) -> [f64; 16] {
    std::array::from_fn(|k| m[(k / 4, k % 4)])
}

fn from_row_major(t: &[f64; 16]) -> Matrix4<f64> {
    Matrix4::from_fn(|i, j| t[4 * i + j])
}

/// A path made absolute (a worker may run elsewhere in the file system).
fn absolute(path: &str) -> String {
    std::path::absolute(path).map_or_else(|_| path.to_string(), |p| p.display().to_string())
}

/// What `Scene.__reduce__` returns: the function that rebuilds a scene, and its argument.
type Reduced<'py> = (Bound<'py, PyAny>, (Vec<Bound<'py, PyAny>>,));

/// A scene: a graph of named objects (groups and meshes), as kepler's scene files describe.
#[pyclass(module = "kepler")]
struct Scene {
    graph: Graph,
    /// The calls that built it, in order (see [`Step`]).
    steps: Vec<Step>,
}

impl Scene {
    /// The object named by its path (`group/name`), or an error.
    fn object(&self, name: &str) -> PyResult<ObjectId> {
        self.graph
            .find(name)
            .ok_or_else(|| err(format!("no object named '{name}'")))
    }

    /// The parent group named `parent`, if any.
    fn parent(&self, parent: Option<&str>) -> PyResult<Option<ObjectId>> {
        parent.map(|p| self.object(p)).transpose()
    }

    /// Carries out one step of building the scene and records it; returns the path of the
    /// object it added.
    fn apply(&mut self, step: Step) -> PyResult<String> {
        let path = match &step {
            Step::Load(path) => {
                self.graph = file::load(Path::new(path)).map_err(err)?;
                String::new()
            }
            Step::Group(name, parent) => {
                let parent = self.parent(parent.as_deref())?;
                let id = self.graph.add_group(parent, name).map_err(err)?;
                self.graph.path(id)
            }
            Step::Mesh(name, vertices, faces, transform, parent) => {
                let vertices = vertices.iter().map(|&p| Point3::from(p)).collect();
                let transform = transform.as_ref().map(from_row_major);
                let mesh = mesh_of(vertices, faces.clone(), transform.as_ref())?;
                self.add(name, mesh, parent.as_deref())?
            }
            Step::File(path, name, transform, parent) => {
                let file = Path::new(path);
                let mesh = kepler::io::read_mesh(file).map_err(err)?;
                let stem = file.file_stem().and_then(|s| s.to_str()).unwrap_or("mesh");
                let mesh = placed(mesh, transform.as_ref().map(from_row_major).as_ref())?;
                let name = name.clone().unwrap_or_else(|| stem.to_string());
                self.add(&name, mesh, parent.as_deref())?
            }
        };
        self.steps.push(step);
        Ok(path)
    }

    /// Adds a mesh and returns its path.
    fn add(&mut self, name: &str, mesh: Mesh, parent: Option<&str>) -> PyResult<String> {
        let parent = self.parent(parent)?;
        let id = self.graph.add_mesh(parent, name, mesh).map_err(err)?;
        Ok(self.graph.path(id))
    }

    /// A mesh step from Python vertices, faces and transform.
    fn mesh_step(
        name: &str,
        vertices: &Bound<'_, PyAny>,
        faces: &Bound<'_, PyAny>,
        transform: Option<&Bound<'_, PyAny>>,
        parent: Option<&str>,
    ) -> PyResult<Step> {
        let vertices = points_of(vertices, "vertices")?;
        Ok(Step::Mesh(
            name.to_string(),
            vertices.iter().map(|p| [p.x, p.y, p.z]).collect(),
            faces_of(faces)?,
            transform_of(transform)?.as_ref().map(row_major),
            parent.map(str::to_string),
        ))
    }
}

#[pymethods]
impl Scene {
    #[new]
    fn new() -> Scene {
        Scene {
            graph: Graph::new(),
            steps: Vec::new(),
        }
    }

    /// A scene read from a scene file (`.toml`) or a mesh file (`.obj`, `.stl`, `.off`,
    /// `.ply`).
    #[staticmethod]
    fn load(path: &str) -> PyResult<Scene> {
        let mut scene = Scene::new();
        scene.apply(Step::Load(absolute(path)))?;
        Ok(scene)
    }

    /// Adds a group; returns its path.
    #[pyo3(signature = (name, parent=None))]
    fn add_group(&mut self, name: &str, parent: Option<&str>) -> PyResult<String> {
        self.apply(Step::Group(name.to_string(), parent.map(str::to_string)))
    }

    /// Adds a mesh from an `(n, 3)` vertex array and faces (an `(m, k)` integer array or a
    /// list of index lists, 0-based), placed by an optional 4×4 transform; returns its path.
    #[pyo3(signature = (name, vertices, faces, transform=None, parent=None))]
    fn add_mesh(
        &mut self,
        name: &str,
        vertices: &Bound<'_, PyAny>,
        faces: &Bound<'_, PyAny>,
        transform: Option<&Bound<'_, PyAny>>,
        parent: Option<&str>,
    ) -> PyResult<String> {
        let step = Scene::mesh_step(name, vertices, faces, transform, parent)?;
        self.apply(step)
    }

    /// Adds a trimesh (or any object with `vertices` and `faces` arrays); returns its path.
    #[pyo3(signature = (name, mesh, transform=None, parent=None))]
    fn add_trimesh(
        &mut self,
        name: &str,
        mesh: &Bound<'_, PyAny>,
        transform: Option<&Bound<'_, PyAny>>,
        parent: Option<&str>,
    ) -> PyResult<String> {
        let (vertices, faces) = (mesh.getattr("vertices")?, mesh.getattr("faces")?);
        let step = Scene::mesh_step(name, &vertices, &faces, transform, parent)?;
        self.apply(step)
    }

    /// Adds the mesh of a mesh file (`.obj`, `.stl`, `.off`, `.ply`); returns its path.
    #[pyo3(signature = (path, name=None, transform=None, parent=None))]
    fn add_file(
        &mut self,
        path: &str,
        name: Option<&str>,
        transform: Option<&Bound<'_, PyAny>>,
        parent: Option<&str>,
    ) -> PyResult<String> {
        self.apply(Step::File(
            absolute(path),
            name.map(str::to_string),
            transform_of(transform)?.as_ref().map(row_major),
            parent.map(str::to_string),
        ))
    }

    /// Pickling: the scene is rebuilt from the calls that built it (files are read again, by
    /// their absolute paths).
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Reduced<'py>> {
        let rebuild = py.import("kepler._kepler")?.getattr("_rebuild")?;
        let steps = self
            .steps
            .iter()
            .map(|step| {
                Ok(match step.clone() {
                    Step::Load(path) => ("load", path).into_pyobject(py)?.into_any(),
                    Step::Group(name, parent) => {
                        ("group", name, parent).into_pyobject(py)?.into_any()
                    }
                    Step::Mesh(name, vertices, faces, transform, parent) => (
                        "mesh",
                        name,
                        vertices,
                        faces,
                        transform.map(Vec::from),
                        parent,
                    )
                        .into_pyobject(py)?
                        .into_any(),
                    Step::File(path, name, transform, parent) => {
                        ("file", path, name, transform.map(Vec::from), parent)
                            .into_pyobject(py)?
                            .into_any()
                    }
                })
            })
            .collect::<PyResult<Vec<_>>>()?;
        Ok((rebuild, (steps,)))
    }

    /// The paths of the scene's objects, depth first.
    fn objects(&self) -> Vec<String> {
        self.graph
            .walk()
            .into_iter()
            .map(|(id, _)| self.graph.path(id))
            .collect()
    }

    /// An object's bounds: `cbox` (its box, `(lo, hi)`), `inbox` (a box inside it, or
    /// `None`), `faces`, `vertices` and `solid`.
    fn bounds<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyDict>> {
        let id = self.object(name)?;
        let cbox = self.graph.cbox(id);
        let dict = PyDict::new(py);
        dict.set_item("cbox", (cbox.min, cbox.max))?;
        let inbox = self.graph.inbox(id).map(|b| (b.aabb.min, b.aabb.max));
        dict.set_item("inbox", inbox)?;
        dict.set_item("faces", self.graph.face_count(id))?;
        dict.set_item("vertices", self.graph.vertex_count(id))?;
        dict.set_item("solid", self.graph.is_solid(id))?;
        Ok(dict)
    }

    /// INCLUDE for each point of an `(n, 3)` array: an int8 array, `kepler.IN` (1),
    /// `kepler.ON` (0) or `kepler.OUT` (-1). Every mesh of the scene must be closed.
    fn include<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'_, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<i8>>> {
        let points = points_of(points, "points")?;
        let graph = &self.graph;
        let answers = py
            .detach(|| {
                IncludeIndex::whole_scene(graph)
                    .map(|index| index.include_all(&points).0)
                    .map_err(|e| e.to_string())
            })
            .map_err(err)?;
        let codes: Vec<i8> = answers
            .into_iter()
            .map(|a| match a {
                Inclusion::In => 1,
                Inclusion::On => 0,
                Inclusion::Out => -1,
            })
            .collect();
        Ok(codes.into_pyarray(py))
    }

    /// VISP for each point of an `(n, 3)` array in a view: a bool array, `True` where the
    /// point is visible.
    #[pyo3(signature = (points, view=None))]
    fn visible<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'_, PyAny>,
        view: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Bound<'py, PyArray1<bool>>> {
        let points = points_of(points, "points")?;
        let view = view_of(&self.graph, view, SvgOptions::default().drawing_aspect())?;
        let graph = &self.graph;
        let answers = py.detach(|| {
            VisibilityIndex::whole_scene(graph, view)
                .visp_all(&points)
                .0
        });
        let visible: Vec<bool> = answers
            .into_iter()
            .map(|a| a == Visibility::Visible)
            .collect();
        Ok(visible.into_pyarray(py))
    }

    /// The scene's hidden-line drawing: a list of `Polyline`s (see `kepler.render`).
    #[pyo3(signature = (view=None, edges="feature", hidden=false, crease_angle=30.0, overlaps="once", order=false))]
    #[allow(clippy::too_many_arguments)]
    fn render(
        &self,
        py: Python<'_>,
        view: Option<&Bound<'_, PyDict>>,
        edges: &str,
        hidden: bool,
        crease_angle: f64,
        overlaps: &str,
        order: bool,
    ) -> PyResult<Vec<Polyline>> {
        draw(
            py,
            &self.graph,
            view,
            edges,
            hidden,
            crease_angle,
            overlaps,
            order,
        )
    }

    /// A grid of `tiles[0]` by `tiles[1]` windows over the scene's picture in a view, each
    /// `((x0, x1), (y0, y1))`, half open, the outer ones reaching to infinity: the windows of
    /// `render_tile` that `kepler.stitch` joins into `render`'s drawing.
    #[pyo3(signature = (view=None, tiles=(8, 8)))]
    fn tile_windows(
        &self,
        view: Option<&Bound<'_, PyDict>>,
        tiles: (usize, usize),
    ) -> PyResult<Vec<Window>> {
        let view = drawing_view(&self.graph, view)?;
        let windows = tile_windows(&self.graph, &view, [tiles.0, tiles.1]).map_err(err)?;
        Ok(windows.iter().map(|w| (w.x.into(), w.y.into())).collect())
    }

    /// The pieces of the drawing inside one window `((x0, x1), (y0, y1))` of the view, as
    /// bytes for `kepler.stitch` (hidden pieces are kept; `stitch` drops them unless asked).
    #[pyo3(signature = (window, view=None, edges="feature", crease_angle=30.0))]
    fn render_tile<'py>(
        &self,
        py: Python<'py>,
        window: Window,
        view: Option<&Bound<'_, PyDict>>,
        edges: &str,
        crease_angle: f64,
    ) -> PyResult<Bound<'py, PyBytes>> {
        let options = options_of(edges, true, crease_angle, "keep")?;
        let view = drawing_view(&self.graph, view)?;
        let window = Rectangle::new(window.0.into(), window.1.into()).map_err(err)?;
        let graph = &self.graph;
        let bytes = py
            .detach(|| {
                draw_tile(graph, &view, &options, &window)
                    .map(|t| t.to_bytes())
                    .map_err(|e| e.to_string())
            })
            .map_err(err)?;
        Ok(PyBytes::new(py, &bytes))
    }

    fn __repr__(&self) -> String {
        format!("Scene({} objects)", self.graph.walk().len())
    }
}

/// The hidden-line drawing of one mesh: a list of `Polyline`s in view coordinates.
#[pyfunction]
#[pyo3(signature = (vertices, faces, view=None, edges="feature", hidden=false, crease_angle=30.0, overlaps="once", order=false))]
#[allow(clippy::too_many_arguments)]
fn render(
    py: Python<'_>,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
    view: Option<&Bound<'_, PyDict>>,
    edges: &str,
    hidden: bool,
    crease_angle: f64,
    overlaps: &str,
    order: bool,
) -> PyResult<Vec<Polyline>> {
    let mut graph = Graph::new();
    graph
        .add_mesh(
            None,
            "mesh",
            mesh_of(points_of(vertices, "vertices")?, faces_of(faces)?, None)?,
        )
        .map_err(err)?;
    draw(
        py,
        &graph,
        view,
        edges,
        hidden,
        crease_angle,
        overlaps,
        order,
    )
}

/// A window as Python sees it: `((x0, x1), (y0, y1))`.
type Window = ((f64, f64), (f64, f64));

/// The drawing of the tiles of a grid (the bytes of `Scene.render_tile` for each window of
/// `Scene.tile_windows`), finished as `render` finishes it: the same polylines as `render`,
/// bit for bit.
#[pyfunction]
#[pyo3(signature = (tiles, hidden=false, overlaps="once", order=false))]
fn stitch(
    py: Python<'_>,
    tiles: Vec<Vec<u8>>,
    hidden: bool,
    overlaps: &str,
    order: bool,
) -> PyResult<Vec<Polyline>> {
    let options = hidden::Options {
        hidden,
        overlaps: overlaps_of(overlaps)?,
        ..hidden::Options::default()
    };
    py.detach(|| {
        let tiles = tiles
            .iter()
            .map(|t| TileDrawing::from_bytes(t))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| e.to_string())?;
        kepler::hidden::tiles::stitch(&tiles, &options)
            .map(|d| finished(d, order))
            .map_err(|e| e.to_string())
    })
    .map_err(err)
}

/// A scene rebuilt from the calls that built it (unpickling a `Scene`).
#[pyfunction]
fn _rebuild(steps: Vec<Bound<'_, PyAny>>) -> PyResult<Scene> {
    let mut scene = Scene::new();
    for step in steps {
        let kind: String = step.get_item(0)?.extract()?;
        let step = match kind.as_str() {
            "load" => Step::Load(step.get_item(1)?.extract()?),
            "group" => {
                let (_, name, parent): (String, String, Option<String>) = step.extract()?;
                Step::Group(name, parent)
            }
            "mesh" => {
                type Args = (
                    String,
                    String,
                    Vec<[f64; 3]>,
                    Vec<Vec<u32>>,
                    Option<[f64; 16]>,
                    Option<String>,
                );
                let (_, name, vertices, faces, transform, parent): Args = step.extract()?;
                Step::Mesh(name, vertices, faces, transform, parent)
            }
            "file" => {
                type Args = (
                    String,
                    String,
                    Option<String>,
                    Option<[f64; 16]>,
                    Option<String>,
                );
                let (_, path, name, transform, parent): Args = step.extract()?;
                Step::File(path, name, transform, parent)
            }
            other => return Err(err(format!("not a step that builds a scene: '{other}'"))),
        };
        scene.apply(step)?;
    }
    Ok(scene)
}

/// The module `kepler._kepler`.
#[pymodule]
fn _kepler(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("KeplerError", m.py().get_type::<KeplerError>())?;
    m.add("IN", 1i8)?;
    m.add("ON", 0i8)?;
    m.add("OUT", -1i8)?;
    m.add_class::<Polyline>()?;
    m.add_class::<Scene>()?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(stitch, m)?)?;
    m.add_function(wrap_pyfunction!(_rebuild, m)?)?;
    Ok(())
}
