//! Python bindings of kepler (PyO3 + maturin): the module `kepler._kepler`, which the Python
//! package `kepler` re-exports (see `python/kepler/__init__.py` and its stubs).
//!
//! Everything here converts and delegates: numpy arrays in, the library's calls, numpy arrays
//! and small objects out, and every library error raised as `kepler.KeplerError` with the
//! library's own message. No geometry is computed here.

use kepler::geometry::{Point3, Vector3};
use kepler::hidden::{self, Drawing, EdgeClass, EdgeSelection};
use kepler::mesh::{Mesh, Validation};
use kepler::output::{SvgOptions, ordered};
use kepler::queries::include::{IncludeIndex, Inclusion};
use kepler::queries::visp::{Visibility, VisibilityIndex};
use kepler::scene::{ObjectId, Scene as Graph, file};
use kepler::views::{View, ViewOptions};
use nalgebra::Matrix4;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
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

/// A mesh from vertices (an `(n, 3)` array or sequence of triples) and faces, placed by an
/// optional 4×4 transform.
fn mesh_of(
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
    transform: Option<&Bound<'_, PyAny>>,
) -> PyResult<Mesh> {
    let mesh = Mesh::from_polygons_with(
        points_of(vertices, "vertices")?,
        faces_of(faces)?,
        Validation::Repair,
    )
    .map_err(err)?;
    placed(mesh, transform)
}

/// The mesh under an optional 4×4 transform (row-major homogeneous matrix).
fn placed(mesh: Mesh, transform: Option<&Bound<'_, PyAny>>) -> PyResult<Mesh> {
    let Some(t) = transform else {
        return Ok(mesh);
    };
    let t: PyReadonlyArray2<'_, f64> = as_array(t, "float64")
        .and_then(|a| a.extract())
        .map_err(|_| err("transform must be a 4×4 array of floats"))?;
    if t.shape() != [4, 4] {
        return Err(err(format!("transform must be 4×4, not {:?}", t.shape())));
    }
    let a = t.as_array();
    let m = Matrix4::from_fn(|i, j| a[[i, j]]);
    mesh.transformed(&m).map_err(err)
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

/// Draws the scene as the command line's `render` does: each stretch of line once unless
/// `overlaps == "keep"`, paths in pen order when `order`.
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
    if !(crease_angle.is_finite() && (0.0..=180.0).contains(&crease_angle)) {
        return Err(err(format!(
            "crease_angle must be between 0 and 180 degrees, not {crease_angle}"
        )));
    }
    let keep = match overlaps {
        "once" => false,
        "keep" => true,
        other => {
            return Err(err(format!(
                "overlaps must be 'once' or 'keep', not '{other}'"
            )));
        }
    };
    if scene.mesh_objects(scene.roots()).is_empty() {
        return Err(err("the scene has no objects to draw"));
    }
    let view = view_of(scene, view, SvgOptions::default().drawing_aspect())?;
    let options = hidden::Options {
        edges: edges_of(edges)?,
        crease_angle,
        hidden,
    };
    let drawing: Drawing = py
        .detach(|| -> Result<Drawing, String> {
            let drawing = hidden::draw(scene, &view, &options).map_err(|e| e.to_string())?;
            let drawing = if keep {
                drawing
            } else {
                hidden::without_overlaps(&drawing).0
            };
            Ok(if order { ordered(&drawing) } else { drawing })
        })
        .map_err(err)?;
    Ok(drawing
        .polylines
        .into_iter()
        .map(|p| Polyline {
            points: p.points,
            class: p.class,
            visible: p.visible,
        })
        .collect())
}

/// A scene: a graph of named objects (groups and meshes), as kepler's scene files describe.
#[pyclass(module = "kepler")]
struct Scene {
    graph: Graph,
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

    /// Adds a mesh and returns its path.
    fn add(&mut self, name: &str, mesh: Mesh, parent: Option<&str>) -> PyResult<String> {
        let parent = self.parent(parent)?;
        let id = self.graph.add_mesh(parent, name, mesh).map_err(err)?;
        Ok(self.graph.path(id))
    }
}

#[pymethods]
impl Scene {
    #[new]
    fn new() -> Scene {
        Scene {
            graph: Graph::new(),
        }
    }

    /// A scene read from a scene file (`.toml`) or a mesh file (`.obj`, `.stl`, `.off`,
    /// `.ply`).
    #[staticmethod]
    fn load(path: &str) -> PyResult<Scene> {
        Ok(Scene {
            graph: file::load(Path::new(path)).map_err(err)?,
        })
    }

    /// Adds a group; returns its path.
    #[pyo3(signature = (name, parent=None))]
    fn add_group(&mut self, name: &str, parent: Option<&str>) -> PyResult<String> {
        let parent = self.parent(parent)?;
        let id = self.graph.add_group(parent, name).map_err(err)?;
        Ok(self.graph.path(id))
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
        let mesh = mesh_of(vertices, faces, transform)?;
        self.add(name, mesh, parent)
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
        let mesh = mesh_of(
            &mesh.getattr("vertices")?,
            &mesh.getattr("faces")?,
            transform,
        )?;
        self.add(name, mesh, parent)
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
        let path = Path::new(path);
        let mesh = kepler::io::read_mesh(path).map_err(err)?;
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("mesh");
        let mesh = placed(mesh, transform)?;
        self.add(name.unwrap_or(stem), mesh, parent)
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
        .add_mesh(None, "mesh", mesh_of(vertices, faces, None)?)
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
    Ok(())
}
