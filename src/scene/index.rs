//! A scene index (`.kix`): a scene written once in a compact binary form, each mesh cut into
//! spatial chunks (Franklin's subobjects) listed with their CBOXes in a table of contents, and
//! read back as exactly the same scene: the same tree, names, camera and meshes, face for face
//! and bit for bit, so every drawing of it is the original scene's.
//!
//! This first form reads every chunk back; the table of contents is what a tile will read to
//! open only the chunks that reach its window (issue 30). Written by hand, like the tiles'
//! bytes (`hidden/tiles/bytes.rs`): a few dozen lines of little-endian fields keep every
//! double bit for bit, with no format crate to track.
//!
//! The format: the magic `KINDEX\0\x01`; the camera (a tag, then its doubles); the meshes'
//! table (per mesh: its vertex and face counts, its counts of repairs, and its chunks' CBOXes,
//! byte offsets and lengths); the objects in tree order, parents first (parent, name, group or
//! mesh, the mesh's number, the instance it copies); then the chunks. A chunk holds faces of
//! one mesh that lie near each other (consecutive along a Morton curve of their first
//! vertices): each face's number, input polygon, diagonals and vertex numbers, and the
//! coordinates of every vertex they use.

use super::{Camera, Content, ObjectId, Projection, Result, Scene};
use crate::geometry::{Aabb, Point3};
use crate::io::FileError;
use crate::le::{Reader, Writer};
use crate::mesh::{Loop, Mesh};
use std::collections::HashMap;
use std::sync::Arc;

/// The first bytes of an index, with the format's version.
const MAGIC: &[u8; 8] = b"KINDEX\x00\x01";

/// The most faces in a chunk.
const CHUNK_FACES: usize = 1 << 14;

/// The index of `scene` as bytes (see the module documentation).
///
/// ```
/// use kepler::scene::{file, index};
/// let scene = file::load("scenes/city.toml".as_ref()).unwrap();
/// let back = index::read(&index::to_bytes(&scene), "city.kix").unwrap();
/// let meshes = |s: &kepler::scene::Scene| -> Vec<kepler::mesh::Mesh> {
///     s.mesh_objects(s.roots()).into_iter().map(|(_, m)| m.clone()).collect()
/// };
/// assert_eq!(meshes(&back), meshes(&scene));
/// ```
pub fn to_bytes(scene: &Scene) -> Vec<u8> {
    let mut head = Writer(MAGIC.to_vec());
    head.camera(scene.camera());
    // Each mesh once (copies share it), numbered in the order first met.
    let order = in_tree_order(scene);
    let mut numbers: HashMap<*const Mesh, u32> = HashMap::new();
    let mut meshes: Vec<&Mesh> = Vec::new();
    for &id in &order {
        if let Content::Mesh(m) = &scene[id].content {
            numbers.entry(Arc::as_ptr(m)).or_insert_with(|| {
                meshes.push(m);
                (meshes.len() - 1) as u32
            });
        }
    }
    let mut body = Writer(Vec::new());
    head.u64(meshes.len() as u64);
    for mesh in &meshes {
        head.u64(mesh.vertices().len() as u64);
        head.u64(mesh.faces().len() as u64);
        for n in [
            mesh.merged_vertices(),
            mesh.degenerate_faces(),
            mesh.split_polygons(),
        ] {
            head.u64(n as u64);
        }
        let order = crate::mesh::faces_in_space_order(mesh);
        let mut chunks: Vec<&[u32]> = order.chunks(CHUNK_FACES).collect();
        if chunks.is_empty() {
            chunks.push(&[]);
        }
        // The vertices no face uses (those of dropped faces) go with the first chunk.
        let mut loose = vec![true; mesh.vertices().len()];
        for f in mesh.faces() {
            f.vertices().iter().for_each(|&v| loose[v as usize] = false);
        }
        let mut loose: Vec<u32> = (0..loose.len() as u32)
            .filter(|&v| loose[v as usize])
            .collect();
        head.u64(chunks.len() as u64);
        for chunk in chunks {
            let start = body.0.len();
            let cbox = chunk_bytes(mesh, chunk, std::mem::take(&mut loose), &mut body);
            cbox.min
                .iter()
                .chain(cbox.max.iter())
                .for_each(|&c| head.f64(c));
            head.u64(start as u64);
            head.u64((body.0.len() - start) as u64);
        }
    }
    let index: HashMap<ObjectId, u32> = order
        .iter()
        .enumerate()
        .map(|(k, &id)| (id, k as u32))
        .collect();
    head.u64(order.len() as u64);
    for &id in &order {
        let object = &scene[id];
        head.u32(object.parent.map_or(0, |p| index[&p] + 1));
        head.text(&object.name);
        match &object.content {
            Content::Subobjects(_) => head.u8(0),
            Content::Mesh(m) => {
                head.u8(1);
                head.u32(numbers[&Arc::as_ptr(m)]);
            }
        }
        match &object.instance_of {
            Some(name) => {
                head.u8(1);
                head.text(name);
            }
            None => head.u8(0),
        }
    }
    head.u64(body.0.len() as u64);
    head.0.extend_from_slice(&body.0);
    head.0
}

/// The objects of `scene` in tree order: each root, then its subtree, parents first.
fn in_tree_order(scene: &Scene) -> Vec<ObjectId> {
    scene
        .roots()
        .iter()
        .flat_map(|&r| scene.subtree(r))
        .collect()
}

/// Writes the faces `chunk` of `mesh`, with the vertices they use and the `loose` ones (see
/// the module documentation); their CBOX.
fn chunk_bytes(mesh: &Mesh, chunk: &[u32], loose: Vec<u32>, w: &mut Writer) -> Aabb {
    let faces = mesh.faces();
    let mut used: Vec<u32> = chunk
        .iter()
        .flat_map(|&f| faces[f as usize].vertices().iter().copied())
        .chain(loose)
        .collect();
    used.sort_unstable();
    used.dedup();
    w.u64(used.len() as u64);
    for &v in &used {
        w.u32(v);
        mesh.vertices()[v as usize].iter().for_each(|&c| w.f64(c));
    }
    w.u64(chunk.len() as u64);
    for &f in chunk {
        let face = &faces[f as usize];
        w.u32(f);
        w.u32(face.polygon);
        w.u8(face.diagonals);
        w.u32(face.vertices.len() as u32);
        face.vertices.iter().for_each(|&v| w.u32(v));
    }
    Aabb::from_points(
        &used
            .iter()
            .map(|&v| mesh.vertices()[v as usize])
            .collect::<Vec<_>>(),
    )
}

/// The scene of an index's bytes; `name` names the file in errors, which say what part of
/// the index is malformed.
pub fn read(bytes: &[u8], name: &str) -> Result<Scene> {
    let bad = |what: &str| FileError::Input {
        path: name.to_string(),
        at: what.to_string(),
        message: "not a kepler scene index, or a damaged one".to_string(),
    };
    let rest = bytes
        .strip_prefix(MAGIC.as_slice())
        .ok_or_else(|| bad("header"))?;
    let mut r = Reader(rest);
    let camera = r.camera().ok_or_else(|| bad("camera"))?;
    let tables = r.mesh_tables().ok_or_else(|| bad("table of meshes"))?;
    let objects = r.objects(tables.len()).ok_or_else(|| bad("objects"))?;
    let body = r.body().ok_or_else(|| bad("chunks"))?;
    let mut meshes = Vec::with_capacity(tables.len());
    for (k, table) in tables.iter().enumerate() {
        let mesh = table.read(body).ok_or_else(|| bad(&format!("mesh {k}")))?;
        let mesh = Mesh::restored(mesh.0, mesh.1, table.repairs).map_err(|e| FileError::Input {
            path: name.to_string(),
            at: format!("mesh {k}"),
            message: e.to_string(),
        })?;
        meshes.push(Arc::new(mesh));
    }
    let mut scene = Scene::new();
    if let Some(camera) = camera {
        scene.set_camera(camera);
    }
    let mut ids: Vec<ObjectId> = Vec::with_capacity(objects.len());
    for (parent, object_name, mesh, instance_of) in objects {
        let parent = match parent {
            0 => None,
            p => Some(*ids.get(p as usize - 1).ok_or_else(|| bad("objects"))?),
        };
        let content = match mesh {
            None => Content::Subobjects(Vec::new()),
            Some(m) => Content::Mesh(meshes[m as usize].clone()),
        };
        let id = scene.insert(parent, object_name, content)?;
        scene.objects[id].instance_of = instance_of;
        ids.push(id);
    }
    Ok(scene)
}

/// An object as the index lists it: its parent (0 for none, else the parent's number plus
/// one), name, mesh number (`None` for a group) and the instance it copies.
type IndexObject = (u32, String, Option<u32>, Option<String>);

/// A mesh's entry in the table of contents.
struct MeshTable {
    vertices: usize,
    faces: usize,
    repairs: [usize; 3],
    /// Each chunk's CBOX, and where its bytes lie among the chunks'.
    chunks: Vec<(Aabb, usize, usize)>,
}

/// A mesh's vertices and faces (loop, diagonals, input polygon), as read.
type Parts = (Vec<Point3>, Vec<(Loop, u8, u32)>);

impl MeshTable {
    /// The mesh's vertices and faces from its chunks in `body`; `None` where a chunk is
    /// malformed or a vertex or face is missing.
    fn read(&self, body: &[u8]) -> Option<Parts> {
        // Each vertex and face takes some bytes of a chunk: counts beyond those are damage.
        if self.vertices > body.len() / 28 || self.faces > body.len() / 13 {
            return None;
        }
        let mut vertices: Vec<Option<Point3>> = vec![None; self.vertices];
        let mut faces: Vec<Option<(Loop, u8, u32)>> = vec![None; self.faces];
        for &(_, start, len) in &self.chunks {
            let mut r = Reader(body.get(start..start.checked_add(len)?)?);
            for _ in 0..r.count()? {
                let v = r.u32()? as usize;
                *vertices.get_mut(v)? = Some(Point3::from(r.triple()?));
            }
            for _ in 0..r.count()? {
                let f = r.u32()? as usize;
                let (polygon, diagonals) = (r.u32()?, r.u8()?);
                let corners = r.u32()? as usize;
                if corners > r.0.len() / 4 {
                    return None;
                }
                let lp: Loop = (0..corners).map(|_| r.u32()).collect::<Option<_>>()?;
                *faces.get_mut(f)? = Some((lp, diagonals, polygon));
            }
            if !r.0.is_empty() {
                return None;
            }
        }
        Some((
            vertices.into_iter().collect::<Option<_>>()?,
            faces.into_iter().collect::<Option<_>>()?,
        ))
    }
}

/// A scene index's fields, written in order.
impl Writer {
    fn text(&mut self, s: &str) {
        self.u32(s.len() as u32);
        self.0.extend_from_slice(s.as_bytes());
    }

    fn camera(&mut self, camera: Option<&Camera>) {
        match camera {
            None => self.u8(0),
            Some(c) => {
                match c.projection {
                    Projection::Orthographic { direction } => {
                        self.u8(1);
                        self.triple(&direction);
                    }
                    Projection::Perspective { eye, target, fov } => {
                        self.u8(2);
                        self.triple(&eye);
                        self.triple(&target);
                        self.f64(fov);
                    }
                }
                self.triple(&c.up);
            }
        }
    }
}

/// A scene index's fields, read in order; `None` for a malformed field.
impl Reader<'_> {
    fn text(&mut self) -> Option<String> {
        let len = self.u32()? as usize;
        let bytes = self.0.get(..len)?;
        self.0 = &self.0[len..];
        String::from_utf8(bytes.to_vec()).ok()
    }

    fn camera(&mut self) -> Option<Option<Camera>> {
        let projection = match self.u8()? {
            0 => return Some(None),
            1 => Projection::Orthographic {
                direction: self.triple()?,
            },
            2 => Projection::Perspective {
                eye: self.triple()?,
                target: self.triple()?,
                fov: self.f64()?,
            },
            _ => return None,
        };
        Some(Some(Camera {
            projection,
            up: self.triple()?,
        }))
    }

    fn mesh_tables(&mut self) -> Option<Vec<MeshTable>> {
        let n = self.count()?;
        let mut tables = Vec::with_capacity(n);
        for _ in 0..n {
            let vertices = usize::try_from(self.u64()?).ok()?;
            let faces = usize::try_from(self.u64()?).ok()?;
            let repairs = [self.u64()?, self.u64()?, self.u64()?].map(|x| x as usize);
            let chunks = (0..self.count()?)
                .map(|_| {
                    let (min, max) = (self.triple()?, self.triple()?);
                    let start = usize::try_from(self.u64()?).ok()?;
                    let len = usize::try_from(self.u64()?).ok()?;
                    Some((Aabb { min, max }, start, len))
                })
                .collect::<Option<_>>()?;
            tables.push(MeshTable {
                vertices,
                faces,
                repairs,
                chunks,
            });
        }
        Some(tables)
    }

    /// The objects (see [`IndexObject`]).
    fn objects(&mut self, meshes: usize) -> Option<Vec<IndexObject>> {
        let n = self.count()?;
        let mut objects = Vec::with_capacity(n);
        for k in 0..n {
            let parent = self.u32()?;
            if parent as usize > k {
                return None;
            }
            let name = self.text()?;
            let mesh = match self.u8()? {
                0 => None,
                1 => Some(self.u32()?),
                _ => return None,
            };
            if mesh.is_some_and(|m| m as usize >= meshes) {
                return None;
            }
            let instance_of = match self.u8()? {
                0 => None,
                1 => Some(self.text()?),
                _ => return None,
            };
            objects.push((parent, name, mesh, instance_of));
        }
        Some(objects)
    }

    /// The chunks' bytes: all that is left, of the length the header says.
    fn body(&mut self) -> Option<&[u8]> {
        let len = usize::try_from(self.u64()?).ok()?;
        (self.0.len() == len).then_some(self.0)
    }
}
