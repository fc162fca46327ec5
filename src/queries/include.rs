//! INCLUDE(A, P) (Franklin 1981, algorithm A): whether a point is in, out of, or on an object.
//!
//! The paper's steps, with ON added for points on a face, edge or vertex:
//! 1. P strictly inside INBOX(A): IN.
//! 2. P outside CBOX(A), or outside its tribox: OUT.
//! 3. A mesh: an exact point-in-polyhedron test (ray parity with symbolic perturbation,
//!    [`classify_among`](crate::mesh::classify_among)).
//! 4. Subobjects: IN if P is in any of them; else ON if it is on any; else OUT.
//!
//! So IN means inside some object, ON on the surface of some object and inside none. Only
//! closed meshes have an inside: INCLUDE on an open one is an error that names it. Closed here
//! means every edge is shared by an even number of faces, so solids that touch along an edge
//! (voxel models: four faces on the edge) are accepted; parity needs nothing more.
//!
//! [`include()`] answers one point with no preprocessing (a leaf tests all its triangles, time
//! linear in the faces, as in the paper); [`IncludeIndex`] builds each mesh's
//! [`ProjectionGrid`] once and answers batches in parallel.
//!
//! ```
//! use kepler::{geometry::Point3, scene::Scene, queries::include::{Inclusion, IncludeIndex}};
//! let mut scene = Scene::new();
//! scene.add_mesh(None, "ring", kepler::solids::torus(2.0, 0.5, 24, 12).unwrap()).unwrap();
//! let index = IncludeIndex::whole_scene(&scene).unwrap();
//! let points = [Point3::new(2.0, 0.0, 0.0), Point3::new(0.0, 0.0, 0.0), Point3::new(2.5, 0.0, 0.0)];
//! let (answers, counters) = index.include_all(&points);
//! assert_eq!(answers, vec![Inclusion::In, Inclusion::Out, Inclusion::On]);
//! assert_eq!(counters.total(), 3);
//! ```

use super::projection_grid::ProjectionGrid;
use super::{Counters, QueryError, Stage, in_parallel};
use crate::geometry::{Aabb, Point3};
use crate::mesh::{Containment, Mesh, classify_point_brute_force};
use crate::scene::{Content, ObjectId, Scene};
use rayon::prelude::*;
use slotmap::SecondaryMap;

/// The answer of INCLUDE.
///
/// ```
/// use kepler::queries::include::Inclusion;
/// assert_eq!(Inclusion::On.to_string(), "ON");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Inclusion {
    /// Strictly inside.
    In,
    /// Strictly outside.
    Out,
    /// On the boundary (a face, edge or vertex), and inside no object.
    On,
}

impl std::fmt::Display for Inclusion {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Inclusion::In => "IN",
            Inclusion::Out => "OUT",
            Inclusion::On => "ON",
        })
    }
}

impl From<Containment> for Inclusion {
    fn from(c: Containment) -> Inclusion {
        match c {
            Containment::Inside => Inclusion::In,
            Containment::Outside => Inclusion::Out,
            Containment::Boundary => Inclusion::On,
        }
    }
}

/// INCLUDE(A, P) for object `id`, with no preprocessing: the answer and the stage that
/// decided it. Errors if the object has an open mesh in it.
///
/// ```
/// use kepler::{geometry::Point3, scene::Scene, queries::{Stage, include::{Inclusion, include}}};
/// let mut s = Scene::new();
/// let g = s.add_group(None, "pair").unwrap();
/// s.add_mesh(Some(g), "a", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let tent = kepler::io::read_mesh(std::path::Path::new("scenes/meshes/tent.stl")).unwrap();
/// let t = s.add_mesh(None, "tent", tent).unwrap();
/// assert_eq!(include(&s, g, &Point3::new(5.0, 0.0, 0.0)).unwrap(), (Inclusion::Out, Stage::Cbox));
/// assert!(include(&s, t, &Point3::origin()).unwrap_err().to_string().contains("open"));
/// ```
pub fn include(scene: &Scene, id: ObjectId, p: &Point3) -> Result<(Inclusion, Stage), QueryError> {
    check_closed(scene, id)?;
    Ok(descend(scene, id, p, &|_, mesh| {
        classify_point_brute_force(mesh, p)
    }))
}

/// INCLUDE prepared for many points: each mesh's projection grid, built once (in parallel).
///
/// ```
/// use kepler::{geometry::Point3, scene::Scene, queries::include::{Inclusion, IncludeIndex}};
/// let mut s = Scene::new();
/// s.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let index = IncludeIndex::whole_scene(&s).unwrap();
/// assert_eq!(index.include(&Point3::new(0.0, 0.0, 1.0)).0, Inclusion::On);
/// ```
#[derive(Debug)]
pub struct IncludeIndex<'s> {
    scene: &'s Scene,
    objects: Vec<ObjectId>,
    grids: SecondaryMap<ObjectId, ProjectionGrid<'s>>,
}

impl<'s> IncludeIndex<'s> {
    /// Prepares INCLUDE for the union of `objects` (and their subobjects). Errors if one of
    /// their meshes is open.
    ///
    /// ```
    /// use kepler::{scene::Scene, queries::include::IncludeIndex};
    /// let mut s = Scene::new();
    /// let c = s.add_mesh(None, "cube", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// assert!(IncludeIndex::new(&s, &[c]).is_ok());
    /// ```
    pub fn new(scene: &'s Scene, objects: &[ObjectId]) -> Result<IncludeIndex<'s>, QueryError> {
        for &id in objects {
            check_closed(scene, id)?;
        }
        // The bounds and the grids need only the meshes: built side by side.
        let leaves = scene.mesh_objects(objects);
        let ((), built) = rayon::join(
            || scene.compute_bounds_of(objects),
            || -> Vec<(ObjectId, ProjectionGrid<'s>)> {
                leaves
                    .par_iter()
                    .map(|&(id, mesh)| (id, ProjectionGrid::new(mesh)))
                    .collect()
            },
        );
        let mut grids = SecondaryMap::new();
        grids.extend(built);
        Ok(IncludeIndex {
            scene,
            objects: objects.to_vec(),
            grids,
        })
    }

    /// Prepares INCLUDE for the whole scene (all its root objects).
    ///
    /// ```
    /// let s = kepler::scene::file::load(std::path::Path::new("scenes/cube.toml")).unwrap();
    /// assert!(kepler::queries::include::IncludeIndex::whole_scene(&s).is_ok());
    /// ```
    pub fn whole_scene(scene: &'s Scene) -> Result<IncludeIndex<'s>, QueryError> {
        IncludeIndex::new(scene, scene.roots())
    }

    /// INCLUDE of one point against the union of the index's objects, and the stage that
    /// decided it.
    ///
    /// ```
    /// use kepler::{geometry::Point3, scene::Scene, queries::{Stage, include::{Inclusion, IncludeIndex}}};
    /// let mut s = Scene::new();
    /// s.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// let index = IncludeIndex::whole_scene(&s).unwrap();
    /// assert_eq!(index.include(&Point3::new(0.0, 0.0, 0.5)), (Inclusion::In, Stage::Inbox));
    /// ```
    pub fn include(&self, p: &Point3) -> (Inclusion, Stage) {
        union(
            self.objects
                .iter()
                .map(|&id| descend(self.scene, id, p, &|leaf, _| self.grids[leaf].classify(p))),
        )
    }

    /// INCLUDE of every point, in parallel, in the order given, with the counts of the stages
    /// that decided them.
    ///
    /// ```
    /// use kepler::{geometry::Point3, scene::Scene, queries::include::{Inclusion, IncludeIndex}};
    /// let mut s = Scene::new();
    /// s.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// let index = IncludeIndex::whole_scene(&s).unwrap();
    /// let (a, c) = index.include_all(&[Point3::origin(), Point3::new(3.0, 0.0, 0.0)]);
    /// assert_eq!(a, vec![Inclusion::In, Inclusion::Out]);
    /// assert_eq!((c.inbox, c.cbox), (1, 1));
    /// ```
    pub fn include_all(&self, points: &[Point3]) -> (Vec<Inclusion>, Counters) {
        in_parallel(points, |p| self.include(p))
    }
}

/// An error naming the first open mesh in the subtree of `id`.
fn check_closed(scene: &Scene, id: ObjectId) -> Result<(), QueryError> {
    for o in scene.subtree(id) {
        if let Some(mesh) = scene[o].mesh() {
            let topology = mesh.topology();
            if topology.odd_edges > 0 {
                return Err(QueryError::NotClosed {
                    object: scene.path(o),
                    boundary_edges: topology.boundary_edges,
                    odd_edges: topology.odd_edges,
                });
            }
        }
    }
    Ok(())
}

/// The paper's recursion, with the leaf test supplied.
fn descend(
    scene: &Scene,
    id: ObjectId,
    p: &Point3,
    leaf: &impl Fn(ObjectId, &Mesh) -> Containment,
) -> (Inclusion, Stage) {
    if scene
        .inbox(id)
        .is_some_and(|inbox| strictly_inside(&inbox.aabb, p))
    {
        return (Inclusion::In, Stage::Inbox);
    }
    if !scene.cbox(id).contains_point(p) {
        return (Inclusion::Out, Stage::Cbox);
    }
    if !scene.tribox(id).contains_point(p) {
        return (Inclusion::Out, Stage::Tribox);
    }
    match scene[id].content() {
        Content::Mesh(mesh) => (leaf(id, mesh).into(), Stage::Faces),
        Content::Subobjects(children) => {
            union(children.iter().map(|&c| descend(scene, c, p, leaf)))
        }
    }
}

/// Combines subobjects' answers: the first IN wins (later ones are not evaluated); else ON if
/// any is ON; else OUT, decided by the dearest stage any of them needed.
fn union(answers: impl Iterator<Item = (Inclusion, Stage)>) -> (Inclusion, Stage) {
    let mut result = (Inclusion::Out, Stage::Cbox);
    for (answer, stage) in answers {
        match answer {
            Inclusion::In => return (Inclusion::In, stage),
            Inclusion::On => result = (Inclusion::On, Stage::Faces),
            Inclusion::Out => result.1 = result.1.max(stage),
        }
    }
    result
}

/// Whether `p` lies in the open box (an INBOX may touch the surface on its boundary).
#[inline]
fn strictly_inside(b: &Aabb, p: &Point3) -> bool {
    (0..3).all(|k| b.min[k] < p[k] && p[k] < b.max[k])
}
