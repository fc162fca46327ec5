//! Visible surfaces: Franklin's VISFAC and VISFAC2 (1981, algorithms D and E): which part of a
//! face an object leaves visible, as exact polygons in the picture.
//!
//! VISFAC(A, F) starts the visibility texture polygon VTP(F) as the whole of F and takes away,
//! for every face G of A, the part of F that G hides: the points of F behind G's plane whose
//! picture lies in G's picture. (The line where the two planes meet is where "behind" changes,
//! so cutting F by G's plane is the paper's "cut by the projection of the line where the two
//! planes meet".) The answer is VISIBLE, HIDDEN or MIXED as VTP(F) is F, empty, or neither.
//!
//! VISFAC2 walks A's hierarchy with the paper's early exits: a subobject whose CBOX lies wholly
//! behind F's plane, or whose picture misses F's, is skipped; one whose INBOX hides every vertex
//! of F (seen from outside the subobject's CBOX) empties VTP(F) at once (the points whose line
//! of sight meets a box form a convex set, so the vertices decide for the whole face); so does
//! a single face G that hides every vertex of F (behind G's plane and inside G's picture); and
//! the walk stops as soon as VTP(F) is empty. Before any of it, a face turned away from the eye
//! on a solid the eye is outside of (closed, consistently oriented, not piercing itself) is
//! HIDDEN at once: its line of sight enters the solid, which it must leave through a face in
//! front of it.
//!
//! The status is decided exactly: a face G counts only when it hides a region of positive
//! area of F, decided from signs of `orient3d` of input points (and of exact degree-two
//! combinations for the points where G crosses F's plane), never from the rounded pictures.
//! So F is VISIBLE exactly when nothing hides any area of it, however the pictures touch.
//! VTP(F) itself is built exactly as well (see `vtp`): F as convex cells of its plane, from
//! which every face that hides some of it takes the convex piece it hides, each decision the
//! exact sign of a plane of the input at a point where two others meet F's plane. So F is
//! HIDDEN exactly when no cell is left, whether one face, several faces together, its own
//! solid or an INBOX hide it; and MIXED polygons have neither slivers nor spikes.
//!
//! The polygons are in picture coordinates (see [`Picture`]), and again in the face's texture
//! coordinates. Each vertex is built once, in f64, from the input coordinates: the picture of an
//! input vertex ([`Picture::point`]), the point where an edge crosses a plane of the input, or
//! the point of F's plane where two other planes of the input meet it (each coordinate a ratio
//! of exact polynomials of the input, each rounded once). So the polygons are the same bits
//! under mirroring and power-of-two scaling of the scene, whatever the order of the work.
//!
//! ```
//! use kepler::{geometry::Vector3, scene::Scene, views::View};
//! use kepler::surfaces::{Status, visfac};
//! let mut scene = Scene::new();
//! let cube = scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
//! let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
//! // The cube hides its own far faces and leaves its near ones whole.
//! let faces = kepler::solids::cube(2.0).unwrap().faces().len();
//! let statuses: Vec<Status> =
//!     (0..faces).map(|f| visfac(&scene, cube, &view, cube, f).unwrap().status).collect();
//! assert_eq!(statuses.iter().filter(|&&s| s == Status::Visible).count(), 3);
//! assert_eq!(statuses.iter().filter(|&&s| s == Status::Hidden).count(), 3);
//! ```

use crate::geometry::exact::ldexp;
use crate::mesh::{Mesh, TextureFrame, faces_in_space_order};
use crate::scene::{Content, ObjectId, Scene, SceneError};
use crate::sight::frustum::{self, Clip};
use crate::sight::own_solid::hidden_by_own_solid;
use crate::sight::range::in_working_range;
use crate::views::{Picture, View, ViewError};
use geo::{Coord, MapCoords, MultiPolygon};
use rayon::prelude::*;
use std::cmp::Ordering;

mod extent;
mod face_grid;
pub mod hatch;
mod index;
mod lines;
mod occluders;
mod overlap;
mod target;
mod vtp;

use index::Index;
use occluders::{Occluder, visfac2};
use target::{Framing, Target, ring, spanning_triangle};
use vtp::Vtp;

/// Why visible surfaces could not be computed: the surfaces layer's error.
///
/// ```
/// use kepler::{scene::Scene, surfaces::{SurfacesError, visfac}, views::View};
/// let mut scene = Scene::new();
/// let cube = scene.add_mesh(None, "cube", kepler::solids::cube(1.0).unwrap()).unwrap();
/// let e = visfac(&scene, cube, &View::standard(), cube, 6).unwrap_err();
/// assert!(matches!(e, SurfacesError::NoFace { face: 6, faces: 6, .. }));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum SurfacesError {
    /// The scene cannot be pictured in the view.
    #[error(transparent)]
    View(#[from] ViewError),
    /// The scene, brought into the kernel's working range, is not valid (see
    /// [`Scene::scaled`]).
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// VISFAC asked of an object without faces.
    #[error("object '{object}': VISFAC needs a face of a mesh object")]
    NotMesh {
        /// The object's path.
        object: String,
    },
    /// VISFAC asked of a face the mesh does not have.
    #[error("object '{object}': no face {face} (it has {faces})")]
    NoFace {
        /// The object's path.
        object: String,
        /// The face asked for (0-based).
        face: usize,
        /// How many faces the mesh has.
        faces: usize,
    },
    /// Hatching asked with an angle or spacings out of range, shades that do not match the
    /// faces, or too many lines (see [`hatch`]).
    #[error("hatching: {0}")]
    Hatch(String),
}

/// `Result` with the surfaces layer's [`SurfacesError`].
pub type Result<T, E = SurfacesError> = std::result::Result<T, E>;

/// How much of a face an object leaves visible.
///
/// ```
/// assert_eq!(format!("{:?}", kepler::surfaces::Status::Mixed), "Mixed");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Nothing of the face is hidden.
    Visible,
    /// All of the face is hidden.
    Hidden,
    /// Part of the face is hidden.
    Mixed,
}

/// The answer of [`visfac`]: the status, the visible polygons of the face in picture
/// coordinates, and how the hierarchy decided.
///
/// ```
/// use kepler::{scene::Scene, views::View, surfaces::{Status, visfac}};
/// let mesh = kepler::solids::cube(2.0).unwrap();
/// let top = mesh.faces().iter().position(|f| f.plane().normal.z > 0.5).unwrap();
/// let mut scene = Scene::new();
/// let cube = scene.add_mesh(None, "cube", mesh).unwrap();
/// let seen = visfac(&scene, cube, &View::standard(), cube, top).unwrap();
/// assert_eq!((seen.status, seen.polygons.0.len()), (Status::Visible, 1));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct VisibleFace {
    /// VISIBLE, HIDDEN or MIXED.
    pub status: Status,
    /// VTP(F) in picture coordinates: the visible part of the face.
    pub polygons: MultiPolygon<f64>,
    /// What decided it.
    pub exits: Exits,
    /// Whether the face is seen edge-on (no area: VISIBLE, no polygons).
    pub edge_on: bool,
}

/// How often each of VISFAC2's tests decided something.
///
/// ```
/// let e = kepler::surfaces::Exits::default();
/// assert_eq!(e.cbox_skipped + e.inbox_hid + e.faces_in_front, 0);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct Exits {
    /// Subobjects skipped because their CBOX cannot hide the face.
    pub cbox_skipped: u64,
    /// Subobjects whose INBOX hid the whole face (VTP emptied at once).
    pub inbox_hid: u64,
    /// Faces that hide some area of the face (decided exactly); each adds a piece to the
    /// difference.
    pub faces_in_front: u64,
    /// Faces that alone hid the whole face (VTP emptied at once, decided exactly).
    pub face_hid: u64,
    /// 1 when the face is turned away from the eye on a solid the eye is outside of (closed,
    /// consistently oriented, not piercing itself): the solid itself hides all of it.
    pub solid_hid: u64,
    /// Faces tested.
    pub faces_tested: u64,
}

/// VISFAC(A, F): how much of face `face` of the mesh object `owner` the object `a` (with its
/// subobjects) leaves visible from `view`. `a` may be `owner` itself (a face never hides
/// itself). A face seen edge-on has no area for anything to hide: VISIBLE, as the paper's
/// VTP(F) stays F, but with no polygons. An error if `owner` is not a mesh object or has no
/// such face.
///
/// ```
/// use kepler::{geometry::Vector3, scene::Scene, views::View, surfaces::{Status, visfac}};
/// use nalgebra::{Matrix4, Vector3 as V};
/// let mut scene = Scene::new();
/// let near = kepler::solids::cube(2.0).unwrap().transformed(&Matrix4::new_translation(&V::new(0.0, 0.0, 3.0))).unwrap();
/// let far = kepler::solids::cube(2.0).unwrap();
/// let top = far.faces().iter().position(|f| f.plane().normal.z > 0.5).unwrap();
/// let a = scene.add_mesh(None, "near", near).unwrap();
/// let b = scene.add_mesh(None, "far", far).unwrap();
/// // From above, the near cube hides the far cube's top face entirely.
/// assert_eq!(visfac(&scene, a, &View::standard(), b, top).unwrap().status, Status::Hidden);
/// ```
pub fn visfac(
    scene: &Scene,
    a: ObjectId,
    view: &View,
    owner: ObjectId,
    face: usize,
) -> Result<VisibleFace> {
    let (seen, shift) = in_working_range::<_, SurfacesError>(scene, view, |scene, view| {
        let (_, clip) = pictured(scene, view)?;
        Ok(visfac_among(scene, &[a], view, owner, face, None, clip.as_ref())?.0)
    })?;
    Ok(seen.scaled_back(view, shift))
}

/// VISFAC against the whole scene (every root object, the face's own included): the visible
/// part of face `face` of the mesh object `owner`.
///
/// ```
/// use kepler::{scene::Scene, views::View, surfaces::{Status, visfac_scene}};
/// let mut scene = Scene::new();
/// let cube = scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let mesh = scene[cube].mesh().unwrap();
/// let bottom = mesh.faces().iter().position(|f| f.plane().normal.z < -0.5).unwrap();
/// assert_eq!(visfac_scene(&scene, &View::standard(), cube, bottom).unwrap().status, Status::Hidden);
/// ```
pub fn visfac_scene(
    scene: &Scene,
    view: &View,
    owner: ObjectId,
    face: usize,
) -> Result<VisibleFace> {
    let (seen, shift) = in_working_range::<_, SurfacesError>(scene, view, |scene, view| {
        let (_, clip) = pictured(scene, view)?;
        Ok(visfac_among(scene, scene.roots(), view, owner, face, None, clip.as_ref())?.0)
    })?;
    Ok(seen.scaled_back(view, shift))
}

/// VISOBJ(A, B) (Franklin 1981, algorithm C): VISIBLE if `a` hides nothing of `b`, HIDDEN if it
/// hides all of it, else MIXED; through `b`'s subobjects down to its faces (VISFAC), leaving
/// out faces seen edge-on.
///
/// ```
/// use kepler::{scene::Scene, views::View, surfaces::{Status, visobj}};
/// use nalgebra::{Matrix4, Vector3};
/// let mut scene = Scene::new();
/// let big = kepler::solids::cube(4.0).unwrap().transformed(&Matrix4::new_translation(&Vector3::new(0.0, 0.0, 5.0))).unwrap();
/// let a = scene.add_mesh(None, "big", big).unwrap();
/// let b = scene.add_mesh(None, "small", kepler::solids::cube(1.0).unwrap()).unwrap();
/// assert_eq!(visobj(&scene, a, b, &View::standard()).unwrap(), Status::Hidden);
/// assert_eq!(visobj(&scene, b, a, &View::standard()).unwrap(), Status::Visible);
/// ```
pub fn visobj(scene: &Scene, a: ObjectId, b: ObjectId, view: &View) -> Result<Status> {
    let (status, _) = in_working_range::<_, SurfacesError>(scene, view, |scene, view| {
        let (_, clip) = pictured(scene, view)?;
        visobj_clipped(scene, a, b, view, clip.as_ref())
    })?;
    Ok(status)
}

/// [`visobj`] with the view's frustum when it clips.
fn visobj_clipped(
    scene: &Scene,
    a: ObjectId,
    b: ObjectId,
    view: &View,
    clip: Option<&Clip>,
) -> Result<Status> {
    let answers: Vec<Status> = match scene[b].content() {
        Content::Subobjects(children) => children
            .iter()
            .map(|&c| visobj_clipped(scene, a, c, view, clip))
            .collect::<Result<_>>()?,
        // Faces seen edge-on have no area to be hidden or seen: they do not count.
        Content::Mesh(mesh) => (0..mesh.faces().len())
            .map(|f| visfac_among(scene, &[a], view, b, f, None, clip).map(|v| v.0))
            .filter(|v| !v.as_ref().is_ok_and(|v| v.edge_on))
            .map(|v| v.map(|v| v.status))
            .collect::<Result<_>>()?,
    };
    Ok(if answers.iter().all(|&s| s == Status::Visible) {
        Status::Visible
    } else if answers.iter().all(|&s| s == Status::Hidden) {
        Status::Hidden
    } else {
        Status::Mixed
    })
}

/// One face's visible part in the whole scene: VISFAC's answer, and its polygons in the face's
/// texture coordinate system (Franklin's texture coordinates; see [`crate::mesh::TextureFrame`]).
///
/// ```
/// let r = kepler::surfaces::FaceReport {
///     object: Default::default(),
///     face: 0,
///     visible: kepler::surfaces::VisibleFace {
///         status: kepler::surfaces::Status::Hidden,
///         polygons: geo::MultiPolygon::new(vec![]),
///         exits: Default::default(),
///         edge_on: false,
///     },
///     texture: geo::MultiPolygon::new(vec![]),
/// };
/// assert_eq!(r.face, 0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct FaceReport {
    /// The mesh object.
    pub object: ObjectId,
    /// The face's index in its mesh.
    pub face: usize,
    /// Status and visible polygons in picture coordinates.
    pub visible: VisibleFace,
    /// The visible polygons in the face's texture coordinates (each vertex built once from the
    /// input, like its picture).
    pub texture: MultiPolygon<f64>,
}

/// The whole-scene pass: every face of every mesh object, with its visible polygons against
/// all objects (its own included), in parallel. Each face is tested only against the faces of
/// each mesh whose pictures may overlap its own (a uniform grid over the picture per mesh),
/// after the hierarchy's CBOX and INBOX exits.
///
/// A perspective eye inside the scene (some vertex not strictly in front of it) sees only
/// what lies inside the view's frustum ([`View::frustum`], at the aspect of
/// [`View::with_clipping`]), as the hidden-line pass draws: each face's visible polygons are
/// VTP(F) cut exactly by the frustum's five planes (through points in doubles placed
/// symmetrically about the frustum's: see `queries/frustum.rs`), so every vertex lies in the
/// picture's window up to the rounding of those points (a few units in the last place). Everything in front of the eye still hides what lies behind it. A face is then
/// VISIBLE only when all of it is seen (inside the frustum, nothing hiding any of it), HIDDEN
/// when nothing of it is seen (behind the eye, wholly outside the frustum, or hidden), MIXED
/// otherwise, a face cut by the edge of the picture included.
///
/// ```
/// use kepler::{geometry::Vector3, scene::Scene, views::View, surfaces::{Status, visible_surfaces}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
/// let faces = visible_surfaces(&scene, &view).unwrap();
/// assert_eq!(faces.iter().filter(|f| f.visible.status == Status::Visible).count(), 3);
/// ```
pub fn visible_surfaces(scene: &Scene, view: &View) -> Result<Vec<FaceReport>> {
    let (reports, shift) = in_working_range(scene, view, visible_surfaces_in_range)?;
    Ok(reports
        .into_iter()
        .map(|r| FaceReport {
            visible: r.visible.scaled_back(view, shift),
            texture: scaled(r.texture, -shift),
            ..r
        })
        .collect())
}

/// [`visible_surfaces`] of a scene and view in the kernel's working range.
fn visible_surfaces_in_range(scene: &Scene, view: &View) -> Result<Vec<FaceReport>> {
    let picture = Picture::of(view);
    let (meshes, clip) = pictured(scene, view)?;
    let clip = clip.as_ref();
    let index = Index::new(scene, &meshes, view, &picture, clip);
    // Faces are decided in an order near in space (each face's occluders are then mostly
    // in the cache, from its neighbours' turns); each report goes to its face's place.
    let mut faces: Vec<(ObjectId, usize, usize)> = Vec::new();
    for &(id, mesh) in &meshes {
        let first = faces.len();
        faces.extend(
            faces_in_space_order(mesh)
                .into_iter()
                .map(|f| (id, f as usize, first + f as usize)),
        );
    }
    let mut decided: Vec<(usize, FaceReport)> = faces
        .par_iter()
        .map(|&(id, f, place)| {
            let (visible, texture) =
                visfac_among(scene, scene.roots(), view, id, f, Some(&index), clip)?;
            let report = FaceReport {
                object: id,
                face: f,
                visible,
                texture,
            };
            Ok((place, report))
        })
        .collect::<Result<_>>()?;
    decided.sort_unstable_by_key(|&(place, _)| place);
    Ok(decided.into_iter().map(|(_, report)| report).collect())
}

/// Polygons scaled by `2^exponent` (exactly, unless a coordinate leaves the normal range).
fn scaled(polygons: MultiPolygon<f64>, exponent: i32) -> MultiPolygon<f64> {
    if exponent == 0 {
        return polygons;
    }
    polygons.map_coords(|c| Coord {
        x: ldexp(c.x, exponent),
        y: ldexp(c.y, exponent),
    })
}

impl VisibleFace {
    /// The answer found in the working range by `2^shift` brought back to the view's scale: a
    /// perspective picture does not scale.
    fn scaled_back(self, view: &View, shift: i32) -> VisibleFace {
        if view.is_perspective() {
            return self;
        }
        VisibleFace {
            polygons: scaled(self.polygons, -shift),
            ..self
        }
    }
}

/// The scene's mesh objects and the frustum when the view clips ([`frustum::pictured`]).
fn pictured<'s>(scene: &'s Scene, view: &View) -> Result<frustum::Pictured<'s>> {
    Ok(frustum::pictured(scene, view)?)
}

/// VISFAC of one face against the union of `objects`, with its visible polygons in the face's
/// texture coordinates: VTP(F) is F minus the pieces hidden by every occluder that hides some
/// area of it, decided and built exactly (see [`vtp`]), cut to the frustum `clip` when the
/// view clips.
fn visfac_among(
    scene: &Scene,
    objects: &[ObjectId],
    view: &View,
    owner: ObjectId,
    face: usize,
    index: Option<&Index>,
    clip: Option<&Clip>,
) -> Result<(VisibleFace, MultiPolygon<f64>)> {
    let mesh = face_mesh(scene, owner, face)?;
    let target = Target::new(mesh, face, view, clip);
    if target.framing == Framing::Outside {
        // Nothing of it in the frustum: nothing of it is seen.
        return Ok(hidden(Exits::default()));
    }
    if target.eye_side == Ordering::Equal {
        // Seen edge-on: no area to hide, so VTP(F) stays F (of zero area, no polygons).
        let nothing = MultiPolygon::new(Vec::new());
        let seen = answer(Status::Visible, nothing.clone(), Exits::default(), true);
        return Ok((seen, nothing));
    }
    let mut exits = Exits::default();
    let back_side = match index.and_then(|i| i.grids.get(owner)) {
        Some(grid) => grid.back_side,
        None if within(scene, owner, objects) => {
            hidden_by_own_solid(scene, owner, mesh, view.eye())
        }
        None => None,
    };
    if back_side == Some(target.eye_side) {
        exits.solid_hid = 1;
        return Ok(hidden(exits));
    }
    let mut occluders = Vec::new();
    let mut all_hidden = false;
    for &a in objects {
        if visfac2(
            scene,
            a,
            &target,
            (owner, face),
            index,
            &mut occluders,
            &mut exits,
        )? {
            all_hidden = true;
            break;
        }
    }
    let frame = &mesh.faces()[face].texture();
    if all_hidden {
        return Ok(hidden(exits));
    }
    // Every occluder hides some area of F (decided exactly), so none means VISIBLE, when all
    // of F is inside the frustum.
    let cut = clip.filter(|_| target.framing == Framing::Across);
    if occluders.is_empty() && cut.is_none() {
        return Ok(whole(&target, frame, exits));
    }
    let vtp = carved(mesh, face, &target, (clip, cut), &occluders);
    Ok(if vtp.is_empty() {
        hidden(exits)
    } else if !vtp.changed() {
        whole(&target, frame, exits)
    } else {
        let (polygons, texture) = vtp.polygons(frame, target.eye_side);
        (answer(Status::Mixed, polygons, exits, false), texture)
    })
}

/// The mesh of the object `owner`, which must be a mesh object with a face `face`.
fn face_mesh(scene: &Scene, owner: ObjectId, face: usize) -> Result<&Mesh> {
    let mesh = scene[owner].mesh().ok_or_else(|| SurfacesError::NotMesh {
        object: scene.path(owner),
    })?;
    if face >= mesh.faces().len() {
        return Err(SurfacesError::NoFace {
            object: scene.path(owner),
            face,
            faces: mesh.faces().len(),
        });
    }
    Ok(mesh)
}

/// VISFAC's answer for a face.
fn answer(status: Status, polygons: MultiPolygon<f64>, exits: Exits, edge_on: bool) -> VisibleFace {
    VisibleFace {
        status,
        polygons,
        exits,
        edge_on,
    }
}

/// A face of which nothing is seen: HIDDEN, without polygons in the picture or the texture.
fn hidden(exits: Exits) -> (VisibleFace, MultiPolygon<f64>) {
    let nothing = MultiPolygon::new(Vec::new());
    (
        answer(Status::Hidden, nothing.clone(), exits, false),
        nothing,
    )
}

/// A face seen whole: VISIBLE, its picture, and its vertices in its texture coordinates
/// (`frame`).
fn whole(target: &Target, frame: &TextureFrame, exits: Exits) -> (VisibleFace, MultiPolygon<f64>) {
    let texture = target
        .vertices
        .iter()
        .map(|v| lines::texture_of(frame, v))
        .collect();
    (
        answer(Status::Visible, target.polygon(), exits, false),
        ring(texture),
    )
}

/// VTP(F) of face `face` of `mesh` (the `target`): F as convex cells of its plane, cut to the
/// frustum `cut` (`clip` when the view clips and F lies across its planes), less what each of
/// the `occluders` hides of it, until nothing is left.
fn carved<'t>(
    mesh: &Mesh,
    face: usize,
    target: &'t Target,
    (clip, cut): (Option<&Clip>, Option<&Clip>),
    occluders: &[Occluder],
) -> Vtp<'t> {
    let (plane, planar) = spanning_triangle(mesh, face, &target.eye);
    let mut vtp = Vtp::new(
        &target.canonical,
        &plane,
        planar,
        &target.triangles,
        target.eye,
        target.eye_side,
        &target.picture,
    );
    if clip.is_some() {
        vtp.may_see_behind();
    }
    if let Some(clip) = cut {
        vtp.clip(clip);
    }
    for occluder in occluders {
        vtp.subtract(
            &occluder.corners,
            occluder.plane,
            occluder.planar,
            &occluder.triangles,
        );
        if vtp.is_empty() {
            break;
        }
    }
    vtp
}

/// Whether `id` is one of `objects` or lies below one of them.
fn within(scene: &Scene, id: ObjectId, objects: &[ObjectId]) -> bool {
    std::iter::successors(Some(id), |&o| scene[o].parent()).any(|o| objects.contains(&o))
}
