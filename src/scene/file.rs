//! The scene file: a hand-writable TOML description of a hierarchical scene.
//!
//! ```toml
//! [camera]                       # optional
//! projection = "perspective"     # or "orthographic" (the default with view-dir)
//! eye = [40, -60, 35]
//! target = [0, 0, 8]
//! up = [0, 0, 1]                 # default (0, 0, 1)
//! fov = 35                       # degrees, perspective only (default 40)
//!
//! [define.window]                # a prototype, placed only by `instance`
//! solid = "box"
//! size = [1.2, 0.2, 1.5]
//!
//! [[object]]                     # a top-level object
//! name = "ground"
//! solid = "box"
//! size = [80, 80, 1]
//! translate = [0, 0, -0.5]
//!
//! [[object]]
//! name = "tower"
//! translate = [10, 0, 0]
//! [[object.object]]              # a subobject of "tower"
//! name = "body"
//! solid = "box"
//! size = [8, 8, 30]
//! translate = [0, 0, 15]
//! [[object.object]]
//! name = "windows"
//! instance = "window"
//! array = { count = [3, 1, 10], step = [2.5, 0, 2.8] }
//! translate = [-2.5, -4.1, 2]
//! ```
//!
//! An object has a `name` and exactly one of: `solid` (a built-in solid with its
//! parameters), `mesh` (an OBJ, STL, OFF or PLY file, relative to the scene file), `instance` (a
//! `[define.NAME]` prototype) or subobjects (`[[object.object]]` tables). Placement keys:
//! `scale` (a number or `[x, y, z]`), `rotate` (degrees about x, then y, then z),
//! `translate`, applied in that order and on top of the placement of the enclosing objects;
//! `array = { count = [nx, ny, nz], step = [dx, dy, dz] }` makes a group of copies.
//! Unknown keys, parameters that do not apply to the solid, and missing ones are errors
//! that name the file and line.

use super::{Camera, ObjectId, Projection, Result, Scene, SceneError, Transform};
use crate::io::{FileError, shortened};
use crate::mesh::{Mesh, Validation};
use crate::solids::{self, Polyhedron};
use nalgebra::{Matrix4, Vector3};
use serde::Deserialize;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use toml::Spanned;

/// Loads a scene: a scene file (`.toml`), or a single mesh file (`.obj`, `.stl`, `.off`,
/// `.ply`) that becomes a scene of one object named after the file. Mesh files are read with
/// [`Validation::Repair`] (see [`load_with`]).
///
/// ```
/// let scene = kepler::scene::file::load("scenes/cube.toml".as_ref()).unwrap();
/// assert_eq!(scene.roots().len(), 1);
/// ```
pub fn load(path: &Path) -> Result<Scene> {
    load_with(path, Validation::Repair)
}

/// [`load`] reading mesh files with the given treatment of degenerate faces and polygons that
/// are not exactly planar ([`Validation::Strict`] refuses them, naming the file and line).
///
/// ```
/// use kepler::{mesh::Validation, scene::file::load_with};
/// let scene = load_with("scenes/meshes.toml".as_ref(), Validation::Strict).unwrap();
/// assert_eq!(scene.roots().len(), 3);
/// ```
pub fn load_with(path: &Path, validation: Validation) -> Result<Scene> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if ext.as_deref() == Some("toml") {
        let text = std::fs::read_to_string(path)
            .map_err(|e| FileError::io(path.display().to_string(), e))?;
        return parse_with(&text, path, validation);
    }
    if ext.as_deref() == Some("kix") {
        let name = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| FileError::io(&name, e))?;
        return super::index::read(&bytes, &name);
    }
    let mesh = crate::io::read_mesh_with(path, validation)?;
    let mut scene = Scene::new();
    let name = path
        .file_stem()
        .map_or_else(|| "mesh".to_string(), |s| s.to_string_lossy().into_owned());
    scene.add_mesh(None, name, mesh)?;
    Ok(scene)
}

/// Parses the text of a scene file; `path` names it in errors and anchors relative mesh
/// paths.
///
/// ```
/// use std::path::Path;
/// let text = "[[object]]\nname = \"c\"\nsolid = \"cube\"\nedge = 2\n";
/// let scene = kepler::scene::file::parse(text, Path::new("inline.toml")).unwrap();
/// assert_eq!(scene.volume(scene.roots()[0]), Some(8.0));
/// let bad = kepler::scene::file::parse("[[object]]\ncolour = 3\n", Path::new("x.toml"));
/// assert!(bad.unwrap_err().to_string().starts_with("x.toml:2: unknown field `colour`"));
/// ```
pub fn parse(text: &str, path: &Path) -> Result<Scene> {
    parse_with(text, path, Validation::Repair)
}

/// [`parse`] reading mesh files with the given treatment of degenerate faces and polygons that
/// are not exactly planar. Errors that echo the text cut what they echo ([`shortened`]).
///
/// ```
/// use kepler::{mesh::Validation, scene::file::parse_with};
/// let key = "k".repeat(1 << 20);
/// let err = parse_with(&format!("[[object]]\n{key} = 3\n"), "x.toml".as_ref(), Validation::Repair);
/// let message = err.unwrap_err().to_string();
/// assert!(message.starts_with("x.toml:2: unknown field `kkkk") && message.len() < 300);
/// ```
pub fn parse_with(text: &str, path: &Path, validation: Validation) -> Result<Scene> {
    let name = path.display().to_string();
    let line_of = |offset: usize| text[..offset.min(text.len())].matches('\n').count() + 1;
    let spec: FileSpec = toml::from_str(text).map_err(|e| FileError::Input {
        path: name.clone(),
        at: e
            .span()
            .map_or("1".to_string(), |s| line_of(s.start).to_string()),
        message: shortened(e.message()),
    })?;
    let mut b = Builder {
        path: name,
        dir: path.parent().map(Path::to_path_buf).unwrap_or_default(),
        line_of: &line_of,
        defines: &spec.define,
        protos: HashMap::new(),
        building: Vec::new(),
        meshes: HashMap::new(),
        validation,
    };
    let mut scene = Scene::new();
    if let Some(c) = &spec.camera {
        scene.set_camera(b.camera(c)?);
    }
    // Every prototype is checked, even one nothing instances, so a typo does not go unseen.
    for (name, define) in &spec.define {
        b.instance(define, name)?;
    }
    let protos = spec
        .object
        .iter()
        .map(|o| b.proto(o))
        .collect::<Result<Vec<_>>>()?;
    let total = protos
        .iter()
        .fold(0u64, |n, p| n.saturating_add(p.object_count()));
    if total > MAX_OBJECTS {
        return Err(FileError::Input {
            path: b.path.clone(),
            at: "1".into(),
            message: format!(
                "the scene would place {total} objects; at most {MAX_OBJECTS} are allowed"
            ),
        }
        .into());
    }
    // The builder's caches let go of their meshes, so that a mesh placed once as it is moves
    // into the scene instead of being copied.
    b.protos.clear();
    b.meshes.clear();
    for (o, proto) in spec.object.iter().zip(protos) {
        place(&mut scene, proto, None, &Matrix4::identity()).map_err(|e| b.at(o, e))?;
    }
    Ok(scene)
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileSpec {
    camera: Option<Spanned<CameraSpec>>,
    #[serde(default)]
    define: BTreeMap<String, Spanned<ObjectSpec>>,
    #[serde(default)]
    object: Vec<Spanned<ObjectSpec>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename_all = "kebab-case")]
struct CameraSpec {
    projection: Option<String>,
    view_dir: Option<[f64; 3]>,
    eye: Option<[f64; 3]>,
    target: Option<[f64; 3]>,
    up: Option<[f64; 3]>,
    fov: Option<f64>,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum Triple {
    Uniform(f64),
    Axes([f64; 3]),
}

impl Triple {
    fn axes(&self) -> [f64; 3] {
        match *self {
            Triple::Uniform(s) => [s; 3],
            Triple::Axes(a) => a,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ArraySpec {
    count: [u32; 3],
    step: [f64; 3],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename_all = "kebab-case")]
struct ObjectSpec {
    name: Option<String>,
    solid: Option<String>,
    mesh: Option<String>,
    instance: Option<String>,
    #[serde(default)]
    object: Vec<Spanned<ObjectSpec>>,
    size: Option<Triple>,
    edge: Option<f64>,
    radius: Option<f64>,
    height: Option<f64>,
    segments: Option<u32>,
    rings: Option<u32>,
    sides: Option<u32>,
    major_radius: Option<f64>,
    minor_radius: Option<f64>,
    outline: Option<Vec<[f64; 2]>>,
    translate: Option<[f64; 3]>,
    rotate: Option<[f64; 3]>,
    scale: Option<Triple>,
    array: Option<ArraySpec>,
}

impl ObjectSpec {
    /// The solid parameters that were given, by their file names.
    fn given_parameters(&self) -> Vec<&'static str> {
        [
            ("size", self.size.is_some()),
            ("edge", self.edge.is_some()),
            ("radius", self.radius.is_some()),
            ("height", self.height.is_some()),
            ("segments", self.segments.is_some()),
            ("rings", self.rings.is_some()),
            ("sides", self.sides.is_some()),
            ("major-radius", self.major_radius.is_some()),
            ("minor-radius", self.minor_radius.is_some()),
            ("outline", self.outline.is_some()),
        ]
        .into_iter()
        .filter_map(|(k, given)| given.then_some(k))
        .collect()
    }

    fn transform(&self) -> Transform {
        Transform {
            scale: self.scale.as_ref().map_or([1.0; 3], Triple::axes),
            rotate: self.rotate.unwrap_or([0.0; 3]),
            translate: self.translate.unwrap_or([0.0; 3]),
        }
    }
}

/// An object in local coordinates, before placement: a mesh with the matrix that will
/// place it (so each vertex is transformed once, by the composed matrix), or a group.
#[derive(Clone)]
enum Proto {
    Leaf {
        name: String,
        mesh: Arc<Mesh>,
        matrix: Matrix4<f64>,
        instance_of: Option<String>,
    },
    Group {
        name: String,
        children: Vec<Proto>,
        instance_of: Option<String>,
    },
}

/// The most objects a scene file may place (nested arrays multiply), so that a mistyped
/// count gives an error instead of exhausting memory.
///
/// ```
/// assert_eq!(kepler::scene::file::MAX_OBJECTS, 10_000_000);
/// ```
pub const MAX_OBJECTS: u64 = 10_000_000;

impl Proto {
    /// How many objects placing this proto creates.
    fn object_count(&self) -> u64 {
        match self {
            Proto::Leaf { .. } => 1,
            Proto::Group { children, .. } => children
                .iter()
                .fold(1u64, |n, c| n.saturating_add(c.object_count())),
        }
    }

    fn renamed(mut self, new: String, instance: Option<&str>) -> Proto {
        match &mut self {
            Proto::Leaf {
                name, instance_of, ..
            }
            | Proto::Group {
                name, instance_of, ..
            } => {
                *name = new;
                if let Some(i) = instance {
                    *instance_of = Some(i.to_string());
                }
            }
        }
        self
    }

    /// Applies `m` after this proto's own placement.
    fn placed(&self, m: &Matrix4<f64>) -> Proto {
        match self {
            Proto::Leaf {
                name,
                mesh,
                matrix,
                instance_of,
            } => Proto::Leaf {
                name: name.clone(),
                mesh: mesh.clone(),
                matrix: m * matrix,
                instance_of: instance_of.clone(),
            },
            Proto::Group {
                name,
                children,
                instance_of,
            } => Proto::Group {
                name: name.clone(),
                children: children.iter().map(|c| c.placed(m)).collect(),
                instance_of: instance_of.clone(),
            },
        }
    }
}

/// Inserts a proto into the scene, transforming each mesh once by its composed matrix (a mesh
/// under the identity is moved, or copied only when another proto shares it).
fn place(
    scene: &mut Scene,
    proto: Proto,
    parent: Option<ObjectId>,
    outer: &Matrix4<f64>,
) -> Result<ObjectId> {
    let (id, instance_of) = match proto {
        Proto::Leaf {
            name,
            mesh,
            matrix,
            instance_of,
        } => {
            let m = outer * matrix;
            let mesh = if m == Matrix4::identity() {
                Arc::unwrap_or_clone(mesh)
            } else {
                mesh.transformed(&m).map_err(|e| SceneError::Object {
                    object: name.clone(),
                    problem: super::ObjectProblem::Mesh(e),
                })?
            };
            (scene.add_mesh(parent, name, mesh)?, instance_of)
        }
        Proto::Group {
            name,
            children,
            instance_of,
        } => {
            let id = scene.add_group(parent, name)?;
            for c in children {
                place(scene, c, Some(id), outer)?;
            }
            (id, instance_of)
        }
    };
    scene.objects[id].instance_of = instance_of;
    Ok(id)
}

struct Builder<'a> {
    path: String,
    dir: PathBuf,
    line_of: &'a dyn Fn(usize) -> usize,
    defines: &'a BTreeMap<String, Spanned<ObjectSpec>>,
    protos: HashMap<String, Proto>,
    building: Vec<String>,
    meshes: HashMap<PathBuf, Arc<Mesh>>,
    validation: Validation,
}

impl Builder<'_> {
    /// Bad input at the line of `at`.
    fn err<T>(&self, at: &Spanned<T>, message: impl Into<String>) -> SceneError {
        let message = shortened(&message.into());
        FileError::at_line(self.path.clone(), (self.line_of)(at.span().start), message).into()
    }

    /// An error caused by what the line of `at` asks for.
    fn at<T>(&self, at: &Spanned<T>, source: impl Into<SceneError>) -> SceneError {
        SceneError::AtLine {
            path: self.path.clone(),
            line: (self.line_of)(at.span().start),
            source: Box::new(source.into()),
        }
    }

    fn camera(&self, c: &Spanned<CameraSpec>) -> Result<Camera> {
        let s = c.get_ref();
        let check = |v: [f64; 3], what: &str| -> Result<[f64; 3]> {
            if v.iter().any(|x| !x.is_finite()) {
                return Err(self.err(c, format!("camera {what} must be finite")));
            }
            Ok(v)
        };
        let up = check(s.up.unwrap_or([0.0, 0.0, 1.0]), "up")?;
        let perspective = match s.projection.as_deref() {
            None => s.eye.is_some() && s.view_dir.is_none(),
            Some("perspective") => true,
            Some("orthographic") => false,
            Some(other) => {
                return Err(self.err(
                    c,
                    format!("unknown projection `{other}` (orthographic or perspective)"),
                ));
            }
        };
        let direction = match (s.view_dir, s.eye, s.target) {
            (Some(d), None, None) if !perspective => check(d, "view-dir")?,
            (None, Some(e), Some(t)) => {
                let (e, t) = (check(e, "eye")?, check(t, "target")?);
                [t[0] - e[0], t[1] - e[1], t[2] - e[2]]
            }
            (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
                return Err(self.err(c, "give either view-dir or eye and target, not both"));
            }
            _ if perspective => {
                return Err(self.err(
                    c,
                    "a perspective camera needs eye and target (and no view-dir)",
                ));
            }
            _ => {
                return Err(self.err(
                    c,
                    "an orthographic camera needs view-dir, or eye and target",
                ));
            }
        };
        let (d, u) = (Vector3::from(direction), Vector3::from(up));
        if d.norm() == 0.0 {
            return Err(self.err(c, "the view direction is zero"));
        }
        if d.cross(&u).norm() <= 1e-12 * d.norm() * u.norm() {
            return Err(self.err(c, "the up vector is zero or parallel to the view direction"));
        }
        let projection = if perspective {
            let fov = s.fov.unwrap_or(40.0);
            if !(fov > 0.0 && fov < 180.0) {
                return Err(self.err(
                    c,
                    format!("fov must be between 0 and 180 degrees, got {fov}"),
                ));
            }
            Projection::Perspective {
                eye: s.eye.unwrap_or_default(),
                target: s.target.unwrap_or_default(),
                fov,
            }
        } else {
            if s.fov.is_some() {
                return Err(self.err(c, "fov applies only to a perspective camera"));
            }
            Projection::Orthographic { direction }
        };
        Ok(Camera { projection, up })
    }

    /// The local-coordinate proto of an object spec, its own placement and array included.
    fn proto(&mut self, o: &Spanned<ObjectSpec>) -> Result<Proto> {
        let s = o.get_ref();
        let base = self.base(o)?;
        let t = s.transform();
        if t.scale
            .iter()
            .chain(&t.rotate)
            .chain(&t.translate)
            .any(|x| !x.is_finite())
        {
            return Err(self.err(o, "scale, rotate and translate must be finite"));
        }
        if t.scale.contains(&0.0) {
            return Err(self.err(o, "a scale factor of 0 flattens the object"));
        }
        let name = s.name.clone().unwrap_or_else(|| match &base {
            Proto::Leaf { name, .. } | Proto::Group { name, .. } => name.clone(),
        });
        let placed = base.placed(&t.matrix()).renamed(name.clone(), None);
        let Some(a) = &s.array else {
            return Ok(placed);
        };
        self.arrayed(o, a, placed, name)
    }

    /// The proto of an object spec before its own placement: its solid, mesh file, instance
    /// or subobjects, exactly one of them.
    fn base(&mut self, o: &Spanned<ObjectSpec>) -> Result<Proto> {
        let s = o.get_ref();
        let kinds = [
            s.solid.is_some(),
            s.mesh.is_some(),
            s.instance.is_some(),
            !s.object.is_empty(),
        ];
        Ok(match kinds.iter().filter(|&&k| k).count() {
            0 => {
                return Err(self.err(
                    o,
                    "an object needs one of `solid`, `mesh`, `instance` or subobjects",
                ));
            }
            1 => {
                if let Some(solid) = &s.solid {
                    self.solid(o, solid)?
                } else {
                    if let Some(&p) = s.given_parameters().first() {
                        return Err(self.err(o, format!("`{p}` applies only to a built-in solid")));
                    }
                    if let Some(file) = &s.mesh {
                        self.mesh_file(o, file)?
                    } else if let Some(def) = &s.instance {
                        self.instance(o, def)?
                    } else {
                        let children = s
                            .object
                            .iter()
                            .map(|c| self.proto(c))
                            .collect::<Result<_>>()?;
                        Proto::Group {
                            name: "group".into(),
                            children,
                            instance_of: None,
                        }
                    }
                }
            }
            _ => {
                return Err(self.err(
                    o,
                    "an object has only one of `solid`, `mesh`, `instance` or subobjects",
                ));
            }
        })
    }

    /// The group of the copies of `placed` that the array `a` of the object spec `o` makes,
    /// named `name`, the copies `name-1`, `name-2`, … (x fastest, then y, then z).
    fn arrayed(
        &self,
        o: &Spanned<ObjectSpec>,
        a: &ArraySpec,
        placed: Proto,
        name: String,
    ) -> Result<Proto> {
        if a.step.iter().any(|x| !x.is_finite()) {
            return Err(self.err(o, "array step must be finite"));
        }
        let total = a.count.iter().map(|&c| u64::from(c)).product::<u64>();
        if total == 0 || total > 1_000_000 {
            return Err(self.err(
                o,
                format!("array count must give 1 to 1,000,000 copies, got {total}"),
            ));
        }
        if total.saturating_mul(placed.object_count()) > MAX_OBJECTS {
            return Err(self.err(
                o,
                format!("this array would place more than {MAX_OBJECTS} objects"),
            ));
        }
        let mut children = Vec::with_capacity(total as usize);
        for k in 0..a.count[2] {
            for j in 0..a.count[1] {
                for i in 0..a.count[0] {
                    let offset = Vector3::new(
                        a.step[0] * f64::from(i),
                        a.step[1] * f64::from(j),
                        a.step[2] * f64::from(k),
                    );
                    let copy = placed
                        .placed(&Matrix4::new_translation(&offset))
                        .renamed(format!("{name}-{}", children.len() + 1), None);
                    children.push(copy);
                }
            }
        }
        Ok(Proto::Group {
            name,
            children,
            instance_of: None,
        })
    }

    fn instance(&mut self, o: &Spanned<ObjectSpec>, def: &str) -> Result<Proto> {
        if let Some(p) = self.protos.get(def) {
            return Ok(p.clone().renamed(def.to_string(), Some(def)));
        }
        let Some(spec) = self.defines.get(def) else {
            return Err(self.err(o, format!("no `[define.{def}]` for this instance")));
        };
        if self.building.iter().any(|b| b == def) {
            return Err(self.err(
                o,
                format!(
                    "`{def}` is defined in terms of itself ({} → {def})",
                    self.building.join(" → ")
                ),
            ));
        }
        self.building.push(def.to_string());
        let proto = self.proto(spec);
        self.building.pop();
        let proto = proto?.renamed(def.to_string(), Some(def));
        self.protos.insert(def.to_string(), proto.clone());
        Ok(proto)
    }

    fn mesh_file(&mut self, o: &Spanned<ObjectSpec>, file: &str) -> Result<Proto> {
        let path = self.dir.join(file);
        let mesh = match self.meshes.get(&path) {
            Some(m) => m.clone(),
            None => {
                let m = crate::io::read_mesh_with(&path, self.validation);
                let m = Arc::new(m.map_err(|e| self.at(o, e))?);
                self.meshes.insert(path.clone(), m.clone());
                m
            }
        };
        let name = path
            .file_stem()
            .map_or_else(|| "mesh".to_string(), |s| s.to_string_lossy().into_owned());
        Ok(Proto::Leaf {
            name,
            mesh,
            matrix: Matrix4::identity(),
            instance_of: None,
        })
    }

    /// The parameters the built-in solid `key` (named `solid` in the spec `o`) takes.
    fn solid_parameters(
        &self,
        o: &Spanned<ObjectSpec>,
        solid: &str,
        key: &str,
    ) -> Result<&'static [&'static str]> {
        Ok(match key {
            "box" => &["size"],
            "cube" => &["edge", "size"],
            "prism" => &["outline", "height"],
            "sphere" | "uv-sphere" => &["radius", "segments", "rings"],
            "torus" => &["major-radius", "minor-radius", "segments", "sides"],
            "cylinder" => &["radius", "height", "segments"],
            _ if Polyhedron::from_name(key).is_some() => &["edge"],
            _ => return Err(self.err(o, format!("unknown solid `{solid}`"))),
        })
    }

    fn solid(&self, o: &Spanned<ObjectSpec>, solid: &str) -> Result<Proto> {
        let s = o.get_ref();
        let key = solid.to_ascii_lowercase().replace(['_', ' '], "-");
        let allowed = self.solid_parameters(o, solid, &key)?;
        if let Some(p) = s
            .given_parameters()
            .into_iter()
            .find(|p| !allowed.contains(p))
        {
            return Err(self.err(
                o,
                format!(
                    "`{p}` does not apply to solid `{solid}` (it takes {})",
                    allowed.join(", ")
                ),
            ));
        }
        let need = |v: Option<f64>, what: &str| {
            v.ok_or_else(|| self.err(o, format!("solid `{solid}` needs `{what}`")))
        };
        let mesh = match key.as_str() {
            "box" => {
                let Some(size) = &s.size else {
                    return Err(self.err(o, "solid `box` needs `size`"));
                };
                solids::cuboid(Vector3::from(size.axes()))
            }
            "cube" => match (s.size.as_ref(), s.edge) {
                (Some(&Triple::Uniform(e)), None) | (None, Some(e)) => solids::cube(e),
                (None, None) => solids::cube(1.0),
                _ => return Err(self.err(o, "solid `cube` takes one number: `edge`")),
            },
            "prism" => {
                let Some(outline) = &s.outline else {
                    return Err(self.err(o, "solid `prism` needs `outline`"));
                };
                let ring: Vec<geo::Coord<f64>> =
                    outline.iter().map(|&[x, y]| geo::Coord { x, y }).collect();
                solids::prism(
                    &geo::Polygon::new(geo::LineString::new(ring), vec![]),
                    need(s.height, "height")?,
                )
            }
            "sphere" | "uv-sphere" => solids::uv_sphere(
                s.radius.unwrap_or(1.0),
                s.segments.unwrap_or(32),
                s.rings.unwrap_or(16),
            ),
            "torus" => solids::torus(
                need(s.major_radius, "major-radius")?,
                need(s.minor_radius, "minor-radius")?,
                s.segments.unwrap_or(48),
                s.sides.unwrap_or(24),
            ),
            "cylinder" => solids::cylinder(
                s.radius.unwrap_or(1.0),
                need(s.height, "height")?,
                s.segments.unwrap_or(32),
            ),
            _ => match Polyhedron::from_name(&key) {
                Some(p) => p.mesh(s.edge.unwrap_or(1.0)),
                None => return Err(self.err(o, format!("unknown solid `{solid}`"))),
            },
        };
        let mesh = mesh.map_err(|e| self.at(o, e))?;
        Ok(Proto::Leaf {
            name: key,
            mesh: Arc::new(mesh),
            matrix: Matrix4::identity(),
            instance_of: None,
        })
    }
}
