//! VISP(A, P) (Franklin 1981, algorithm B): whether object A hides point P from the eye; and
//! ray shooting, the first face a ray meets.
//!
//! The paper's steps, for any [`View`]:
//! 1. The line of sight from P to the eye misses CBOX(A): VISIBLE.
//! 2. It passes through the interior of INBOX(A), and the eye is outside CBOX(A): HIDDEN. (A
//!    line of sight into the solid must then leave it through a face between the point and
//!    the eye; from an eye inside the solid, points inside it are in plain view.)
//! 3. A face of A hides P: HIDDEN. A face hides P when P lies strictly behind its plane (the
//!    plane separates P from the eye) and the line of sight passes through the face. A face
//!    seen edge-on hides nothing, and a point on a face (or on its plane) is not hidden by it,
//!    so a point on the frontmost face that contains it is VISIBLE.
//! 4. Subobjects: HIDDEN if any hides P; else VISIBLE.
//!
//! Every test is exact: `orient3d` against the eye ([`Eye`]), a point or a point at infinity.
//! A line of sight that passes exactly through an edge or a vertex is moved by the symbolic
//! perturbation of [`Eye::perturbed_orient3d`], so it passes through exactly one of the faces
//! around an edge between two front faces (and P behind it is HIDDEN), and on one side of a
//! silhouette edge (beside it or through both its faces, the same for every point behind it).
//!
//! ```
//! use kepler::{geometry::Point3, scene::Scene, views::View, queries::visp::{Visibility, VisibilityIndex}};
//! let mut s = Scene::new();
//! s.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
//! let index = VisibilityIndex::whole_scene(&s, View::standard());
//! assert_eq!(index.visp(&Point3::new(0.5, 0.5, -3.0)).0, Visibility::Hidden);
//! assert_eq!(index.visp(&Point3::new(0.5, 0.5, 1.0)).0, Visibility::Visible);
//! ```

use super::{Counters, Stage, in_parallel};
use crate::geometry::predicates::orient3d;
use crate::geometry::ray::{Ray, compare_hits, hit_point, pierces};
use crate::geometry::{Point3, Vector3};
use crate::mesh::{Mesh, TriangleTree};
use crate::scene::{Content, ObjectId, Scene};
use crate::sight::Sight;
use crate::views::{Eye, View};
use rayon::prelude::*;
use slotmap::SecondaryMap;
use std::cmp::Ordering;

/// The answer of VISP.
///
/// ```
/// assert_eq!(kepler::queries::visp::Visibility::Hidden.to_string(), "HIDDEN");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Visibility {
    /// Nothing hides the point.
    Visible,
    /// Some face hides the point.
    Hidden,
}

impl std::fmt::Display for Visibility {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Visibility::Visible => "VISIBLE",
            Visibility::Hidden => "HIDDEN",
        })
    }
}

/// Whether the triangle `t` hides `p` from `eye`, exactly (see the module documentation).
///
/// ```
/// use kepler::{geometry::{Point3, Vector3}, views::Eye, queries::visp::hides};
/// let t = [Point3::new(0.0, 0.0, 1.0), Point3::new(4.0, 0.0, 1.0), Point3::new(0.0, 4.0, 1.0)];
/// let eye = Eye::Infinity(Vector3::z());
/// assert!(hides(&eye, &t, &Point3::new(1.0, 1.0, 0.0)));
/// assert!(!hides(&eye, &t, &Point3::new(1.0, 1.0, 1.0))); // on the triangle
/// assert!(!hides(&eye, &t, &Point3::new(3.0, 3.0, 0.0))); // beside it
/// ```
#[inline]
pub fn hides(eye: &Eye, t: &[Point3; 3], p: &Point3) -> bool {
    let eye_side = eye.orient3d(&t[0], &t[1], &t[2]);
    if eye_side == Ordering::Equal || orient3d(&t[0], &t[1], &t[2], p) != eye_side.reverse() {
        return false;
    }
    let s = eye.perturbed_orient3d(p, &t[0], &t[1]);
    s == eye.perturbed_orient3d(p, &t[1], &t[2]) && s == eye.perturbed_orient3d(p, &t[2], &t[0])
}

/// VISP(A, P) for object `id` with no preprocessing (a mesh tests all its triangles): the
/// answer and the stage that decided it.
///
/// ```
/// use kepler::{geometry::Point3, scene::Scene, views::View, queries::{Stage, visp::{Visibility, visp}}};
/// let mut s = Scene::new();
/// let c = s.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let view = View::standard();
/// assert_eq!(visp(&s, c, &view, &Point3::new(5.0, 0.0, 0.0)), (Visibility::Visible, Stage::Cbox));
/// assert_eq!(visp(&s, c, &view, &Point3::new(0.5, 0.0, -2.0)), (Visibility::Hidden, Stage::Inbox));
/// ```
pub fn visp(scene: &Scene, id: ObjectId, view: &View, p: &Point3) -> (Visibility, Stage) {
    let sight = Sight::to_eye(p, view.eye());
    descend(scene, id, &sight, &|_| true, &|_, mesh: &Mesh| {
        (0..mesh.triangles().len()).any(|t| hides(view.eye(), &mesh.triangle(t), p))
    })
}

/// The paper's recursion, with the leaf test (does this mesh hide the point?) supplied, and
/// which objects' INBOX to use (computing one costs more than it saves for a large
/// non-convex mesh whose faces answer through an index).
pub(crate) fn descend(
    scene: &Scene,
    id: ObjectId,
    sight: &Sight,
    inbox_wanted: &impl Fn(ObjectId) -> bool,
    leaf: &impl Fn(ObjectId, &Mesh) -> bool,
) -> (Visibility, Stage) {
    let cbox = scene.cbox(id);
    if !sight.may_meet(&cbox) {
        return (Visibility::Visible, Stage::Cbox);
    }
    if sight.eye_outside(&cbox)
        && inbox_wanted(id)
        && scene
            .inbox(id)
            .is_some_and(|inbox| sight.surely_meets_open(&inbox.aabb))
    {
        return (Visibility::Hidden, Stage::Inbox);
    }
    match scene[id].content() {
        Content::Mesh(mesh) => {
            let hidden = leaf(id, mesh);
            (
                if hidden {
                    Visibility::Hidden
                } else {
                    Visibility::Visible
                },
                Stage::Faces,
            )
        }
        Content::Subobjects(children) => any_hides(
            children
                .iter()
                .map(|&c| descend(scene, c, sight, inbox_wanted, leaf)),
        ),
    }
}

/// HIDDEN at the first subobject that hides; else VISIBLE, by the dearest stage needed.
pub(crate) fn any_hides(answers: impl Iterator<Item = (Visibility, Stage)>) -> (Visibility, Stage) {
    let mut stage = Stage::Cbox;
    for (answer, s) in answers {
        if answer == Visibility::Hidden {
            return (answer, s);
        }
        stage = stage.max(s);
    }
    (Visibility::Visible, stage)
}

/// Where a ray first meets a face.
///
/// ```
/// use kepler::{geometry::{Point3, Vector3}, scene::Scene, queries::visp::VisibilityIndex, geometry::ray::Ray};
/// let mut s = Scene::new();
/// let c = s.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let index = VisibilityIndex::whole_scene(&s, kepler::views::View::standard());
/// let hit = index.first_hit(&Ray { origin: Point3::new(0.25, 0.5, -5.0), direction: Vector3::z() }).unwrap();
/// assert_eq!((hit.object, hit.point), (c, Point3::new(0.25, 0.5, -1.0)));
/// assert_eq!(s[c].mesh().unwrap().faces()[hit.face].plane().normal.z.signum(), -1.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// The object whose face is hit.
    pub object: ObjectId,
    /// The face's index in the object's mesh.
    pub face: usize,
    /// The index of the triangle hit in the mesh's triangles.
    pub triangle: usize,
    /// The point hit, computed once from input coordinates (a few ulps from the exact point).
    pub point: Point3,
}

/// VISP and ray shooting prepared for one view: an R-tree over each mesh's triangles, built
/// once (in parallel).
///
/// ```
/// use kepler::{geometry::{Point3, Vector3}, scene::Scene, views::View, queries::visp::{Visibility, VisibilityIndex}};
/// let mut s = Scene::new();
/// s.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let view = View::orthographic(Vector3::new(-1.0, -1.0, -1.0), Vector3::z()).unwrap();
/// let index = VisibilityIndex::whole_scene(&s, view);
/// assert_eq!(index.visp(&Point3::new(-1.0, -1.0, -1.0)).0, Visibility::Hidden); // the back corner
/// assert_eq!(index.visp(&Point3::new(1.0, 1.0, 1.0)).0, Visibility::Visible); // the front corner
/// ```
#[derive(Debug)]
pub struct VisibilityIndex<'s> {
    scene: &'s Scene,
    view: View,
    objects: Vec<ObjectId>,
    trees: SecondaryMap<ObjectId, TriangleTree>,
}

impl<'s> VisibilityIndex<'s> {
    /// Prepares VISP from `view` for the union of `objects` (and their subobjects).
    ///
    /// ```
    /// use kepler::{scene::Scene, views::View, queries::visp::VisibilityIndex};
    /// let mut s = Scene::new();
    /// let c = s.add_mesh(None, "c", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// assert_eq!(VisibilityIndex::new(&s, &[c], View::standard()).view(), &View::standard());
    /// ```
    pub fn new(scene: &'s Scene, objects: &[ObjectId], view: View) -> VisibilityIndex<'s> {
        scene.compute_bounds_of(objects);
        let leaves = scene.mesh_objects(objects);
        let built: Vec<(ObjectId, TriangleTree)> = leaves
            .par_iter()
            .map(|&(id, mesh)| (id, TriangleTree::new(mesh)))
            .collect();
        let mut trees = SecondaryMap::new();
        trees.extend(built);
        VisibilityIndex {
            scene,
            view,
            objects: objects.to_vec(),
            trees,
        }
    }

    /// Prepares VISP from `view` for the whole scene (all its root objects).
    ///
    /// ```
    /// let s = kepler::scene::file::load(std::path::Path::new("scenes/cube.toml")).unwrap();
    /// let index = kepler::queries::visp::VisibilityIndex::whole_scene(&s, kepler::views::View::standard());
    /// assert!(!index.view().is_perspective());
    /// ```
    pub fn whole_scene(scene: &'s Scene, view: View) -> VisibilityIndex<'s> {
        VisibilityIndex::new(scene, scene.roots(), view)
    }

    /// The view.
    ///
    /// ```
    /// let s = kepler::scene::Scene::new();
    /// let index = kepler::queries::visp::VisibilityIndex::whole_scene(&s, kepler::views::View::standard());
    /// assert_eq!(index.view(), &kepler::views::View::standard());
    /// ```
    pub fn view(&self) -> &View {
        &self.view
    }

    /// VISP of one point against the index's objects, and the stage that decided it.
    ///
    /// ```
    /// use kepler::{geometry::Point3, scene::Scene, views::View, queries::{Stage, visp::{Visibility, VisibilityIndex}}};
    /// let mut s = Scene::new();
    /// s.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// let index = VisibilityIndex::whole_scene(&s, View::standard());
    /// // On the top face: on the frontmost face that contains it.
    /// assert_eq!(index.visp(&Point3::new(0.2, 0.3, 1.0)), (Visibility::Visible, Stage::Faces));
    /// ```
    pub fn visp(&self, p: &Point3) -> (Visibility, Stage) {
        let eye = self.view.eye();
        self.visp_by((p, 0.0), |t| hides(eye, t, p))
    }

    /// VISP of a point given by its face test `hides` (whether a triangle hides the point,
    /// decided exactly however the point is given) and a point `near` it, within `radius`,
    /// for the bounds (whose tests are widened by that radius: see `sight.rs`).
    pub(crate) fn visp_by(
        &self,
        (near, radius): (&Point3, f64),
        hides: impl Fn(&[Point3; 3]) -> bool,
    ) -> (Visibility, Stage) {
        let sight = Sight::to_eye(near, self.view.eye()).blurred(radius);
        any_hides(self.objects.iter().map(|&id| {
            descend(self.scene, id, &sight, &|_| true, &|leaf, _| {
                self.trees[leaf]
                    .select(|b| sight.may_meet(b))
                    .any(|(_, t)| hides(&t))
            })
        }))
    }

    /// VISP of every point, in parallel, in the order given, with the counts of the stages
    /// that decided them.
    ///
    /// ```
    /// use kepler::{geometry::Point3, scene::Scene, views::View, queries::visp::{Visibility, VisibilityIndex}};
    /// let mut s = Scene::new();
    /// s.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// let index = VisibilityIndex::whole_scene(&s, View::standard());
    /// let (a, c) = index.visp_all(&[Point3::new(0.0, 0.0, -5.0), Point3::new(0.0, 0.0, 5.0)]);
    /// assert_eq!(a, vec![Visibility::Hidden, Visibility::Visible]);
    /// assert_eq!((c.inbox, c.cbox), (1, 1));
    /// ```
    pub fn visp_all(&self, points: &[Point3]) -> (Vec<Visibility>, Counters) {
        in_parallel(points, |p| self.visp(p))
    }

    /// The first face the ray meets (its closed triangles, so an edge or a vertex counts),
    /// through the same hierarchy, or `None`. A face whose plane contains the ray, or the
    /// ray's origin, is not met. Which face is first is decided exactly; faces met at the same
    /// point are ordered by object (depth first) and then face index. A zero direction meets
    /// nothing.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, scene::Scene, views::View, queries::visp::VisibilityIndex, geometry::ray::Ray};
    /// let mut s = Scene::new();
    /// s.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// let index = VisibilityIndex::whole_scene(&s, View::standard());
    /// let from_inside = Ray { origin: Point3::origin(), direction: Vector3::new(1.0, 1.0, 1.0) };
    /// assert_eq!(index.first_hit(&from_inside).unwrap().point, Point3::new(1.0, 1.0, 1.0));
    /// let away = Ray { origin: Point3::new(0.0, 0.0, 2.0), direction: Vector3::z() };
    /// assert!(index.first_hit(&away).is_none());
    /// ```
    pub fn first_hit(&self, ray: &Ray) -> Option<Hit> {
        if ray.direction == Vector3::zeros() {
            return None;
        }
        let sight = Sight::ray(&ray.origin, &ray.direction);
        let mut best: Option<(Hit, [Point3; 3])> = None;
        for &root in &self.objects {
            for id in self.scene.subtree(root) {
                let (Some(tree), Some(mesh)) = (self.trees.get(id), self.scene[id].mesh()) else {
                    continue;
                };
                if !sight.may_meet(&self.scene.cbox(id)) {
                    continue;
                }
                for (t, corners) in tree.select(|b| sight.may_meet(b)) {
                    if !pierces(ray, &corners) {
                        continue;
                    }
                    let candidate = Hit {
                        object: id,
                        face: mesh.face_of(t),
                        triangle: t,
                        point: Point3::origin(),
                    };
                    let better = match &best {
                        None => true,
                        Some((current, current_corners)) => {
                            match compare_hits(ray, &corners, current_corners) {
                                Ordering::Less => true,
                                Ordering::Greater => false,
                                Ordering::Equal => {
                                    candidate.object == current.object
                                        && (candidate.face, t) < (current.face, current.triangle)
                                }
                            }
                        }
                    };
                    if better {
                        best = Some((candidate, corners));
                    }
                }
            }
        }
        best.map(|(hit, corners)| Hit {
            point: hit_point(ray, &corners),
            ..hit
        })
    }
}
